// The unit cube of cube.geo (same parameters n, distort) with one more face set, "boundary":
// all six outer faces, so that one deck line can prescribe a field on every boundary node.
Include "cube.geo";

Physical Surface("boundary") = {1:4, 9:12, 13:16, 21:24, 25:28, 33:36};
