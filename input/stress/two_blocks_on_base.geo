// Two elastic blocks side by side on one elastic base (input/stress/two_pairs_friction.deck):
// one model with two contact pairs of different friction coefficients. Plane-strain slab of
// thickness c along z; x along the base, y up. Built point by point with the built-in kernel
// (as meshes/block_on_base.geo), so that the touching bodies never share nodes.
//
// Groups: volumes left, right, base; surfaces left_bottom, right_bottom (contact masters),
// base_top (contact slave), left_top, right_top, base_bottom, and front (z = 0) / back (z = c)
// faces of every body: left_front, left_back, right_front, right_back, base_front, base_back.

DefineConstant[
  blockLength = {10, Name "Parameters/blockLength"},
  blockHeight = {3, Name "Parameters/blockHeight"},
  spacing = {2, Name "Parameters/spacing", Help "distance between the two blocks"},
  margin = {1, Name "Parameters/margin", Help "base overhang beyond each block"},
  baseHeight = {1, Name "Parameters/baseHeight"},
  thickness = {0.5, Name "Parameters/thickness"},
  nx = {5, Min 1, Name "Parameters/nx", Help "elements along x per block"},
  ny = {2, Min 1, Name "Parameters/ny", Help "elements along y per block"},
  nbx = {12, Min 1, Name "Parameters/nbx", Help "base elements along x"}
];

// Macro TransfiniteBox: [x0,x0+lx] x [y0,y0+ly] x [0,thickness] with nxr x nyr x 1 hexahedra;
// sets boxVolume and the faces boxFront (z = 0), boxBack, boxBottom (y = y0), boxTop.
Macro TransfiniteBox
  p = newp;
  For layer In {0:1}
    Point(p + 4 * layer) = {x0, y0, layer * thickness};
    Point(p + 4 * layer + 1) = {x0 + lx, y0, layer * thickness};
    Point(p + 4 * layer + 2) = {x0 + lx, y0 + ly, layer * thickness};
    Point(p + 4 * layer + 3) = {x0, y0 + ly, layer * thickness};
  EndFor
  l = newl;
  For layer In {0:1}
    For side In {0:3}
      Line(l + 4 * layer + side) = {p + 4 * layer + side, p + 4 * layer + (side + 1) % 4};
    EndFor
    Transfinite Curve{l + 4 * layer, l + 4 * layer + 2} = nxr + 1;
    Transfinite Curve{l + 4 * layer + 1, l + 4 * layer + 3} = nyr + 1;
  EndFor
  For corner In {0:3}
    Line(l + 8 + corner) = {p + corner, p + 4 + corner};
    Transfinite Curve{l + 8 + corner} = 2;
  EndFor
  loop = newll;
  Curve Loop(loop) = {l, l + 1, l + 2, l + 3};
  Curve Loop(loop + 1) = {l + 4, l + 5, l + 6, l + 7};
  Curve Loop(loop + 2) = {l, l + 9, -(l + 4), -(l + 8)};
  Curve Loop(loop + 3) = {l + 1, l + 10, -(l + 5), -(l + 9)};
  Curve Loop(loop + 4) = {l + 2, l + 11, -(l + 6), -(l + 10)};
  Curve Loop(loop + 5) = {l + 3, l + 8, -(l + 7), -(l + 11)};
  s = news;
  For face In {0:5}
    Plane Surface(s + face) = {loop + face};
  EndFor
  Transfinite Surface{s:s + 5};
  Recombine Surface{s:s + 5};
  shell = newsl;
  Surface Loop(shell) = {s:s + 5};
  boxVolume = newv;
  Volume(boxVolume) = {shell};
  Transfinite Volume{boxVolume} = {p:p + 7};
  boxFront = s; boxBack = s + 1; boxBottom = s + 2; boxTop = s + 4;
Return

x0 = margin; y0 = 0; lx = blockLength; ly = blockHeight; nxr = nx; nyr = ny;
Call TransfiniteBox;
left = boxVolume; leftFront = boxFront; leftBack = boxBack; leftBottom = boxBottom;
leftTop = boxTop;

x0 = margin + blockLength + spacing;
Call TransfiniteBox;
right = boxVolume; rightFront = boxFront; rightBack = boxBack; rightBottom = boxBottom;
rightTop = boxTop;

x0 = 0; y0 = -baseHeight; lx = 2 * (margin + blockLength) + spacing; ly = baseHeight;
nxr = nbx; nyr = 1;
Call TransfiniteBox;
base = boxVolume; baseFront = boxFront; baseBack = boxBack; baseBottom = boxBottom;
baseTop = boxTop;

Physical Volume("left") = {left};
Physical Volume("right") = {right};
Physical Volume("base") = {base};
Physical Surface("left_bottom") = {leftBottom};
Physical Surface("left_top") = {leftTop};
Physical Surface("left_front") = {leftFront};
Physical Surface("left_back") = {leftBack};
Physical Surface("right_bottom") = {rightBottom};
Physical Surface("right_top") = {rightTop};
Physical Surface("right_front") = {rightFront};
Physical Surface("right_back") = {rightBack};
Physical Surface("base_top") = {baseTop};
Physical Surface("base_bottom") = {baseBottom};
Physical Surface("base_front") = {baseFront};
Physical Surface("base_back") = {baseBack};
