// Structured mesh generators for the benchmark geometries.
#pragma once

#include <cstdint>

#include "engine/mesh/mesh_data.hpp"

namespace loom {

// How the quadrilaterals of a structured grid are split into triangles.
//  right:       every quad cut by the same diagonal (lower-left to upper-right);
//  alternating: the diagonal alternates from quad to quad (checkerboard);
//  shifted:     seed 000 Fig 7b: every other row of nodes is shifted by half an edge and gets the two end
//               points added, so that the triangles between rows are nearly equilateral.
enum class GridPattern { right, alternating, shifted };

struct RectangleSpec {
  Vec2 origin = Vec2::Zero();
  Vec2 size = Vec2::Ones();
  int nx = 1, ny = 1;
  GridPattern pattern = GridPattern::right;
  bool quads = false;  // quadrilaterals (MeshData::quads) instead of triangles; pattern unused
};

MeshData generate_rectangle(const RectangleSpec& spec);

// Cook's membrane: the trapezoid (0,0), (48,44), (48,60), (0,44), meshed by bilinear mapping of an
// nx by ny structured grid (nx along the clamped-to-loaded direction), cut into triangles by `pattern` or
// kept as quadrilaterals.
MeshData generate_cooks_membrane(int nx, int ny, GridPattern pattern, bool quads = false);

// Moves interior nodes by a random vector of length up to `fraction` of the node's smallest altitude in
// its triangles (deterministic for a given seed); boundary nodes stay, so the outline is unchanged.
// No triangle inverts for fraction < 0.264. A quadrilateral counts as the four triangles of its two
// diagonals: none inverts, so every quadrilateral stays convex.
void distort_interior_nodes(MeshData& mesh, double fraction, std::uint64_t seed);

void scale_mesh(MeshData& mesh, double factor);

}  // namespace loom
