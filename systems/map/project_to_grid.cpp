#include "systems/map/project_to_grid.hpp"

namespace loom {

template <int D>
void project_to_grid(const StepContext&, const Cells& grid, const Points<D>& particles, const PointLocations& loc,
                     Nodes<D>& grid_nodes) {
  Nodes<D>& g = grid_nodes;
  const bool dynamic = g.v_n.used(), mixed = g.p.used(), osgs = g.proj_u.used(), volumes = g.lumped_volume.used();
  // 1. Reset: the grid starts the step undeformed and empty.
  for_each_index(g.size(), [&](Index i) {
    g.u[i].setZero();
    g.lumped_mass[i] = 0.0;
    if (dynamic) g.v_n[i].setZero(), g.a_n[i].setZero(), g.v[i].setZero(), g.a[i].setZero();
    if (mixed) g.p[i] = 0.0;
    if (osgs) g.proj_u[i].setZero(), g.proj_p[i] = 0.0;
    if (volumes) g.lumped_volume[i] = 0.0;
  });
  // 2. Mass-weighted sums, cell by cell (race-free: the cells of a colour share no node).
  const auto ahead = [&](Index c) {
    loc.prefetch_points_in(c, particles.mass, loc.N, particles.v, particles.a, particles.pressure, particles.proj_u, particles.proj_p);
    if (volumes) loc.prefetch_points_in(c, particles.volume, particles.F);
  };
  for_each_occupied_cell_by_colour_looking_ahead(grid, loc, ahead, [&](Index c) {
    const Index* corner = grid.cell_nodes(c);
    const Index* pts = loc.points_in(c);
    for (Index k = 0; k < loc.count_in(c); ++k) {
      const Index p = pts[k];
      const double m = particles.mass[p];
      for (int a = 0; a < grid.stride; ++a) {
        const Index i = corner[a];
        const double w = loc.N[p][a] * m;
        g.lumped_mass[i] += w;
        if (dynamic) g.v_n[i] += w * particles.v[p], g.a_n[i] += w * particles.a[p];
        if (mixed) g.p[i] += w * particles.pressure[p];
        if (osgs) g.proj_u[i] += w * particles.proj_u[p], g.proj_p[i] += w * particles.proj_p[p];
        if (volumes) g.lumped_volume[i] += loc.N[p][a] * particles.volume[p] * particles.F[p].determinant();
      }
    }
  });
  // 3. Divide by the nodal mass (nodes without mass stay zero: they are inactive).
  for_each_index(g.size(), [&](Index i) {
    const double m = g.lumped_mass[i];
    if (!(m > 0.0)) return;
    if (dynamic) g.v_n[i] /= m, g.a_n[i] /= m, g.v[i] = g.v_n[i], g.a[i] = g.a_n[i];
    if (mixed) g.p[i] /= m;
    if (osgs) g.proj_u[i] /= m, g.proj_p[i] /= m;
  });
}


template void project_to_grid<2>(const StepContext&, const Cells&, const Points<2>&, const PointLocations&, Nodes<2>&);
template void project_to_grid<3>(const StepContext&, const Cells&, const Points<3>&, const PointLocations&, Nodes<3>&);

}  // namespace loom
