// The integration domains of seed 001's cell blocks (es_*: the edges' smoothing domains; fem_*: the
// triangles) with their geometry in B_n, and the triangles' reference areas that the pressure terms and the
// lumped mass use (cells.measure). Shared by the fem model (once) and the es_pfem remesh (every remesh).
#pragma once

#include <vector>

#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// Appends the domains of every block that integrates on domains to `edges` (empty stores are skipped);
// j_projection[b] is body b's option.
void build_domains(const Nodes<2>& nodes, const std::vector<Cells>& cells, const std::vector<char>& j_projection,
                   std::vector<Edges<2>>& edges);

// cells.measure of those blocks = the triangle's area in the reference configuration X (a fixed mesh).
void set_reference_areas(const Nodes<2>& nodes, std::vector<Cells>& cells);

}  // namespace loom
