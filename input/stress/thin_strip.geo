// Half of a thin strip, x in [0, a], y in [0, b], z in [0, t], one layer of nx x 1 hexahedra
// extruded along z (each element's thickness axis, for solid_shell8 with thickness=auto), for
// input/stress/thin_shell_on_cylinder.deck. Groups: volume "strip"; faces "bottom" (z = 0),
// "top", "symmetry" (x = 0), "end" (x = a), "front" (y = 0), "back" (y = b); curve "end_bottom"
// (x = a, z = 0), a line support that leaves the end section free to rotate and stretch.

DefineConstant[
  a = {0.5, Name "Parameters/a", Help "half span along x"},
  b = {0.05, Name "Parameters/b", Help "width along y"},
  t = {0.0005, Name "Parameters/t", Help "thickness along z"},
  nx = {50, Min 1, Name "Parameters/nx", Help "elements along x"}
];

Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0};
Point(3) = {a, b, 0};
Point(4) = {0, b, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = 2;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Surface{1};
Recombine Surface{1};
strip[] = Extrude{0, 0, t}{ Surface{1}; Layers{1}; Recombine; };

Physical Volume("strip") = {strip[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {strip[0]};
Physical Surface("front") = {strip[2]};
Physical Surface("end") = {strip[3]};
Physical Surface("back") = {strip[4]};
Physical Surface("symmetry") = {strip[5]};
Physical Curve("end_bottom") = {2};
