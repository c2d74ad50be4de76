// Test fixture: the unit cube with a physical group name in Latin-1 (0xe9 for e-acute),
// which gmsh passes on as it is; the XDMF sidecar was then not well-formed XML.
Include "cube.geo";
Physical Surface("café") = {1};
