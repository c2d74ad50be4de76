// Plate a x b in the xy-plane, thickness t along z, one layer of 27-node (second-order,
// complete) hexahedra for 18-node solid-shells: the extrusion direction z is each element's
// local zeta (thickness) axis. Groups: volume plate; faces bottom (z = 0), top (z = t),
// xmin, xmax, ymin, ymax (the lateral edges of the plate).

DefineConstant[
  a = {10, Name "Parameters/a", Help "length along x"},
  b = {10, Name "Parameters/b", Help "width along y"},
  t = {0.1, Name "Parameters/t", Help "thickness along z"},
  nx = {4, Min 1, Name "Parameters/nx"},
  ny = {4, Min 1, Name "Parameters/ny"}
];

Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 0;  // Hex27, not the 20-node serendipity hexahedron

Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0};
Point(3) = {a, b, 0};
Point(4) = {0, b, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Surface{1};
Recombine Surface{1};
plate[] = Extrude{0, 0, t}{ Surface{1}; Layers{1}; Recombine; };

Physical Volume("plate") = {plate[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {plate[0]};
Physical Surface("ymin") = {plate[2]};
Physical Surface("xmax") = {plate[3]};
Physical Surface("ymax") = {plate[4]};
Physical Surface("xmin") = {plate[5]};
