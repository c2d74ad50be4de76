// Mesh import through the gmsh C++ API: opens a .msh file or meshes a .geo file at run time
// (3D, with the element order the .geo requests) and converts its physical groups to a Mesh.
#pragma once

#include "mesh/mesh.hpp"
#include "spec/problem_spec.hpp"

namespace cc {

// Loads spec.path (.msh opened as is; .geo meshed in 3D). For a .geo, each of spec.parameters
// overrides the DefineConstant of that name (like gmsh's `-setnumber NAME VALUE`, which is not
// used because gmsh 4.8 keeps its values for the rest of the process); a parameter the .geo
// (or a file it Includes) does not declare with DefineConstant is an error, and a .msh takes
// no parameters.
//
// Physical groups become (all group names must be non-empty and unique across dimensions;
// an unnamed group is an error because the deck refers to groups by name):
//   3D -> ElementBlock (gmsh type 5 -> Hex8, 12 -> Hex27; any other volume type is an error),
//         blocks in increasing physical tag order;
//   2D -> FaceSet (type 3 -> Quad4, 10 -> Quad9), each face oriented outward of its owning
//         volume element (see orientFaceSets); a face that is not a boundary face of exactly
//         one volume element of a physical volume is an error;
//   every group (0D..3D) -> NodeSet of the same name with all nodes of its elements.
// Nodes are numbered 0..N-1 in increasing gmsh tag order; only nodes used by elements of
// physical groups are kept (others are dropped). Mesh::gmshNodeTags and the gmshElementTags of
// blocks and face sets map back to gmsh tags for messages.
// Every volume element must have det J > 0 at its nodes and centre (checkElementJacobians).
//
// Errors (missing file, gmsh parse or meshing errors, unsupported elements, inverted elements)
// are InputErrors at spec.where carrying gmsh's own message. gmsh's terminal output is
// silenced. Each call initializes and finalizes gmsh, so loadMesh may be called any number of
// times; calls are serialized (gmsh has global state) and must not overlap other gmsh use.
Mesh loadMesh(const MeshSpec& spec);

}  // namespace cc
