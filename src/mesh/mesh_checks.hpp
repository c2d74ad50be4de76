// Checks and fix-ups of an imported mesh in its reference configuration: element validity
// (positive Jacobian) and outward orientation of boundary face sets. Called by loadMesh; public
// so that meshes built by other means (tests, generators) get the same treatment.
#pragma once

#include "common/source_location.hpp"
#include "mesh/mesh.hpp"

namespace cc {

// Throws InputError at `where` ("inverted element ...", naming the gmsh element tag, the group
// and the value) unless det J > 0 at every nodal point and the centre of every volume element
// (Hex8: 8 corners and centre; Hex27: its 27 nodes; Hex18: its 18 nodes and centre).
void checkElementJacobians(const Mesh& mesh, const SourceLocation& where);

// Matches every face of every face set to the volume element that owns it (by its corner
// nodes), fills ownerBlock/ownerElement and rewrites the face's nodes in the owner's outward
// order (mesh.hpp conventions), keeping the face's first corner first. Throws InputError at
// `where` naming the face set if a face is not a boundary face of exactly one Hex8/Hex27
// element of the mesh, or if its type does not match the owner's (Quad4 on Hex8, Quad9 on Hex27).
void orientFaceSets(Mesh& mesh, const SourceLocation& where);

}  // namespace cc
