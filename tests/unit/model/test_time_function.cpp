// Time functions: muParser expressions in t, x, y, z; tables with interpolation and clamping;
// parse errors as InputError at the spec's location.
#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"
#include "model/time_function.hpp"

namespace cc {
namespace {

FunctionSpec expression(const std::string& text) {
  FunctionSpec spec;
  spec.expression = text;
  spec.where = {"deck.inp", 12, 20};
  return spec;
}

TEST(TimeFunction, ExpressionOfTimeAndPosition) {
  const auto ramp = makeFunction(expression("-7e-3*min(t,1) + 2.5e-4*max(t-1,0)"));
  EXPECT_DOUBLE_EQ((*ramp)(0.5), -3.5e-3);
  EXPECT_DOUBLE_EQ((*ramp)(3.0), -7e-3 + 5e-4);
  const auto field = makeFunction(expression("x + 2*y - z*t + sin(pi/2) + abs(-1)"));
  EXPECT_DOUBLE_EQ((*field)(2.0, Eigen::Vector3d(1.0, 3.0, 0.5)), 1.0 + 6.0 - 1.0 + 1.0 + 1.0);
}

TEST(TimeFunction, TableInterpolatesAndStaysConstantBeyondItsEnds) {
  FunctionSpec spec;
  spec.kind = FunctionSpec::Kind::Table;
  spec.table = {{0.0, 0.0}, {1.0, 2.0}, {3.0, -2.0}};
  const auto table = makeFunction(spec);
  EXPECT_DOUBLE_EQ((*table)(-1.0), 0.0);
  EXPECT_DOUBLE_EQ((*table)(0.25), 0.5);
  EXPECT_DOUBLE_EQ((*table)(1.0), 2.0);
  EXPECT_DOUBLE_EQ((*table)(2.5), -1.0);
  EXPECT_DOUBLE_EQ((*table)(10.0), -2.0);
}

TEST(TimeFunction, TableTimesMustIncrease) {
  FunctionSpec spec;
  spec.kind = FunctionSpec::Kind::Table;
  spec.table = {{0.0, 0.0}, {1.0, 2.0}, {1.0, 3.0}};
  spec.where = {"deck.inp", 4, 1};
  try {
    makeFunction(spec);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.where().line, 4);
    EXPECT_NE(std::string(error.what()).find("increase strictly"), std::string::npos);
  }
}

TEST(TimeFunction, ParseErrorQuotesExpressionAndLocation) {
  try {
    makeFunction(expression("2*t + foo"));
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind("deck.inp:12:20: error: ", 0), 0u) << message;
    EXPECT_NE(message.find("\"2*t + foo\""), std::string::npos) << message;
    EXPECT_NE(message.find("foo"), message.find("\"2*t + foo\"")) << message;
    EXPECT_NE(message.find("character 7"), std::string::npos) << message;
  }
  EXPECT_THROW(makeFunction(expression("sin(t")), InputError);
}

TEST(TimeFunction, NonFiniteValueIsAnInputError) {
  const auto function = makeFunction(expression("1/t"));
  EXPECT_DOUBLE_EQ((*function)(2.0), 0.5);
  EXPECT_THROW((*function)(0.0), InputError);
}

}  // namespace
}  // namespace cc
