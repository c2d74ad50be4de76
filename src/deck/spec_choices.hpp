// The deck spelling of every enumerated ProblemSpec value, declared once: the keyword table
// takes its `choices` from here and the handlers map the chosen word back to the value.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "spec/problem_spec.hpp"

namespace cc::deck {

template <class T>
using Choices = std::vector<std::pair<std::string, T>>;

template <class T>
std::vector<std::string> choiceNames(const Choices<T>& choices) {
  std::vector<std::string> names;
  for (const auto& choice : choices) names.push_back(choice.first);
  return names;
}

// `name` is a declared spelling (the line parser has already resolved abbreviations).
template <class T>
T choiceValue(const Choices<T>& choices, const std::string& name) {
  for (const auto& choice : choices) {
    if (choice.first == name) return choice.second;
  }
  throw std::logic_error("deck: undeclared choice '" + name + "'");
}

// Clause words naming vector components, in x, y, z order.
inline const std::vector<std::string> kDisplacementComponents = {"ux", "uy", "uz"};
inline const std::vector<std::string> kForceComponents = {"fx", "fy", "fz"};

const Choices<MaterialSpec::Model>& materialModels();
const Choices<ElementBlockSpec::Type>& elementTypes();
const Choices<int>& thicknessAxes();  // auto = -1, x/y/z = 0/1/2 (ElementBlockSpec)
const Choices<RigidSurfaceSpec::Shape>& rigidShapes();
const Choices<ContactSpec::Kind>& contactKinds();
const Choices<ContactSpec::Enforcement>& contactEnforcements();
const Choices<ContactSpec::MasterSurface>& masterSurfaces();
const Choices<ContactSpec::MasterEdge>& masterEdges();
const Choices<ContactSpec::Integration>& contactIntegrations();
const Choices<NewtonSpec::Criterion>& convergenceCriteria();
const Choices<NewtonSpec::Predictor>& newtonPredictors();
const Choices<LinearSolverSpec::Method>& linearSolverMethods();
const Choices<bool TangentPartsSpec::*>& tangentParts();  // snake_case field names
const Choices<bool OutputSpec::*>& outputFields();

// `tangent=` presets: full, no_curvature, main (TangentMode::Paper with these parts), exact.
struct TangentPreset {
  ContactSpec::TangentMode mode = ContactSpec::TangentMode::Paper;
  TangentPartsSpec parts;
};
const Choices<TangentPreset>& tangentPresets();

}  // namespace cc::deck
