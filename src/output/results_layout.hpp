// Names and row types of the results file layout (docs/output-format.md), shared by the writer,
// the XDMF sidecar, the reader and the run comparison so that every path is spelled once.
#pragma once

#include <cstddef>
#include <string>

#include "output/hdf5_io.hpp"

namespace cc::layout {

inline constexpr const char* kFormatName = "CovContact results";
// 2: /cutbacks stores the reason as a fixed-length string (parallel HDF5 cannot write
// variable-length data); version 1 files (variable-length reason) are still read.
inline constexpr int kFormatVersion = 2;

inline constexpr const char* kMeshGroup = "/mesh";
inline constexpr const char* kCoordinates = "/mesh/coordinates";
inline constexpr const char* kBlocksGroup = "/mesh/blocks";
inline constexpr const char* kNodeSetsGroup = "/mesh/node_sets";
inline constexpr const char* kFaceSetsGroup = "/mesh/face_sets";
inline constexpr const char* kStepsGroup = "/steps";
inline constexpr const char* kConvergence = "/convergence";
inline constexpr const char* kCutbacks = "/cutbacks";
inline constexpr const char* kSummaryGroup = "/summary";

// Dataset names inside a step group /steps/<6-digit step>.
inline constexpr const char* kDisplacement = "displacement";
inline constexpr const char* kReaction = "reaction";
inline constexpr const char* kStress = "stress";
inline constexpr int kStressComponents = 6;  // Voigt order xx yy zz xy yz xz
inline constexpr const char* kSetReactions = "set_reactions";
inline constexpr const char* kContactGroup = "contact";
inline constexpr const char* kEnergyGroup = "energy";
inline constexpr const char* kTotalForce = "total_force";
// 0..M-1 per contact pair: the vertex cells of its point cloud in the XDMF sidecar.
inline constexpr const char* kVertexIds = "vertex_ids";

// "000042": zero-padded so that the steps sort in order in any HDF5 viewer.
std::string stepGroupName(int step);
// Full path of a step group, "/steps/000042".
std::string stepGroupPath(int step);
// A user name (block, set, pair) as an HDF5 link name: '/' would open a sub-group, so it becomes
// '_'; "." (the group itself) becomes "_". The original name is kept in the "name" attribute.
std::string linkName(const std::string& name);

// One row of /convergence (memory layout of the compound type).
struct ConvergenceRow {
  int step;
  int attempt;
  int iteration;
  double time;
  double residual;
  double relativeResidual;
  double energy;
  double relativeEnergy;
  double wallSeconds;
};

// One row of /cutbacks; the reason is a UTF-8 string of at most kReasonBytes - 1 bytes, null
// terminated (cutbackRow shortens a longer one at a character boundary, ending it with "...").
inline constexpr std::size_t kReasonBytes = 1024;
struct CutbackRow {
  int step;
  double time;
  double newDt;
  char reason[kReasonBytes];
};
CutbackRow cutbackRow(int step, double time, double newDt, const std::string& reason);
// The row as format version 1 stored it (variable-length reason), for reading older files.
struct CutbackRowV1 {
  int step;
  double time;
  double newDt;
  const char* reason;
};

// File compound types of the two tables (also the memory types: fields are named and offset).
h5::Type convergenceRowType();
h5::Type cutbackRowType();
h5::Type cutbackRowTypeV1();

}  // namespace cc::layout
