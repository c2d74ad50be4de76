// Cantilever beam L x h x b: x along the length, y along the height h, z across the width b.
// Transfinite hexahedra nx x ny x nz. Groups: volume beam; faces clamp (x = 0) and tip (x = L).

DefineConstant[
  L = {10, Name "Parameters/L", Help "length along x"},
  h = {1, Name "Parameters/h", Help "height along y"},
  b = {1, Name "Parameters/b", Help "width along z"},
  nx = {10, Min 1, Name "Parameters/nx"},
  ny = {2, Min 1, Name "Parameters/ny"},
  nz = {2, Min 1, Name "Parameters/nz"}
];

// The clamp face is the x = 0 rectangle (y up, z across), extruded along +x into the beam.
Point(1) = {0, 0, 0};
Point(2) = {0, h, 0};
Point(3) = {0, h, b};
Point(4) = {0, 0, b};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Transfinite Curve{1, 3} = ny + 1;
Transfinite Curve{2, 4} = nz + 1;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Surface{1};
Recombine Surface{1};
beam[] = Extrude{L, 0, 0}{ Surface{1}; Layers{nx}; Recombine; };

Physical Volume("beam") = {beam[1]};
Physical Surface("clamp") = {1};
Physical Surface("tip") = {beam[0]};
