// A block (top face z = 0) and, optionally, an elastic indenter above it (a sphere or a cylinder
// along y of radius R, touching the block at the origin), meshed with structured hexahedra for
// Hertz and Cattaneo-Mindlin verification: elements of uniform size h = c/m in the zone
// |x|, |y|, |z| < c around the contact, growing by `ratio` per element outside it.
//
// symx = 1 keeps x >= 0 only (symmetry plane x = 0), symy = 1 likewise for y; thickness > 0
// makes a plane-strain slab 0 <= y <= thickness, one element thick (cylinders).
// Groups per body B (block, indenter): volume B; surfaces B_top, B_bottom (the block's top and the
// indenter's bottom are the contact faces), B_xmin, B_xmax, B_ymin, B_ymax.
// Every point of the axis x = y = 0 inside the bodies' range is a mesh node (probe points).

DefineConstant[
  L = {16, Name "Parameters/L", Help "half-size in x and y (size when symmetric)"},
  H = {16, Name "Parameters/H", Help "depth of the block"},
  Hi = {16, Name "Parameters/Hi", Help "height of the indenter above its lowest point"},
  c = {1.5, Name "Parameters/c", Help "half-size of the uniformly meshed contact zone"},
  m = {8, Min 1, Name "Parameters/m", Help "elements across c (element size h = c/m)"},
  ratio = {1.3, Min 1.01, Name "Parameters/ratio", Help "element growth ratio outside the zone"},
  symx = {1, Name "Parameters/symx", Help "1: x >= 0 only, 0: -L <= x <= L"},
  symy = {1, Name "Parameters/symy", Help "1: y >= 0 only, 0: -L <= y <= L"},
  thickness = {0, Name "Parameters/thickness", Help "> 0: plane-strain slab of this thickness"},
  indenter = {0, Name "Parameters/indenter", Help "0: none, 1: sphere, 2: cylinder along y"},
  R = {100, Name "Parameters/R", Help "indenter radius"}
];

h = c / m;

// Lattice of patch corners and the element count of each interval. An interval graded outwards
// has kOut elements (the first about h * ratio, growing geometrically to the outer edge).
kOut = Ceil(Log(1 + (L - c) * (ratio - 1) / (h * ratio)) / Log(ratio));
If (symx)
  xs[] = {0, c, L};  xCount[] = {m, kOut};  xOutward[] = {0, 1};
Else
  xs[] = {-L, -c, c, L};  xCount[] = {kOut, 2 * m, kOut};  xOutward[] = {-1, 0, 1};
EndIf
If (thickness > 0)
  ys[] = {0, thickness};  yCount[] = {1};  yOutward[] = {0};
ElseIf (symy)
  ys[] = {0, c, L};  yCount[] = {m, kOut};  yOutward[] = {0, 1};
Else
  ys[] = {-L, -c, c, L};  yCount[] = {kOut, 2 * m, kOut};  yOutward[] = {-1, 0, 1};
EndIf
nxs = #xs[];
nys = #ys[];

// Layers of an extrusion over `depth`: m uniform layers down to c, then graded ones.
Macro ExtrusionLayers
  nGraded = Ceil(Log(1 + (depth - c) * (ratio - 1) / (h * ratio)) / Log(ratio));
  gradedSum = 0;
  For i In {1:nGraded}
    gradedSum += h * ratio^i;
  EndFor
  layerCounts[] = {};
  layerHeights[] = {};
  For i In {1:m}
    layerCounts[] += 1;
    layerHeights[] += i * h / depth;
  EndFor
  zLayer = c;
  For i In {1:nGraded}
    zLayer += (depth - c) / gradedSum * h * ratio^i;
    layerCounts[] += 1;
    layerHeights[] += zLayer / depth;
  EndFor
Return

// One body: its contact face as patches on the lattice (flat, spherical or cylindrical), extruded
// by `depth` along z * `direction`. Inputs: shape (0 flat, 1 sphere, 2 cylinder), direction,
// depth, body (0 block, 1 indenter). Outputs: the physical groups.
Macro Body
  // Sphere centre / cylinder axis height: the shape touches z = lift at the origin.
  zCentre = R + lift;
  corner[] = {};
  // Centres of the arcs (one per lattice line) and of the sphere: not on the body's boundary, so
  // they are moved explicitly with it. Each point exists once (coherence would merge copies).
  centres[] = {};
  If (shape > 0)
    axisCentre = newp;  Point(axisCentre) = {0, 0, zCentre};  centres[] += axisCentre;
    centreAtY[] = {};
    For j In {0:nys - 1}
      If (ys[j] == 0)
        centreAtY[] += axisCentre;
      Else
        p = newp;  Point(p) = {0, ys[j], zCentre};  centres[] += p;  centreAtY[] += p;
      EndIf
    EndFor
    centreAtX[] = {};
    For i In {0:nxs - 1}
      If (xs[i] == 0)
        centreAtX[] += axisCentre;
      Else
        p = newp;  Point(p) = {xs[i], 0, zCentre};  centres[] += p;  centreAtX[] += p;
      EndIf
    EndFor
  EndIf
  For i In {0:nxs - 1}
    For j In {0:nys - 1}
      zCorner = lift;
      If (shape == 1)
        zCorner += R - Sqrt(R^2 - xs[i]^2 - ys[j]^2);
      ElseIf (shape == 2)
        zCorner += R - Sqrt(R^2 - xs[i]^2);
      EndIf
      p = newp;  Point(p) = {xs[i], ys[j], zCorner};
      corner[] += p;
    EndFor
  EndFor
  // Curves along x (from corner (i,j) to (i+1,j)) and along y, oriented away from the zone so
  // that one Progression grades them outwards; alongX/alongY hold signed tags in lattice order.
  alongX[] = {};
  For j In {0:nys - 1}
    For i In {0:nxs - 2}
      first = corner[i * nys + j];  second = corner[(i + 1) * nys + j];  sign = 1;
      If (xOutward[i] < 0)
        first = corner[(i + 1) * nys + j];  second = corner[i * nys + j];  sign = -1;
      EndIf
      l = newl;
      If (shape == 0)
        Line(l) = {first, second};
      Else
        Circle(l) = {first, centreAtY[j], second};
      EndIf
      If (xOutward[i] == 0)
        Transfinite Curve{l} = xCount[i] + 1;
      Else
        Transfinite Curve{l} = xCount[i] + 1 Using Progression ratio;
      EndIf
      alongX[] += sign * l;
    EndFor
  EndFor
  alongY[] = {};
  For i In {0:nxs - 1}
    For j In {0:nys - 2}
      first = corner[i * nys + j];  second = corner[i * nys + j + 1];  sign = 1;
      If (yOutward[j] < 0)
        first = corner[i * nys + j + 1];  second = corner[i * nys + j];  sign = -1;
      EndIf
      l = newl;
      If (shape == 1)
        Circle(l) = {first, centreAtX[i], second};
      Else
        Line(l) = {first, second};
      EndIf
      If (yOutward[j] == 0)
        Transfinite Curve{l} = yCount[j] + 1;
      Else
        Transfinite Curve{l} = yCount[j] + 1 Using Progression ratio;
      EndIf
      alongY[] += sign * l;
    EndFor
  EndFor
  // Patches, each with its loop in the order: y = ys[j], x = xs[i+1], y = ys[j+1], x = xs[i].
  patches[] = {};
  patchI[] = {};
  patchJ[] = {};
  For i In {0:nxs - 2}
    For j In {0:nys - 2}
      loop = newll;
      Curve Loop(loop) = {alongX[j * (nxs - 1) + i], alongY[(i + 1) * (nys - 1) + j],
                          -alongX[(j + 1) * (nxs - 1) + i], -alongY[i * (nys - 1) + j]};
      s = news;
      If (shape == 0)
        Plane Surface(s) = {loop};
      ElseIf (shape == 1)
        Surface(s) = {loop} In Sphere {axisCentre};
      Else
        Surface(s) = {loop};
      EndIf
      Transfinite Surface{s};
      Recombine Surface{s};
      patches[] += s;  patchI[] += i;  patchJ[] += j;
    EndFor
  EndFor
  Call ExtrusionLayers;
  extruded[] = Extrude {0, 0, direction * depth} {
    Surface{patches[]}; Layers{layerCounts[], layerHeights[]}; Recombine;
  };
  volumes[] = {};  far[] = {};  xmin[] = {};  xmax[] = {};  ymin[] = {};  ymax[] = {};
  For k In {0:#patches[] - 1}
    far[] += extruded[6 * k];
    volumes[] += extruded[6 * k + 1];
    If (patchJ[k] == 0)
      ymin[] += extruded[6 * k + 2];
    EndIf
    If (patchI[k] == nxs - 2)
      xmax[] += extruded[6 * k + 3];
    EndIf
    If (patchJ[k] == nys - 2)
      ymax[] += extruded[6 * k + 4];
    EndIf
    If (patchI[k] == 0)
      xmin[] += extruded[6 * k + 5];
    EndIf
  EndFor
  If (body == 0)
    Physical Volume("block") = {volumes[]};
    Physical Surface("block_top") = {patches[]};
    Physical Surface("block_bottom") = {far[]};
    Physical Surface("block_xmin") = {xmin[]};
    Physical Surface("block_xmax") = {xmax[]};
    Physical Surface("block_ymin") = {ymin[]};
    Physical Surface("block_ymax") = {ymax[]};
  Else
    Physical Volume("indenter") = {volumes[]};
    Physical Surface("indenter_bottom") = {patches[]};
    Physical Surface("indenter_top") = {far[]};
    Physical Surface("indenter_xmin") = {xmin[]};
    Physical Surface("indenter_xmax") = {xmax[]};
    Physical Surface("indenter_ymin") = {ymin[]};
    Physical Surface("indenter_ymax") = {ymax[]};
  EndIf
Return

shape = 0;  direction = -1;  depth = H;  body = 0;  lift = 0;
Call Body;
If (indenter > 0)
  // The indenter is built lifted clear of the block, so that gmsh's automatic coherence (which
  // joins the patches of each body) cannot merge the point or line where the bodies touch, and is
  // then lowered onto the block with coherence switched off (with the centres of its arcs and
  // sphere, which are not part of its boundary).
  shape = indenter;  direction = 1;  depth = Hi;  body = 1;  lift = H;
  Call Body;
  Geometry.AutoCoherence = 0;
  Translate {0, 0, -lift} { Volume{volumes[]}; Point{centres[]}; }
EndIf
