// Paper example 6.1's block and base (block_on_base.geo, same parameters) with one more surface
// group: block_corner, the block's bottom and right side together, a master surface with a
// sharp 90-degree edge (the smoothing's creases, docs/verification/smooth_master.md).
Include "block_on_base.geo";
Physical Surface("block_corner") = {blockBottom, blockRight};
