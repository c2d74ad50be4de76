// A ball dragged across a block (issue 14): half model, symmetry plane y = 0 (half = 1), or the
// whole model (half = 0) for drags that leave that plane.
//
// Block: [0,L] x [0,W] x [0,H], nx x ny x nz transfinite hexahedra (whole: [0,L] x [-W,W] x
// [0,H], nx x 2 ny x nz).
// Ball: a cap of a thick spherical shell, centre (x0, 0, H + R + gap), outer radius R (the
// contact face), inner radius R - t. The cap is one face of a "cube sphere": the directions
// (X, Y, -1) with |X| <= T and 0 <= Y <= T (whole: |Y| <= T), T = tan(angle), projected on the
// two spheres, so its edges are great circles and its sides plane; nb elements along x, nb / 2
// across (whole: nb), nr through the wall. Its lowest point touches the block's top (gap = 0),
// and that point is never a geometric point of the block, so the built-in kernel cannot glue
// the bodies.
//
// Groups: volumes block, ball; surfaces block_top (z = H), block_bottom (z = 0), block_ymin
// (y = 0; whole: y = -W), ball_bottom (the outer spherical face: contact), ball_top (the inner
// face: driven), ball_ymin (y = 0; half model only).

DefineConstant[
  L = {10, Name "Parameters/L", Help "block length (x)"},
  W = {4, Name "Parameters/W", Help "block half-width (y)"},
  H = {3, Name "Parameters/H", Help "block thickness (z)"},
  nx = {20, Min 1, Name "Parameters/nx"},
  ny = {8, Min 1, Name "Parameters/ny"},
  nz = {6, Min 1, Name "Parameters/nz"},
  R = {3, Name "Parameters/R", Help "ball radius"},
  t = {0.75, Name "Parameters/t", Help "ball wall thickness"},
  angle = {60, Name "Parameters/angle", Help "cap half opening along the axes, degrees"},
  x0 = {3, Name "Parameters/x0", Help "ball centre x position"},
  nb = {16, Min 2, Name "Parameters/nb", Help "ball elements along x (even)"},
  nr = {2, Min 1, Name "Parameters/nr", Help "ball elements through the wall"},
  gap = {0, Min 0, Name "Parameters/gap", Help "initial gap"},
  withBall = {1, Name "Parameters/withBall", Help "0: the block alone (a rigid ball)"},
  half = {1, Name "Parameters/half", Help "1: half model about y = 0, 0: the whole model"}
];

// Block: a line along x, extruded along y, then along z.
yLow = half ? 0 : -W;
p1 = newp;  Point(p1) = {0, yLow, 0};
p2 = newp;  Point(p2) = {L, yLow, 0};
l1 = newl;  Line(l1) = {p1, p2};
Transfinite Curve{l1} = nx + 1;
blockBase[] = Extrude {0, W - yLow, 0} { Curve{l1}; Layers{half ? ny : 2 * ny}; Recombine; };
block[] = Extrude {0, 0, H} { Surface{blockBase[1]}; Layers{nz}; Recombine; };
Physical Volume("block") = {block[1]};
Physical Surface("block_bottom") = {blockBase[1]};
Physical Surface("block_top") = {block[0]};
// Extrude of the base (curves l1, its copy at y = W, and the two ends): block[2] is the side
// swept by l1, the face y = yLow.
Physical Surface("block_ymin") = {block[2]};

If (withBall)
zc = H + R + gap;
T = Tan(angle * Pi / 180);
c = newp;  Point(c) = {x0, 0, zc};
// Corner k of the cap in direction (X, Y, -1) on the sphere of radius r.
dx[] = {-T, T, T, -T};
dy[] = {half ? 0 : -T, half ? 0 : -T, T, T};
For side In {0:1}
  r = (side == 0) ? R : R - t;
  For k In {0:3}
    n = Sqrt(dx[k] * dx[k] + dy[k] * dy[k] + 1);
    corner[side * 4 + k] = newp;
    Point(corner[side * 4 + k]) = {x0 + r * dx[k] / n, r * dy[k] / n, zc - r / n};
  EndFor
  For k In {0:3}
    arc[side * 4 + k] = newl;
    Circle(arc[side * 4 + k]) = {corner[side * 4 + k], c, corner[side * 4 + (k + 1) % 4]};
  EndFor
  loop = newll;  Curve Loop(loop) = {arc[side * 4 + 0], arc[side * 4 + 1], arc[side * 4 + 2], arc[side * 4 + 3]};
  cap[side] = news;  Surface(cap[side]) = {loop} In Sphere {c};
EndFor
For k In {0:3}
  radial[k] = newl;  Line(radial[k]) = {corner[k], corner[4 + k]};
EndFor
For k In {0:3}
  loop = newll;
  Curve Loop(loop) = {arc[k], radial[(k + 1) % 4], -arc[4 + k], -radial[k]};
  wall[k] = news;  Plane Surface(wall[k]) = {loop};
EndFor
Transfinite Curve{arc[0], arc[2], arc[4], arc[6]} = nb + 1;
Transfinite Curve{arc[1], arc[3], arc[5], arc[7]} = (half ? nb / 2 : nb) + 1;
Transfinite Curve{radial[]} = nr + 1;
Transfinite Surface{cap[], wall[]};
Recombine Surface{cap[], wall[]};
shell = newsl;  Surface Loop(shell) = {cap[0], cap[1], wall[]};
ball = newv;  Volume(ball) = {shell};
Transfinite Volume{ball};
Physical Volume("ball") = {ball};
Physical Surface("ball_bottom") = {cap[0]};
Physical Surface("ball_top") = {cap[1]};
If (half)
Physical Surface("ball_ymin") = {wall[0]};
EndIf
EndIf
