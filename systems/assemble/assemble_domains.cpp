#include "systems/assemble/assemble_domains.hpp"

#include "engine/mesh/triangle_geometry.hpp"
#include "systems/assemble/cell_scatterer.hpp"
#include "systems/assemble/elements/smoothed_domain.hpp"

namespace loom {
namespace {

template <int NEN, bool Mixed>
void assemble_domains(const StepContext& ctx, bool tangent, const std::vector<BodyMaterial>& materials, const Nodes<2>& nodes,
                      const BoundaryConditions<2>& bc, Edges<2>& domains, const CellScatter& scatter, LinearSystem& system,
                      std::atomic<Index>& inverted) {
  using L = SmoothedLayout<NEN, Mixed>;
  LocalMap<L::size> map{};
  if constexpr (Mixed) {
    for (int k = 0; k < L::size; ++k) map.to_scatter[k] = k;  // three dofs per node in the run: the same layout
  } else {
    map = displacement_map<NEN>(system.dofs.per_node);
  }
  const CellScatterer<L::size> out(map, scatter, bc, nodes, system);
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
    SmoothedDomain<NEN> d;
    for (int a = 0; a < NEN; ++a) {
      const Index n = stencil.node(k, a);
      d.du.row(a) = (nodes.u[n] - nodes.u_n[n]).transpose();
      if constexpr (Mixed) d.p[a] = nodes.p[n];
      d.Np[a] = domains.pressure_weight[k * NEN + a];
    }
    d.b = Eigen::Map<const NodalVectors<NEN>>(domains.gradient(k));
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

}  // namespace

void assemble_domain_block(const StepContext& ctx, bool tangent, const std::vector<BodyMaterial>& materials, const Nodes<2>& nodes,
                           const BoundaryConditions<2>& bc, Edges<2>& domains, const CellScatter& scatter, LinearSystem& system,
                           std::atomic<Index>& inverted) {
  const bool mixed = has_pressure(domains.stencil.formulation);
  if (domains.stride() == 4) {
    if (mixed) assemble_domains<4, true>(ctx, tangent, materials, nodes, bc, domains, scatter, system, inverted);
    else assemble_domains<4, false>(ctx, tangent, materials, nodes, bc, domains, scatter, system, inverted);
  } else {
    if (mixed) assemble_domains<3, true>(ctx, tangent, materials, nodes, bc, domains, scatter, system, inverted);
    else assemble_domains<3, false>(ctx, tangent, materials, nodes, bc, domains, scatter, system, inverted);
  }
}

Index inverted_triangles(const Nodes<2>& nodes, const Cells& cells) {
  std::atomic<Index> bad{0};
  for_each_index(cells.size(), [&](Index c) {
    if (!(signed_area(nodes.position(cells.node(c, 0)), nodes.position(cells.node(c, 1)), nodes.position(cells.node(c, 2))) > 0.0))
      bad.fetch_add(1, std::memory_order_relaxed);
  });
  return bad.load();
}

void assemble_triangle_pressure_terms(bool tangent, const std::vector<BodyMaterial>& materials, const Nodes<2>& nodes,
                                      const BoundaryConditions<2>& bc, const Cells& cells, const CellScatter& scatter,
                                      LinearSystem& system) {
  LocalMap<3> map{};
  for (int a = 0; a < 3; ++a) map.to_scatter[a] = 3 * a + 2;
  const CellScatterer<3> out(map, scatter, bc, nodes, system);
  for_each_cell_by_colour(cells, [&](Index c) {
    const BodyMaterial& material = materials[std::size_t(cells.body[c])];
    Vec3 p, gap, r = Vec3::Zero();
    for (int a = 0; a < 3; ++a) p[a] = nodes.p[cells.node(c, a)];
    Mat3 K = Mat3::Zero();
    triangle_pressure_terms(cells.measure[c], material.inverse_bulk, material.alpha_over_G, p, r, &K);
    if (out.gap(c, gap)) r += K * gap;
    out.scatter(c, r, tangent ? &K : nullptr);
  });
}

}  // namespace loom
