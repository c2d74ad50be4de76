// Deck spellings of the enumerated ProblemSpec values and the tangent presets.
#include "deck/spec_choices.hpp"

namespace cc::deck {

const Choices<MaterialSpec::Model>& materialModels() {
  static const Choices<MaterialSpec::Model> choices = {
      {"svk", MaterialSpec::Model::StVenantKirchhoff},
      {"neohooke", MaterialSpec::Model::NeoHooke},
      {"neohooke_decoupled", MaterialSpec::Model::NeoHookeDecoupled}};
  return choices;
}

const Choices<ElementBlockSpec::Type>& elementTypes() {
  static const Choices<ElementBlockSpec::Type> choices = {
      {"hex8", ElementBlockSpec::Type::Hex8},
      {"solid_shell8", ElementBlockSpec::Type::SolidShell8},
      {"solid_shell18", ElementBlockSpec::Type::SolidShell18}};
  return choices;
}

const Choices<int>& thicknessAxes() {
  static const Choices<int> choices = {{"auto", -1}, {"x", 0}, {"y", 1}, {"z", 2}};
  return choices;
}

const Choices<RigidSurfaceSpec::Shape>& rigidShapes() {
  static const Choices<RigidSurfaceSpec::Shape> choices = {
      {"plane", RigidSurfaceSpec::Shape::Plane},
      {"cylinder", RigidSurfaceSpec::Shape::Cylinder},
      {"parabolic_cylinder", RigidSurfaceSpec::Shape::ParabolicCylinder},
      {"sphere", RigidSurfaceSpec::Shape::Sphere}};
  return choices;
}

const Choices<ContactSpec::Kind>& contactKinds() {
  static const Choices<ContactSpec::Kind> choices = {
      {"sts", ContactSpec::Kind::SegmentToSegment},
      {"nts", ContactSpec::Kind::NodeToSegment},
      {"stas", ContactSpec::Kind::SegmentToAnalytical}};
  return choices;
}

const Choices<ContactSpec::Enforcement>& contactEnforcements() {
  static const Choices<ContactSpec::Enforcement> choices = {
      {"penalty", ContactSpec::Enforcement::Penalty},
      {"augmented", ContactSpec::Enforcement::Augmented}};
  return choices;
}

const Choices<ContactSpec::MasterSurface>& masterSurfaces() {
  static const Choices<ContactSpec::MasterSurface> choices = {
      {"faceted", ContactSpec::MasterSurface::Faceted},
      {"smooth", ContactSpec::MasterSurface::Smooth}};
  return choices;
}

const Choices<ContactSpec::MasterEdge>& masterEdges() {
  static const Choices<ContactSpec::MasterEdge> choices = {
      {"sharp", ContactSpec::MasterEdge::Sharp}, {"fade", ContactSpec::MasterEdge::Fade}};
  return choices;
}

const Choices<ContactSpec::Integration>& contactIntegrations() {
  static const Choices<ContactSpec::Integration> choices = {
      {"gauss", ContactSpec::Integration::Gauss}, {"segments", ContactSpec::Integration::Segments}};
  return choices;
}

const Choices<NewtonSpec::Criterion>& convergenceCriteria() {
  static const Choices<NewtonSpec::Criterion> choices = {
      {"energy", NewtonSpec::Criterion::Energy},
      {"residual", NewtonSpec::Criterion::Residual},
      {"both", NewtonSpec::Criterion::Both},
      {"either", NewtonSpec::Criterion::Either}};
  return choices;
}

const Choices<NewtonSpec::Predictor>& newtonPredictors() {
  static const Choices<NewtonSpec::Predictor> choices = {
      {"prescribed", NewtonSpec::Predictor::Prescribed},
      {"extrapolate", NewtonSpec::Predictor::Extrapolate}};
  return choices;
}

const Choices<LinearSolverSpec::Method>& linearSolverMethods() {
  using Method = LinearSolverSpec::Method;
  static const Choices<Method> choices = {
      {"auto", Method::Auto},   {"cholmod", Method::Cholmod},          {"umfpack", Method::Umfpack},
      {"mumps", Method::Mumps}, {"superlu_dist", Method::SuperluDist}, {"amg", Method::Amg},
      {"gamg", Method::Gamg}};
  return choices;
}

const Choices<bool TangentPartsSpec::*>& tangentParts() {
  static const Choices<bool TangentPartsSpec::*> choices = {
      {"normal_main", &TangentPartsSpec::normalMain},
      {"normal_rotational", &TangentPartsSpec::normalRotational},
      {"normal_curvature", &TangentPartsSpec::normalCurvature},
      {"stick_main", &TangentPartsSpec::stickMain},
      {"stick_rotational", &TangentPartsSpec::stickRotational},
      {"stick_curvature", &TangentPartsSpec::stickCurvature},
      {"slide_constitutive", &TangentPartsSpec::slideConstitutive},
      {"slide_rotational", &TangentPartsSpec::slideRotational},
      {"slide_curvature", &TangentPartsSpec::slideCurvature},
      {"slide_unsymmetric_curvature", &TangentPartsSpec::slideUnsymmetricCurvature}};
  return choices;
}

const Choices<bool OutputSpec::*>& outputFields() {
  static const Choices<bool OutputSpec::*> choices = {{"displacement", &OutputSpec::displacement},
                                                      {"reaction", &OutputSpec::reaction},
                                                      {"stress", &OutputSpec::stress},
                                                      {"contact", &OutputSpec::contact}};
  return choices;
}

namespace {

TangentPartsSpec withoutCurvature() {
  TangentPartsSpec parts;
  parts.normalCurvature = false;
  parts.stickCurvature = false;
  parts.slideCurvature = false;
  parts.slideUnsymmetricCurvature = false;
  return parts;
}

TangentPartsSpec mainPartsOnly() {
  TangentPartsSpec parts;
  for (const auto& [name, field] : tangentParts()) parts.*field = false;
  parts.normalMain = true;
  parts.stickMain = true;
  parts.slideConstitutive = true;
  return parts;
}

}  // namespace

const Choices<TangentPreset>& tangentPresets() {
  using Mode = ContactSpec::TangentMode;
  static const Choices<TangentPreset> choices = {
      {"full", {Mode::Paper, TangentPartsSpec{}}},
      {"no_curvature", {Mode::Paper, withoutCurvature()}},
      {"main", {Mode::Paper, mainPartsOnly()}},
      {"exact", {Mode::Exact, TangentPartsSpec{}}}};
  return choices;
}

}  // namespace cc::deck
