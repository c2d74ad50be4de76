// Test fixture: two unit cubes stacked along z as 1 x 1 x 1 hexahedra each.
// Groups: volumes lower, upper; surfaces bottom (z = 0), top (z = 2).
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Transfinite Curve{1, 2, 3, 4} = 2;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Surface{1};
Recombine Surface{1};
lower[] = Extrude {0, 0, 1} { Surface{1}; Layers{1}; Recombine; };
upper[] = Extrude {0, 0, 1} { Surface{lower[0]}; Layers{1}; Recombine; };

Physical Volume("lower") = {lower[1]};
Physical Volume("upper") = {upper[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {upper[0]};
