// Newton and cut-back parameters, declared once and shared by the `newton`, `cutback` and
// `steps` keywords (on `steps` they apply to one phase only).
#pragma once

#include <vector>

#include "deck/keyword_decl.hpp"
#include "deck/parsed_line.hpp"
#include "spec/problem_spec.hpp"

namespace cc::deck {

// With their defaults, taken from NewtonSpec and CutbackSpec (spec/problem_spec.hpp), where each
// default is written once.
std::vector<ValueDecl> newtonParameters();
std::vector<ValueDecl> cutbackParameters();
// Both sets without defaults (absent = the sticky value), cut-back max/factor renamed
// cutback_max/cutback_factor, as accepted on a `steps` line.
std::vector<ValueDecl> phaseOnlyParameters();

// Copies the parameters given on `line` into the settings. The line is a `newton`, `cutback` or
// `steps` line.
void applyNewtonParameters(const ParsedLine& line, NewtonSpec& newton);
void applyCutbackParameters(const ParsedLine& line, CutbackSpec& cutback);
// Defaults that depend on the whole deck, once it is read: the line search of the phases that
// do not set it (on with an augmented contact pair).
void resolveNewtonDefaults(ProblemSpec& spec);

}  // namespace cc::deck
