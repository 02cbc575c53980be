// Accepts a converged step on the integration domains of seed 001 (run after commit_step, which moved
// u_n): the history b^e_n <- b^e, each triangle's stored stress (the mean of its three edges' stress, or
// its own domain's for fem_up / fem_u; seed 001 §3.5, what output and probes read; a tetrahedron's: the mean
// of its four faces'), the particles' nodal J
// where it is kept (es_pfem: J^l_n+1 = J^l_n j^l, j^l = sum_k j^k V^k / sum_k V^k over the domains whose
// pressure node l is, V^k at t_n+1; eq 56, the dimension factor h cancels), and the domains' geometry in
// the new B_n.
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"

namespace loom {

template <int D>
void commit_domains(const StepContext& ctx, const std::vector<Cells>& cells, Nodes<D>& nodes, std::vector<QuadPoints<D>>& quad,
                    std::vector<Edges<D>>& edges);

// J^k of domain k: the mean nodal J of its pressure nodes (an edge's two ends, a triangle's corners; a face's
// three nodes, a tetrahedron's corners).
template <int D>
double domain_nodal_jacobian(const Nodes<D>& nodes, const Edges<D>& e, Index k);
// The isochoric part of b^e with the volume ratio J: (J^2 / det b^e)^(1/3) b^e.
Mat3 with_volume_ratio(const Mat3& be, double J);
// b^e_n <- with_volume_ratio(b^e_n, J^k) (eq 56's back projection; domains with j_projection, after
// update_nodal_jacobian).
template <int D>
void project_volumetric_part(const Nodes<D>& nodes, Edges<D>& e);

// J^l *= j^l from the domains' det f of the step (eq 56).
template <int D>
void update_nodal_jacobian(const std::vector<Edges<D>>& edges, Nodes<D>& nodes);

// The simplices' stored stress from their domains (also at set-up and after a restore).
template <int D>
void domain_stress_to_cells(const std::vector<Edges<D>>& edges, std::vector<QuadPoints<D>>& quad);

}  // namespace loom
