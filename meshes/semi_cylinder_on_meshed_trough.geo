// Paper example 6.3 with a *meshed* master (issue 16, part 2): the semi-cylinder of
// semi_cylinder.geo on a block whose top face is the parabolic cylinder z = c x^2 (axis y),
// meshed by nx flat-chord Quad4 segments along x (nodes exactly on the parabola) and ny along y,
// one hex8 layer of thickness tb below. Compared with the analytic (STAS) surface of
// input/paper/semi_cylinder_6_3_model.inc, faceted and smoothed (Nagata) master.
//
// Groups: those of semi_cylinder.geo, plus volume "trough", faces "trough_top" (the master,
// outward normal +z) and "trough_bottom", node set "trough_all" (every trough node, fixed).

Include "semi_cylinder.geo";

DefineConstant[
  c = {0.05, Name "Parameters/c", Help "parabola z = c x^2"},
  x0 = {-1, Name "Parameters/x0", Help "trough start in x"},
  x1 = {3, Name "Parameters/x1", Help "trough end in x"},
  y0 = {-0.5, Name "Parameters/y0", Help "trough start in y"},
  y1 = {4.5, Name "Parameters/y1", Help "trough end in y"},
  nx = {16, Min 1, Name "Parameters/nx", Help "segments along x"},
  nyt = {5, Min 1, Name "Parameters/nyt", Help "segments along y"},
  tb = {0.5, Name "Parameters/tb", Help "block thickness"}
];

For i In {0 : nx}
  xi = x0 + i * (x1 - x0) / nx;
  Point(2000 + i) = {xi, y0, c * xi * xi};
EndFor
For i In {0 : nx - 1}
  Line(2000 + i) = {2000 + i, 2001 + i};
  Transfinite Curve{2000 + i} = 2;
EndFor
top[] = {};
For i In {0 : nx - 1}
  strip[] = Extrude {0, y1 - y0, 0} { Curve{2000 + i}; Layers{nyt}; Recombine; };
  top[] += strip[1];
EndFor
volumes[] = {};
bottom[] = {};
For i In {0 : nx - 1}
  block[] = Extrude {0, 0, -tb} { Surface{top[i]}; Layers{1}; Recombine; };
  bottom[] += block[0];
  volumes[] += block[1];
EndFor

Physical Volume("trough") = {volumes[]};
Physical Surface("trough_top") = {top[]};
Physical Surface("trough_bottom") = {bottom[]};
