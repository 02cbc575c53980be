// Scene expressions (engine/scene/expression): muparser in t, x, y with pi; unknown names are compile
// errors naming the name; time dependence is detected.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/core/errors.hpp"
#include "engine/scene/expression.hpp"

namespace loom {

TEST(Expression, EvaluatesTimeCoordinatesAndPi) {
  const Expression e("2*t + 3*x - y + pi", "test.toml:1:1");
  EXPECT_DOUBLE_EQ(e(0.5, 2.0, 4.0), 1.0 + 6.0 - 4.0 + M_PI);
  EXPECT_DOUBLE_EQ(e(0.0, 0.0, 0.0), M_PI);
  EXPECT_EQ(e.text(), "2*t + 3*x - y + pi");
}

TEST(Expression, EvaluatesFunctionsOfTheVariables) {
  const Expression e("sin(pi*x/2) * t^2", "");
  EXPECT_NEAR(e(3.0, 1.0, 0.0), 9.0, 1e-14);
}

TEST(Expression, DetectsTimeDependence) {
  EXPECT_TRUE(Expression("-0.2 * t / 200", "").depends_on_time());
  EXPECT_FALSE(Expression("x + y", "").depends_on_time());
  EXPECT_FALSE(Expression("6.25", "").depends_on_time());
}

TEST(Expression, ANumberIsConstant) {
  EXPECT_TRUE(Expression("6.25", "").is_constant());
  EXPECT_TRUE(Expression("2*pi", "").is_constant());
  EXPECT_FALSE(Expression("x", "").is_constant());
}

TEST(Expression, CompileErrorNamesAnUnknownVariable) {
  const std::string err = Expression::compile_error("2*q + x");
  EXPECT_FALSE(err.empty());
  EXPECT_NE(err.find("q"), std::string::npos) << err;
  EXPECT_TRUE(Expression::compile_error("2*t + x*y").empty());
}

TEST(Expression, CompileErrorReportsSyntax) {
  EXPECT_FALSE(Expression::compile_error("2*(x + 1").empty());
  EXPECT_FALSE(Expression::compile_error("").empty());
}

TEST(Expression, ConstructorThrowsInputErrorNamingWhere) {
  try {
    Expression e("speed * t", "test.toml:7:12: boundary[0].displacement.x");
    FAIL() << "no exception";
  } catch (const InputError& err) {
    const std::string msg = err.what();
    EXPECT_NE(msg.find("test.toml:7:12"), std::string::npos) << msg;
    EXPECT_NE(msg.find("speed"), std::string::npos) << msg;
  }
}

TEST(Expression, NonFiniteValueIsARunError) {
  const Expression e("1 / x", "test.toml:3:5");
  EXPECT_DOUBLE_EQ(e(0, 2, 0), 0.5);
  EXPECT_THROW(e(0, 0, 0), RunError);
}

// A constant that is not a number is bad input at once (loom check), with where it is; a non-constant
// expression is judged where it is evaluated (above).
TEST(Expression, NonFiniteConstantIsBadInput) {
  for (const char* text : {"sqrt(-9.81)", "1/0", "-9.81 * ln(0)"}) {
    SCOPED_TRACE(text);
    try {
      Expression e(text, "test.toml:4:9");
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("test.toml:4:9"), std::string::npos) << msg;
      EXPECT_NE(msg.find("its value is not finite"), std::string::npos) << msg;
    }
    EXPECT_NE(Expression::compile_error(text).find("its value is not finite"), std::string::npos);
  }
  EXPECT_TRUE(Expression::compile_error("sqrt(9.81)").empty());
}

TEST(Expression, MovedExpressionStillEvaluates) {
  Expression a("x + 1", "");
  Expression b = std::move(a);
  EXPECT_DOUBLE_EQ(b(0, 2, 0), 3.0);
}

}  // namespace loom
