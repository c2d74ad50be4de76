// Test fixture for the deck tests: a block [0.25,0.75]^2 x [0,0.5] resting on a base
// [0,1]^2 x [-0.5,0]; separate volumes (no shared nodes). Groups: volumes block, base;
// surfaces block_bottom, block_top, base_top, base_bottom.
DefineConstant[ n = {2, Min 1, Name "Parameters/n"} ];

Macro ExtrudedBox  // the box [x0,x0+l] x [y0,y0+l] x [z0,z0+h]; sets boxBottom, boxTop, boxVolume
  p = newp;
  Point(p) = {x0, y0, z0};
  Point(p + 1) = {x0 + l, y0, z0};
  Point(p + 2) = {x0 + l, y0 + l, z0};
  Point(p + 3) = {x0, y0 + l, z0};
  c = newl;
  For side In {0:3}
    Line(c + side) = {p + side, p + (side + 1) % 4};
  EndFor
  Transfinite Curve{c:c + 3} = n + 1;
  loop = newcl;
  Curve Loop(loop) = {c:c + 3};
  boxBottom = news;
  Plane Surface(boxBottom) = {loop};
  Transfinite Surface{boxBottom};
  Recombine Surface{boxBottom};
  extruded[] = Extrude {0, 0, h} { Surface{boxBottom}; Layers{n}; Recombine; };
  boxTop = extruded[0];
  boxVolume = extruded[1];
Return

x0 = 0; y0 = 0; z0 = -0.5; l = 1; h = 0.5;
Call ExtrudedBox;
Physical Volume("base") = {boxVolume};
Physical Surface("base_bottom") = {boxBottom};
Physical Surface("base_top") = {boxTop};

x0 = 0.25; y0 = 0.25; z0 = 0; l = 0.5; h = 0.5;
Call ExtrudedBox;
Physical Volume("block") = {boxVolume};
Physical Surface("block_bottom") = {boxBottom};
Physical Surface("block_top") = {boxTop};
