// Ironing with the slab's top side edges rounded: meshes/ironing.geo with the slab's y-z
// cross-section given corners of radius rEdge at the top (issue 14). With stick friction under
// the die, the sharp edge is a corner of singular contact pressure that grows with each mesh
// refinement, and the refined drags fail there (docs/verification/sliding.md, forty-eighth
// session); rounded, the pressure stays bounded and they pass the steps the sharp slab fails.
//
// Slab: [0,L] x [0,W] x [0,H], its top edges along x rounded; nx x ny x nz transfinite
// hexahedra (na of the ny across the top and na/2 of the nz up each side lie on the arcs).
// Die, groups and parameters otherwise as in meshes/ironing.geo (its header says what they are).

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
  rEdge = {0.5, Name "Parameters/rEdge", Help "radius of the slab's rounded top side edges"},
  na = {2, Min 2, Name "Parameters/na", Help "elements around each rounded edge (even)"},
  withDie = {1, Name "Parameters/withDie", Help "0: the slab alone (the die is a rigid surface)"}
];

// Slab: its y-z cross-section with the top corners rounded (radius rEdge), extruded along x.
// One transfinite surface with its corners at the bottom and at the middles of the two arcs,
// so that every side has matching element counts: bottom ny, top na/2 + (ny - na) + na/2,
// right and left (nz - na/2) + na/2.
pA = newp;  Point(pA) = {0, 0, 0};
pB = newp;  Point(pB) = {0, W, 0};
pC = newp;  Point(pC) = {0, W, H - rEdge};
pD = newp;  Point(pD) = {0, W - rEdge, H};
pE = newp;  Point(pE) = {0, rEdge, H};
pF = newp;  Point(pF) = {0, 0, H - rEdge};
cR = newp;  Point(cR) = {0, W - rEdge, H - rEdge};
cL = newp;  Point(cL) = {0, rEdge, H - rEdge};
mR = newp;  Point(mR) = {0, W - rEdge + rEdge * Sqrt(0.5), H - rEdge + rEdge * Sqrt(0.5)};
mL = newp;  Point(mL) = {0, rEdge - rEdge * Sqrt(0.5), H - rEdge + rEdge * Sqrt(0.5)};
lAB = newl;  Line(lAB) = {pA, pB};
lBC = newl;  Line(lBC) = {pB, pC};
aCM = newl;  Circle(aCM) = {pC, cR, mR};
aMD = newl;  Circle(aMD) = {mR, cR, pD};
lDE = newl;  Line(lDE) = {pD, pE};
aEM = newl;  Circle(aEM) = {pE, cL, mL};
aMF = newl;  Circle(aMF) = {mL, cL, pF};
lFA = newl;  Line(lFA) = {pF, pA};
Transfinite Curve{lAB} = ny + 1;
Transfinite Curve{lBC, lFA} = nz - na / 2 + 1;
Transfinite Curve{aCM, aMD, aEM, aMF} = na / 2 + 1;
Transfinite Curve{lDE} = ny - na + 1;
slabLoop = newll;  Curve Loop(slabLoop) = {lAB, lBC, aCM, aMD, lDE, aEM, aMF, lFA};
section = news;  Plane Surface(section) = {slabLoop};
Transfinite Surface{section} = {pA, pB, mR, mL};
Recombine Surface{section};
slab[] = Extrude {L, 0, 0} { Surface{section}; Layers{nx}; Recombine; };
// slab[]: the far face, the volume, then one face per curve of the loop, in its order.
Physical Volume("slab") = {slab[1]};
Physical Surface("slab_bottom") = {slab[2]};
Physical Surface("slab_top") = {slab[4], slab[5], slab[6], slab[7], slab[8]};

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
