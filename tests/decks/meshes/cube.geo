// Test fixture for the deck tests: the unit cube [0,1]^3 as n x n x n transfinite hexahedra.
// Groups: volume cube; surfaces bottom (z = 0), top (z = 1).
DefineConstant[ n = {2, Min 1, Name "Parameters/n"} ];

Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Transfinite Curve{1, 2, 3, 4} = n + 1;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Surface{1};
Recombine Surface{1};
top[] = Extrude {0, 0, 1} { Surface{1}; Layers{n}; Recombine; };

Physical Volume("cube") = {top[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {top[0]};
