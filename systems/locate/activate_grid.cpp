#include "systems/locate/activate_grid.hpp"

#include "engine/core/errors.hpp"
#include "systems/locate/ghost_faces.hpp"
#include "systems/locate/grid_system.hpp"

namespace loom {

template <int D>
void activate_grid(const StepContext& ctx, const Cells& grid, const PointLocations& particle_loc, const BoundaryConditions<D>& bc,
                   GridActivity& activity, LinearSystem& system) {
  const Index n_cells = grid.size();
  const Index fem_from = activity.always_active_from == kNoIndex ? n_cells : activity.always_active_from;
  auto active = [&](Index c) { return c >= fem_from || particle_loc.count_in(c) > 0; };
  // 1. Has the active set changed?
  bool changed = activity.cell_active.size() != std::size_t(n_cells) || activity.version == 0;
  if (!changed)
    for (Index c = 0; c < fem_from && !changed; ++c) changed = activity.cell_active[std::size_t(c)] != char(active(c));
  if (!changed) return;

  // 2. Active cells (ascending and by colour) and nodes.
  activity.cell_active.assign(std::size_t(n_cells), 0);
  activity.active_index.assign(std::size_t(n_cells), kNoIndex);
  activity.active_cells.clear();
  const Index n_nodes = Index(bc.target.size()) / bc.per_node;
  activity.node_active.assign(std::size_t(n_nodes), 0);
  for (Index c = 0; c < n_cells; ++c) {
    if (!active(c)) continue;
    activity.cell_active[std::size_t(c)] = 1;
    activity.active_index[std::size_t(c)] = Index(activity.active_cells.size());
    activity.active_cells.push_back(c);
    for (int a = 0; a < grid.stride; ++a) activity.node_active[std::size_t(grid.node(c, a))] = 1;
  }
  activity.colour_offsets.assign(std::size_t(grid.n_colours()) + 1, 0);
  activity.active_by_colour.clear();
  for (Index k = 0; k < grid.n_colours(); ++k) {
    for (Index s = grid.colour_offsets[std::size_t(k)]; s < grid.colour_offsets[std::size_t(k) + 1]; ++s)
      if (activity.cell_active[std::size_t(grid.by_colour[std::size_t(s)])]) activity.active_by_colour.push_back(grid.by_colour[std::size_t(s)]);
    activity.colour_offsets[std::size_t(k) + 1] = Index(activity.active_by_colour.size());
  }
  ++activity.version;

  // 3. The Newton system: the built one if the new active set fits in it, else one built around it (and on a
  // restart, first the one the checkpointed run had).
  const bool ghost = ctx.scene && ctx.scene->grid.ghost_penalty > 0.0;
  if (ghost) find_ghost_faces(grid, n_nodes, activity);
  if (activity.system_cells.empty() && !activity.system_base.empty()) build_grid_system(grid, bc, ghost, activity, system);
  if (fit_grid_system(ghost, activity, system)) return;
  activity.system_base = activity.active_cells;
  build_grid_system(grid, bc, ghost, activity, system);
  LOOM_CHECK(fit_grid_system(ghost, activity, system), RunError, "the grid's Newton system does not hold the active set it was built around");
}


template void activate_grid<2>(const StepContext&, const Cells&, const PointLocations&, const BoundaryConditions<2>&, GridActivity&, LinearSystem&);
template void activate_grid<3>(const StepContext&, const Cells&, const PointLocations&, const BoundaryConditions<3>&, GridActivity&, LinearSystem&);

}  // namespace loom
