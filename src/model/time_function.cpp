// Time functions: muParser expressions in t, x, y, z, and piecewise-linear tables that stay
// constant beyond their first and last points.
#include "model/time_function.hpp"

#include <fmt/format.h>
#include <muParser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <string>
#include <string_view>

#include "common/errors.hpp"

namespace cc {

namespace {

// muParser's message with its 0-based "position N" turned into the 1-based character a user
// counts, or the character appended when the message names none.
std::string parserMessage(const mu::Parser::exception_type& error, const std::string& expression) {
  std::string message = error.GetMsg();
  while (!message.empty() && (message.back() == '.' || message.back() == ' ')) message.pop_back();
  const std::string marker = "at position ";
  const std::size_t at = message.find(marker);
  const int character = static_cast<int>(error.GetPos()) + 1;
  if (at != std::string::npos) {
    std::size_t end = at + marker.size();
    while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end]))) ++end;
    message.replace(at, end - at, fmt::format("at character {}", character));
  } else if (character >= 1 && character <= static_cast<int>(expression.size())) {
    message += fmt::format(" (at character {})", character);
  }
  return message;
}

// muParser's assignment operators (=, +=, -=, *=, /=) change a variable and return the value:
// "t=5" would prescribe 5 at every time. A function has no business assigning, so any '=' that
// is not part of a comparison (==, !=, <=, >=) is refused, at its character.
void rejectAssignment(const std::string& expression, const SourceLocation& where) {
  for (std::size_t i = 0; i < expression.size(); ++i) {
    if (expression[i] != '=') continue;
    if (i + 1 < expression.size() && expression[i + 1] == '=') {
      ++i;  // ==
      continue;
    }
    if (i > 0 && std::string_view("<>!").find(expression[i - 1]) != std::string_view::npos)
      continue;
    throw InputError(where, fmt::format("expression \"{}\" assigns with '=' at character {}; a "
                                        "function of t cannot assign (compare with '==')",
                                        expression, i + 1));
  }
}

class ExpressionFunction final : public ScalarFunction {
 public:
  ExpressionFunction(const FunctionSpec& spec, FunctionVariables variables) : where_(spec.where) {
    parser_.DefineVar("t", &t_);
    const bool withPosition = variables == FunctionVariables::TimeAndPosition;
    if (withPosition) {
      parser_.DefineVar("x", &position_[0]);
      parser_.DefineVar("y", &position_[1]);
      parser_.DefineVar("z", &position_[2]);
    }
    parser_.DefineConst("pi", std::numbers::pi);
    rejectAssignment(spec.expression, where_);
    try {
      parser_.SetExpr(spec.expression);
      parser_.Eval();  // muParser parses lazily: force it now so errors point at the deck
      // muParser's comma operator returns the last of several values: "-2,5e-3*t" (a decimal
      // comma) would prescribe 5e-3*t. Commas belong only inside function arguments.
      if (parser_.GetNumResults() > 1) {
        throw InputError(where_,
                         fmt::format("expression \"{}\" is {} comma-separated values; a function "
                                     "gives one (write decimals with a point: 2.5e-3, not 2,5e-3)",
                                     spec.expression, parser_.GetNumResults()));
      }
      // Asked after the checks above: GetUsedVar re-parses, and the next Eval parses again.
      for (const auto& [name, variable] : parser_.GetUsedVar()) {
        if (name == "x" || name == "y" || name == "z") dependsOnPosition_ = true;
      }
    } catch (const mu::Parser::exception_type& error) {
      throw InputError(where_, fmt::format("cannot parse expression \"{}\": {}{}", spec.expression,
                                           parserMessage(error, spec.expression),
                                           withPosition ? "" : " (a function of t only here)"));
    }
  }

  ExpressionFunction(const ExpressionFunction&) = delete;  // the parser points at our members
  ExpressionFunction& operator=(const ExpressionFunction&) = delete;

  double operator()(double t, const Eigen::Vector3d& position) const override {
    t_ = t;
    for (int axis = 0; axis < 3; ++axis) position_[axis] = position[axis];
    double value = 0;
    try {
      value = parser_.Eval();
    } catch (const mu::Parser::exception_type& error) {
      throw InputError(where_, fmt::format("evaluating \"{}\" at t = {}: {}", parser_.GetExpr(), t,
                                           error.GetMsg()));
    }
    if (!std::isfinite(value)) {
      throw InputError(where_,
                       fmt::format("expression \"{}\" is not finite at t = {}, x = ({}, "
                                   "{}, {})",
                                   parser_.GetExpr(), t, position[0], position[1], position[2]));
    }
    return value;
  }

  bool dependsOnPosition() const override { return dependsOnPosition_; }

 private:
  SourceLocation where_;
  bool dependsOnPosition_ = false;
  mutable mu::Parser parser_;
  mutable double t_ = 0;
  mutable double position_[3] = {0, 0, 0};
};

class TableFunction final : public ScalarFunction {
 public:
  explicit TableFunction(const FunctionSpec& spec) : points_(spec.table) {
    if (points_.empty()) throw InputError(spec.where, "a table needs at least one (t, value) pair");
    for (std::size_t k = 0; k < points_.size(); ++k) {
      if (!std::isfinite(points_[k].first) || !std::isfinite(points_[k].second)) {
        throw InputError(spec.where, fmt::format("table entry {} is not a finite number", k + 1));
      }
      if (k > 0 && !(points_[k].first > points_[k - 1].first)) {
        throw InputError(spec.where,
                         fmt::format("table times must increase strictly (entry {}: t = {} after "
                                     "t = {})",
                                     k + 1, points_[k].first, points_[k - 1].first));
      }
    }
  }

  double operator()(double t, const Eigen::Vector3d&) const override {
    if (t <= points_.front().first) return points_.front().second;
    if (t >= points_.back().first) return points_.back().second;
    const auto upper =
        std::upper_bound(points_.begin(), points_.end(), t,
                         [](double time, const auto& point) { return time < point.first; });
    const auto lower = upper - 1;
    const double fraction = (t - lower->first) / (upper->first - lower->first);
    return lower->second + fraction * (upper->second - lower->second);
  }

  bool dependsOnPosition() const override { return false; }

 private:
  std::vector<std::pair<double, double>> points_;
};

}  // namespace

std::unique_ptr<ScalarFunction> makeFunction(const FunctionSpec& spec,
                                             FunctionVariables variables) {
  if (spec.kind == FunctionSpec::Kind::Table) return std::make_unique<TableFunction>(spec);
  return std::make_unique<ExpressionFunction>(spec, variables);
}

}  // namespace cc
