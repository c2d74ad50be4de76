// Ironing (after Puso & Laursen 2004): a soft slab and a die with a cylindrical face above it.
//
// Slab: [0,L] x [0,W] x [0,H], nx x ny x nz transfinite hexahedra.
// Die: a sector of a thick cylindrical shell, axis along y at (x0, ., H + R + gap), outer radius
// R (the contact face), inner radius R - t, opening angle +-angle (degrees) about the downward
// vertical, over y in [(W - dieWidth)/2, (W + dieWidth)/2] (dieWidth = W: exactly as wide as the
// slab; larger: overhanging on both sides). Its lowest line touches the slab top (gap = 0).
// nd elements around the arc, nr through the wall, ndy across the width.
//
// Each body is built from its own points and extruded on its own, and the only point where the
// bodies could touch (the die's lowest line) is never a geometric point of the slab, so the
// built-in kernel cannot glue them.
//
// Groups: volumes slab, die; surfaces slab_top (z = H), slab_bottom (z = 0), die_bottom (the
// cylindrical contact face), die_top (the inner arc face, where the die is driven).

DefineConstant[
  L = {10, Name "Parameters/L", Help "slab length (x)"},
  W = {4, Name "Parameters/W", Help "slab width (y)"},
  H = {3, Name "Parameters/H", Help "slab thickness (z)"},
  nx = {18, Min 1, Name "Parameters/nx"},
  ny = {8, Min 1, Name "Parameters/ny"},
  nz = {6, Min 1, Name "Parameters/nz"},
  R = {3, Name "Parameters/R", Help "die radius"},
  t = {0.75, Name "Parameters/t", Help "die wall thickness"},
  angle = {70, Name "Parameters/angle", Help "die half opening angle, degrees"},
  x0 = {3, Name "Parameters/x0", Help "die axis x position"},
  dieWidth = {5, Name "Parameters/dieWidth", Help "die width (y)"},
  nd = {20, Min 2, Name "Parameters/nd", Help "die elements around the arc (even)"},
  nr = {2, Min 1, Name "Parameters/nr", Help "die elements through the wall"},
  ndy = {10, Min 1, Name "Parameters/ndy", Help "die elements across the width"},
  gap = {0, Min 0, Name "Parameters/gap", Help "initial gap"},
  withDie = {1, Name "Parameters/withDie", Help "0: the slab alone (the die is a rigid surface)"}
];

// Slab: a line along x, extruded along y, then along z.
p1 = newp;  Point(p1) = {0, 0, 0};
p2 = newp;  Point(p2) = {L, 0, 0};
l1 = newl;  Line(l1) = {p1, p2};
Transfinite Curve{l1} = nx + 1;
slabBase[] = Extrude {0, W, 0} { Curve{l1}; Layers{ny}; Recombine; };
slab[] = Extrude {0, 0, H} { Surface{slabBase[1]}; Layers{nz}; Recombine; };
Physical Volume("slab") = {slab[1]};
Physical Surface("slab_bottom") = {slabBase[1]};
Physical Surface("slab_top") = {slab[0]};

// Die: the sector in the plane y = y0, extruded over the width.
If (withDie)
y0 = (W - dieWidth) / 2;
zc = H + R + gap;
a = angle * Pi / 180;
c = newp;  Point(c) = {x0, y0, zc};
o1 = newp;  Point(o1) = {x0 - R * Sin(a), y0, zc - R * Cos(a)};
o2 = newp;  Point(o2) = {x0, y0, zc - R};
o3 = newp;  Point(o3) = {x0 + R * Sin(a), y0, zc - R * Cos(a)};
ri = R - t;
i1 = newp;  Point(i1) = {x0 - ri * Sin(a), y0, zc - ri * Cos(a)};
i2 = newp;  Point(i2) = {x0, y0, zc - ri};
i3 = newp;  Point(i3) = {x0 + ri * Sin(a), y0, zc - ri * Cos(a)};
ca = newl;  Circle(ca) = {o1, c, o2};
cb = newl;  Circle(cb) = {o2, c, o3};
cc = newl;  Circle(cc) = {i1, c, i2};
cd = newl;  Circle(cd) = {i2, c, i3};
s1 = newl;  Line(s1) = {o1, i1};
s2 = newl;  Line(s2) = {o2, i2};
s3 = newl;  Line(s3) = {o3, i3};
Transfinite Curve{ca, cb, cc, cd} = nd / 2 + 1;
Transfinite Curve{s1, s2, s3} = nr + 1;
ll1 = newll;  Curve Loop(ll1) = {ca, s2, -cc, -s1};
f1 = news;  Plane Surface(f1) = {ll1};
ll2 = newll;  Curve Loop(ll2) = {cb, s3, -cd, -s2};
f2 = news;  Plane Surface(f2) = {ll2};
Transfinite Surface{f1, f2};
Recombine Surface{f1, f2};
die[] = Extrude {0, dieWidth, 0} { Surface{f1, f2}; Layers{ndy}; Recombine; };
// Extrude of a 4-sided surface: [top, volume, then the sides from its curves in loop order].
Physical Volume("die") = {die[1], die[7]};
Physical Surface("die_bottom") = {die[2], die[8]};
Physical Surface("die_top") = {die[4], die[10]};
EndIf
