#include "systems/update/lumped_mass.hpp"

#include "systems/assemble/elements/element_mass.hpp"

namespace loom {

template <int D>
void compute_lumped_mass(const std::vector<Cells>& cells, const std::vector<QuadPoints<D>>& quad,
                         const std::vector<BodyMaterial>& materials, Nodes<D>& nodes) {
  nodes.lumped_mass.assign(nodes.size(), 0.0);
  for (std::size_t b = 0; b < cells.size(); ++b) {
    const Cells& cb = cells[b];
    const QuadPoints<D>& qb = quad[b];
    for (Index c = 0; c < cb.size(); ++c) {  // serial: scatter to shared nodes, done once
      // Seed 001's triangles know their reference area (a remeshed triangle has no F of its own).
      double volume0 = 0.0;
      if (integrates_on_domains(cb.formulation) && cb.measure.used()) volume0 = cb.measure[c];
      else
        for (int q = 0; q < qb.per_cell; ++q) volume0 += qb.weight_n[c * qb.per_cell + q] / qb.F_n[c * qb.per_cell + q].determinant();
      const double rho = materials[std::size_t(cb.body[c])].density;
      if (cb.type == CellType::quad9) {
        double dV0[9];
        for (int q = 0; q < 9; ++q) dV0[q] = qb.weight_n[c * 9 + q] / qb.F_n[c * 9 + q].determinant();
        const auto m = quad9_lumped_mass(dV0);
        for (int a = 0; a < 9; ++a) nodes.lumped_mass[cb.node(c, a)] += rho * m[a];
      } else if (cb.type == CellType::tri6) {
        const auto m = tri6_lumped_mass(volume0);
        for (int a = 0; a < 6; ++a) nodes.lumped_mass[cb.node(c, a)] += rho * m[a];
      } else if (cb.type == CellType::tet10) {
        const auto m = tet10_lumped_mass(volume0);
        for (int a = 0; a < 10; ++a) nodes.lumped_mass[cb.node(c, a)] += rho * m[a];
      } else if (cb.type == CellType::tet4) {
        for (int a = 0; a < 4; ++a) nodes.lumped_mass[cb.node(c, a)] += rho * volume0 / 4.0;
      } else {
        for (int a = 0; a < 3; ++a) nodes.lumped_mass[cb.node(c, a)] += rho * volume0 / 3.0;
      }
    }
  }
}

template void compute_lumped_mass<2>(const std::vector<Cells>&, const std::vector<QuadPoints<2>>&, const std::vector<BodyMaterial>&,
                                     Nodes<2>&);
template void compute_lumped_mass<3>(const std::vector<Cells>&, const std::vector<QuadPoints<3>>&, const std::vector<BodyMaterial>&,
                                     Nodes<3>&);

}  // namespace loom
