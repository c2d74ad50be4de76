// Test support: in-process deck runs with recorded results.
#include "deck_runner.hpp"

#include <stdexcept>

#include "deck/deck_parser.hpp"

namespace cc::test {

namespace {

class RecordingObserver : public StepObserver {
 public:
  RecordingObserver(DeckRun& run, bool withStress) : run_(run), withStress_(withStress) {}
  void iteration(const IterationRecord& record) override { run_.iterations.push_back(record); }
  void cutback(const CutbackRecord& record) override { run_.cutbacks.push_back(record); }
  void stepConverged(int step, double time, int iterations, int cutbacks,
                     const Eigen::VectorXd& displacement, const Eigen::VectorXd& internalForce,
                     bool) override {
    run_.model->accountEnergy(time, displacement, internalForce);
    const StepRecord record = run_.model->stepRecord(step, time, iterations, cutbacks, displacement,
                                                     internalForce, withStress_);
    RecordedStep copy;
    copy.step = step;
    copy.time = time;
    copy.iterations = iterations;
    copy.cutbacks = cutbacks;
    copy.displacement = *record.displacement;
    copy.reaction = *record.reaction;
    copy.setReactions = record.setReactions;
    if (record.stress) copy.stress = *record.stress;
    copy.contact = record.contact;
    copy.energy = record.energy;
    run_.steps.push_back(std::move(copy));
  }

 private:
  DeckRun& run_;
  bool withStress_;
};

DeckRun run(const ProblemSpec& spec, bool withStress) {
  DeckRun result;
  result.model = buildModel(spec);
  RecordingObserver observer(result, withStress);
  LoadStepper stepper(*result.model, observer, spec.phases, spec.linearSolver);
  result.summary = stepper.run();
  return result;
}

}  // namespace

Eigen::Vector3d RecordedStep::setReaction(const std::string& name) const {
  for (const auto& [set, force] : setReactions) {
    if (set == name) return force;
  }
  throw std::out_of_range("no reaction for set " + name);
}

StepRecord RecordedStep::record() const {
  StepRecord view;
  view.step = step;
  view.time = time;
  view.iterations = iterations;
  view.cutbacks = cutbacks;
  view.displacement = &displacement;
  view.reaction = &reaction;
  view.setReactions = setReactions;
  if (stress.size() > 0) view.stress = &stress;
  view.contact = contact;
  view.energy = energy;
  return view;
}

const ContactPairRecord& RecordedStep::pair(const std::string& name) const {
  for (const ContactPairRecord& record : contact) {
    if (record.name == name) return record;
  }
  throw std::out_of_range("no contact pair " + name);
}

std::vector<IterationRecord> DeckRun::iterationsOf(int step) const {
  std::vector<IterationRecord> rows;
  for (const IterationRecord& row : iterations) {
    if (row.step == step) rows.push_back(row);
  }
  return rows;
}

DeckRun runDeckFile(const std::string& path, bool withStress) {
  return run(parseDeck(path), withStress);
}

DeckRun runDeckText(const std::string& text, const std::string& virtualPath, bool withStress) {
  return run(parseDeckText(text, virtualPath), withStress);
}

}  // namespace cc::test
