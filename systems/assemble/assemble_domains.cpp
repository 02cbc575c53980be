#include "systems/assemble/assemble_domains.hpp"

#include "engine/mesh/tet_mesh.hpp"
#include "engine/mesh/triangle_geometry.hpp"
#include "systems/assemble/cell_scatterer.hpp"
#include "systems/assemble/elements/smoothed_domain.hpp"

namespace loom {
namespace {

template <int NEN, bool Mixed, int D>
void assemble_domains(const StepContext& ctx, bool tangent, const std::vector<BodyMaterial>& materials, const Nodes<D>& nodes,
                      const BoundaryConditions<D>& bc, Edges<D>& domains, const CellScatter& scatter, LinearSystem& system,
                      std::atomic<Index>& inverted) {
  using L = SmoothedLayout<NEN, Mixed, D>;
  LocalMap<L::size> map{};
  if constexpr (Mixed) {
    for (int k = 0; k < L::size; ++k) map.to_scatter[k] = k;  // D + 1 dofs per node in the run: the same layout
  } else {
    map = displacement_map<NEN, D>(system.dofs.per_node);
  }
  const CellScatterer<L::size, D> out(map, scatter, bc, nodes, system);
  const Cells& stencil = domains.stencil;
  const auto ahead = [&](Index k) {
    if (tangent) out.prefetch_row(k);
    prefetch_object(domains.be_n[k]);
    for (int a = 0; a < NEN; ++a) {
      const Index n = stencil.node(k, a);
      prefetch_object(nodes.u[n]), prefetch_object(nodes.u_n[n]);
    }
  };
  for_each_cell_by_colour_looking_ahead(stencil, ahead, [&](Index k) {
    if (tangent) out.prefetch_entries(k);
    SmoothedDomain<NEN, D> d;
    for (int a = 0; a < NEN; ++a) {
      const Index n = stencil.node(k, a);
      d.du.row(a) = (nodes.u[n] - nodes.u_n[n]).transpose();
      if constexpr (Mixed) d.p[a] = nodes.p[n];
      d.Np[a] = domains.pressure_weight[k * NEN + a];
    }
    d.b = Eigen::Map<const NodalVectors<NEN, D>>(domains.gradient(k));
    d.V_n = domains.volume_n[k];
    d.be_n = domains.be_n[k];
    d.dt = ctx.dt;
    typename L::Vector gap;
    const bool lagging = out.gap(k, gap);
    const bool need_K = tangent || lagging;
    typename L::Vector r = L::Vector::Zero();
    typename L::Matrix K = L::Matrix::Zero();
    SmoothedDomainState state;
    const BodyMaterial& material = materials[std::size_t(stencil.body[k])];
    const bool ok = std::visit([&](const auto& m) { return smoothed_domain<NEN, Mixed>(m, d, r, need_K ? &K : nullptr, state); },
                               material.model);
    if (!ok) return void(inverted.fetch_add(1, std::memory_order_relaxed));
    domains.be[k] = state.be, domains.stress[k] = state.sigma, domains.jacobian_step[k] = state.j;
    if (lagging) r += K * gap;
    out.scatter(k, r, tangent ? &K : nullptr);
  });
}

double signed_measure(const Nodes<2>& nodes, const Cells& cells, Index c) {
  return signed_area(nodes.position(cells.node(c, 0)), nodes.position(cells.node(c, 1)), nodes.position(cells.node(c, 2)));
}
double signed_measure(const Nodes<3>& nodes, const Cells& cells, Index c) {
  return tet_volume(nodes.position(cells.node(c, 0)), nodes.position(cells.node(c, 1)), nodes.position(cells.node(c, 2)),
                    nodes.position(cells.node(c, 3)));
}

}  // namespace

template <int D>
void assemble_domain_block(const StepContext& ctx, bool tangent, const std::vector<BodyMaterial>& materials, const Nodes<D>& nodes,
                           const BoundaryConditions<D>& bc, Edges<D>& domains, const CellScatter& scatter, LinearSystem& system,
                           std::atomic<Index>& inverted) {
  // The stencil of an interior edge (face) has D + 2 nodes, that of a boundary one or a whole simplex D + 1.
  const bool mixed = has_pressure(domains.stencil.formulation);
  if (domains.stride() == D + 2) {
    if (mixed) assemble_domains<D + 2, true, D>(ctx, tangent, materials, nodes, bc, domains, scatter, system, inverted);
    else assemble_domains<D + 2, false, D>(ctx, tangent, materials, nodes, bc, domains, scatter, system, inverted);
  } else {
    if (mixed) assemble_domains<D + 1, true, D>(ctx, tangent, materials, nodes, bc, domains, scatter, system, inverted);
    else assemble_domains<D + 1, false, D>(ctx, tangent, materials, nodes, bc, domains, scatter, system, inverted);
  }
}

template <int D>
Index inverted_simplices(const Nodes<D>& nodes, const Cells& cells) {
  std::atomic<Index> bad{0};
  for_each_index(cells.size(), [&](Index c) {
    if (!(signed_measure(nodes, cells, c) > 0.0)) bad.fetch_add(1, std::memory_order_relaxed);
  });
  return bad.load();
}

template <int D>
void assemble_simplex_pressure_terms(bool tangent, const std::vector<BodyMaterial>& materials, const Nodes<D>& nodes,
                                     const BoundaryConditions<D>& bc, const Cells& cells, const CellScatter& scatter, LinearSystem& system) {
  constexpr int N = D + 1;
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  LocalMap<N> map{};
  for (int a = 0; a < N; ++a) map.to_scatter[a] = (D + 1) * a + D;
  const CellScatterer<N, D> out(map, scatter, bc, nodes, system);
  for_each_cell_by_colour(cells, [&](Index c) {
    const BodyMaterial& material = materials[std::size_t(cells.body[c])];
    Vector p, gap, r = Vector::Zero();
    for (int a = 0; a < N; ++a) p[a] = nodes.p[cells.node(c, a)];
    Matrix K = Matrix::Zero();
    simplex_pressure_terms<D>(cells.measure[c], material.inverse_bulk, material.alpha_over_G, p, r, &K);
    if (out.gap(c, gap)) r += K * gap;
    out.scatter(c, r, tangent ? &K : nullptr);
  });
}

template void assemble_domain_block<2>(const StepContext&, bool, const std::vector<BodyMaterial>&, const Nodes<2>&, const BoundaryConditions<2>&,
                                       Edges<2>&, const CellScatter&, LinearSystem&, std::atomic<Index>&);
template void assemble_domain_block<3>(const StepContext&, bool, const std::vector<BodyMaterial>&, const Nodes<3>&, const BoundaryConditions<3>&,
                                       Edges<3>&, const CellScatter&, LinearSystem&, std::atomic<Index>&);
template Index inverted_simplices<2>(const Nodes<2>&, const Cells&);
template Index inverted_simplices<3>(const Nodes<3>&, const Cells&);
template void assemble_simplex_pressure_terms<2>(bool, const std::vector<BodyMaterial>&, const Nodes<2>&, const BoundaryConditions<2>&,
                                                 const Cells&, const CellScatter&, LinearSystem&);
template void assemble_simplex_pressure_terms<3>(bool, const std::vector<BodyMaterial>&, const Nodes<3>&, const BoundaryConditions<3>&,
                                                 const Cells&, const CellScatter&, LinearSystem&);

}  // namespace loom
