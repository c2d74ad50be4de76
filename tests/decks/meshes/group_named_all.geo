// Test fixture: the unit cube of cube.geo with one more physical surface named "all", the name
// of the deck's built-in set of every node (refused).
Include "cube.geo";

Physical Surface("all") = {top[0]};
