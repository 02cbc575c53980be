// Sliver removal with the points fixed: the 3D remesh's step R3.4 (specs/3d-free-surface.md §0.2, §3). Bad
// tetrahedra are replaced by 2-3 flips across interior faces and by edge removal around interior edges
// (Shewchuk 2002, "Two discrete optimization algorithms for the topological improvement of tetrahedral
// meshes"; a ring of 3 is the 3-2 flip), each accepted only when it raises the worst quality of the tets it
// replaces (max-min). Faces used by one tet (the surface) and edges on them are never touched, so the surface
// and the volume are unchanged exactly; no point is moved, added or removed.
#pragma once

#include <array>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

// q = 3 r_in / r_circ: 1 for the regular tetrahedron, 0 for a flat one (and for coincident corners); scale and
// rotation invariant. Its sign is that of the volume (b - a).((c - a) x (d - a)), so an inverted tet ranks below
// every valid one.
double tet_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

struct FlipSettings {
  double threshold = 0.2;  // tets with q below it are visited (spec: q_flip)
  int max_passes = 3;      // passes over the list of bad tets, each recomputing it
};

struct FlipStats {
  Index flips23 = 0;        // 2 tets across an interior face -> 3 around a new edge
  Index flips32 = 0;        // edge removal with a ring of 3 (3 -> 2)
  Index edge_removals = 0;  // edge removal with a ring of 4..7 (n -> 2n - 4)
  Index below_before = 0, below_after = 0;   // tets with q < threshold
  double worst_before = 1, worst_after = 1;  // smallest q (1 for an empty mesh)
  int passes = 0;                            // passes that ran
};

// tets: 4 point indices per tetrahedron, positively oriented ((b-a).((c-a)x(d-a)) > 0; flat to round-off is fine, as
// a Delaunay's cells are exactly positive, but a truly inverted tet voids the guarantees), not overlapping, conforming
// (a face is shared by at most two tets; a face found in more is treated as surface and never flipped). Improves in
// place; every tet it creates has 6V > 1e-12 l_max^3.
// Output order: the tets no flip touched keep their original relative order, followed by the tets the flips
// created in the order they were made (minus those later flipped again). Deterministic: the visits follow
// ascending (q, sorted corners) and ties are broken on sorted point indices, so the result (as a set of tets)
// depends neither on the order of the tets nor on an even permutation of a tet's corners.
// `origin` (optional): per output tet, its index in the input, or kNoIndex for a tet a flip created.
// `neighbours` (optional): in, when it has one entry per tet, the input's tet_face_neighbours (engine/mesh/
// tet_adjacency.hpp, kNoIndex for a non-manifold face), which saves finding them; out, the output's, kNoIndex on the
// surface.
FlipStats improve_by_flips(const std::vector<Vec3>& points, std::vector<Index>& tets, const FlipSettings& settings,
                           std::vector<Index>* origin = nullptr, std::vector<std::array<Index, 4>>* neighbours = nullptr);

struct DelaunayRepairStats {
  Index flips = 0;          // 2-3 and 3-2 flips made
  Index failing_after = 0;  // interior faces still not locally Delaunay (beyond delaunay_check.hpp's margin)
  Index stuck = 0;          // of those, faces beside a sliver (q < 0.1, or below the threshold if lower) that no flip mends
  int passes = 0;
  FlipStats slivers;        // the sliver pass after the flips (none when nothing was flipped)
};

// Lawson's flips toward the Delaunay triangulation from a mesh that has nearly stayed one (the 3D remesh's local
// repair, remesh_3d.hpp): every interior face that fails the in-sphere test of delaunay_check.hpp (with its margin)
// is flipped, 2-3 where the two tets' union is convex across it, else 3-2 around one of its edges held by three
// tets, in passes over the failing faces in the order of their sorted corners until none is left or none can be
// flipped. A flip is made only when its tets are positive and none is worse (q) than both `floor` and the worst of the
// tets it replaces, so that the repair does not make the slivers improve_by_flips removes, nor undo its flips. Each
// flip strictly lowers the lifted volume, so the passes end; the surface and the points are never changed. `tets`
// and `neighbours` (as improve_by_flips: in, optional; out, kNoIndex on the surface) are rewritten: untouched tets in
// their order, then the new ones. Deterministic and independent of the order of the tets (as improve_by_flips).
DelaunayRepairStats repair_delaunay(const std::vector<Vec3>& points, std::vector<Index>& tets, const FlipSettings& slivers,
                                    std::vector<std::array<Index, 4>>* neighbours = nullptr);

}  // namespace loom
