// Values of the scene's probes at the converged state, in the order of SceneSpec::probes:
//  reaction:      sum over the boundary's prescribed dofs of the given component of r = f_int + M a - f_ext,
//                 the force the constraint exerts on the body (its sign follows the axis);
//  point:         displacement component of the node nearest to the probe's reference coordinates;
//  newton:        Newton iterations (linear solves) of the step, summed over its cut-back sub-steps;
//  extent:        largest or smallest current coordinate of the body's nodes along a component;
//  pressure_jump: mean over the body's interior edges of |p_1 - p_2|, the cell pressures
//                 p = -tr(sigma)/3 (averaged over a cell's points) on either side: a measure of pressure
//                 oscillations (seed 000 Fig 9);
//  volume:        area of the body in the converged configuration (sum of the point weights dV_n);
//  remesh:        a quantity of the step's remesh (pfem);
//  stress:        a component of the Cauchy stress at the reference point `at`: in each cell that holds the
//                 point, the quadrature points' stresses (from F_n) fitted linearly -- the 3-point rule at
//                 barycentric l_q = (2/3, 1/6, 1/6) gives sigma(l) = sum_q sigma_q (2 l_q - 1/3) -- or the
//                 one point's value, evaluated at the point and averaged over those cells (at a node: the
//                 usual nodal average of extrapolated element stresses); quad9: the biquadratic interpolation
//                 of its 3 x 3 Gauss values;
//  wall_force:    a component (x, y, along the normal) of the force a wall exerts on the bodies (`walls`, from
//                 wall_results at the converged state);
//  penetration:   the largest distance of a node behind the wall (or behind any wall);
//  speed:         the largest |v_n| over the body's nodes;
//  mass:          the body's mass: density times the reference area of its cells (a seed-001 triangle's reference
//                 area A_0, else dV_n / det F_n per quadrature point; for p1p1_uphi F is F~, det F~ = phi);
//  volume and mass of a probe with an inlet count each cell's part downstream of the inlet's section (the cell's
//                 corner triangle at x_n clipped by the section's line; 3D: the corner tetrahedron by the disc's plane
//                 where the disc is at the time of the probe);
//  section (3D):  the cut of the body's corner tetrahedra at x_n by a plane: its area, or the largest (smallest)
//                 coordinate of its points along a component (systems/output/tet_sections.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"
#include "engine/store/walls.hpp"
#include "systems/assemble/materials/material.hpp"
#include "systems/remesh/remesh.hpp"

namespace loom {

struct StressSample {
  Index block = 0, cell = 0;
  std::array<double, 4> l{};  // barycentric coordinates of the point in the cell's corner triangle (tetrahedron); quad9: (xi, eta)
};

// The probe's reference point `at` in D dimensions (3D: with at_z).
template <int D>
inline Vec<D> probe_point(const ProbeSpec& p) {
  if constexpr (D == 2) return p.at;
  else return Vec3(p.at.x(), p.at.y(), p.at_z);
}

// A plane (x - point(t)) . normal = 0 whose point moves at `velocity` during [start, start + duration] (an inlet's disc).
struct MovingPlane {
  Vec3 point = Vec3::Zero(), normal = Vec3::Zero(), velocity = Vec3::Zero();
  double start = 0.0, duration = 0.0;
  Vec3 point_at(double t) const { return point + std::clamp(t - start, 0.0, duration) * velocity; }
};

struct ProbePlan {
  std::vector<ProbeSpec> probes;
  std::vector<std::vector<StressSample>> samples;  // stress probes: the cells that hold the point
  std::vector<Index> node;                    // point probes: nearest node; others kNoIndex
  std::vector<std::vector<Index>> nodes;      // extent probes: the body's nodes
  std::vector<std::vector<std::array<Index, 3>>> cell_pairs;  // pressure_jump: (block, cell, cell) across interior edges
  std::vector<std::array<Vec2, 2>> downstream;  // volume, mass with an inlet: a point of its section and the inflow normal
  std::vector<MovingPlane> planes;               // 3D: a section probe's plane; an inlet's disc plane (volume, mass)
};

// The part of triangle (a, b, c) on the side of the line through `point` that `normal` points to, as a fraction of
// its area (0 for a degenerate triangle).
double fraction_downstream(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& point, const Vec2& normal);

// Finds the node of each point probe (nearest in reference coordinates, among the nodes of its body), the
// nodes of extent probes and the interior edges of pressure_jump probes.
// Instantiated for D = 2 and 3 (3D: the kinds the loader allows there, without pressure_jump).
template <int D>
ProbePlan plan_probes(const SceneSpec& scene, const Nodes<D>& nodes, const std::vector<Cells>& cells,
                      const std::vector<Index>& node_body);

template <int D>
void evaluate_probes(const StepContext& ctx, const ProbePlan& plan, const std::vector<BodyMaterial>& materials,
                     const Nodes<D>& nodes, const std::vector<Cells>& cells, const std::vector<QuadPoints<D>>& quad,
                     const LinearSystem& system, const BoundaryConditions<D>& bc, int newton_iterations,
                     const RemeshStats& remesh, const std::vector<WallResult>& walls, std::vector<double>& values,
                     const std::vector<Edges<D>>* domains = nullptr);

double stress_component(const Mat3& sigma, StressComponent c);

// Mean pressure -tr(sigma)/3 of a cell over its points, from the committed deformation (F_n).
double cell_pressure(const BodyMaterial& material, const QuadPoints<2>& quad, Index cell);

}  // namespace loom
