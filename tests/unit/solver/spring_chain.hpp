// Test problem for Newton and the load stepper: a chain of axial springs along x (node i at
// X = i), y and z fixed, node 0 fixed in x, the last node either loaded or displaced in x.
// Spring laws with closed-form solutions; a switch makes items fail for large time steps.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fem/assembler.hpp"
#include "solver/nonlinear_problem.hpp"

namespace cc::test {

// Axial force N(extension) and its derivative.
struct SpringLaw {
  std::function<double(double)> force;
  std::function<double(double)> stiffness;

  static SpringLaw linear(double k) {
    return {[k](double d) { return k * d; }, [k](double) { return k; }};
  }
  // N = k (d + a d^3): hardening for a > 0.
  static SpringLaw cubic(double k, double a) {
    return {[k, a](double d) { return k * (d + a * d * d * d); },
            [k, a](double d) { return k * (1 + 3 * a * d * d); }};
  }
  // N = atan(d): softening towards a plateau, where full Newton steps overshoot.
  static SpringLaw arctangent() {
    return {[](double d) { return std::atan(d); }, [](double d) { return 1 / (1 + d * d); }};
  }
  // N = d up to the peak force 1 at d = 1, then 1 - (d - 1) / 2: pulled by more than 1 there
  // is no equilibrium, and Newton alternates between tangents +1 and -1/2 (a fold).
  static SpringLaw peaked() {
    return {[](double d) { return d < 1 ? d : 1 - 0.5 * (d - 1); },
            [](double d) { return d < 1 ? 1.0 : -0.5; }};
  }
  // N = d below d = 1 and d + 1 from there: a force between 1 and 2 has no equilibrium, yet
  // every tangent is +1 (no fold: the positive-determinant stops of the refined ironing drags).
  static SpringLaw jumped() {
    return {[](double d) { return d < 1 ? d : d + 1; }, [](double) { return 1.0; }};
  }
};

class SpringItems : public Contribution {
 public:
  SpringItems(int springs, SpringLaw law) : law_(std::move(law)) {
    for (int s = 0; s < springs; ++s) nodes_.push_back({s, s + 1});
  }
  // Items report NotFinite when t_{n+1} - t_n > failThreshold and failFrom < t_{n+1} <= failUntil.
  double failThreshold = std::numeric_limits<double>::infinity();
  double failFrom = -std::numeric_limits<double>::infinity();
  double failUntil = std::numeric_limits<double>::infinity();
  // Fail as above only in evaluations without viscous stabilisation (AssemblyState::
  // viscousFactor 0), a fold that stabilisation carries; the factor of the last evaluation.
  bool failsOnlyUnstabilized = false;
  double lastViscousFactor = 0;

  std::string name() const override { return "springs"; }
  std::size_t itemCount() const override { return nodes_.size(); }
  std::span<const int> itemNodes(std::size_t item) const override { return nodes_[item]; }
  LocalStatus evaluate(std::size_t item, const AssemblyState& state, Eigen::VectorXd& force,
                       Eigen::MatrixXd* tangent) override {
    lastViscousFactor = state.viscousFactor;
    if (state.time - state.previousTime > failThreshold && state.time > failFrom &&
        state.time <= failUntil && (!failsOnlyUnstabilized || state.viscousFactor == 0)) {
      return LocalStatus::failure(FailureKind::NotFinite, "step too large for the mock");
    }
    const int first = nodes_[item][0], second = nodes_[item][1];
    const double extension = (state.current->col(second) - state.current->col(first))[0] -
                             (state.reference->col(second) - state.reference->col(first))[0];
    const double axial = law_.force(extension);
    force[0] = -axial;
    force[3] = axial;
    if (tangent) {
      const double k = law_.stiffness(extension);
      (*tangent)(0, 0) = (*tangent)(3, 3) = k;
      (*tangent)(0, 3) = (*tangent)(3, 0) = -k;
    }
    return LocalStatus::success();
  }

 private:
  SpringLaw law_;
  std::vector<std::vector<int>> nodes_;
};

class SpringChain : public NonlinearProblem {
 public:
  // endDisplacement set: the last node's x is prescribed; otherwise endForce loads it.
  SpringChain(int springs, SpringLaw law, std::function<double(double)> endDisplacement,
              std::function<double(double)> endForce = {}, bool fixStart = true)
      : springs_(springs, std::move(law)),
        endDisplacement_(std::move(endDisplacement)),
        endForce_(std::move(endForce)),
        reference_(Eigen::Matrix3Xd::Zero(3, springs + 1)) {
    const int nodes = springs + 1;
    for (int n = 0; n < nodes; ++n) reference_(0, n) = n;
    std::vector<bool> constrained(3 * nodes, false);
    for (int n = 0; n < nodes; ++n) constrained[3 * n + 1] = constrained[3 * n + 2] = true;
    constrained[0] = fixStart;
    if (endDisplacement_) constrained[3 * springs] = true;
    dofs_ = DofMap(std::vector<bool>(nodes, true), constrained);
    assembler_ = std::make_unique<Assembler>(dofs_, std::vector<Contribution*>{&springs_});
  }

  SpringItems& items() { return springs_; }
  const SpringItems& items() const { return springs_; }
  int lastDof() const { return 3 * static_cast<int>(springs_.itemCount()); }
  int commits = 0;
  int restores = 0;

  const DofMap& dofMap() const override { return dofs_; }
  const Eigen::Matrix3Xd& referenceCoordinates() const override { return reference_; }
  void prescribedValues(double t, Eigen::VectorXd& values) const override {
    values.setZero(dofs_.numPrescribed());
    for (int p = 0; p < dofs_.numPrescribed(); ++p) {
      if (dofs_.prescribedDofs()[p] == lastDof()) values[p] = endDisplacement_(t);
    }
  }
  void externalForces(double t, Eigen::VectorXd& force) const override {
    force.setZero(3 * dofs_.numNodes());
    if (endForce_) force[lastDof()] = endForce_(t);
  }
  void assemble(const AssemblyState& state, Eigen::VectorXd& internalForce,
                SystemMatrices* tangent) override {
    assembler_->assemble(state, internalForce, tangent);
  }
  void commitStep() override { ++commits; }
  void restoreStep() override { ++restores; }

 private:
  SpringItems springs_;
  std::function<double(double)> endDisplacement_;
  std::function<double(double)> endForce_;
  Eigen::Matrix3Xd reference_;
  DofMap dofs_;
  std::unique_ptr<Assembler> assembler_;
};

// A chain whose "contact points" the test says kept switching (describeSwitchingContact).
struct SwitchingChain : SpringChain {
  using SpringChain::SpringChain;
  std::string switching;
  std::string describeSwitchingContact() override { return switching; }
};

struct ConvergedStep {
  int step;
  double time;
  int iterations;
  int cutbacks;
  bool written;
  Eigen::VectorXd displacement;
  Eigen::VectorXd internalForce;
};

class RecordingObserver : public StepObserver {
 public:
  std::vector<IterationRecord> iterations;
  std::vector<CutbackRecord> cutbacks;
  std::vector<ConvergedStep> steps;
  std::vector<std::string> notes;
  std::size_t stopAfterIterations = std::numeric_limits<std::size_t>::max();

  void iteration(const IterationRecord& record) override { iterations.push_back(record); }
  void cutback(const CutbackRecord& record) override { cutbacks.push_back(record); }
  void stepConverged(int step, double time, int iterationCount, int cutbackCount,
                     const Eigen::VectorXd& displacement, const Eigen::VectorXd& internalForce,
                     bool writeOutput) override {
    steps.push_back(
        {step, time, iterationCount, cutbackCount, writeOutput, displacement, internalForce});
  }
  void note(const std::string& line) override { notes.push_back(line); }
  bool stopRequested() const override { return iterations.size() >= stopAfterIterations; }
};

}  // namespace cc::test
