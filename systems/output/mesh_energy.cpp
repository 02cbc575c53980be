#include "systems/output/mesh_energy.hpp"

#include "systems/output/elastic_energy.hpp"

namespace loom {

MeshEnergy mesh_energy(const std::vector<BodyMaterial>& materials, const Nodes<2>& nodes, const std::vector<Cells>& cells,
                       const std::vector<QuadPoints<2>>& quad, const BoundaryConditions<2>& bc) {
  MeshEnergy e;
  if (nodes.v_n.used() && nodes.lumped_mass.used())
    for (Index i = 0; i < nodes.size(); ++i) e.kinetic += 0.5 * nodes.lumped_mass[i] * nodes.v_n[i].squaredNorm();
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const QuadPoints<2>& q = quad[k];
    for (Index c = 0; c < cells[k].size(); ++c) {
      const BodyMaterial& m = materials[std::size_t(cells[k].body[c])];
      for (int i = 0; i < q.per_cell; ++i) {
        const Index point = c * q.per_cell + i;
        const Mat3& F = q.F_n[point];
        e.elastic += q.weight_n[point] / F.determinant() * elastic_energy(m, F);
      }
    }
  }
  const int pn = bc.per_node;
  if (bc.external.size() > 0)
    for (Index i = 0; i < nodes.size(); ++i)
      for (int d = 0; d < 2; ++d) e.potential -= bc.external[i * pn + d] * nodes.u_n[i][d];
  return e;
}

}  // namespace loom
