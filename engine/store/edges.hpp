// Edges: integration domains that no single cell owns (DESIGN §2), the smoothing domains of the
// edge-based smoothed FEM of seed 001 (§3.3, eqs 30-35). The domain of edge k is made of the sub-triangles
// (a, b, centroid) of the one or two triangles that share k; its volume is V^k = sum_e A_e / 3 and its
// smoothed gradients are the area-weighted means b~_I = (1 / V^k) sum_e (A_e / 3) grad N_I^e over its
// stencil: the edge's nodes a, b and the opposite vertex of each adjacent triangle (4 nodes inside the body,
// 3 on its boundary). The element-integrated variants (fem_up, fem_u) use the same store with one domain
// per triangle: stencil = the corners, V = A_e, b~ = grad N^e (smoothing over one triangle is the
// triangle).
//
// One store holds domains of one stencil size (the connectivity block `stencil` has a fixed stride), so a
// body has two stores (interior and boundary edges) or one (triangles). Geometry is that of B_n: b~ and V_n
// are recomputed at each commit and remesh. History (seed 001 §1.1): the elastic left Cauchy-Green tensor
// b^e of the domain, the only internal variable; J = sqrt(det b^e) because the flow is isochoric.
//
// In 3D (Edges<3>) the domains are those of faces (engine/mesh/smoothing_faces.hpp): the sub-tetrahedra (face,
// centroid) of the one or two tetrahedra that share a face, V^k = sum_e V_e / 4, stencils of 5 nodes inside the
// body and 4 on its surface; fem_up, fem_u have one domain per tetrahedron. "triangles" then holds tetrahedra.
#pragma once

#include "engine/core/types.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/column.hpp"

namespace loom {

template <int D>
struct Edges {
  // Connectivity, body and colour of the domains (type stencil3 or stencil4; 3D: stencil4 or stencil5): slots
  // 0 and 1 are the edge's nodes a, b (for a triangle domain: its corners), slots 2 (, 3) the opposite vertices;
  // 3D: slots 0-2 the face's nodes, 3 (, 4) the opposite vertices.
  Cells stencil{CellType::stencil3};
  // true: each domain is one whole triangle (fem_up, fem_u), not the smoothing domain of an edge.
  bool whole_triangles = false;
  Index cell_block = 0;  // the triangle block (index into the run's Cells stores) the domains were built from
  // Per body (indexed by the stencil's body column): b^e's volumetric part from the nodal J after every step
  // (seed 001 eq 56). Empty: no body asks for it.
  std::vector<char> j_projection;
  // Geometrically linear material (linear_elastic): the geometry stays that of the reference mesh, so that
  // strains and forces are those of small-displacement theory over any number of steps.
  bool reference_geometry = false;
  // The triangles (3D: tetrahedra) of the owning cell block that make up the domain (2 per domain; the second
  // is kNoIndex on the boundary and for triangle domains).
  Column<Index> triangles;
  Column<double> volume_n;         // V^k in B_n, L^D
  Column<double> grad;             // b~_I(x_n): stride * D per domain, 1/L
  Column<double> pressure_weight;  // N_p^k of each stencil node: 1/2 at a and b for an edge, 1/3 per corner of a triangle
                                   // (3D: 1/3 per node of a face, 1/4 per corner of a tetrahedron)
  Column<Vec<D>> midpoint;         // midpoint of the edge (centroid of a triangle domain; 3D: of the face or tetrahedron) in B_n
  Column<Mat3> be_n;               // converged elastic left Cauchy-Green tensor b^e_n (history)
  Column<Mat3> be;                 // b^e at the iterate
  Column<Mat3> stress;             // Cauchy stress at the iterate (output, probes)
  Column<double> jacobian_step;    // j = det f of the step at the iterate (nodal J projection, seed 001 eq 56)

  Edges() {
    triangles.use();
    volume_n.use();
    grad.use();
    pressure_weight.use();
    midpoint.use();
    be_n.use();
    be.use();
    stress.use();
    jacobian_step.use();
  }

  Index size() const { return stencil.size(); }
  int stride() const { return stencil.stride; }

  // Sizes every column to n domains (the stencil connectivity is sized by its builder).
  void resize(Index n) {
    triangles.resize(2 * n, kNoIndex);
    volume_n.resize(n, 0.0);
    grad.resize_strided(n, stride() * D, 0.0);
    pressure_weight.resize_strided(n, stride(), 0.0);
    midpoint.resize(n, Vec<D>::Zero());
    be_n.resize(n, Mat3::Identity());
    be.resize(n, Mat3::Identity());
    stress.resize(n, Mat3::Zero());
    jacobian_step.resize(n, 1.0);
  }

  double* gradient(Index k) { return grad.data() + static_cast<std::size_t>(k) * stride() * D; }
  const double* gradient(Index k) const { return grad.data() + static_cast<std::size_t>(k) * stride() * D; }

  template <class Visit>
  void for_each_column(Visit&& f) {
    stencil.for_each_column(f);
    f("triangles", triangles), f("volume_n", volume_n), f("grad", grad), f("pressure_weight", pressure_weight),
        f("midpoint", midpoint), f("be_n", be_n), f("be", be), f("stress", stress), f("jacobian_step", jacobian_step);
  }
  template <class Visit>
  void for_each_column(Visit&& f) const {
    const_cast<Edges*>(this)->for_each_column([&](const char* name, const auto& c) { f(name, c); });
  }
};

}  // namespace loom
