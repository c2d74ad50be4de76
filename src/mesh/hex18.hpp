// Solid-shell preparation of element blocks: Hex27 -> Hex18 (drop the mid-thickness layer) and
// reordering of hexahedra so that their local zeta axis is a chosen thickness direction.
#pragma once

#include "mesh/mesh.hpp"

namespace cc {

// Turns Hex27 block `blockIndex` into Hex18 (biquadratic in the shell plane, linear in
// thickness) by dropping each element's 9 nodes at zeta = 0; the thickness direction is the
// element's local zeta axis (the extrusion direction of a .geo that extrudes a surface with
// Layers{1} and Recombine; see orientThickness to choose it). Output ordering per mesh.hpp:
// nodes 0-8 the zeta = -1 Quad9, 9-17 the zeta = +1 Quad9.
// The dropped nodes become orphans (no element uses them; the DofMap leaves them inactive) and
// are removed from every node set unless another block still uses them. Quad9 face sets on the
// elements' top/bottom faces stay valid unchanged (same nodes, same owner). Face sets on
// lateral faces keep their mid-thickness nodes, which no longer belong to any element: they
// must not be used as contact surfaces (the model builder rejects that).
// Throws std::invalid_argument if the block is not Hex27 (callers report the deck error).
void convertToSolidShell18(Mesh& mesh, int blockIndex);

// Renumbers the nodes of every element of Hex8 or Hex27 block `blockIndex` (a rotation of the
// reference cell, so det J stays positive) so that the local zeta axis is the local axis most
// nearly parallel to global axis `globalAxis` (0 = x, 1 = y, 2 = z) and points the same way.
// Face sets keep their nodes and owners. Throws std::invalid_argument for other block types
// or axes.
void orientThickness(Mesh& mesh, int blockIndex, int globalAxis);

}  // namespace cc
