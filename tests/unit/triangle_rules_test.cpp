// engine/mesh/triangle_rules: each rule integrates every monomial x^i y^j of its degree exactly on the
// reference triangle (exact value i! j! / (i + j + 2)!), not every monomial of the next degree (so the
// stated degree is the rule's), and its points lie inside the triangle.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/mesh/triangle_rules.hpp"

namespace loom {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// Largest relative error over the monomials of total degree d (area of the reference triangle: 1/2).
double worst_error(const std::vector<TrianglePoint>& rule, int d) {
  double worst = 0.0;
  for (int i = 0; i <= d; ++i) {
    const int j = d - i;
    double q = 0.0;
    for (const auto& p : rule) q += 0.5 * p.w * std::pow(p.l[1], i) * std::pow(p.l[2], j);
    const double exact = factorial(i) * factorial(j) / factorial(i + j + 2);
    worst = std::max(worst, std::abs(q - exact) / exact);
  }
  return worst;
}

TEST(TriangleRules, IntegrateMonomialsUpToTheirDegreeExactly) {
  for (int n : triangle_rule_sizes()) {
    const auto& rule = triangle_rule(n);
    ASSERT_EQ(int(rule.size()), n);
    const int degree = triangle_rule_degree(n);
    for (int d = 0; d <= degree; ++d) EXPECT_LE(worst_error(rule, d), 1e-13) << n << " points, degree " << d;
    EXPECT_GT(worst_error(rule, degree + 1), 1e-8) << n << " points integrate degree " << degree + 1 << " too";
  }
}

TEST(TriangleRules, PointsAreInsideAndWeightsPositive) {
  for (int n : triangle_rule_sizes())
    for (const auto& p : triangle_rule(n)) {
      EXPECT_GT(p.w, 0.0);
      EXPECT_NEAR(p.l[0] + p.l[1] + p.l[2], 1.0, 1e-15);
      for (double l : p.l) EXPECT_GT(l, 0.0) << n << " points";
    }
}

TEST(TriangleRules, SeedCountsAreAvailableAndOthersAreNot) {
  for (int n : {1, 3, 6, 12, 16, 33}) EXPECT_TRUE(has_triangle_rule(n)) << n;
  for (int n : {0, 2, 4, 7, 13, 34}) EXPECT_FALSE(has_triangle_rule(n)) << n;
  EXPECT_THROW(triangle_rule(4), std::invalid_argument);
}

}  // namespace
}  // namespace loom
