#include "systems/output/mesh_energy.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <variant>

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

// The stored energy of the smoothed elements' domains: psi(b^e_n) per unit reference volume V_0 = V_n / sqrt(det b^e_n)
// (Hencky), or per unit volume of the reference geometry with eps = (b^e - I) / 2 (Hooke). For the mixed elements
// (es_up, fem_up) only psi's deviatoric part: their volumetric energy is that of the pressure unknown (below).
template <int D>
double domain_energy(const std::vector<BodyMaterial>& materials, const std::vector<Edges<D>>& domains, bool deviatoric_only) {
  double energy = 0.0;
  for (const Edges<D>& e : domains) {
    const bool deviatoric = deviatoric_only && has_pressure(e.stencil.formulation);
    for (Index k = 0; k < e.size(); ++k) {
      const BodyMaterial& m = materials[std::size_t(e.stencil.body[k])];
      const Mat3& be = e.be_n[k];
      if (const auto* hp = std::get_if<HenckyPerzyna>(&m.model)) {
        const double det = be.determinant();
        energy += e.volume_n[k] / std::sqrt(det) * hp->energy(deviatoric ? Mat3(be / std::cbrt(det)) : be);
      } else if (const auto* le = std::get_if<LinearElastic>(&m.model)) {  // the history holds I + 2 eps
        const Mat3 eps = 0.5 * (be - Mat3::Identity());
        const Mat3 dev = eps - eps.trace() / 3.0 * Mat3::Identity();
        energy += e.volume_n[k] * (deviatoric ? le->mu * dev.squaredNorm() : 0.5 * le->lambda * eps.trace() * eps.trace() + le->mu * eps.squaredNorm());
      }
    }
  }
  return energy;
}

// The volumetric energy of a mixed smoothed element's triangle: 1/2 p^T K_pp,K p with the element's own pressure
// mass K_pp,K,ab = A_0 (1 + d_ab) / (12 K) (eq 42; assemble_domains; a tetrahedron's V_0 (1 + d_ab) / (20 K)). With the weak constraint solved, this is the
// volumetric part of the condensed stiffness's energy (small strains: 1/2 u^T G K_pp^-1 G^T u); psi's own volumetric
// part exceeds it by the pressure's projection error, which swings with the deformation (2 % of the energy of a
// bending fem_up beam). The PPP term (alpha_stab) is left out, as for p1p1_uphi.
template <int D>
double pressure_energy(const BodyMaterial& m, const Nodes<D>& nodes, const Cells& cells, Index c) {
  Eigen::Matrix<double, D + 1, 1> p;
  for (int a = 0; a < D + 1; ++a) p[a] = nodes.p_n[cells.node(c, a)];
  constexpr double mass_denominator = D == 2 ? 12.0 : 20.0;
  return 0.5 * m.inverse_bulk * cells.measure[c] / mass_denominator * (p.squaredNorm() + p.sum() * p.sum());
}

}  // namespace

template <int D>
MeshEnergy mesh_energy(const std::vector<BodyMaterial>& materials, const Nodes<D>& nodes, const std::vector<Cells>& cells,
                       const std::vector<QuadPoints<D>>& quad, const BoundaryConditions<D>& bc, const std::vector<Edges<D>>* domains) {
  MeshEnergy e;
  if (nodes.v_n.used() && nodes.lumped_mass.used())
    for (Index i = 0; i < nodes.size(); ++i) e.kinetic += 0.5 * nodes.lumped_mass[i] * nodes.v_n[i].squaredNorm();
  if (domains) e.elastic += domain_energy(materials, *domains, nodes.p_n.used());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (integrates_on_domains(cells[k].formulation)) {  // its energy is its domains' (and its pressure's)
      if (has_pressure(cells[k].formulation) && nodes.p_n.used() && cells[k].measure.used())
        for (Index c = 0; c < cells[k].size(); ++c) e.elastic += pressure_energy(materials[std::size_t(cells[k].body[c])], nodes, cells[k], c);
      continue;
    }
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
        const auto* hp = std::get_if<HenckyPerzyna>(&m.model);
        const double psi = hp && q.be_n.used() ? hp->energy(q.be_n[point]) : elastic_energy(m, F);  // a yielding Hencky: of its b^e
        e.elastic += (mixed ? share : q.weight_n[point] / F.determinant()) * psi;
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
                                   const std::vector<QuadPoints<2>>&, const BoundaryConditions<2>&, const std::vector<Edges<2>>*);
template MeshEnergy mesh_energy<3>(const std::vector<BodyMaterial>&, const Nodes<3>&, const std::vector<Cells>&,
                                   const std::vector<QuadPoints<3>>&, const BoundaryConditions<3>&, const std::vector<Edges<3>>*);

}  // namespace loom
