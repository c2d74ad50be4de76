// The solve block: `solve` ... `end`, sticky `newton`/`cutback` settings and `steps` phases.
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "deck/deck_state.hpp"
#include "deck/solve_parameters.hpp"
#include "deck/spec_choices.hpp"

namespace cc::deck {

namespace {
// Steps are numbered with an int (results file, restart, records); the sum over all phases is
// bounded well below its overflow, leaving room for the cut-back attempts counted beside it.
constexpr long long kMaxTotalSteps = 1'000'000'000;
}  // namespace

namespace {

// Spelling of a cut-back parameter on a `steps` line, where a bare max= or factor= would not
// say what it limits.
std::string phaseSpelling(const std::string& cutbackName) {
  return cutbackName == "max" || cutbackName == "factor" ? "cutback_" + cutbackName : cutbackName;
}

// The deck spelling of a default taken from the spec structs, where every default is written once:
// shortest form, exponent without '+' or leading zeros (1e6, 1e-10, 0.5).
std::string defaultText(double value) {
  std::string text = fmt::format("{:g}", value);
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  const bool negative = exponent.front() == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return text.substr(0, e) + "e" + (negative ? "-" : "") + (exponent.empty() ? "0" : exponent);
}
std::string defaultText(int value) {
  return std::to_string(value);
}
std::string defaultText(bool value) {
  return value ? "yes" : "no";
}

std::string criterionName(NewtonSpec::Criterion criterion) {
  for (const auto& [name, value] : convergenceCriteria()) {
    if (value == criterion) return name;
  }
  throw std::logic_error("deck: undeclared convergence criterion");
}

std::string predictorName(NewtonSpec::Predictor predictor) {
  for (const auto& [name, value] : newtonPredictors()) {
    if (value == predictor) return name;
  }
  throw std::logic_error("deck: undeclared Newton predictor");
}

}  // namespace

std::vector<ValueDecl> newtonParameters() {
  const NewtonSpec defaults;
  return {integerValue("maxit", "Newton iterations per step before the step counts as failed")
              .withRange(Range::atLeast(1))
              .withDefault(defaultText(defaults.maxIterations)),
          numberValue("residual", "tolerance on the relative residual norm |R_k| / |R_0|")
              .withRange(Range::greaterThan(0))
              .withDefault(defaultText(defaults.residualTolerance)),
          numberValue("energy", "tolerance on the relative energy norm |du_k . R_k| / |du_0 . R_0|")
              .withRange(Range::greaterThan(0))
              .withDefault(defaultText(defaults.energyTolerance)),
          enumValue("converge", choiceNames(convergenceCriteria()),
                    "which tolerance decides convergence: energy, residual, both, or either")
              .withDefault(criterionName(defaults.criterion)),
          numberValue("diverge", "the step fails when |R_k| exceeds this multiple of |R_0|")
              .withRange(Range::greaterThan(1))
              .withDefault(defaultText(defaults.divergenceFactor)),
          boolValue("line_search",
                    "backtracking line search along the Newton direction from the first "
                    "iteration; when not given: yes in a deck with an enforcement=augmented "
                    "contact pair, otherwise no. Without it the line search still takes a failed "
                    "attempt's retry and the rest of an attempt whose residual stops improving "
                    "or whose contact active set cycles near convergence"),
          enumValue("predictor", choiceNames(newtonPredictors()),
                    "first iterate of a step: the converged state with the prescribed increment "
                    "(prescribed), or plus the last step's increment scaled to dt (extrapolate; "
                    "not at a step where a rigid surface's motion turns)")
              .withDefault(predictorName(defaults.predictor)),
          boolValue("penalty_continuation",
                    "a step that fails with and without line search at a contact penalty more "
                    "than 100 times its automatic value is retried by solves at penalties growing "
                    "10-fold from the automatic one")
              .withDefault(defaultText(defaults.penaltyContinuation)),
          numberValue("aug_inner",
                      "augmented-Lagrangian contact: a re-solve after a multiplier update stops "
                      "once its residual has fallen to this fraction of its first, so that the "
                      "updates interleave with Newton iterations; the step is solved to the full "
                      "criterion once the update rule is met. 0: every re-solve converges fully "
                      "(Uzawa per converged step)")
              .withRange(Range::between(0, true, 1, false))
              .withDefault(defaultText(defaults.augmentedInnerTolerance)),
          numberValue("stabilize",
                      "viscous stabilisation: every solid node carries the force C m (x - x_n) / "
                      "dt, m its share of the elements' volumes, x_n its place at the last "
                      "converged step; passes an instability or a body held by contact alone, "
                      "and the energy balance reports its dissipation. 0: off")
              .withRange(Range::atLeast(0))
              .withDefault(defaultText(defaults.stabilization)),
          numberValue("stabilize_share",
                      "viscous stabilisation whose factor the run chooses: the phase's first step "
                      "is solved without it, then C is set so that a step like that one would "
                      "dissipate this fraction of its external work (of the loads, supports and "
                      "moving rigid surfaces: the share each step's line reports); replaces "
                      "stabilize=. 0: off")
              .withRange(Range::between(0, true, 1, false))
              .withDefault(defaultText(defaults.stabilizationShare)),
          numberValue("stabilize_on_failure",
                      "viscous stabilisation only where steps fail without it: such a step "
                      "(after its line-search retry) is solved again at the same step size with "
                      "the factor C, and its cut-backs and the next steps keep it until "
                      "grow_after of them in a row converged easily; replaces stabilize=, "
                      "stabilize_share= and stabilize_on_failure_share=. 0: off")
              .withRange(Range::atLeast(0))
              .withDefault(defaultText(defaults.stabilizationOnFailure)),
          numberValue("stabilize_on_failure_share",
                      "as stabilize_on_failure, with the factor chosen by the run: after every "
                      "step that converged without stabilisation, C is set so that a step like it "
                      "would dissipate this fraction of its external work, and a failing step is "
                      "stabilised with the last such C (before any such step, "
                      "e.g. for a body that only contact holds: C = F E dt / L^2 from the "
                      "stiffness, E and L = V^(1/3) of the element set with the smallest E / "
                      "L^2, lowered by each stabilised step that dissipates more than F); "
                      "replaces the three above. 0: off")
              .withRange(Range::between(0, true, 1, false))
              .withDefault(defaultText(defaults.stabilizationOnFailureShare))};
}

std::vector<ValueDecl> cutbackParameters() {
  const CutbackSpec defaults;
  return {integerValue("max", "cut-backs allowed per step before the run stops")
              .withRange(Range::atLeast(0))
              .withDefault(defaultText(defaults.maxCutbacks)),
          numberValue("factor", "dt multiplier after a failed attempt")
              .withRange(Range::between(0, false, 1, false))
              .withDefault(defaultText(defaults.factor)),
          integerValue("grow_after", "consecutive easy steps before dt grows again")
              .withRange(Range::atLeast(1))
              .withDefault(defaultText(defaults.growAfter)),
          numberValue("grow_factor", "dt multiplier on regrowth (never beyond the phase's dt)")
              .withRange(Range::atLeast(1))
              .withDefault(defaultText(defaults.growFactor)),
          integerValue("easy", "a step is easy if it converged within this many iterations")
              .withRange(Range::atLeast(1))
              .withDefault(defaultText(defaults.easyIterations))};
}

std::vector<ValueDecl> phaseOnlyParameters() {
  std::vector<ValueDecl> parameters;
  for (const ValueDecl& parameter : newtonParameters()) {
    parameters.push_back(parameter.withDefault(""));
  }
  for (const ValueDecl& parameter : cutbackParameters()) {
    parameters.push_back(parameter.withDefault("").renamed(phaseSpelling(parameter.name)));
  }
  for (ValueDecl& parameter : parameters) parameter.description += " (this phase only)";
  return parameters;
}

void applyNewtonParameters(const ParsedLine& line, NewtonSpec& newton) {
  auto use = [&](const char* name) { return line.given(name); };
  if (use("maxit")) newton.maxIterations = line.integer("maxit");
  if (use("residual")) newton.residualTolerance = line.number("residual");
  if (use("energy")) newton.energyTolerance = line.number("energy");
  if (use("converge")) {
    newton.criterion = choiceValue(convergenceCriteria(), line.text("converge"));
  }
  if (use("diverge")) newton.divergenceFactor = line.number("diverge");
  if (use("line_search")) {
    newton.lineSearch = line.flag("line_search");
    newton.lineSearchChosen = true;
  }
  if (use("predictor")) {
    newton.predictor = choiceValue(newtonPredictors(), line.text("predictor"));
  }
  if (use("penalty_continuation")) {
    newton.penaltyContinuation = line.flag("penalty_continuation");
  }
  if (use("aug_inner")) newton.augmentedInnerTolerance = line.number("aug_inner");
  // One way to set the factor: the last one given replaces the others (a phase's
  // stabilize_share= over the newton line's stabilize=, and back).
  const int ways = int(use("stabilize")) + int(use("stabilize_share")) +
                   int(use("stabilize_on_failure")) + int(use("stabilize_on_failure_share"));
  if (ways > 1) {
    line.fail(line.where(),
              "give one of stabilize=C (the factor), stabilize_share=F (the factor chosen by "
              "the run), stabilize_on_failure=C (the factor for failing steps only) and "
              "stabilize_on_failure_share=F (the factor for failing steps, chosen by the run)");
  }
  const auto stabilizeBy = [&newton](double factor, double share, double onFailure,
                                     double onFailureShare) {
    newton.stabilization = factor;
    newton.stabilizationShare = share;
    newton.stabilizationOnFailure = onFailure;
    newton.stabilizationOnFailureShare = onFailureShare;
  };
  if (use("stabilize")) stabilizeBy(line.number("stabilize"), 0, 0, 0);
  if (use("stabilize_share")) stabilizeBy(0, line.number("stabilize_share"), 0, 0);
  if (use("stabilize_on_failure")) stabilizeBy(0, 0, line.number("stabilize_on_failure"), 0);
  if (use("stabilize_on_failure_share")) {
    stabilizeBy(0, 0, 0, line.number("stabilize_on_failure_share"));
  }
}

// The augmented Lagrangian's re-solves start from a converged state whose contact forces the
// multiplier update has just moved by eps g; at penalties from 100 times the automatic one plain
// Newton cycled there and every step needed line-search retries and cut-backs (the small block of
// test_augmented_lagrangian.cpp at 100 eps_ref: 282 Newton iterations, +210 discarded, 11
// cut-backs; with the line search from the start 56, none), and the line search costs nothing at
// softer penalties (docs/verification/augmented_lagrangian.md).
// The factor reuse's solves (relative error ~1e-12 instead of a refined direct solve's ~1e-14)
// are off there: Anderson-accelerated Uzawa amplifies the round-off of the solves, and the
// block at a tenth of the automatic penalty took 17 steps with cut-backs instead of 5 with them
// (test_augmented_lagrangian.cpp; the same as UMFPACK without refinement, solvers.md).
void resolveNewtonDefaults(ProblemSpec& spec) {
  const bool augmented = spec.hasAugmentedContact();
  for (PhaseSpec& phase : spec.phases) {
    if (!phase.newton.lineSearchChosen) phase.newton.lineSearch = augmented;
  }
  if (!spec.linearSolver.reuseFactorChosen) spec.linearSolver.reuseFactor = !augmented;
}

void applyCutbackParameters(const ParsedLine& line, CutbackSpec& cutback) {
  const bool onStepsLine = line.keyword().name == "steps";
  auto name = [&](const std::string& cutbackName) {
    return onStepsLine ? phaseSpelling(cutbackName) : cutbackName;
  };
  auto use = [&](const std::string& cutbackName) { return line.given(name(cutbackName)); };
  if (use("max")) cutback.maxCutbacks = line.integer(name("max"));
  if (use("factor")) cutback.factor = line.number(name("factor"));
  if (use("grow_after")) cutback.growAfter = line.integer(name("grow_after"));
  if (use("grow_factor")) cutback.growFactor = line.number(name("grow_factor"));
  if (use("easy")) cutback.easyIterations = line.integer(name("easy"));
}

void handleSolve(const ParsedLine& line, DeckState& state) {
  if (state.solveAt) {
    line.fail(line.where(), fmt::format("a deck has one solve block; the first one starts at {}",
                                        state.solveAt->str()));
  }
  state.solveAt = line.where();
  state.insideSolve = true;
  state.spec.linearSolver.method = choiceValue(linearSolverMethods(), line.text("solver"));
  if (line.given("reuse_factor")) {
    state.spec.linearSolver.reuseFactor = line.flag("reuse_factor");
    state.spec.linearSolver.reuseFactorChosen = true;
  }
  state.spec.linearSolver.where = line.where();
}

void handleEnd(const ParsedLine& line, DeckState& state) {
  if (state.spec.phases.empty()) {
    line.fail(state.solveAt.value_or(line.where()),
              "the solve block has no 'steps' line; add e.g. 'steps 10 dt=0.1' before 'end'");
  }
  state.insideSolve = false;
}

void handleNewton(const ParsedLine& line, DeckState& state) {
  applyNewtonParameters(line, state.newton);
}

void handleCutback(const ParsedLine& line, DeckState& state) {
  applyCutbackParameters(line, state.cutback);
}

void handleSteps(const ParsedLine& line, DeckState& state) {
  PhaseSpec phase;
  phase.steps = static_cast<int>(line.positional(0).integer);
  phase.dt = line.number("dt");
  phase.outputEvery = line.integer("output_every");
  phase.newton = state.newton;
  phase.cutback = state.cutback;
  applyNewtonParameters(line, phase.newton);
  applyCutbackParameters(line, phase.cutback);
  phase.where = line.where();
  // Times and step numbers must stay meaningful: each step must move time, the phase must end at
  // a finite time (dt=1e308 gave step times inf), and the steps of all phases are numbered with
  // an int (two phases of 2^31-1 steps overflowed it).
  double phaseStart = 0;
  long long stepsBefore = 0;
  for (const PhaseSpec& earlier : state.spec.phases) {
    phaseStart += earlier.steps * earlier.dt;
    stepsBefore += earlier.steps;
  }
  const double phaseEnd = phaseStart + phase.steps * phase.dt;
  if (!std::isfinite(phaseEnd)) {
    line.fail(line.where(), fmt::format("this phase would end at t = {:.6g} (from t = {:.6g}, {} "
                                        "steps of dt = {:.6g}): times must stay finite",
                                        phaseEnd, phaseStart, phase.steps, phase.dt));
  }
  if (phase.steps > 0 && !(phaseStart + phase.dt > phaseStart)) {
    line.fail(line.where(), fmt::format("dt = {:.6g} does not move time at t = {:.17g} (it is "
                                        "below the round-off of t): use a larger dt",
                                        phase.dt, phaseStart));
  }
  if (stepsBefore + phase.steps > kMaxTotalSteps) {
    line.fail(line.where(), fmt::format("the phases have {} steps in all; at most {} are "
                                        "supported",
                                        stepsBefore + phase.steps, kMaxTotalSteps));
  }
  state.spec.phases.push_back(phase);
}

}  // namespace cc::deck
