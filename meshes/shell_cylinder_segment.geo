// Cylindrical shell segment for solid-shell verification (Scordelis-Lo roof, pinched cylinder):
// axis x, mid-surface radius R, x in [0, L], angle theta in [0, angle] measured from +z towards
// +y, so a point is (x, r sin(theta), r cos(theta)). One element layer of thickness t between
// r = R - t/2 and R + t/2, nx x nt transfinite hexahedra, trilinear (order = 1, Hex8) or
// triquadratic (order = 2, Hex27 for solid_shell18). The transfinite corners are listed inner
// face first, so each element's local zeta axis points radially outwards (thickness=auto).
// Groups: volume "shell"; faces "end0" (x = 0), "end1" (x = L), "side0" (theta = 0),
// "side1" (theta = angle), "inner", "outer"; thickness lines "corner_end0_side0",
// "corner_end0_side1", "corner_end1_side0", "corner_end1_side1" (the two face nodes there).

DefineConstant[
  R = {25, Name "Parameters/R", Help "mid-surface radius"},
  L = {25, Name "Parameters/L", Help "length along the axis x"},
  angle = {40, Name "Parameters/angle", Help "opening angle in degrees"},
  t = {0.25, Name "Parameters/t", Help "thickness"},
  nx = {16, Min 1, Name "Parameters/nx", Help "elements along x"},
  nt = {16, Min 1, Name "Parameters/nt", Help "elements along the arc"},
  order = {1, Choices {1, 2}, Name "Parameters/order", Help "1: Hex8, 2: Hex27"}
];

Mesh.ElementOrder = order;
Mesh.SecondOrderIncomplete = 0;  // Hex27, not the 20-node serendipity hexahedron

theta = angle * Pi / 180;
radii[] = {R - t / 2, R + t / 2};

Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
// Corner points p(end, side, face) = 10 + end + 2 side + 4 face.
For face In {0 : 1}
  For side In {0 : 1}
    For end In {0 : 1}
      Point(10 + end + 2 * side + 4 * face) =
          {end * L, radii[face] * Sin(side * theta), radii[face] * Cos(side * theta)};
    EndFor
  EndFor
EndFor
// Arcs a(end, face) = 20 + end + 2 face; axial lines l(side, face) = 30 + side + 2 face;
// thickness lines h(end, side) = 40 + end + 2 side.
For face In {0 : 1}
  For end In {0 : 1}
    Circle(20 + end + 2 * face) = {10 + end + 4 * face, 1 + end, 12 + end + 4 * face};
  EndFor
  For side In {0 : 1}
    Line(30 + side + 2 * face) = {10 + 2 * side + 4 * face, 11 + 2 * side + 4 * face};
  EndFor
EndFor
For end In {0 : 1}
  For side In {0 : 1}
    Line(40 + end + 2 * side) = {10 + end + 2 * side, 14 + end + 2 * side};
  EndFor
EndFor
Transfinite Curve{20 : 23} = nt + 1;
Transfinite Curve{30 : 33} = nx + 1;
Transfinite Curve{40 : 43} = 2;

// Faces: inner/outer cylinders, the two ends and the two sides.
For face In {0 : 1}
  Curve Loop(50 + face) = {30 + 2 * face, 21 + 2 * face, -(31 + 2 * face), -(20 + 2 * face)};
  Surface(50 + face) = {50 + face};
EndFor
For end In {0 : 1}
  Curve Loop(52 + end) = {20 + end, 40 + end + 2, -(22 + end), -(40 + end)};
  Plane Surface(52 + end) = {52 + end};
EndFor
For side In {0 : 1}
  Curve Loop(54 + side) = {30 + side, 41 + 2 * side, -(32 + side), -(40 + 2 * side)};
  Plane Surface(54 + side) = {54 + side};
EndFor
Transfinite Surface{50 : 55};
Recombine Surface{50 : 55};
Surface Loop(60) = {50 : 55};
Volume(60) = {60};
Transfinite Volume{60} = {10, 11, 13, 12, 14, 15, 17, 16};
Recombine Volume{60};

Physical Volume("shell") = {60};
Physical Surface("inner") = {50};
Physical Surface("outer") = {51};
Physical Surface("end0") = {52};
Physical Surface("end1") = {53};
Physical Surface("side0") = {54};
Physical Surface("side1") = {55};
Physical Curve("corner_end0_side0") = {40};
Physical Curve("corner_end1_side0") = {41};
Physical Curve("corner_end0_side1") = {42};
Physical Curve("corner_end1_side1") = {43};
