// Which edges of a polygon cross another of its edges. A PFEM boundary polygon is the outline of a valid mesh
// when it is built, but the step then moves its points: a fold that closes, or a surface point pushed through
// another part of the surface (loom has no self-contact), leaves two boundary edges crossing. Inserted as
// constraints of the next triangulation, two crossing edges would create a point at their intersection that no
// particle carries; the remesh leaves such edges out of the constraints instead (the surface is repaired there
// by the triangulation).
#pragma once

#include <vector>

#include "engine/core/types.hpp"
#include "systems/remesh/remesh_types.hpp"

namespace loom {

// Flags (1) every edge that properly crosses another (a point inside both). Edges that only share an end point,
// or where an end point lies on the other edge, do not cross: a triangulation splits a constraint at a point on
// it without creating one. Exact orientation predicates; a uniform bucket grid keeps it O(n) for a polygon of
// edges of similar length.
std::vector<char> crossing_edges(const std::vector<Vec2>& x, const std::vector<Edge>& edges);

}  // namespace loom
