#include "systems/map/interpolate_to_particles.hpp"

#include "engine/core/parallel.hpp"
#include "engine/mesh/grid_shape.hpp"
#include "systems/locate/locate_points.hpp"

namespace loom {
namespace {

template <class T, class Column>
T interpolate(int corners, const Index* corner, const Vec4& N, const Column& values) {
  T sum = N[0] * values[corner[0]] + N[1] * values[corner[1]] + N[2] * values[corner[2]];
  if (corners == 4) sum += N[3] * values[corner[3]];
  return sum;
}

template <int NC>
Mat3 increment_gradient(const Cells& grid, const Nodes<2>& g, Index c, const Vec4& N) {
  const CornerGradients<NC> dN = grid_shape_gradients<NC>(grid, g, c, N);
  Mat3 dF = Mat3::Identity();
  for (int a = 0; a < NC; ++a) dF.topLeftCorner<2, 2>() += g.u[grid.node(c, a)] * dN.row(a);
  return dF;
}

}  // namespace

void interpolate_to_particles(const StepContext& ctx, const Cells& grid, const Nodes<2>& grid_nodes,
                              const PointLocations& loc, Points<2>& particles) {
  const Nodes<2>& g = grid_nodes;
  const bool dynamic = particles.v.used() && g.a.used(), mixed = particles.pressure.used() && g.p.used();
  const bool osgs = particles.proj_u.used() && g.proj_u.used();
  for_each_index(particles.X.size(), [&](Index p) {
    const Index c = loc.cell[p];
    const Index* corner = grid.cell_nodes(c);
    const Vec4& N = loc.N[p];
    const int nc = grid.stride;
    particles.u[p] += interpolate<Vec2>(nc, corner, N, g.u);
    const Mat3 dF = nc == 4 ? increment_gradient<4>(grid, g, c, N) : increment_gradient<3>(grid, g, c, N);
    particles.F[p] = dF * particles.F[p];
    if (dynamic) {
      const Vec2 a_new = interpolate<Vec2>(nc, corner, N, g.a);
      particles.v[p] += ctx.dt * ((1.0 - kNewmarkGamma) * particles.a[p] + kNewmarkGamma * a_new);
      particles.a[p] = a_new;
    }
    if (mixed) particles.pressure[p] = interpolate<double>(nc, corner, N, g.p);
    if (osgs) {
      particles.proj_u[p] = interpolate<Vec2>(nc, corner, N, g.proj_u);
      particles.proj_p[p] = interpolate<double>(nc, corner, N, g.proj_p);
    }
  });
}

void move_with_grid(const StepContext&, const Cells& grid, const Nodes<2>& grid_nodes, const GridActivity& activity,
                    const PointLocations& loc, Points<2>& points) {
  for_each_index(points.X.size(), [&](Index p) {
    Vec4 N;
    const Index c = host_active_cell(grid, grid_nodes, activity, loc.cell[p], points.position(p), N);
    if (c != kNoIndex) points.u[p] += interpolate<Vec2>(grid.stride, grid.cell_nodes(c), N, grid_nodes.u);
  });
}

}  // namespace loom
