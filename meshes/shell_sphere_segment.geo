// Spherical shell segment for solid-shell verification (pinched hemisphere): centre at the
// origin, mid-surface radius R, polar angle psi (from +z) in [polar0, polar1], azimuth phi (from
// +x towards +y) in [0, azimuth], so a point is r (sin psi cos phi, sin psi sin phi, cos psi).
// One element layer of thickness t between r = R - t/2 and R + t/2, na x np transfinite
// hexahedra, trilinear (order = 1, Hex8) or triquadratic (order = 2, Hex27 for solid_shell18).
// The transfinite corners are listed inner face first, so each element's local zeta axis
// points radially outwards (thickness=auto).
// Groups: volume "shell"; faces "azimuth0" (phi = 0), "azimuth1" (phi = azimuth), "hole"
// (psi = polar0), "rim" (psi = polar1), "inner", "outer"; thickness lines "rim_azimuth0",
// "rim_azimuth1", "hole_azimuth0", "hole_azimuth1" (the two face nodes there); the single inner
// node "rim_azimuth0_inner" (to remove a rigid translation without constraining a rotation).

DefineConstant[
  R = {10, Name "Parameters/R", Help "mid-surface radius"},
  t = {0.04, Name "Parameters/t", Help "thickness"},
  polar0 = {18, Name "Parameters/polar0", Help "polar angle of the hole edge, degrees"},
  polar1 = {90, Name "Parameters/polar1", Help "polar angle of the rim, degrees"},
  azimuth = {90, Name "Parameters/azimuth", Help "azimuthal extent, degrees"},
  na = {16, Min 1, Name "Parameters/na", Help "elements along the azimuth"},
  np = {16, Min 1, Name "Parameters/np", Help "elements along the meridian"},
  order = {1, Choices {1, 2}, Name "Parameters/order", Help "1: Hex8, 2: Hex27"}
];

Mesh.ElementOrder = order;
Mesh.SecondOrderIncomplete = 0;  // Hex27, not the 20-node serendipity hexahedron

polars[] = {polar0 * Pi / 180, polar1 * Pi / 180};
azimuths[] = {0, azimuth * Pi / 180};
radii[] = {R - t / 2, R + t / 2};

Point(1) = {0, 0, 0};
// Centres of the parallels: c(face, pole side) = 2 + pole + 2 face.
For face In {0 : 1}
  For pole In {0 : 1}
    Point(2 + pole + 2 * face) = {0, 0, radii[face] * Cos(polars[pole])};
  EndFor
EndFor
// Corner points p(azimuth side, pole side, face) = 10 + side + 2 pole + 4 face.
For face In {0 : 1}
  For pole In {0 : 1}
    For side In {0 : 1}
      Point(10 + side + 2 * pole + 4 * face) =
          {radii[face] * Sin(polars[pole]) * Cos(azimuths[side]),
           radii[face] * Sin(polars[pole]) * Sin(azimuths[side]), radii[face] * Cos(polars[pole])};
    EndFor
  EndFor
EndFor
// Parallels q(pole, face) = 20 + pole + 2 face; meridians m(side, face) = 30 + side + 2 face;
// thickness lines h(side, pole) = 40 + side + 2 pole.
For face In {0 : 1}
  For pole In {0 : 1}
    Circle(20 + pole + 2 * face) = {10 + 2 * pole + 4 * face, 2 + pole + 2 * face,
                                    11 + 2 * pole + 4 * face};
  EndFor
  For side In {0 : 1}
    Circle(30 + side + 2 * face) = {10 + side + 4 * face, 1, 12 + side + 4 * face};
  EndFor
EndFor
For pole In {0 : 1}
  For side In {0 : 1}
    Line(40 + side + 2 * pole) = {10 + side + 2 * pole, 14 + side + 2 * pole};
  EndFor
EndFor
Transfinite Curve{20 : 23} = na + 1;
Transfinite Curve{30 : 33} = np + 1;
Transfinite Curve{40 : 43} = 2;

For face In {0 : 1}
  Curve Loop(50 + face) = {20 + 2 * face, 31 + 2 * face, -(21 + 2 * face), -(30 + 2 * face)};
  Surface(50 + face) = {50 + face} In Sphere {1};
EndFor
For pole In {0 : 1}
  Curve Loop(52 + pole) = {20 + pole, 41 + 2 * pole, -(22 + pole), -(40 + 2 * pole)};
  Surface(52 + pole) = {52 + pole};
EndFor
For side In {0 : 1}
  Curve Loop(54 + side) = {30 + side, 42 + side, -(32 + side), -(40 + side)};
  Surface(54 + side) = {54 + side};
EndFor
Transfinite Surface{50 : 55};
Recombine Surface{50 : 55};
Surface Loop(60) = {50 : 55};
Volume(60) = {60};
Transfinite Volume{60} = {12, 13, 11, 10, 16, 17, 15, 14};
Recombine Volume{60};

Physical Volume("shell") = {60};
Physical Surface("inner") = {50};
Physical Surface("outer") = {51};
Physical Surface("hole") = {52};
Physical Surface("rim") = {53};
Physical Surface("azimuth0") = {54};
Physical Surface("azimuth1") = {55};
Physical Curve("hole_azimuth0") = {40};
Physical Curve("hole_azimuth1") = {41};
Physical Curve("rim_azimuth0") = {42};
Physical Curve("rim_azimuth1") = {43};
Physical Point("rim_azimuth0_inner") = {12};
