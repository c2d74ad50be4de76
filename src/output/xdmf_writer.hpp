// XDMF 3 sidecar for ParaView: a temporal collection with, per written step, a spatial collection
// of one grid per element block plus one Polyvertex point cloud per contact pair, all referencing
// datasets of the HDF5 results file. The file is complete after every step: it is replaced
// atomically (temporary + rename) while small, and appended in place once rewriting would cost
// more than the step (see kDefaultAtomicRewriteLimit).
#pragma once

#include <cstddef>
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

// Rewriting the whole file per step costs O(file size), O(steps^2) over a run: measured about
// 16 s for 1000 steps of 4.6 KiB on a loaded machine. Up to this size (some 500 steps of a
// two-block model with contact) a SIGKILL can never leave a broken XDMF file; beyond it each step
// is one in-place write of a few KiB, which a SIGKILL can cut (the HDF5 file is not affected).
inline constexpr size_t kDefaultAtomicRewriteLimit = 2 << 20;  // bytes

class XdmfWriter {
 public:
  // Creates (truncates) xdmfPath; h5FileName is written as a path relative to the XDMF file.
  XdmfWriter(std::string xdmfPath, std::string h5FileName, long numNodes, long numElements,
             std::vector<XdmfBlock> blocks, size_t atomicRewriteLimit = kDefaultAtomicRewriteLimit);

  void appendStep(const XdmfStep& step);

 private:
  std::string blockGrid(const XdmfBlock& block, const XdmfStep& step) const;
  std::string contactGrid(const std::string& pair, long points, const XdmfStep& step) const;
  std::string dataItem(const std::string& dims, const char* numberType, int precision,
                       const std::string& h5Path) const;
  // Writes <path>.tmp and renames it over <path>: rename is atomic, an in-place append is not
  // (a SIGKILL can cut a write() at a page boundary; seen with check_kill.py --measure).
  void replaceFile() const;
  // Writes grid + closing tags over the old closing tags.
  void appendInPlace(const std::string& grid);

  std::string path_;
  std::string h5FileName_;
  long numNodes_ = 0;
  long numElements_ = 0;
  std::vector<XdmfBlock> blocks_;
  size_t atomicRewriteLimit_ = kDefaultAtomicRewriteLimit;
  std::string steps_;        // the step grids, while the file is replaced atomically
  size_t footerOffset_ = 0;  // where the closing tags start
};

}  // namespace cc
