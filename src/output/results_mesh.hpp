// Writes the mesh group of a results file once (coordinates, blocks, node and face sets) and says
// how ParaView should draw each block (the XDMF topology and the connectivity in VTK order).
#pragma once

#include <vector>

#include "mesh/mesh.hpp"
#include "output/hdf5_io.hpp"
#include "output/xdmf_writer.hpp"

namespace cc {

std::vector<XdmfBlock> writeMesh(h5::FileRef file, const Mesh& mesh);

// Node order ParaView (VTK) uses for a cell type, as indices into our connectivity row:
// Hex27 is reordered from gmsh to VTK_TRIQUADRATIC_HEXAHEDRON; Hex18 keeps only its 8 corners.
// Empty for types drawn in their stored order.
std::vector<int> visualNodeOrder(CellType type);

}  // namespace cc
