// engine/mesh/tetrahedron_rules: each rule has positive weights summing to 1 and its points strictly inside
// the tetrahedron; it integrates every monomial x^a y^b z^c of its degree exactly on the reference
// tetrahedron (exact value a! b! c! / (a + b + c + 3)!, times 6 for weights that are fractions of the
// volume 1/6), and not every monomial of the next degree (so the stated degree is the rule's); the 4- and
// 14-point rules are the FEM's kTet4Rule4 and kTetrahedronRule14 bit for bit; other counts throw.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/core/errors.hpp"
#include "engine/mesh/tetrahedron_rules.hpp"
#include "systems/assemble/elements/tet10.hpp"
#include "systems/assemble/elements/tet4.hpp"

namespace loom {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// Largest relative error over the monomials x^a y^b z^c of total degree d, x y z = l1 l2 l3.
double worst_error(const std::vector<TetrahedronRulePoint>& rule, int d) {
  double worst = 0.0;
  for (int a = 0; a <= d; ++a)
    for (int b = 0; a + b <= d; ++b) {
      const int c = d - a - b;
      double q = 0.0;
      for (const auto& p : rule) q += p.w * std::pow(p.l[1], a) * std::pow(p.l[2], b) * std::pow(p.l[3], c);
      const double exact = 6.0 * factorial(a) * factorial(b) * factorial(c) / factorial(d + 3);
      worst = std::max(worst, std::abs(q - exact) / exact);
    }
  return worst;
}

TEST(TetrahedronRules, SizesAndDegrees) {
  EXPECT_EQ(tetrahedron_rule_sizes(), (std::vector<int>{1, 4, 14, 24}));
  const int degree[] = {1, 2, 5, 6};
  for (std::size_t i = 0; i < 4; ++i) {
    const int n = tetrahedron_rule_sizes()[i];
    EXPECT_TRUE(has_tetrahedron_rule(n));
    EXPECT_EQ(int(tetrahedron_rule(n).size()), n);
    EXPECT_EQ(tetrahedron_rule_degree(n), degree[i]) << n << " points";
  }
}

TEST(TetrahedronRules, WeightsPositiveAndPointsInside) {
  for (int n : tetrahedron_rule_sizes()) {
    double sum = 0.0;
    for (const auto& p : tetrahedron_rule(n)) {
      EXPECT_GT(p.w, 0.0) << n << " points";
      sum += p.w;
      EXPECT_NEAR(p.l[0] + p.l[1] + p.l[2] + p.l[3], 1.0, 1e-15) << n << " points";
      for (double l : p.l) EXPECT_GT(l, 0.0) << n << " points";
    }
    EXPECT_NEAR(sum, 1.0, 1e-15) << n << " points";
  }
}

TEST(TetrahedronRules, IntegrateMonomialsUpToTheirDegreeExactly) {
  for (int n : tetrahedron_rule_sizes()) {
    const auto& rule = tetrahedron_rule(n);
    const int degree = tetrahedron_rule_degree(n);
    for (int d = 0; d <= degree; ++d) EXPECT_LE(worst_error(rule, d), 1e-14) << n << " points, degree " << d;
    EXPECT_GT(worst_error(rule, degree + 1), 1e-8) << n << " points integrate degree " << degree + 1 << " too";
  }
}

TEST(TetrahedronRules, FourAndFourteenPointsAreTheFemRulesBitForBit) {
  const auto& r4 = tetrahedron_rule(4);
  for (int q = 0; q < 4; ++q) {
    EXPECT_EQ(r4[std::size_t(q)].w, 0.25);
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(r4[std::size_t(q)].l[k], kTet4Rule4[q][k]) << "point " << q << ", coordinate " << k;
  }
  const auto& r14 = tetrahedron_rule(14);
  for (int q = 0; q < 14; ++q) {
    EXPECT_EQ(r14[std::size_t(q)].w, kTetrahedronRule14[q].w) << "point " << q;
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(r14[std::size_t(q)].l[k], kTetrahedronRule14[q].l[k]) << "point " << q << ", coordinate " << k;
  }
}

TEST(TetrahedronRules, OtherCountsThrowListingTheAvailableOnes) {
  for (int n : {0, 2, 3, 5, 12, 15, 48}) {
    EXPECT_FALSE(has_tetrahedron_rule(n)) << n;
    EXPECT_EQ(tetrahedron_rule_degree(n), 0) << n;
    EXPECT_THROW(tetrahedron_rule(n), InputError) << n;
  }
  try {
    tetrahedron_rule(12);
    ADD_FAILURE() << "tetrahedron_rule(12) did not throw";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("1, 4, 14, 24"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace loom
