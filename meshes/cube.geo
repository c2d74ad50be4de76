// Unit cube [0,1]^3 meshed with n x n x n transfinite hexahedra, optionally distorted, for
// element, patch and mesh tests. Groups: volume "cube"; faces xmin, xmax, ymin, ymax, zmin, zmax.
//
// The cube is built from 2 x 2 x 2 sub-blocks around one interior vertex so that moving that
// vertex (parameter distort) distorts every element while the outer faces stay planar: the
// total volume stays 1 and each face keeps area 1. With distort = 0 the mesh is uniform.

DefineConstant[
  n = {2, Min 2, Name "Parameters/n", Help "elements per edge (>= 2)"},
  distort = {0, Min 0, Max 0.99, Name "Parameters/distort",
             Help "moves the interior vertex by distort * centreShift; 0 = uniform mesh"}
];

If (n < 2)
  Error("cube.geo: n must be at least 2 (the cube is built from 2 x 2 x 2 sub-blocks)");
EndIf

// Direction and size of the interior vertex's shift at distort = 1. Each component is at most
// 0.2 of the unit edge, i.e. at most 40% of a sub-block, which keeps every element valid.
centreShift[] = {0.2, -0.15, 0.1};

nLow = Floor(n / 2);   // elements in the lower sub-block along each axis
nHigh = n - nLow;      // elements in the upper sub-block
split = nLow / n;      // lattice coordinate of the interior vertex before distortion

Geometry.AutoCoherence = 0;

// 3 x 3 x 3 lattice of points p(i,j,k) = 1 + i + 3j + 9k. Lattice index 1 is the split plane;
// a point follows the interior vertex's shift in exactly the directions where its index is 1,
// so face-centre points move within their face and edge midpoints along their edge.
For k In {0:2}
  For j In {0:2}
    For i In {0:2}
      index[] = {i, j, k};
      For d In {0:2}
        position[d] = (index[d] == 0) ? 0 : ((index[d] == 2) ? 1 : split);
        position[d] += (index[d] == 1) ? distort * centreShift[d] : 0;
      EndFor
      Point(1 + i + 3 * j + 9 * k) = {position[0], position[1], position[2]};
    EndFor
  EndFor
EndFor

// Lines along x (1..18), y (19..36), z (37..54); segment index 0 is the lower sub-block.
For k In {0:2}
  For j In {0:2}
    For i In {0:1}
      Line(1 + i + 2 * j + 6 * k) = {1 + i + 3 * j + 9 * k, 2 + i + 3 * j + 9 * k};
      Transfinite Curve{1 + i + 2 * j + 6 * k} = ((i == 0) ? nLow : nHigh) + 1;
    EndFor
  EndFor
EndFor
For k In {0:2}
  For j In {0:1}
    For i In {0:2}
      Line(19 + i + 3 * j + 6 * k) = {1 + i + 3 * j + 9 * k, 4 + i + 3 * j + 9 * k};
      Transfinite Curve{19 + i + 3 * j + 6 * k} = ((j == 0) ? nLow : nHigh) + 1;
    EndFor
  EndFor
EndFor
For k In {0:1}
  For j In {0:2}
    For i In {0:2}
      Line(37 + i + 3 * j + 9 * k) = {1 + i + 3 * j + 9 * k, 10 + i + 3 * j + 9 * k};
      Transfinite Curve{37 + i + 3 * j + 9 * k} = ((k == 0) ? nLow : nHigh) + 1;
    EndFor
  EndFor
EndFor

// Faces normal to z (1..12), x (13..24), y (25..36). Interior faces may be non-planar, hence
// "Surface" (transfinite interpolation of the four edges) instead of "Plane Surface".
For k In {0:2}
  For j In {0:1}
    For i In {0:1}
      Curve Loop(1 + i + 2 * j + 4 * k) = {1 + i + 2 * j + 6 * k, 20 + i + 3 * j + 6 * k,
                                           -(1 + i + 2 * (j + 1) + 6 * k), -(19 + i + 3 * j + 6 * k)};
      Surface(1 + i + 2 * j + 4 * k) = {1 + i + 2 * j + 4 * k};
    EndFor
  EndFor
EndFor
For i In {0:2}
  For k In {0:1}
    For j In {0:1}
      Curve Loop(13 + j + 2 * k + 4 * i) = {19 + i + 3 * j + 6 * k, 37 + i + 3 * (j + 1) + 9 * k,
                                            -(19 + i + 3 * j + 6 * (k + 1)), -(37 + i + 3 * j + 9 * k)};
      Surface(13 + j + 2 * k + 4 * i) = {13 + j + 2 * k + 4 * i};
    EndFor
  EndFor
EndFor
For j In {0:2}
  For k In {0:1}
    For i In {0:1}
      Curve Loop(25 + i + 2 * k + 4 * j) = {1 + i + 2 * j + 6 * k, 38 + i + 3 * j + 9 * k,
                                            -(1 + i + 2 * j + 6 * (k + 1)), -(37 + i + 3 * j + 9 * k)};
      Surface(25 + i + 2 * k + 4 * j) = {25 + i + 2 * k + 4 * j};
    EndFor
  EndFor
EndFor

For k In {0:1}
  For j In {0:1}
    For i In {0:1}
      Surface Loop(1 + i + 2 * j + 4 * k) = {
        1 + i + 2 * j + 4 * k, 1 + i + 2 * j + 4 * (k + 1),
        13 + j + 2 * k + 4 * i, 13 + j + 2 * k + 4 * (i + 1),
        25 + i + 2 * k + 4 * j, 25 + i + 2 * k + 4 * (j + 1)};
      Volume(1 + i + 2 * j + 4 * k) = {1 + i + 2 * j + 4 * k};
    EndFor
  EndFor
EndFor

Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};

Physical Volume("cube") = {1:8};
Physical Surface("zmin") = {1:4};
Physical Surface("zmax") = {9:12};
Physical Surface("xmin") = {13:16};
Physical Surface("xmax") = {21:24};
Physical Surface("ymin") = {25:28};
Physical Surface("ymax") = {33:36};
