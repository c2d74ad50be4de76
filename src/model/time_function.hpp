// Time functions: scalar functions of time t (and the reference position x, y, z) used for
// prescribed displacements, loads and rigid-surface motions. Built from a FunctionSpec as a
// muParser expression or a piecewise-linear table.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "spec/problem_spec.hpp"

namespace cc {

class ScalarFunction {
 public:
  virtual ~ScalarFunction() = default;
  // Not thread-safe (muParser keeps state); evaluate from one thread.
  virtual double operator()(double t, const Eigen::Vector3d& position) const = 0;
  double operator()(double t) const { return (*this)(t, Eigen::Vector3d::Zero()); }
  // False if the value is the same at every position (a table, an expression without x, y, z):
  // a comparison of two conditions then needs one evaluation per time, not one per node.
  virtual bool dependsOnPosition() const = 0;
};

// Which variables an expression may use: prescribed displacements and loads see the reference
// position, rigid-surface motions only the time (a position there has no meaning).
enum class FunctionVariables { TimeAndPosition, TimeOnly };

// Throws InputError (at spec.where) if the expression does not parse or uses unknown names.
std::unique_ptr<ScalarFunction> makeFunction(
    const FunctionSpec& spec, FunctionVariables variables = FunctionVariables::TimeAndPosition);

}  // namespace cc
