// A small synthetic run for the output tests: a mesh with Hex8, Hex27 and Hex18 blocks, named node
// and face sets, and step records whose every value is a known function of (step, index).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"
#include "output/results_writer.hpp"
#include "records/result_records.hpp"

namespace cc::test {

// A block placed as the parallelepiped origin + u*edges.col(0) + v*edges.col(1) + w*edges.col(2)
// over (u, v, w) in [0, 1]^3, so a viewer's node positions can be checked against it.
struct BlockPlacement {
  std::string block;
  Eigen::Vector3d origin;
  Eigen::Matrix3d edges;
};

struct SyntheticMesh {
  Mesh mesh;
  std::vector<BlockPlacement> placements;  // of the Hex27 and Hex18 blocks
};

// "base": 2 x 2 x 1 unit Hex8 cubes; "cap27": one sheared Hex27; "shell18": one sheared Hex18.
SyntheticMesh makeSyntheticMesh();

// Owns the fields a StepRecord points to.
struct SyntheticStep {
  Eigen::Matrix3Xd displacement;
  Eigen::Matrix3Xd reaction;
  Eigen::Matrix<double, 6, Eigen::Dynamic> stress;
  StepRecord record;  // points into the members above: do not copy a SyntheticStep
  SyntheticStep() = default;
  SyntheticStep(const SyntheticStep&) = delete;
  SyntheticStep& operator=(const SyntheticStep&) = delete;
};

// Values are smooth non-integer functions of (step, node/point, component), so that any mix-up
// of rows, columns, steps or pairs changes them.
void fillSyntheticStep(const Mesh& mesh, int step, SyntheticStep& out);

// Exactly representable values for the kill test, reproduced by check_kill.py:
// displacement(node, c) = 1000 * step + 3 * node + c; the set reaction of "top" = (step, -step,
// 0.5).
void fillIntegerStep(const Mesh& mesh, int step, SyntheticStep& out);

IterationRecord syntheticIteration(int step, int attempt, int iteration);

RunInfo syntheticRunInfo();

}  // namespace cc::test
