// Flat plate or strip a x b in the xy-plane, thickness t along z, for solid-shell verification
// (thin cantilever strips, the cantilever rolled up by an end moment): one layer of nx x ny
// hexahedra, trilinear (order = 1, Hex8) or triquadratic (order = 2, Hex27 for solid_shell18).
// The extrusion direction z is each element's local zeta (thickness) axis (thickness=auto).
// Groups: volume "plate"; faces "bottom" (z = -t/2), "top" (z = t/2), "xmin", "xmax", "ymin",
// "ymax"; the mid-plane is z = 0.

DefineConstant[
  a = {1, Name "Parameters/a", Help "length along x"},
  b = {0.1, Name "Parameters/b", Help "width along y"},
  t = {0.001, Name "Parameters/t", Help "thickness along z"},
  nx = {32, Min 1, Name "Parameters/nx", Help "elements along x"},
  ny = {1, Min 1, Name "Parameters/ny", Help "elements along y"},
  order = {1, Choices {1, 2}, Name "Parameters/order", Help "1: Hex8, 2: Hex27"}
];

Mesh.ElementOrder = order;
Mesh.SecondOrderIncomplete = 0;  // Hex27, not the 20-node serendipity hexahedron

Point(1) = {0, 0, -t / 2};
Point(2) = {a, 0, -t / 2};
Point(3) = {a, b, -t / 2};
Point(4) = {0, b, -t / 2};
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
