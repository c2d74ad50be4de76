// XDMF 3 sidecar for ParaView: a temporal collection with, per written step, a spatial collection
// of one grid per element block plus one Polyvertex point cloud per contact pair, all referencing
// datasets of the HDF5 results file. The file is replaced (write a temporary, rename) after each
// step, so a reader or a kill only ever sees a complete document.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace cc {

// How one element block is shown: XDMF topology name and the dataset holding its connectivity in
// the order ParaView expects (see writeMesh in results_mesh.hpp).
struct XdmfBlock {
  std::string name;
  std::string topology;  // "Hexahedron", "Hexahedron_27"
  long numElements = 0;
  int nodesPerCell = 0;
  std::string connectivityPath;  // HDF5 path
  long firstElement = 0;         // row of the block's first element in the step's stress dataset
};

// What one step group of the HDF5 file contains.
struct XdmfStep {
  int step = 0;
  double time = 0;
  bool displacement = false;
  bool reaction = false;
  bool stress = false;
  std::vector<std::pair<std::string, long>> contactPairs;  // pair name, number of points
};

class XdmfWriter {
 public:
  // Creates (truncates) xdmfPath; h5FileName is written as a path relative to the XDMF file.
  XdmfWriter(std::string xdmfPath, std::string h5FileName, long numNodes, long numElements,
             std::vector<XdmfBlock> blocks);

  void appendStep(const XdmfStep& step);

 private:
  std::string blockGrid(const XdmfBlock& block, const XdmfStep& step) const;
  std::string contactGrid(const std::string& pair, long points, const XdmfStep& step) const;
  std::string dataItem(const std::string& dims, const char* numberType, int precision,
                       const std::string& h5Path) const;
  // Writes <path>.tmp and renames it over <path>: rename is atomic, an in-place append is not
  // (a SIGKILL can cut a write() at a page boundary; measured with check_kill.py --measure).
  void replaceFile() const;

  std::string path_;
  std::string h5FileName_;
  long numNodes_ = 0;
  long numElements_ = 0;
  std::vector<XdmfBlock> blocks_;
  std::string steps_;  // the step grids written so far
};

}  // namespace cc
