#include "systems/map/interpolate_to_particles.hpp"

#include "engine/core/parallel.hpp"
#include "engine/mesh/grid_shape.hpp"
#include "systems/locate/locate_points.hpp"

namespace loom {
namespace {

// Linear in N: the values at a point of a cell with `corners` corners (tri3: 3; quad4, tet4: 4).
template <class T, class Column>
T interpolate(int corners, const Index* corner, const Vec4& N, const Column& values) {
  T sum = N[0] * values[corner[0]] + N[1] * values[corner[1]] + N[2] * values[corner[2]];
  if (corners == 4) sum += N[3] * values[corner[3]];
  return sum;
}

template <int NC, int D>
Mat3 increment_gradient(const Cells& grid, const Nodes<D>& g, Index c, const Vec4& N) {
  const CornerGradients<NC, D> dN = grid_shape_gradients<NC>(grid, g, c, N);
  Mat3 dF = Mat3::Identity();
  for (int a = 0; a < NC; ++a) dF.topLeftCorner<D, D>() += g.u[grid.node(c, a)] * dN.row(a);
  return dF;
}

}  // namespace

template <int D>
void interpolate_to_particles(const StepContext& ctx, const Cells& grid, const Nodes<D>& grid_nodes,
                              const PointLocations& loc, Points<D>& particles) {
  const Nodes<D>& g = grid_nodes;
  const bool dynamic = particles.v.used() && g.a.used(), mixed = particles.pressure.used() && g.p.used();
  const bool osgs = particles.proj_u.used() && g.proj_u.used();
  const bool history = particles.be.used() && loc.be.used();
  for_each_index(particles.X.size(), [&](Index p) {
    const Index c = loc.cell[p];
    const Index* corner = grid.cell_nodes(c);
    const Vec4& N = loc.N[p];
    const int nc = grid.stride;
    particles.u[p] += interpolate<Vec<D>>(nc, corner, N, g.u);
    Mat3 dF;
    if constexpr (D == 3) dF = increment_gradient<4, 3>(grid, g, c, N);
    else dF = nc == 4 ? increment_gradient<4, 2>(grid, g, c, N) : increment_gradient<3, 2>(grid, g, c, N);
    particles.F[p] = dF * particles.F[p];
    if (history) particles.be[p] = loc.be[p];  // the return map of the converged iterate (the last assembly's)
    if (dynamic) {
      // FLIP: the particle takes the increment of the grid's Newmark velocity, v_I^{n+1} - v_I^n =
      // dt ((1 - gamma) a_I^n + gamma a_I^{n+1}), a_I^n the projection of the particles' accelerations that the
      // grid integrated. (Taking the particle's own a_p^n instead adds dt (1 - gamma)(a_p^n - sum N_I a_I^n) each
      // step, a part of the acceleration no grid equation balanced; the energy grew without bound once particles
      // crossed cells back and forth: docs/mpm/velocity_update.md.)
      const Vec<D> a_old = interpolate<Vec<D>>(nc, corner, N, g.a_n), a_new = interpolate<Vec<D>>(nc, corner, N, g.a);
      particles.v[p] += ctx.dt * ((1.0 - kNewmarkGamma) * a_old + kNewmarkGamma * a_new);
      particles.a[p] = a_new;
    }
    if (mixed) particles.pressure[p] = interpolate<double>(nc, corner, N, g.p);
    if (osgs) {
      particles.proj_u[p] = interpolate<Vec<D>>(nc, corner, N, g.proj_u);
      particles.proj_p[p] = interpolate<double>(nc, corner, N, g.proj_p);
    }
  });
}

template <int D>
void move_with_grid(const StepContext&, const Cells& grid, const Nodes<D>& grid_nodes, const GridActivity& activity,
                    const PointLocations& loc, Points<D>& points) {
  for_each_index(points.X.size(), [&](Index p) {
    Vec4 N;
    const Index c = host_active_cell(grid, grid_nodes, activity, loc.cell[p], points.position(p), N);
    if (c != kNoIndex) points.u[p] += interpolate<Vec<D>>(grid.stride, grid.cell_nodes(c), N, grid_nodes.u);
  });
}


template void interpolate_to_particles<2>(const StepContext&, const Cells&, const Nodes<2>&, const PointLocations&, Points<2>&);
template void interpolate_to_particles<3>(const StepContext&, const Cells&, const Nodes<3>&, const PointLocations&, Points<3>&);
template void move_with_grid<2>(const StepContext&, const Cells&, const Nodes<2>&, const GridActivity&, const PointLocations&, Points<2>&);
template void move_with_grid<3>(const StepContext&, const Cells&, const Nodes<3>&, const GridActivity&, const PointLocations&, Points<3>&);

}  // namespace loom
