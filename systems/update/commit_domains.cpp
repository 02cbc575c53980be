#include "systems/update/commit_domains.hpp"

#include <cmath>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "systems/assemble/smoothing_geometry.hpp"

namespace loom {

template <int D>
void domain_stress_to_cells(const std::vector<Edges<D>>& edges, std::vector<QuadPoints<D>>& quad) {
  for (const Edges<D>& e : edges) std::fill(quad[std::size_t(e.cell_block)].stress_n.begin(), quad[std::size_t(e.cell_block)].stress_n.end(), Mat3::Zero());
  // Serial: a simplex gathers from up to D + 1 domains of two stores; this runs once per step.
  for (const Edges<D>& e : edges) {
    QuadPoints<D>& q = quad[std::size_t(e.cell_block)];
    const double share = e.whole_triangles ? 1.0 : 1.0 / double(D + 1);  // every triangle has three edges, a tetrahedron four faces
    for (Index k = 0; k < e.size(); ++k)
      for (int j = 0; j < 2; ++j)
        if (const Index t = e.triangles[2 * k + j]; t != kNoIndex) q.stress_n[t] += share * e.stress[k];
  }
}

template <int D>
void update_nodal_jacobian(const std::vector<Edges<D>>& edges, Nodes<D>& nodes) {
  std::vector<double> jV(std::size_t(nodes.size()), 0.0), V(std::size_t(nodes.size()), 0.0);
  // Serial: nodes gather from many domains; once per step.
  for (const Edges<D>& e : edges) {
    const int S = e.stride();
    for (Index k = 0; k < e.size(); ++k) {
      const double volume = e.jacobian_step[k] * e.volume_n[k];  // V^k at t_n+1
      for (int a = 0; a < S; ++a)
        if (e.pressure_weight[k * S + a] > 0.0) {
          const std::size_t l = std::size_t(e.stencil.node(k, a));
          jV[l] += e.jacobian_step[k] * volume, V[l] += volume;
        }
    }
  }
  for (Index l = 0; l < nodes.size(); ++l)
    if (V[std::size_t(l)] > 0.0) nodes.J_node[l] *= jV[std::size_t(l)] / V[std::size_t(l)];
}

template <int D>
double domain_nodal_jacobian(const Nodes<D>& nodes, const Edges<D>& e, Index k) {
  const int S = e.stride();
  double J = 0.0, w = 0.0;
  for (int a = 0; a < S; ++a)
    if (const double n = e.pressure_weight[k * S + a]; n > 0.0) J += n * nodes.J_node[e.stencil.node(k, a)], w += n;
  return J / w;
}

Mat3 with_volume_ratio(const Mat3& be, double J) { return be * (std::pow(J, 2.0 / 3.0) / std::cbrt(be.determinant())); }

template <int D>
void project_volumetric_part(const Nodes<D>& nodes, Edges<D>& e) {
  for_each_index(e.size(), [&](Index k) {
    if (e.j_projection[std::size_t(e.stencil.body[k])]) e.be_n[k] = e.be[k] = with_volume_ratio(e.be_n[k], domain_nodal_jacobian(nodes, e, k));
  });
}

template <int D>
void commit_domains(const StepContext& ctx, const std::vector<Cells>& cells, Nodes<D>& nodes, std::vector<QuadPoints<D>>& quad,
                    std::vector<Edges<D>>& edges) {
  for (Edges<D>& e : edges) for_each_index(e.size(), [&](Index k) { e.be_n[k] = e.be[k]; });
  domain_stress_to_cells(edges, quad);
  if (nodes.J_node.used()) update_nodal_jacobian(edges, nodes);
  for (Edges<D>& e : edges)
    if (!e.j_projection.empty()) project_volumetric_part(nodes, e);
  Index bad = 0;
  for (Edges<D>& e : edges)
    if (!e.reference_geometry) bad += compute_smoothing_geometry(nodes, cells[std::size_t(e.cell_block)], e);
  LOOM_CHECK(bad == 0, RunError, bad << " smoothing domains are inverted in the converged configuration of step " << ctx.step);
}

#define LOOM_COMMIT_DOMAINS(D)                                                                                                        \
  template void commit_domains<D>(const StepContext&, const std::vector<Cells>&, Nodes<D>&, std::vector<QuadPoints<D>>&,              \
                                  std::vector<Edges<D>>&);                                                                            \
  template double domain_nodal_jacobian<D>(const Nodes<D>&, const Edges<D>&, Index);                                                  \
  template void project_volumetric_part<D>(const Nodes<D>&, Edges<D>&);                                                               \
  template void update_nodal_jacobian<D>(const std::vector<Edges<D>>&, Nodes<D>&);                                                    \
  template void domain_stress_to_cells<D>(const std::vector<Edges<D>>&, std::vector<QuadPoints<D>>&);
LOOM_COMMIT_DOMAINS(2)
LOOM_COMMIT_DOMAINS(3)
#undef LOOM_COMMIT_DOMAINS

}  // namespace loom
