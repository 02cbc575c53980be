// Symmetric quadrature rules on the triangle (D. A. Dunavant, IJNME 21 (1985) 1129-1148) with 1, 3, 6, 12,
// 16 and 33 points, exact for polynomials of degree 1, 2, 4, 6, 8 and 12: the positions and weights of
// the material points generated in a body cell (seed 003 §6: 3, 12, 33 "material points per element").
// Points are barycentric coordinates; weights sum to 1 (multiply by the cell area).
#pragma once

#include <vector>

namespace loom {

struct TrianglePoint {
  double l[3];  // barycentric coordinates
  double w;     // weight, fraction of the area
};

// The point counts that have a rule, in increasing order.
const std::vector<int>& triangle_rule_sizes();
bool has_triangle_rule(int n_points);
// Polynomial degree integrated exactly by the rule with n_points (0 if there is none).
int triangle_rule_degree(int n_points);
// The rule with n_points; throws std::invalid_argument if there is none.
const std::vector<TrianglePoint>& triangle_rule(int n_points);

}  // namespace loom
