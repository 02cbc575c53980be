// A mesh as a builder produces it, before it is loaded into stores: coordinates and tri3 connectivity, and
// what a mesh file adds -- the mid-nodes of 6-node triangles (which may sit off the straight edges) and the
// named regions (gmsh physical groups).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

// A named region of a mesh file: its corner nodes, and for a curve the edges of its line elements. A mid-node
// belongs to a curve when its edge is one of the curve's (not every edge between two of its corners: where two
// curves of one group meet at a corner cell, that cell's third edge joins two of their nodes), and to a surface
// when both corners of its edge do; so a region keeps its meaning when PFEM re-creates the mid-nodes.
struct MeshRegion {
  std::string name;
  int dim = 0;                 // 0 points, 1 curves, 2 surfaces, 3 volumes
  std::vector<Index> corners;  // indices into MeshData::X, ascending
  std::vector<std::array<Index, 2>> edges;  // curves: the end corners of each line element, lower index first
};

struct MeshData {
  std::vector<Vec2> X;           // corner node coordinates
  std::vector<Index> triangles;  // 3 node indices per triangle, counter-clockwise
  std::vector<Index> quads;      // or 4 per quadrilateral, counter-clockwise (generators asked for quads)
  // 6-node triangles read from a file: the mid-nodes of edges (c0,c1), (c1,c2), (c2,c0) of every triangle,
  // indices into mid_X. Empty for generated meshes (their mid-nodes are made on straight edges).
  std::vector<Vec2> mid_X;
  std::vector<Index> mid_nodes;
  std::vector<MeshRegion> regions;
  std::vector<std::size_t> source_tag;  // per triangle: its element tag in the file (for messages)
  Index n_triangles() const { return Index(triangles.size() / 3); }
  const MeshRegion* region(const std::string& name) const {
    for (const auto& r : regions)
      if (r.name == name) return &r;
    return nullptr;
  }
};

}  // namespace loom
