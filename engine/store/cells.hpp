// Cells: mesh or grid cells of one type (one store per cell type and body, DESIGN §2).
// Connectivity is flat with a fixed stride; cells are ordered as generated and grouped by colour through
// `by_colour` so that assembly can scatter race-free and deterministically (STYLE §4).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/core/types.hpp"
#include "engine/store/column.hpp"

namespace loom {

// quad4: MPM background grids only. stencil3/stencil4/stencil5: the node stencils of integration domains that
// no single cell owns (edge- and face-based smoothing domains, engine/store/edges.hpp); never output as cells.
// quad9: biquadratic quadrilaterals (engine/mesh/quad9_shape.hpp), corners first, then mid-sides and centre.
// tet4, tet10: linear and quadratic tetrahedra in VTK's node order (systems/assemble/elements/tet4.hpp, tet10.hpp).
enum class CellType { tri3, tri6, quad4, stencil3, stencil4, quad9, tet4, tet10, stencil5 };  // new types at the end (checkpoints)

// Element formulation of a cell block: what the assembly computes on its cells.
//  p1:        linear displacement triangle (tri3, one point);
//  tri6:      quadratic displacement triangle (tri6, three points; seed 000 §4.1);
//  p1p1_uphi: mixed linear triangle, displacement and nodal volume dilatation phi with polynomial
//             pressure projection (tri3, three points; seed 000 §4.2);
//  p1p1_up:   mixed linear displacement / linear pressure on an MPM background grid, material points as
//             quadrature points (seed 003 eqs 16-26).
//  es_up, es_u: edge-based smoothed linear triangles (seed 001 §3): integrated over the smoothing domain of
//             each edge, mixed u-p (nodal pressure, PPP with alpha_stab) or displacement only; on linear
//             tetrahedra face-based smoothed (the domain of each face);
//  fem_up, fem_u: the same kernels integrated over each triangle or tetrahedron (the seed's FEM-UP and FEM-U);
//  quad9:     biquadratic displacement quadrilateral (quad9, 3 x 3 Gauss points; seed 004's FEM bodies).
enum class Formulation { p1, tri6, p1p1_uphi, p1p1_up, es_up, es_u, fem_up, fem_u, quad9 };

inline const char* formulation_name(Formulation f) {
  switch (f) {
    case Formulation::p1: return "p1";
    case Formulation::tri6: return "tri6";
    case Formulation::p1p1_uphi: return "p1p1_uphi";
    case Formulation::p1p1_up: return "p1p1_up";
    case Formulation::es_up: return "es_up";
    case Formulation::es_u: return "es_u";
    case Formulation::fem_up: return "fem_up";
    case Formulation::fem_u: return "fem_u";
    case Formulation::quad9: return "quad9";
  }
  return "?";
}


inline int nodes_per_cell(CellType t) {
  switch (t) {
    case CellType::tri3: case CellType::stencil3: return 3;
    case CellType::quad4: case CellType::stencil4: case CellType::tet4: return 4;
    case CellType::stencil5: return 5;
    case CellType::tri6: return 6;
    case CellType::quad9: return 9;
    case CellType::tet10: return 10;
  }
  return 0;
}
inline CellType cell_type_of(Formulation f) {
  return f == Formulation::tri6 ? CellType::tri6 : f == Formulation::quad9 ? CellType::quad9 : CellType::tri3;
}
// Corner nodes of a cell of `stride` nodes: the first ones of its connectivity (tri3, tri6: 3; quad4, quad9, tet4,
// tet10: 4).
inline int corners_of_stride(int stride) { return stride == 4 || stride == 9 || stride == 10 ? 4 : 3; }
// Formulations with the nodal dilatation phi as an unknown.
inline bool has_dilatation(Formulation f) { return f == Formulation::p1p1_uphi; }
// Formulations with the nodal pressure p as an unknown on a mesh (seed 001 eq 25: sigma = dev sigma + p I).
inline bool has_pressure(Formulation f) { return f == Formulation::es_up || f == Formulation::fem_up; }
// Formulations integrated over domains of the Edges store (seed 001): edges or, for fem_*, whole triangles.
inline bool integrates_on_domains(Formulation f) {
  return f == Formulation::es_up || f == Formulation::es_u || f == Formulation::fem_up || f == Formulation::fem_u;
}
inline bool edge_smoothed(Formulation f) { return f == Formulation::es_up || f == Formulation::es_u; }
inline const char* cell_type_name(CellType t) {
  constexpr const char* names[] = {"tri3", "tri6", "quad4", "stencil3", "stencil4", "quad9", "tet4", "tet10", "stencil5"};
  return names[int(t)];
}

struct Cells {
  CellType type = CellType::tri3;
  Formulation formulation = Formulation::p1;
  int stride = 3;           // nodes per cell
  Column<Index> nodes;      // n_cells * stride node indices, counter-clockwise corners first
  Column<Index> body;       // owning body index
  Column<Index> colour;     // colour of each cell: cells of one colour share no node
  // Background grids only (MPM): the grid never moves, so its geometry is computed once.
  Column<Index> neighbour;  // one per side (side_corners): the cell across it, kNoIndex on the boundary
  Column<double> measure;   // cell area, L^2
  Column<Mat32> gradient;   // tri3: dN^a/dx of the corners (constant over the cell), 1/L; quad4, quad9: unused
  Column<Mat43> gradient_3d;  // tet4 grids: dN^a/dx of the corners, 1/L

  // Cells grouped by colour: the cells of colour k are by_colour[colour_offsets[k] .. colour_offsets[k+1]).
  std::vector<Index> by_colour;
  std::vector<Index> colour_offsets;

  explicit Cells(CellType t = CellType::tri3, Formulation f = Formulation::p1)
      : type(t), formulation(f), stride(nodes_per_cell(t)) {
    nodes.use();
    body.use();
    colour.use();
  }

  Index size() const { return stride == 0 ? 0 : nodes.size() / stride; }
  Index n_colours() const { return colour_offsets.empty() ? 0 : Index(colour_offsets.size()) - 1; }
  const Index* cell_nodes(Index c) const { return nodes.data() + static_cast<std::size_t>(c) * stride; }
  Index node(Index c, int a) const { return nodes[c * stride + a]; }
  // Corner cells (tri3, quad4) and quad9: as many sides as corners. Side a of a triangle is the one opposite
  // corner a (what a walk crosses when barycentric coordinate a is negative); side a of a quadrilateral runs
  // from corner a to corner a + 1 (quad9: through mid-side node 4 + a).
  int sides() const { return corners_of_stride(stride); }
  std::pair<Index, Index> side_corners(Index c, int a) const {
    if (stride == 3) return {node(c, (a + 1) % 3), node(c, (a + 2) % 3)};
    return {node(c, a), node(c, (a + 1) % sides())};
  }

  template <class Visit>
  void for_each_column(Visit&& f) {
    f("nodes", nodes), f("body", body), f("colour", colour), f("neighbour", neighbour), f("measure", measure), f("gradient", gradient),
        f("gradient_3d", gradient_3d);
  }
  template <class Visit>
  void for_each_column(Visit&& f) const {
    const_cast<Cells*>(this)->for_each_column([&](const char* name, const auto& c) { f(name, c); });
  }
};

}  // namespace loom
