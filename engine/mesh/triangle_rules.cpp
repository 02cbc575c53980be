#include "engine/mesh/triangle_rules.hpp"

#include <array>
#include <map>
#include <stdexcept>
#include <string>

namespace loom {
namespace {

// Orbits of the symmetry group: the centroid, (a, a, 1-2a) and the six permutations of (a, b, 1-a-b).
void centroid(std::vector<TrianglePoint>& r, double w) { r.push_back({{1.0 / 3, 1.0 / 3, 1.0 / 3}, w}); }
void orbit3(std::vector<TrianglePoint>& r, double w, double a) {
  const double b = 1.0 - 2.0 * a;
  r.push_back({{a, a, b}, w});
  r.push_back({{a, b, a}, w});
  r.push_back({{b, a, a}, w});
}
void orbit6(std::vector<TrianglePoint>& r, double w, double a, double b) {
  const double c = 1.0 - a - b;
  for (const auto& l : {std::array<double, 3>{a, b, c}, {a, c, b}, {b, a, c}, {b, c, a}, {c, a, b}, {c, b, a}})
    r.push_back({{l[0], l[1], l[2]}, w});
}

std::map<int, std::vector<TrianglePoint>> build_rules() {
  std::map<int, std::vector<TrianglePoint>> rules;
  auto& r1 = rules[1];  // degree 1
  centroid(r1, 1.0);
  auto& r3 = rules[3];  // degree 2
  orbit3(r3, 1.0 / 3, 1.0 / 6);
  auto& r6 = rules[6];  // degree 4
  orbit3(r6, 0.223381589678011, 0.445948490915965);
  orbit3(r6, 0.109951743655322, 0.091576213509771);
  auto& r12 = rules[12];  // degree 6
  orbit3(r12, 0.116786275726379, 0.249286745170910);
  orbit3(r12, 0.050844906370207, 0.063089014491502);
  orbit6(r12, 0.082851075618374, 0.053145049844817, 0.310352451033784);
  auto& r16 = rules[16];  // degree 8
  centroid(r16, 0.144315607677787);
  orbit3(r16, 0.095091634267285, 0.459292588292723);
  orbit3(r16, 0.103217370534718, 0.170569307751760);
  orbit3(r16, 0.032458497623198, 0.050547228317031);
  orbit6(r16, 0.027230314174435, 0.008394777409958, 0.263112829634638);
  auto& r33 = rules[33];  // degree 12
  orbit3(r33, 0.025731066440455, 0.488217389773805);
  orbit3(r33, 0.043692544538038, 0.439724392294460);
  orbit3(r33, 0.062858224217885, 0.271210385012116);
  orbit3(r33, 0.034796112930709, 0.127576145541586);
  orbit3(r33, 0.006166261051559, 0.021317350453210);
  orbit6(r33, 0.040371557766381, 0.115343494534698, 0.275713269685514);
  orbit6(r33, 0.022356773202303, 0.022838332222257, 0.281325580989940);
  orbit6(r33, 0.017316231108659, 0.025734050548330, 0.116251915907597);
  return rules;
}

const std::map<int, std::vector<TrianglePoint>>& rules() {
  static const auto r = build_rules();
  return r;
}

}  // namespace

const std::vector<int>& triangle_rule_sizes() {
  static const std::vector<int> sizes = [] {
    std::vector<int> s;
    for (const auto& [n, rule] : rules()) s.push_back(n);
    return s;
  }();
  return sizes;
}

bool has_triangle_rule(int n_points) { return rules().count(n_points) != 0; }

int triangle_rule_degree(int n_points) {
  switch (n_points) {
    case 1: return 1;
    case 3: return 2;
    case 6: return 4;
    case 12: return 6;
    case 16: return 8;
    case 33: return 12;
    default: return 0;
  }
}

const std::vector<TrianglePoint>& triangle_rule(int n_points) {
  auto it = rules().find(n_points);
  if (it == rules().end()) throw std::invalid_argument("no triangle rule with " + std::to_string(n_points) + " points");
  return it->second;
}

}  // namespace loom
