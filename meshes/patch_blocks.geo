// Contact patch test: two stacked blocks [0,W] x [0,W] touching on z = 0, each meshed with its own
// structured hexahedra, so that their contact faces do not match (nl != nu) or match (nl = nu).
// `skew` moves the interior grid lines of the upper block's contact face (a distorted mesh).
//
// Groups: volumes lower, upper; surfaces lower_top, lower_bottom, lower_xmin, lower_ymin,
// upper_bottom, upper_top, upper_xmin, upper_ymin.

DefineConstant[
  W = {1, Name "Parameters/W", Help "width of both blocks"},
  T = {0.5, Name "Parameters/T", Help "height of each block"},
  nl = {4, Min 1, Name "Parameters/nl", Help "lower block: elements along x and y"},
  nu = {5, Min 1, Name "Parameters/nu", Help "upper block: elements along x and y"},
  nz = {2, Min 1, Name "Parameters/nz", Help "elements through each block's height"},
  skew = {0, Name "Parameters/skew", Help "upper block: progression of its in-plane grid (0: uniform)"}
];

// One block: the rectangle at z = lift extruded by `height` (negative: downwards).
Macro MakeBlock
  p1 = newp;  Point(p1) = {0, 0, lift};
  p2 = newp;  Point(p2) = {W, 0, lift};
  p3 = newp;  Point(p3) = {W, W, lift};
  p4 = newp;  Point(p4) = {0, W, lift};
  l1 = newl;  Line(l1) = {p1, p2};
  l2 = newl;  Line(l2) = {p2, p3};
  l3 = newl;  Line(l3) = {p4, p3};
  l4 = newl;  Line(l4) = {p1, p4};
  If (progression > 1)
    Transfinite Curve{l1, l2, l3, l4} = count + 1 Using Progression progression;
  Else
    Transfinite Curve{l1, l2, l3, l4} = count + 1;
  EndIf
  loop = newll;  Curve Loop(loop) = {l1, l2, -l3, -l4};
  face = news;  Plane Surface(face) = {loop};
  Transfinite Surface{face};
  Recombine Surface{face};
  extruded[] = Extrude {0, 0, height} { Surface{face}; Layers{nz}; Recombine; };
  // extruded: far face, volume, then the sides along l1 (y = 0), l2, l3, l4 (x = 0).
Return

count = nl;  progression = 1;  height = -T;  lift = 0;
Call MakeBlock;
Physical Volume("lower") = {extruded[1]};
Physical Surface("lower_top") = {face};
Physical Surface("lower_bottom") = {extruded[0]};
Physical Surface("lower_ymin") = {extruded[2]};
Physical Surface("lower_xmin") = {extruded[5]};

// The upper block is built clear of the lower one, so that gmsh's automatic coherence cannot merge
// their coincident corners, and is then lowered with coherence switched off.
count = nu;  progression = 1 + skew;  height = T;  lift = 2 * T;
Call MakeBlock;
Geometry.AutoCoherence = 0;
Translate {0, 0, -lift} { Volume{extruded[1]}; }
Physical Volume("upper") = {extruded[1]};
Physical Surface("upper_bottom") = {face};
Physical Surface("upper_top") = {extruded[0]};
Physical Surface("upper_ymin") = {extruded[2]};
Physical Surface("upper_xmin") = {extruded[5]};
