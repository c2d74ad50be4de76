// The solve block: `solve` ... `end`, sticky `newton`/`cutback` settings and `steps` phases.
#include <fmt/format.h>

#include <stdexcept>

#include "deck/deck_state.hpp"
#include "deck/solve_parameters.hpp"
#include "deck/spec_choices.hpp"

namespace cc::deck {

namespace {

// Spelling of a cut-back parameter on a `steps` line, where a bare max= or factor= would not
// say what it limits.
std::string phaseSpelling(const std::string& cutbackName) {
  return cutbackName == "max" || cutbackName == "factor" ? "cutback_" + cutbackName : cutbackName;
}

const KeywordDecl& keywordNamed(const std::string& name) {
  for (const KeywordDecl& keyword : keywordTable()) {
    if (keyword.name == name) return keyword;
  }
  throw std::logic_error("deck: no keyword " + name);
}

// A line holding only the keyword, so that every parameter takes its declared default.
ParsedLine defaultsOf(const std::string& keywordName) {
  LogicalLine line;
  line.tokens.push_back({Token::Kind::Word, keywordName, SourceLocation{"<defaults>", 1, 1}});
  line.end = line.tokens.front().where;
  return ParsedLine(line, keywordNamed(keywordName));
}

}  // namespace

std::vector<ValueDecl> newtonParameters() {
  return {integerValue("maxit", "Newton iterations per step before the step counts as failed")
              .withRange(Range::atLeast(1))
              .withDefault("30"),
          numberValue("residual", "tolerance on the relative residual norm |R_k| / |R_0|")
              .withRange(Range::greaterThan(0))
              .withDefault("1e-10"),
          numberValue("energy", "tolerance on the relative energy norm |du_k . R_k| / |du_0 . R_0|")
              .withRange(Range::greaterThan(0))
              .withDefault("1e-16"),
          enumValue("converge", choiceNames(convergenceCriteria()),
                    "which tolerance decides convergence: energy, residual, both, or either")
              .withDefault("energy"),
          numberValue("diverge", "the step fails when |R_k| exceeds this multiple of |R_0|")
              .withRange(Range::greaterThan(1))
              .withDefault("1e6"),
          boolValue("line_search", "backtracking line search along the Newton direction")
              .withDefault("no")};
}

std::vector<ValueDecl> cutbackParameters() {
  return {integerValue("max", "cut-backs allowed per step before the run stops")
              .withRange(Range::atLeast(0))
              .withDefault("10"),
          numberValue("factor", "dt multiplier after a failed attempt")
              .withRange(Range::between(0, false, 1, false))
              .withDefault("0.5"),
          integerValue("grow_after", "consecutive easy steps before dt grows again")
              .withRange(Range::atLeast(1))
              .withDefault("3"),
          numberValue("grow_factor", "dt multiplier on regrowth (never beyond the phase's dt)")
              .withRange(Range::atLeast(1))
              .withDefault("2"),
          integerValue("easy", "a step is easy if it converged within this many iterations")
              .withRange(Range::atLeast(1))
              .withDefault("6")};
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

void applyNewtonParameters(const ParsedLine& line, NewtonSpec& newton, bool includeDefaults) {
  auto use = [&](const char* name) { return includeDefaults || line.given(name); };
  if (use("maxit")) newton.maxIterations = line.integer("maxit");
  if (use("residual")) newton.residualTolerance = line.number("residual");
  if (use("energy")) newton.energyTolerance = line.number("energy");
  if (use("converge")) {
    newton.criterion = choiceValue(convergenceCriteria(), line.text("converge"));
  }
  if (use("diverge")) newton.divergenceFactor = line.number("diverge");
  if (use("line_search")) newton.lineSearch = line.flag("line_search");
}

void applyCutbackParameters(const ParsedLine& line, CutbackSpec& cutback, bool includeDefaults) {
  const bool onStepsLine = line.keyword().name == "steps";
  auto name = [&](const std::string& cutbackName) {
    return onStepsLine ? phaseSpelling(cutbackName) : cutbackName;
  };
  auto use = [&](const std::string& cutbackName) {
    return includeDefaults || line.given(name(cutbackName));
  };
  if (use("max")) cutback.maxCutbacks = line.integer(name("max"));
  if (use("factor")) cutback.factor = line.number(name("factor"));
  if (use("grow_after")) cutback.growAfter = line.integer(name("grow_after"));
  if (use("grow_factor")) cutback.growFactor = line.number(name("grow_factor"));
  if (use("easy")) cutback.easyIterations = line.integer(name("easy"));
}

NewtonSpec initialNewton() {
  NewtonSpec newton;
  applyNewtonParameters(defaultsOf("newton"), newton, true);
  return newton;
}

CutbackSpec initialCutback() {
  CutbackSpec cutback;
  applyCutbackParameters(defaultsOf("cutback"), cutback, true);
  return cutback;
}

void handleSolve(const ParsedLine& line, DeckState& state) {
  if (state.solveAt) {
    line.fail(line.where(), fmt::format("a deck has one solve block; the first one starts at {}",
                                        state.solveAt->str()));
  }
  state.solveAt = line.where();
  state.insideSolve = true;
  state.spec.linearSolver.method = choiceValue(linearSolverMethods(), line.text("solver"));
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
  applyNewtonParameters(line, state.newton, false);
}

void handleCutback(const ParsedLine& line, DeckState& state) {
  applyCutbackParameters(line, state.cutback, false);
}

void handleSteps(const ParsedLine& line, DeckState& state) {
  PhaseSpec phase;
  phase.steps = static_cast<int>(line.positional(0).integer);
  phase.dt = line.number("dt");
  phase.outputEvery = line.integer("output_every");
  phase.newton = state.newton;
  phase.cutback = state.cutback;
  applyNewtonParameters(line, phase.newton, false);
  applyCutbackParameters(line, phase.cutback, false);
  phase.where = line.where();
  state.spec.phases.push_back(phase);
}

}  // namespace cc::deck
