// Newton and cut-back parameters, declared once and shared by the `newton`, `cutback` and
// `steps` keywords (on `steps` they apply to one phase only).
#pragma once

#include <vector>

#include "deck/keyword_decl.hpp"
#include "deck/parsed_line.hpp"
#include "spec/problem_spec.hpp"

namespace cc::deck {

std::vector<ValueDecl> newtonParameters();   // with their initial (default) values
std::vector<ValueDecl> cutbackParameters();  // with their initial (default) values
// Both sets without defaults (absent = the sticky value), cut-back max/factor renamed
// cutback_max/cutback_factor, as accepted on a `steps` line.
std::vector<ValueDecl> phaseOnlyParameters();

// Copies the parameters given on `line` (all, defaults included, if includeDefaults) into the
// settings. The line is a `newton`, `cutback` or `steps` line.
void applyNewtonParameters(const ParsedLine& line, NewtonSpec& newton, bool includeDefaults);
void applyCutbackParameters(const ParsedLine& line, CutbackSpec& cutback, bool includeDefaults);

// The settings before any `newton`/`cutback` line: the declared defaults.
NewtonSpec initialNewton();
CutbackSpec initialCutback();

}  // namespace cc::deck
