#include "systems/loads/apply_grid_loads.hpp"

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "engine/mesh/quad9_shape.hpp"
#include "systems/locate/locate_points.hpp"
#include "systems/map/project_to_grid.hpp"

namespace loom {
namespace {

// An expression at a point (z only in 3D: a 2D call is the one it always was).
template <int D>
double evaluate_at(const Expression& e, double t, const Vec<D>& X) {
  if constexpr (D == 3) return e(t, X.x(), X.y(), X.z());
  else return e(t, X.x(), X.y());
}

}  // namespace

template <int D>
void apply_grid_loads(const StepContext& ctx, const Cells& grid, const Nodes<D>& grid_nodes, const GridActivity& activity,
                      const Points<D>& particles, const PointLocations& particle_loc, const Points<D>& traction_points,
                      const PointLocations& traction_loc, BoundaryConditions<D>& bc) {
  const int pn = bc.per_node;
  // 1. Prescribed values.
  for (const auto& p : bc.prescribed) {
    // Method mpm_fem moves the nodes (X = X^ + u_n): a prescribed displacement is a function of the undeformed X^.
    const Vec<D> X = grid_nodes.u_n.used() ? Vec<D>(grid_nodes.X[p.node] - grid_nodes.u_n[p.node]) : grid_nodes.X[p.node];
    const Expression& g = bc.expressions[std::size_t(p.expression)];
    const bool displacement = p.dof % pn < D;
    bc.target[p.dof] = displacement ? evaluate_at<D>(g, ctx.t, X) - evaluate_at<D>(g, ctx.t - ctx.dt, X) : evaluate_at<D>(g, ctx.t, X);
  }
  bc.external.setZero();
  if (!bc.has_loads) return;

  // 2. Body forces at the particles.
  const Index n = particles.X.size();
  bc.particle_body_force.resize(std::size_t(n));
  // Expressions are not thread-safe (muparser): evaluated serially, once per step.
  for (Index p = 0; p < n; ++p) {
    const auto& e = bc.body_force[std::size_t(particles.body[p])];
    Vec<D> b = Vec<D>::Zero();
    for (int d = 0; d < D; ++d)
      if (e[std::size_t(d)] != kNoIndex) b[d] = evaluate_at<D>(bc.expressions[std::size_t(e[std::size_t(d)])], ctx.t, particles.X[p]);
    bc.particle_body_force[std::size_t(p)] = b;
  }
  // FEM cells of method mpm_fem: at their Gauss points in the undeformed body (X - u_n).
  bc.fem_body_force.clear();
  if constexpr (D == 2) if (activity.always_active_from != kNoIndex) {
    const Quad9Gauss& rule = quad9_gauss();
    for (Index c = activity.always_active_from; c < grid.size(); ++c) {
      const auto& e = bc.body_force[std::size_t(grid.body[c])];
      for (std::size_t q = 0; q < 9; ++q) {
        const Quad9Values N = quad9_shape(rule.xi[q]);
        Vec2 X = Vec2::Zero();
        for (int a = 0; a < 9; ++a) X += N[a] * (grid_nodes.X[grid.node(c, a)] - grid_nodes.u_n[grid.node(c, a)]);
        Vec2 b = Vec2::Zero();
        for (int d = 0; d < 2; ++d)
          if (e[std::size_t(d)] != kNoIndex) b[d] = bc.expressions[std::size_t(e[std::size_t(d)])](ctx.t, X.x(), X.y());
        bc.fem_body_force.push_back(b);
      }
    }
  }
  // Particle Newmark (seed 004) applies the body force at the particles in its kernel, and takes no tractions.
  if (ctx.scene && ctx.scene->mpm.scheme == MpmScheme::particle_newmark) return;
  const auto ahead = [&](Index c) { particle_loc.prefetch_points_in(c, particles.mass, bc.particle_body_force, particle_loc.N); };
  for_each_occupied_cell_by_colour_looking_ahead(grid, particle_loc, ahead, [&](Index c) {
    const Index* pts = particle_loc.points_in(c);
    for (Index k = 0; k < particle_loc.count_in(c); ++k) {
      const Index p = pts[k];
      const Vec<D> f = particles.mass[p] * bc.particle_body_force[std::size_t(p)];
      for (int a = 0; a < grid.stride; ++a)
        for (int d = 0; d < D; ++d) bc.external[pn * grid.node(c, a) + d] += particle_loc.N[p][a] * f[d];
    }
  });

  // 3. Tractions at the traction points (their forces kept for the energy probe's potential of the loads).
  bc.traction_point_force.resize(std::size_t(traction_points.X.size()));
  for (Index q = 0; q < traction_points.X.size(); ++q) {
    const auto& e = bc.traction_point_expression[std::size_t(q)];
    const Vec<D>& X = traction_points.X[q];
    Vec<D> t = Vec<D>::Zero();
    for (int d = 0; d < D; ++d)
      if (e[std::size_t(d)] != kNoIndex) t[d] = evaluate_at<D>(bc.expressions[std::size_t(e[std::size_t(d)])], ctx.t, X);
    const Vec<D> x = traction_points.position(q);
    Vec4 N;
    const Index c = host_active_cell(grid, grid_nodes, activity, traction_loc.cell[q], x, N);
    LOOM_CHECK(c != kNoIndex, RunError,
               "traction point " << q << " (reference position " << Coordinates<D>{X} << ") at " << Coordinates<D>{x}
                                 << " has no grid cell holding particles next to it at step " << ctx.step << ": its load cannot reach the body");
    const Vec<D> f = traction_points.volume[q] * t;
    bc.traction_point_force[std::size_t(q)] = f;
    for (int a = 0; a < grid.stride; ++a)
      for (int d = 0; d < D; ++d) bc.external[pn * grid.node(c, a) + d] += N[a] * f[d];
  }
}


template void apply_grid_loads<2>(const StepContext&, const Cells&, const Nodes<2>&, const GridActivity&, const Points<2>&, const PointLocations&,
                                  const Points<2>&, const PointLocations&, BoundaryConditions<2>&);
template void apply_grid_loads<3>(const StepContext&, const Cells&, const Nodes<3>&, const GridActivity&, const Points<3>&, const PointLocations&,
                                  const Points<3>&, const PointLocations&, BoundaryConditions<3>&);

}  // namespace loom
