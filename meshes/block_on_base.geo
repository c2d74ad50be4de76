// Paper example 6.1 (Konyukhov & Schweizerhof 2005, Fig. 4): an elastic block 20 x 5 x 0.5
// resting on a lower supplementary block (the "rigid" base; its stiffness comes from the deck).
//
// Axes: x along the block length a = 20, y vertical (block height b = 5; the paper's vertical
// displacement v acts along y, the horizontal u along x), z through the thickness c = 0.5.
// The block occupies [0,blockLength] x [gap, gap+blockHeight] x [0,thickness]; the base is
// centred below it: x in blockLength/2 -+ baseLength/2, y in [-baseHeight, 0], same z range.
// The two bodies are separate volumes that never share nodes, even where they touch
// (gap = 0) or have equal lengths, so the contact interface may be non-matching (nx != nbx).
//
// Groups: volumes block, base; surfaces block_bottom (contact master), base_top (contact
// slave), block_top, base_bottom, block_left, block_right, block_front (z=0), block_back
// (z=c), base_front, base_back; curve block_bottom_edge (the block's lower edge at z = 0,
// for plots along the contact surface).

DefineConstant[
  nx = {20, Min 1, Name "Parameters/nx", Help "block elements along x"},
  ny = {5, Min 1, Name "Parameters/ny", Help "block elements along y"},
  nz = {1, Min 1, Name "Parameters/nz", Help "elements through the thickness (both bodies)"},
  nbx = {24, Min 1, Name "Parameters/nbx", Help "base elements along x"},
  nby = {1, Min 1, Name "Parameters/nby", Help "base elements along y"},
  blockLength = {20, Name "Parameters/blockLength"},
  blockHeight = {5, Name "Parameters/blockHeight"},
  thickness = {0.5, Name "Parameters/thickness"},
  baseLength = {24, Name "Parameters/baseLength"},
  baseHeight = {1, Name "Parameters/baseHeight"},
  gap = {0, Min 0, Name "Parameters/gap", Help "initial gap between block and base"}
];

// Each body is built point by point (no Extrude, Translate or Coherence), so the built-in
// kernel never merges the coincident points and curves of the two bodies (e.g. when
// baseLength = blockLength and gap = 0), which would glue them together.
//
// Macro TransfiniteBox: the box [x0,x0+lx] x [y0,y0+ly] x [0,thickness] with nxr x nyr x nz
// transfinite hexahedra. Sets boxVolume and the faces boxFront (z = 0), boxBack (z = thickness),
// boxBottom (y = y0), boxRight (x = x0+lx), boxTop (y = y0+ly), boxLeft (x = x0) and the curve
// boxBottomFrontCurve (y = y0, z = 0).
Macro TransfiniteBox
  p = newp;
  For layer In {0:1}
    Point(p + 4 * layer) = {x0, y0, layer * thickness};
    Point(p + 4 * layer + 1) = {x0 + lx, y0, layer * thickness};
    Point(p + 4 * layer + 2) = {x0 + lx, y0 + ly, layer * thickness};
    Point(p + 4 * layer + 3) = {x0, y0 + ly, layer * thickness};
  EndFor
  l = newl;
  For layer In {0:1}  // the rectangle's perimeter at z = 0 (l..l+3) and z = thickness (l+4..l+7)
    For side In {0:3}
      Line(l + 4 * layer + side) = {p + 4 * layer + side, p + 4 * layer + (side + 1) % 4};
    EndFor
    Transfinite Curve{l + 4 * layer, l + 4 * layer + 2} = nxr + 1;
    Transfinite Curve{l + 4 * layer + 1, l + 4 * layer + 3} = nyr + 1;
  EndFor
  For corner In {0:3}  // through the thickness (l+8..l+11)
    Line(l + 8 + corner) = {p + corner, p + 4 + corner};
    Transfinite Curve{l + 8 + corner} = nz + 1;
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
  boxFront = s; boxBack = s + 1; boxBottom = s + 2; boxRight = s + 3; boxTop = s + 4;
  boxLeft = s + 5; boxBottomFrontCurve = l;
Return

x0 = 0; y0 = gap; lx = blockLength; ly = blockHeight; nxr = nx; nyr = ny;
Call TransfiniteBox;
block = boxVolume; blockFront = boxFront; blockBack = boxBack; blockBottom = boxBottom;
blockRight = boxRight; blockTop = boxTop; blockLeft = boxLeft;
blockBottomEdge = boxBottomFrontCurve;

x0 = (blockLength - baseLength) / 2; y0 = -baseHeight; lx = baseLength; ly = baseHeight;
nxr = nbx; nyr = nby;
Call TransfiniteBox;
base = boxVolume; baseFront = boxFront; baseBack = boxBack; baseBottom = boxBottom;
baseTop = boxTop;

Physical Volume("block") = {block};
Physical Volume("base") = {base};
Physical Surface("block_bottom") = {blockBottom};
Physical Surface("block_right") = {blockRight};
Physical Surface("block_top") = {blockTop};
Physical Surface("block_left") = {blockLeft};
Physical Surface("block_front") = {blockFront};
Physical Surface("block_back") = {blockBack};
Physical Surface("base_bottom") = {baseBottom};
Physical Surface("base_top") = {baseTop};
Physical Surface("base_front") = {baseFront};
Physical Surface("base_back") = {baseBack};
Physical Curve("block_bottom_edge") = {blockBottomEdge};
