#include "engine/mesh/tetrahedron_rules.hpp"

#include <map>
#include <string>

#include "engine/core/errors.hpp"

namespace loom {
namespace {

// 4 points (degree 2): (a, b, b, b), a = (5 + 3 sqrt 5) / 20, b = (5 - sqrt 5) / 20; the literals of
// kTet4RuleA and kTet4RuleB (systems/assemble/elements/tet4.hpp).
constexpr double kR4a = 0.58541019662496845446, kR4b = 0.13819660112501051518;

// 14 points (degree 5): the literals and expressions of kTetrahedronRule14 (systems/assemble/elements/
// tet10.hpp). They agree with the 60-digit solution of the moment equations to 3e-15 (moment errors below
// 1.4e-15 relative), not to the last bit; they are kept so that both rules are the same doubles.
constexpr double kR14a1 = 0.09273525031089191, kR14w1 = 0.07349304311636307;
constexpr double kR14a2 = 0.3108859192633009, kR14w2 = 0.11268792571801792;
constexpr double kR14b = 0.04550370412564707, kR14w3 = 0.04254602077707932;
constexpr double kR14c1 = 1 - 3 * kR14a1, kR14c2 = 1 - 3 * kR14a2, kR14d = 0.5 - kR14b;

// 24 points (degree 6, Keast 1986): correctly rounded doubles of the 60-digit solution.
constexpr double kR24a1 = 0.21460287125915203, kR24w1 = 0.039922750258167494;
constexpr double kR24a2 = 0.040673958534611351, kR24w2 = 0.010077211055320643;
constexpr double kR24a3 = 0.32233789014227548, kR24w3 = 0.055357181543654724;
constexpr double kR24a4 = 0.063661001875017525, kR24b4 = 0.26967233145831582, kR24w4 = 27.0 / 560;
constexpr double kR24c1 = 1 - 3 * kR24a1, kR24c2 = 1 - 3 * kR24a2, kR24c3 = 1 - 3 * kR24a3;
constexpr double kR24c4 = 1 - 2 * kR24a4 - kR24b4;

using Rule = std::vector<TetrahedronRulePoint>;

// Orbit (a, a, a, c): the point with c in slot k comes k-th (point q sits nearest corner q when c > a).
void orbit4(Rule& r, double w, double a, double c) {
  for (int k = 0; k < 4; ++k) {
    TetrahedronRulePoint p{{a, a, a, a}, w};
    p.l[k] = c;
    r.push_back(p);
  }
}
// Orbit (b, b, d, d): the slots of the two b's in the order (0 1) (0 2) (0 3) (1 2) (1 3) (2 3).
void orbit6(Rule& r, double w, double b, double d) {
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      TetrahedronRulePoint p{{d, d, d, d}, w};
      p.l[i] = p.l[j] = b;
      r.push_back(p);
    }
}
// Orbit (a, a, b, c): the slots of the two a's as in orbit6, then b before c in the other two slots and
// after them.
void orbit12(Rule& r, double w, double a, double b, double c) {
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      int rest[2], n = 0;
      for (int k = 0; k < 4; ++k)
        if (k != i && k != j) rest[n++] = k;
      for (int s = 0; s < 2; ++s) {
        TetrahedronRulePoint p{{a, a, a, a}, w};
        p.l[rest[s]] = b;
        p.l[rest[1 - s]] = c;
        r.push_back(p);
      }
    }
}

std::map<int, Rule> build_rules() {
  std::map<int, Rule> rules;
  rules[1].push_back({{0.25, 0.25, 0.25, 0.25}, 1.0});  // degree 1
  orbit4(rules[4], 0.25, kR4b, kR4a);                   // degree 2
  auto& r14 = rules[14];                                // degree 5
  orbit4(r14, kR14w1, kR14a1, kR14c1);
  orbit4(r14, kR14w2, kR14a2, kR14c2);
  orbit6(r14, kR14w3, kR14b, kR14d);
  auto& r24 = rules[24];  // degree 6
  orbit4(r24, kR24w1, kR24a1, kR24c1);
  orbit4(r24, kR24w2, kR24a2, kR24c2);
  orbit4(r24, kR24w3, kR24a3, kR24c3);
  orbit12(r24, kR24w4, kR24a4, kR24b4, kR24c4);
  return rules;
}

const std::map<int, Rule>& rules() {
  static const auto r = build_rules();
  return r;
}

}  // namespace

const std::vector<int>& tetrahedron_rule_sizes() {
  static const std::vector<int> sizes = [] {
    std::vector<int> s;
    for (const auto& [n, rule] : rules()) s.push_back(n);
    return s;
  }();
  return sizes;
}

bool has_tetrahedron_rule(int n_points) { return rules().count(n_points) != 0; }

int tetrahedron_rule_degree(int n_points) {
  switch (n_points) {
    case 1: return 1;
    case 4: return 2;
    case 14: return 5;
    case 24: return 6;
    default: return 0;
  }
}

const std::vector<TetrahedronRulePoint>& tetrahedron_rule(int n_points) {
  auto it = rules().find(n_points);
  if (it == rules().end()) {
    std::string sizes;
    for (int n : tetrahedron_rule_sizes()) sizes += (sizes.empty() ? "" : ", ") + std::to_string(n);
    throw InputError("no tetrahedron rule with " + std::to_string(n_points) + " points (available: " + sizes + ")");
  }
  return it->second;
}

}  // namespace loom
