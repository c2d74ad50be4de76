// Paper example 6.3 (Konyukhov & Schweizerhof 2005, Fig. 14): a short semi-circular cylindrical
// shell that slides on a rigid parabolic cylinder. Axis along y through (0, *, R); the half ring
// hangs below it, so the outer surface touches the plane z = 0 along the line x = 0 at the start.
//
// A point at angle theta (from -z towards +x, theta in [-90, 90] degrees) and radius r is
// (r sin(theta), y, R - r cos(theta)), y in [-l/2, l/2]. One element layer between the inner
// radius R - t and the outer (contact) radius R; nt elements around the half circumference
// ("16" of the paper's 16 x 3) and ny along the length l ("3"). Two transfinite quarter volumes
// (a single gmsh arc must span less than 180 degrees); the corners are listed inner face first,
// so each element's local zeta axis points radially outwards (thickness=auto for solid-shells).
//
// Groups: volume "semi_cylinder"; faces "outer" (contact master), "inner", "end_front"
// (y = -l/2), "end_back" (y = l/2), "edge_left" (theta = -90), "edge_right" (theta = 90) and
// "top_edges" (both straight edges, at the height of the axis: the loaded faces).

DefineConstant[
  R = {1, Name "Parameters/R", Help "outer (contact) radius"},
  l = {0.4, Name "Parameters/l", Help "length along the axis y"},
  t = {0.1, Name "Parameters/t", Help "shell thickness (inwards from R)"},
  nt = {16, Min 2, Step 2, Name "Parameters/nt", Help "elements around the half circumference (even)"},
  ny = {3, Min 1, Name "Parameters/ny", Help "elements along the axis"}
];

radii[] = {R - t, R};
// Centre points of the arcs at the two ends: C(end) = 90 + end.
For end In {0 : 1}
  Point(90 + end) = {0, -l / 2 + end * l, R};
EndFor
// Corner points P(k, end, face) = 100 + k + 3 end + 6 face at theta_k = (k - 1) 90 degrees.
For face In {0 : 1}
  For end In {0 : 1}
    For k In {0 : 2}
      theta = (k - 1) * Pi / 2;
      Point(100 + k + 3 * end + 6 * face) =
          {radii[face] * Sin(theta), -l / 2 + end * l, R - radii[face] * Cos(theta)};
    EndFor
  EndFor
EndFor
// Arcs A(q, end, face) = 200 + q + 2 end + 4 face (quarter q from theta_q to theta_q+1),
// axial lines L(k, face) = 300 + k + 3 face, thickness lines T(k, end) = 400 + k + 3 end.
For face In {0 : 1}
  For end In {0 : 1}
    For q In {0 : 1}
      Circle(200 + q + 2 * end + 4 * face) =
          {100 + q + 3 * end + 6 * face, 90 + end, 101 + q + 3 * end + 6 * face};
    EndFor
  EndFor
  For k In {0 : 2}
    Line(300 + k + 3 * face) = {100 + k + 6 * face, 103 + k + 6 * face};
  EndFor
EndFor
For end In {0 : 1}
  For k In {0 : 2}
    Line(400 + k + 3 * end) = {100 + k + 3 * end, 106 + k + 3 * end};
  EndFor
EndFor
Transfinite Curve{200 : 207} = nt / 2 + 1;
Transfinite Curve{300 : 305} = ny + 1;
Transfinite Curve{400 : 405} = 2;

// Cylinder faces S(q, face) = 500 + q + 2 face, end faces E(q, end) = 600 + q + 2 end,
// radial faces D(k) = 700 + k (D(1) is shared by the two quarters).
For face In {0 : 1}
  For q In {0 : 1}
    Curve Loop(500 + q + 2 * face) = {300 + q + 3 * face, 200 + q + 2 + 4 * face,
                                      -(301 + q + 3 * face), -(200 + q + 4 * face)};
    Surface(500 + q + 2 * face) = {500 + q + 2 * face};
  EndFor
EndFor
For end In {0 : 1}
  For q In {0 : 1}
    Curve Loop(600 + q + 2 * end) = {200 + q + 2 * end, 401 + q + 3 * end,
                                      -(204 + q + 2 * end), -(400 + q + 3 * end)};
    Plane Surface(600 + q + 2 * end) = {600 + q + 2 * end};
  EndFor
EndFor
For k In {0 : 2}
  Curve Loop(700 + k) = {300 + k, 403 + k, -(303 + k), -(400 + k)};
  Plane Surface(700 + k) = {700 + k};
EndFor
Transfinite Surface{500 : 503, 600 : 603, 700 : 702};
Recombine Surface{500 : 503, 600 : 603, 700 : 702};
For q In {0 : 1}
  Surface Loop(800 + q) = {500 + q, 502 + q, 600 + q, 602 + q, 700 + q, 701 + q};
  Volume(800 + q) = {800 + q};
  Transfinite Volume{800 + q} = {100 + q, 103 + q, 104 + q, 101 + q,
                                 106 + q, 109 + q, 110 + q, 107 + q};
EndFor
Recombine Volume{800 : 801};

Physical Volume("semi_cylinder") = {800, 801};
Physical Surface("outer") = {502, 503};
Physical Surface("inner") = {500, 501};
Physical Surface("end_front") = {600, 601};
Physical Surface("end_back") = {602, 603};
Physical Surface("edge_left") = {700};
Physical Surface("edge_right") = {702};
Physical Surface("top_edges") = {700, 702};
