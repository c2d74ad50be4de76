// Test fixture for the deck tests: a .geo file gmsh cannot read (syntax error on line 5), so
// meshing it at run time must fail with a located error rather than a crash.
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Line(1) = {1, 2;
