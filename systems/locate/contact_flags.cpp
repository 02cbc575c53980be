#include "systems/locate/contact_flags.hpp"

#include "engine/core/parallel.hpp"

namespace loom {

std::vector<unsigned char> find_wall_sides(const Cells& grid, const BoundaryConditions<2>& bc, Index n_nodes,
                                           const std::vector<char>* interface_node) {
  std::vector<unsigned char> held(std::size_t(n_nodes), 0);  // bit d: component d prescribed
  for (const auto& p : bc.prescribed)
    if (p.dof % bc.per_node < 2) held[std::size_t(p.node)] |= (unsigned char)(1u << (p.dof % bc.per_node));
  std::vector<unsigned char> walls(std::size_t(grid.size()), 0);
  if (grid.stride != 9) return walls;
  for (Index c = 0; c < grid.size(); ++c)
    for (int s = 0; s < 4; ++s) {
      bool wall = true, shared = interface_node != nullptr;
      for (int a : {s, 4 + s, (s + 1) % 4}) {
        wall = wall && held[std::size_t(grid.node(c, a))] == 3;
        shared = shared && (*interface_node)[std::size_t(grid.node(c, a))];
      }
      wall = wall || shared;
      if (wall) walls[std::size_t(c)] |= (unsigned char)(1u << s);
    }
  return walls;
}

void flag_soft_cells(const StepContext&, const Cells& grid, const std::vector<char>& outside_node, GridActivity& act) {
  if (act.flags_version == act.version && act.inside_nodes.size() == act.active_cells.size()) return;
  std::vector<char> outside = outside_node;
  for (Index c = 0; c < grid.size(); ++c)
    if (!act.cell_active[std::size_t(c)])
      for (int a = 0; a < grid.stride; ++a) outside[std::size_t(grid.node(c, a))] = 1;
  act.inside_nodes.assign(act.active_cells.size(), 0);
  for (std::size_t k = 0; k < act.active_cells.size(); ++k)
    for (int a = 0; a < grid.stride; ++a) act.inside_nodes[k] += !outside[std::size_t(grid.node(act.active_cells[k], a))];
  act.flags_version = act.version;
}

void mark_receding_particles(const StepContext&, const Cells& grid, const Nodes<2>& g, const std::vector<unsigned char>& wall_sides,
                             const Points<2>& particles, PointLocations& loc) {
  for_each_index(particles.X.size(), [&](Index p) {
    loc.receding[p] = kNoIndex;
    const Index c = loc.cell[p];
    const unsigned mask = wall_sides[std::size_t(c)];
    if (mask == 0) return;
    double fastest = 0.0;
    for (int s = 0; s < 4; ++s) {
      if (!(mask & (1u << s))) continue;
      // Inward normal: the cell lies to the left of its counter-clockwise side.
      const Vec2 d = g.X[grid.node(c, (s + 1) % 4)] - g.X[grid.node(c, s)];
      // Relative to the side's mid-node: a wall is at rest, an FEM body's face moves (seed 004 §5).
      const Vec2 v = g.v.used() ? Vec2(particles.v[p] - g.v[grid.node(c, 4 + s)]) : particles.v[p];
      const double away = v.dot(Vec2(-d.y(), d.x())) / d.norm();
      if (away > fastest) fastest = away, loc.receding[p] = s;
    }
  });
}

}  // namespace loom
