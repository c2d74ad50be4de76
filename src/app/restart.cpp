// Restart of a run from a results file: reading the stored state into the model and the stepper.
#include "app/restart.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "common/errors.hpp"
#include "output/restart_io.hpp"

namespace cc::app {

StartState restartFrom(const std::string& file, int fromStep, Model& model) {
  RestartPoint point = readRestart(file, fromStep);
  try {
    model.restoreHistory(point.record);
  } catch (const std::invalid_argument& mismatch) {
    throw InputError(SourceLocation{file, 0, 0},
                     fmt::format("step {} does not fit the deck's model ({}); restart with the "
                                 "deck and mesh that wrote it",
                                 point.step, mismatch.what()));
  }
  StartState start;
  start.step = point.step;
  start.time = point.time;
  start.displacement = std::move(point.record.displacement);
  start.stepSize = {point.record.stepFraction, point.record.easySteps, point.record.stabilizing,
                    point.record.stabilizedEasySteps};
  start.lastIncrement = std::move(point.record.lastIncrement);
  start.lastDt = point.record.lastDt;
  start.viscousFactor = point.record.viscousFactor;
  start.viscousFactorFromStiffness = point.record.viscousFactorFromStiffness;
  model.startEnergyAccount(start.time, start.displacement, point.record.energy);
  return start;
}

RestartRecord restartRecordOf(const Model& model, const Eigen::VectorXd& displacement,
                              const StepSize& nextStepSize, const LoadStepper& stepper) {
  RestartRecord record = model.saveHistory();
  if (const Eigen::VectorXd* increment = stepper.lastIncrement()) {
    record.lastIncrement = *increment;
    record.lastDt = stepper.lastDt();
  }
  record.displacement = displacement;
  record.stepFraction = nextStepSize.fraction;
  record.easySteps = nextStepSize.easySteps;
  record.viscousFactor = stepper.chosenViscousFactor();
  record.viscousFactorFromStiffness = stepper.chosenFactorFromStiffness();
  record.stabilizing = nextStepSize.stabilizing;
  record.stabilizedEasySteps = nextStepSize.stabilizedEasySteps;
  record.energy = model.energyRestartData();
  return record;
}

}  // namespace cc::app
