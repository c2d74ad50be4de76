// Paper example 6.2 (Konyukhov & Schweizerhof 2005, Fig. 8): a parabolic block on a fixed
// parabolic cylindrical base; both contact surfaces follow z = c x^2 (eq. 113).
//
// Axes: x along the parabola, z vertical (the parabola's axis), y across (the base's generatrix).
// Block: x in [-halfLength, halfLength], y in [0, width], between z = c x^2 and z = c x^2 +
// height (a parabolic slab of constant vertical height; the paper gives H and L only), nx x 1 x nz
// 27-node hexahedra for 18-node solid-shells (z is the thickness axis, so the contact faces are
// the elements' bottom faces). Base: x in [-baseHalfLength, baseHalfLength], same y range, from
// c x^2 - baseHeight to c x^2, nbx x 1 x 1 27-node hexahedra; its top nodes are the NTS slave
// nodes. With the defaults the base lies exactly under the block with the same node spacing
// (0.5 along x), so every slave node coincides with a node of the block's bottom face (both use
// the same mid-node placement below), the end slave nodes included.
//
// Each element edge along x is its own quadratic Bezier curve from x_k to x_k+1 = x_k + h, with
// control point (x_k + h/2, c x_k x_k+1): exactly the arc of z = c x^2, so the mesh vertices lie
// on the parabola at equal steps in x. gmsh places the second-order mid-edge nodes on the arc
// at equal arc length, not at x_k + h/2 (at most 0.0032 apart for h = 1, c = 0.03); the
// biquadratic surface through them deviates from the parabola by less than 3.8e-5 and its
// slope jumps across elements by less than 2e-5.
//
// Groups: volumes block, base; surfaces block_bottom (contact master), block_top, block_front
// (y = 0), block_back (y = width), block_left, block_right, base_top (slave nodes),
// base_bottom, base_front, base_back; curves block_bottom_edge and base_top_edge (at y = 0,
// for plots along the contact surface) and block_top_middle (the top face's line across y at
// x = 0 for even nx: where the block is held or driven horizontally).

DefineConstant[
  c = {0.03, Name "Parameters/c", Help "parabola coefficient, z = c x^2"},
  halfLength = {10, Name "Parameters/halfLength", Help "block: half of its length along x (L)"},
  height = {5, Name "Parameters/height", Help "block: vertical height (H)"},
  width = {1, Name "Parameters/width", Help "extent along y (both bodies)"},
  baseHalfLength = {10, Name "Parameters/baseHalfLength"},
  baseHeight = {1, Name "Parameters/baseHeight"},
  nx = {20, Min 1, Name "Parameters/nx", Help "block elements along x"},
  nz = {5, Min 1, Name "Parameters/nz", Help "block element layers along z"},
  nbx = {20, Min 1, Name "Parameters/nbx", Help "base elements along x"}
];

Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 0;  // Hex27, converted to 18-node solid-shells by the program

// Macro ParabolaSlab: the slab over the parabola z = c x^2, x in [x0, x0 + 2 a] (nCurve element
// columns), y in [0, width] (one element), from the parabola to dz above it (nLayers layers, dz
// may be negative), one transfinite volume per element column. Built entity by entity, without Extrude:
// the built-in kernel merges coincident entities after every extrusion, and that would glue the
// block to the base where their surfaces touch. Sets slabVolumes[], slabParabola[] (faces on
// the parabola), slabOffset[] (the faces dz away), slabFront[] (y = 0), slabBack[] (y = width),
// slabLeft, slabRight (the ends x = x0, x = x0 + 2 a) and slabCurves[] (the parabola at y = 0).
Macro ParabolaSlab
  h = 2 * a / nCurve;
  // Corner points: index 4 k + 2 side + level, side 0 at y = 0, level 0 on the parabola.
  corner = newp;
  For k In {0:nCurve}
    xk = x0 + k * h;
    For side In {0:1}
      For level In {0:1}
        Point(corner + 4 * k + 2 * side + level) = {xk, side * width, c * xk * xk + level * dz};
      EndFor
    EndFor
  EndFor
  // Arcs along x: index 4 k + 2 side + level; Bezier control points (x_k + h/2, c x_k x_k+1).
  control = newp;
  arcs = newl;
  For k In {0:nCurve - 1}
    xk = x0 + k * h;
    For side In {0:1}
      For level In {0:1}
        m = control + 4 * k + 2 * side + level;
        Point(m) = {xk + h / 2, side * width, c * xk * (xk + h) + level * dz};
        Bezier(arcs + 4 * k + 2 * side + level) = {corner + 4 * k + 2 * side + level, m,
                                                   corner + 4 * (k + 1) + 2 * side + level};
      EndFor
    EndFor
  EndFor
  // At each x_k: lines across (index 4 k + level) and along z (index 4 k + 2 + side).
  lines = newl;
  For k In {0:nCurve}
    For level In {0:1}
      Line(lines + 4 * k + level) = {corner + 4 * k + level, corner + 4 * k + 2 + level};
    EndFor
    For side In {0:1}
      Line(lines + 4 * k + 2 + side) = {corner + 4 * k + 2 * side, corner + 4 * k + 2 * side + 1};
    EndFor
  EndFor
  Transfinite Curve{arcs:arcs + 4 * nCurve - 1} = 2;
  Transfinite Curve{lines:lines + 4 * nCurve + 3} = 2;
  For k In {0:nCurve}
    Transfinite Curve{lines + 4 * k + 2, lines + 4 * k + 3} = nLayers + 1;
  EndFor
  // Faces across x at each x_k, shared by the columns on both sides.
  ends = news;
  For k In {0:nCurve}
    loop = newll;
    Curve Loop(loop) = {lines + 4 * k, lines + 4 * k + 3, -(lines + 4 * k + 1), -(lines + 4 * k + 2)};
    Plane Surface(ends + k) = {loop};
  EndFor
  slabVolumes[] = {}; slabParabola[] = {}; slabOffset[] = {}; slabFront[] = {}; slabBack[] = {};
  slabCurves[] = {};
  For k In {0:nCurve - 1}
    arc = arcs + 4 * k;  // + 2 side + level
    faces[] = {};
    For level In {0:1}  // the faces on the parabola (level 0) and dz away (level 1)
      loop = newll;
      Curve Loop(loop) = {arc + level, lines + 4 * (k + 1) + level, -(arc + 2 + level),
                          -(lines + 4 * k + level)};
      face = news;
      Surface(face) = {loop};
      faces[] += face;
    EndFor
    For side In {0:1}  // the faces at y = 0 (side 0) and y = width (side 1)
      loop = newll;
      Curve Loop(loop) = {arc + 2 * side, lines + 4 * (k + 1) + 2 + side, -(arc + 2 * side + 1),
                          -(lines + 4 * k + 2 + side)};
      face = news;
      Surface(face) = {loop};
      faces[] += face;
    EndFor
    shell = newsl;
    Surface Loop(shell) = {faces[], ends + k, ends + k + 1};
    volume = newv;
    Volume(volume) = {shell};
    Transfinite Surface{faces[], ends + k, ends + k + 1};
    Recombine Surface{faces[], ends + k, ends + k + 1};
    Transfinite Volume{volume};
    slabVolumes[] += volume;
    slabParabola[] += faces[0]; slabOffset[] += faces[1];
    slabFront[] += faces[2]; slabBack[] += faces[3];
    slabCurves[] += arc;
  EndFor
  slabLeft = ends; slabRight = ends + nCurve;
  slabMiddle = lines + 4 * Floor(nCurve / 2) + 1;  // across y at the middle x_k, dz away
Return

a = halfLength; x0 = -halfLength; nCurve = nx; dz = height; nLayers = nz;
Call ParabolaSlab;
block[] = slabVolumes[]; blockBottom[] = slabParabola[]; blockTop[] = slabOffset[];
blockFront[] = slabFront[]; blockBack[] = slabBack[]; blockLeft = slabLeft; blockRight = slabRight;
blockBottomEdge[] = slabCurves[]; blockTopMiddle = slabMiddle;

a = baseHalfLength; x0 = -baseHalfLength; nCurve = nbx; dz = -baseHeight; nLayers = 1;
Call ParabolaSlab;
base[] = slabVolumes[]; baseTop[] = slabParabola[]; baseBottom[] = slabOffset[];
baseFront[] = slabFront[]; baseBack[] = slabBack[]; baseTopEdge[] = slabCurves[];

Physical Volume("block") = {block[]};
Physical Volume("base") = {base[]};
Physical Surface("block_bottom") = {blockBottom[]};
Physical Surface("block_top") = {blockTop[]};
Physical Surface("block_front") = {blockFront[]};
Physical Surface("block_back") = {blockBack[]};
Physical Surface("block_left") = {blockLeft};
Physical Surface("block_right") = {blockRight};
Physical Surface("base_top") = {baseTop[]};
Physical Surface("base_bottom") = {baseBottom[]};
Physical Surface("base_front") = {baseFront[]};
Physical Surface("base_back") = {baseBack[]};
Physical Curve("block_top_middle") = {blockTopMiddle};
Physical Curve("block_bottom_edge") = {blockBottomEdge[]};
Physical Curve("base_top_edge") = {baseTopEdge[]};
