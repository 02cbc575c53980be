#include "systems/locate/ghost_faces.hpp"

#include "engine/mesh/colouring.hpp"

namespace loom {

std::pair<Index, Index> append_face_nodes(const Cells& grid, Index c, int a, Index n, std::vector<Index>& conn) {
  const auto [i, j] = grid.side_corners(c, a);
  for (int k = 0; k < grid.stride; ++k) conn.push_back(grid.node(c, k));
  for (int k = 0; k < grid.stride; ++k)  // the corners of n off the face, in n's order (ghost_face.hpp)
    if (const Index m = grid.node(n, k); m != i && m != j) conn.push_back(m);
  return {i, j};
}

void find_ghost_faces(const Cells& grid, Index n_nodes, GridActivity& act) {
  const int nc = grid.stride, sides = grid.sides(), nf = 2 * nc - 2;
  // 1. Cut cells: active cells with a corner of an inactive cell.
  std::vector<char> near_inactive(std::size_t(n_nodes), 0);
  for (Index c = 0; c < grid.size(); ++c)
    if (!act.cell_active[std::size_t(c)])
      for (int a = 0; a < nc; ++a) near_inactive[std::size_t(grid.node(c, a))] = 1;
  auto cut = [&](Index c) {
    for (int a = 0; a < nc; ++a)
      if (near_inactive[std::size_t(grid.node(c, a))]) return true;
    return false;
  };
  // 2. Faces between two active cells, one of them cut, each once (from its lower-numbered cell).
  act.ghost_faces = Cells(grid.type, grid.formulation);
  act.ghost_faces.stride = nf;
  auto& conn = act.ghost_faces.nodes.values();
  act.ghost_cells.clear(), act.ghost_ends.clear();
  for (Index c : act.active_cells) {
    const bool c_cut = cut(c);
    for (int a = 0; a < sides; ++a) {
      const Index n = grid.neighbour[std::size_t(sides) * std::size_t(c) + std::size_t(a)];
      if (n == kNoIndex || n < c || !act.cell_active[std::size_t(n)] || !(c_cut || cut(n))) continue;
      const auto [i, j] = append_face_nodes(grid, c, a, n, conn);
      act.ghost_cells.insert(act.ghost_cells.end(), {c, n});
      act.ghost_ends.insert(act.ghost_ends.end(), {i, j});
    }
  }
  act.ghost_faces.body.assign(Index(act.ghost_cells.size() / 2), 0);
  colour_cells(act.ghost_faces, n_nodes);
}

}  // namespace loom
