// Builds the integration domains of the edge-based smoothed FEM (seed 001 §3.3) from a block of linear
// triangles: the topology only (stencils, adjacent triangles, pressure weights, colours). Their geometry in
// B_n is systems/assemble/smoothing_geometry's, recomputed at every commit; the topology changes only
// when the mesh does (set-up, remesh).
//
// Stencil order of an edge domain (engine/store/edges.hpp): slots 0, 1 are the edge's nodes a, b as they
// run counter-clockwise in the first adjacent triangle (the one with the smaller index), slot 2 that
// triangle's opposite vertex, slot 3 (interior edges) the opposite vertex of the second one. Edges are
// numbered in order of first appearance over the triangles in index order and their sides (0-1, 1-2,
// 2-0), so the stores depend on the connectivity only.
#pragma once

#include "engine/core/types.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"

namespace loom {

// The two stores of a body: one per stencil size (a store's connectivity has a fixed stride).
struct EdgeDomains {
  Edges<2> interior;  // stencil4: edges shared by two triangles
  Edges<2> boundary;  // stencil3: edges of one triangle
};

// From a tri3 block (only the first 3 nodes of each cell are read; the body of a domain is that of its
// first adjacent triangle). Every column is sized and the stencils are coloured; the geometry columns are
// left at zero. Throws InputError for an edge shared by more than two triangles or a triangle with a
// repeated node. n_nodes bounds the node indices.
EdgeDomains build_edge_domains(const Cells& triangles, Index n_nodes);

}  // namespace loom
