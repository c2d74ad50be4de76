// Named analytic references of a deck (`reference QUANTITY analytic NAME PARAM=VALUE ...`):
// hertz_sphere, hertz_cylinder, cattaneo_mindlin_sphere, cattaneo_mindlin_cylinder. Each turns
// the deck's parameters and the measured loads of a step into the analytic value of the quantity.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "spec/problem_spec.hpp"
#include "verification/quantity.hpp"

namespace cc::verification {

// How a step is compared: the measured value (for loads: the magnitude of the full contact's
// load, i.e. |F| / fraction) and the analytic value, or nullopt where the solution does not
// apply yet (no load).
struct AnalyticComparison {
  std::function<double(const StepRecord&)> measured;
  std::function<std::optional<double>(const StepRecord&)> reference;
};

// Throws InputError at the reference's line for an unknown solution, a quantity the solution
// does not give, or a missing, unknown or out-of-range parameter.
AnalyticComparison makeAnalyticComparison(const ReferenceSpec& spec, const Quantity& quantity,
                                          const Model& model);

// The solution names and the parameters each accepts (for messages and documentation).
std::vector<std::string> analyticSolutionNames();

}  // namespace cc::verification
