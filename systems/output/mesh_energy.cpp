#include "systems/output/mesh_energy.hpp"

#include "systems/output/elastic_energy.hpp"

namespace loom {
namespace {

template <int D>
double reference_simplex_volume(const Nodes<D>& nodes, const Cells& cells, Index c) {
  if constexpr (D == 2) {
    const Vec2 a = nodes.X[cells.node(c, 1)] - nodes.X[cells.node(c, 0)], b = nodes.X[cells.node(c, 2)] - nodes.X[cells.node(c, 0)];
    return 0.5 * (a.x() * b.y() - a.y() * b.x());
  } else {
    const Vec3& o = nodes.X[cells.node(c, 0)];
    return (nodes.X[cells.node(c, 1)] - o).cross(nodes.X[cells.node(c, 2)] - o).dot(nodes.X[cells.node(c, 3)] - o) / 6.0;
  }
}

}  // namespace

template <int D>
MeshEnergy mesh_energy(const std::vector<BodyMaterial>& materials, const Nodes<D>& nodes, const std::vector<Cells>& cells,
                       const std::vector<QuadPoints<D>>& quad, const BoundaryConditions<D>& bc) {
  MeshEnergy e;
  if (nodes.v_n.used() && nodes.lumped_mass.used())
    for (Index i = 0; i < nodes.size(); ++i) e.kinetic += 0.5 * nodes.lumped_mass[i] * nodes.v_n[i].squaredNorm();
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const QuadPoints<D>& q = quad[k];
    const bool mixed = has_dilatation(cells[k].formulation);
    for (Index c = 0; c < cells[k].size(); ++c) {
      const BodyMaterial& m = materials[std::size_t(cells[k].body[c])];
      // p1p1_uphi: F_n holds F~ (det F~ = phi, not J), so dV_0 comes from the reference simplex, shared equally by
      // its D + 1 points; the energy is that of F~ (the PPP term, a stabilisation, is left out).
      const double share = mixed ? reference_simplex_volume(nodes, cells[k], c) / q.per_cell : 0.0;
      for (int i = 0; i < q.per_cell; ++i) {
        const Index point = c * q.per_cell + i;
        const Mat3& F = q.F_n[point];
        e.elastic += (mixed ? share : q.weight_n[point] / F.determinant()) * elastic_energy(m, F);
      }
    }
  }
  const int pn = bc.per_node;
  if (bc.external.size() > 0)
    for (Index i = 0; i < nodes.size(); ++i)
      for (int d = 0; d < D; ++d) e.potential -= bc.external[i * pn + d] * nodes.u_n[i][d];
  return e;
}

template MeshEnergy mesh_energy<2>(const std::vector<BodyMaterial>&, const Nodes<2>&, const std::vector<Cells>&,
                                   const std::vector<QuadPoints<2>>&, const BoundaryConditions<2>&);
template MeshEnergy mesh_energy<3>(const std::vector<BodyMaterial>&, const Nodes<3>&, const std::vector<Cells>&,
                                   const std::vector<QuadPoints<3>>&, const BoundaryConditions<3>&);

}  // namespace loom
