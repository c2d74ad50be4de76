// Test fixture: a .geo that ends with gmsh's Exit command (which calls exit(0) inside gmsh).
Include "cube.geo";
Exit;
