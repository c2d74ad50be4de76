// `covcontact run DECK --restart FILE.h5 [--from-step K]`: continuing a run from a converged
// step stored in a results file (displacement, element and contact history, step size), and the
// restart record every written step carries so that any run can be continued.
#pragma once

#include <Eigen/Core>
#include <string>

#include "model/model.hpp"
#include "records/result_records.hpp"
#include "solver/load_stepper.hpp"

namespace cc::app {

// Reads step `fromStep` of `file` (-1: the last step with restart data), restores the model's
// element and contact history from it and returns where the stepper starts. Throws OutputError
// if the file cannot be read or lacks the step, InputError (located at the results file) if the
// stored state does not fit the model built from the deck.
StartState restartFrom(const std::string& file, int fromStep, Model& model);

// The state a restart from the step that just converged needs.
RestartRecord restartRecordOf(const Model& model, const Eigen::VectorXd& displacement,
                              const StepSize& nextStepSize, const LoadStepper& stepper);

}  // namespace cc::app
