// A quarter of a block [0,L] x [0,L] x [-H,0] (symmetry planes x = 0 and y = 0), meshed with
// transfinite hexahedra graded towards the origin of its top face, where a contact patch
// (Hertz, Cattaneo-Mindlin) develops. The element size at the origin is about h0 along x, y
// and hz0 along z; sizes grow geometrically away from it.
//
// Groups: volume block; surfaces top (z = 0, the contact surface), bottom (z = -H), symx (x = 0),
// symy (y = 0), farx (x = L), fary (y = L).

DefineConstant[
  L = {4, Name "Parameters/L", Help "in-plane size of the quarter block"},
  H = {4, Name "Parameters/H", Help "depth of the block"},
  n = {16, Min 2, Name "Parameters/n", Help "elements along x and y"},
  nz = {12, Min 2, Name "Parameters/nz", Help "elements along z"},
  grading = {1.2, Min 1, Name "Parameters/grading", Help "size ratio of neighbouring elements"},
  gradingz = {1.25, Min 1, Name "Parameters/gradingz", Help "size ratio along the depth"}
];

Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, L, 0};
Point(4) = {0, L, 0};
Point(5) = {0, 0, -H};
Point(6) = {L, 0, -H};
Point(7) = {L, L, -H};
Point(8) = {0, L, -H};

// Top and bottom rectangles; every curve is oriented away from the x = 0 / y = 0 / z = 0
// planes so that one Progression grades all of them towards the origin's edges.
Line(1) = {1, 2};  // top, y = 0
Line(2) = {4, 3};  // top, y = L
Line(3) = {1, 4};  // top, x = 0
Line(4) = {2, 3};  // top, x = L
Line(5) = {5, 6};
Line(6) = {8, 7};
Line(7) = {5, 8};
Line(8) = {6, 7};
Line(9) = {1, 5};   // vertical edges, graded away from z = 0
Line(10) = {2, 6};
Line(11) = {3, 7};
Line(12) = {4, 8};

Transfinite Curve{1, 2, 3, 4, 5, 6, 7, 8} = n + 1 Using Progression grading;
Transfinite Curve{9, 10, 11, 12} = nz + 1 Using Progression gradingz;

Curve Loop(1) = {1, 4, -2, -3};    Plane Surface(1) = {1};   // top
Curve Loop(2) = {5, 8, -6, -7};    Plane Surface(2) = {2};   // bottom
Curve Loop(3) = {3, 12, -7, -9};   Plane Surface(3) = {3};   // x = 0
Curve Loop(4) = {1, 10, -5, -9};   Plane Surface(4) = {4};   // y = 0
Curve Loop(5) = {4, 11, -8, -10};  Plane Surface(5) = {5};   // x = L
Curve Loop(6) = {2, 11, -6, -12};  Plane Surface(6) = {6};   // y = L
Transfinite Surface{1:6};
Recombine Surface{1:6};
Surface Loop(1) = {1:6};
Volume(1) = {1};
Transfinite Volume{1};

Physical Volume("block") = {1};
Physical Surface("top") = {1};
Physical Surface("bottom") = {2};
Physical Surface("symx") = {3};
Physical Surface("symy") = {4};
Physical Surface("farx") = {5};
Physical Surface("fary") = {6};
