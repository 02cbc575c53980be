// The integration domains of seed 001's cell blocks (es_*: the edges' smoothing domains, in 3D the faces';
// fem_*: the triangles or tetrahedra) with their geometry in B_n, and the simplices' reference measures that the
// pressure terms and the lumped mass use (cells.measure). Shared by the fem model (once) and the es_pfem remesh
// (every remesh).
#pragma once

#include <vector>

#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// Appends the domains of every block that integrates on domains to `edges` (empty stores are skipped);
// j_projection[b] is body b's option.
template <int D>
void build_domains(const Nodes<D>& nodes, const std::vector<Cells>& cells, const std::vector<char>& j_projection,
                   std::vector<Edges<D>>& edges);

// cells.measure of those blocks = the simplex's area (volume) in the reference configuration X (a fixed mesh).
template <int D>
void set_reference_areas(const Nodes<D>& nodes, std::vector<Cells>& cells);

}  // namespace loom
