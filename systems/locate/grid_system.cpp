#include "systems/locate/grid_system.hpp"

#include "systems/locate/ghost_faces.hpp"


namespace loom {

template <int D>
void build_grid_system(const Cells& grid, const BoundaryConditions<D>& bc, bool ghost, GridActivity& activity, LinearSystem& system) {
  const Index n_cells = grid.size(), n_nodes = Index(bc.target.size()) / bc.per_node;
  const int nc = grid.stride;
  // 1. The base cells and their nodes; the system cells: those and every cell sharing a node with them.
  std::vector<char> in_base(std::size_t(n_cells), 0), base_node(std::size_t(n_nodes), 0), other_node(std::size_t(n_nodes), 0);
  for (Index c : activity.system_base) in_base[std::size_t(c)] = 1;
  for (Index c = 0; c < n_cells; ++c)
    for (int a = 0; a < nc; ++a) (in_base[std::size_t(c)] ? base_node : other_node)[std::size_t(grid.node(c, a))] = 1;
  auto has_node = [&](Index c, const std::vector<char>& flag) {
    for (int a = 0; a < nc; ++a)
      if (flag[std::size_t(grid.node(c, a))]) return true;
    return false;
  };
  activity.system_cells.clear();
  activity.scatter_entry.assign(std::size_t(n_cells), kNoIndex);
  for (Index c = 0; c < n_cells; ++c)
    if (in_base[std::size_t(c)] || has_node(c, base_node)) {
      activity.scatter_entry[std::size_t(c)] = Index(activity.system_cells.size());
      activity.system_cells.push_back(c);
    }

  // 2. With the ghost penalty: the sides where a ghost face may appear. A ghost face lies between two active
  // cells of which one is cut (has a node of an inactive cell); after a move by one layer, a cut cell is a
  // cell with a node on the base's boundary (a base cell or a layer cell), or a base cell sharing a node with
  // such a base cell.
  Cells band_faces(grid.type, grid.formulation);
  if (ghost) {
    std::vector<char> boundary_node(std::size_t(n_nodes), 0), band(std::size_t(n_cells), 0), inner_band_node(std::size_t(n_nodes), 0);
    for (Index i = 0; i < n_nodes; ++i) boundary_node[std::size_t(i)] = base_node[std::size_t(i)] && other_node[std::size_t(i)];
    for (Index c : activity.system_cells)
      if (has_node(c, boundary_node)) {
        band[std::size_t(c)] = 1;
        if (in_base[std::size_t(c)])
          for (int a = 0; a < nc; ++a) inner_band_node[std::size_t(grid.node(c, a))] = 1;
      }
    for (Index c : activity.system_base)
      if (has_node(c, inner_band_node)) band[std::size_t(c)] = 1;
    const int sides = grid.sides();
    band_faces.stride = 2 * nc - 2;
    auto& conn = band_faces.nodes.values();
    for (Index c : activity.system_cells)
      for (int a = 0; a < sides; ++a) {
        const Index n = grid.neighbour[std::size_t(sides) * std::size_t(c) + std::size_t(a)];
        if (n == kNoIndex || n < c || activity.scatter_entry[std::size_t(n)] == kNoIndex || !(band[std::size_t(c)] || band[std::size_t(n)])) continue;
        append_face_nodes(grid, c, a, n, conn);
      }
    band_faces.body.assign(Index(conn.size()) / band_faces.stride, 0);
  }

  // 3. Dofs: absent outside the system cells, prescribed where a boundary prescribes them, free otherwise.
  std::vector<char> system_node(std::size_t(n_nodes), 0);
  for (Index c : activity.system_cells)
    for (int a = 0; a < nc; ++a) system_node[std::size_t(grid.node(c, a))] = 1;
  const int pn = bc.per_node;
  std::vector<DofKind> kinds(std::size_t(n_nodes) * std::size_t(pn), DofKind::free);
  for (Index i = 0; i < n_nodes; ++i)
    if (!system_node[std::size_t(i)])
      for (int d = 0; d < pn; ++d) kinds[std::size_t(i) * std::size_t(pn) + std::size_t(d)] = DofKind::absent;
  for (const auto& p : bc.prescribed)
    if (kinds[std::size_t(p.dof)] == DofKind::free) kinds[std::size_t(p.dof)] = DofKind::prescribed;
  system.dofs.build(pn, std::move(kinds));

  // 4. Pattern and the cells' scatter.
  if (ghost) build_pattern({&grid, &band_faces}, system.dofs, system.pattern, {&activity.system_cells, nullptr});
  else build_pattern({&grid}, system.dofs, system.pattern, {&activity.system_cells});
  system.scatter.resize(ghost ? 2 : 1);
  build_scatter(grid, system.dofs, system.pattern, system.scatter[0], &activity.system_cells);
  if (ghost) system.scatter[1] = CellScatter{};
  system.resize_vectors();
  ++activity.rebuilds;
}

bool fit_grid_system(bool ghost, GridActivity& activity, LinearSystem& system) {
  if (activity.system_cells.empty() || 2 * activity.active_cells.size() < activity.system_base.size()) return false;
  for (Index c : activity.active_cells)
    if (activity.scatter_entry[std::size_t(c)] == kNoIndex) return false;
  if (ghost) {
    bool complete = true;
    build_scatter(activity.ghost_faces, system.dofs, system.pattern, system.scatter[1], nullptr, &complete);
    if (!complete) return false;
  }
  const DofMap& dofs = system.dofs;
  activity.dormant_dofs.clear();
  for (Index i = 0; i < dofs.n_nodes(); ++i) {
    if (activity.node_active[std::size_t(i)]) continue;
    for (int d = 0; d < dofs.per_node; ++d)
      if (dofs.kind[std::size_t(dofs.dof(i, d))] == DofKind::free) activity.dormant_dofs.push_back(dofs.dof(i, d));
  }
  return true;
}


template void build_grid_system<2>(const Cells&, const BoundaryConditions<2>&, bool, GridActivity&, LinearSystem&);
template void build_grid_system<3>(const Cells&, const BoundaryConditions<3>&, bool, GridActivity&, LinearSystem&);

}  // namespace loom
