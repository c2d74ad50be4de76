// Test support: run a deck in-process (parse, build the model, load-step it) and keep what the
// solver reported: per-step records (with copies of the fields), per-iteration convergence
// rows, cut-backs and the run summary. For tests that assert numbers of whole runs.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "records/result_records.hpp"
#include "solver/load_stepper.hpp"

namespace cc::test {

struct RecordedStep {
  int step = 0;
  double time = 0;
  int iterations = 0;
  int cutbacks = 0;
  Eigen::Matrix3Xd displacement;
  Eigen::Matrix3Xd reaction;
  std::vector<std::pair<std::string, Eigen::Vector3d>> setReactions;
  Eigen::Matrix<double, 6, Eigen::Dynamic> stress;  // empty unless asked for
  std::vector<ContactPairRecord> contact;
  EnergyRecord energy;

  Eigen::Vector3d setReaction(const std::string& name) const;
  const ContactPairRecord& pair(const std::string& name) const;
  // The step as a StepRecord (without restart data), e.g. to feed a ReferenceTracker as the run
  // command does; its fields point to this step's copies, so it is valid while this step lives.
  StepRecord record() const;
};

struct DeckRun {
  std::unique_ptr<Model> model;
  RunSummary summary;
  std::vector<RecordedStep> steps;
  std::vector<IterationRecord> iterations;
  std::vector<CutbackRecord> cutbacks;

  // Convergence rows of one step (all attempts), in order.
  std::vector<IterationRecord> iterationsOf(int step) const;
};

// Runs the deck file at `path` (relative paths in it resolve against its directory).
DeckRun runDeckFile(const std::string& path, bool withStress = false);
// Runs deck text; `virtualPath` names it and anchors its relative paths (e.g. a path inside the
// source tree, so that "../../meshes/x.geo" resolves).
DeckRun runDeckText(const std::string& text, const std::string& virtualPath,
                    bool withStress = false);

}  // namespace cc::test
