// Builds the integration domains of the face-based smoothed FEM (the 3D form of seed 001 §3.3) from a block
// of linear tetrahedra: the topology only (stencils, adjacent tetrahedra, pressure weights, colours). Their
// geometry in B_n is systems/assemble/smoothing_geometry's, as for the 2D edge domains.
//
// The domain of face k is made of the sub-tetrahedra (face, centroid) of the one or two tetrahedra that share
// it, a quarter of each one's volume. Stencil order (engine/store/edges.hpp): slots 0-2 are the face's nodes as
// kTetFaces orders them in the first adjacent tetrahedron (the one with the smaller index), so that their
// normal points out of it; slot 3 is that tetrahedron's opposite vertex, slot 4 (interior faces) the opposite
// vertex of the second. Faces are numbered in order of first appearance over the tetrahedra in index order and
// their faces in kTetFaces order, so the stores depend on the connectivity only.
//
// The pressure of a face domain is the linear pressure at the face's centroid (seed 001 eq 41, "evaluated at
// the mid point"): N_p = 1/3 on slots 0-2, 0 on the opposite vertices. A tetrahedron has four faces, an
// interior one two domains: faces = (4T + B) / 2 for T tetrahedra and B surface faces.
#pragma once

#include "engine/core/types.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"

namespace loom {

// The two stores of a body: one per stencil size.
struct FaceDomains {
  Edges<3> interior;  // stencil5: faces shared by two tetrahedra
  Edges<3> boundary;  // stencil4: faces of one tetrahedron
};

// From a tet4 block (only the first 4 nodes of each cell are read; the body of a domain is that of its first
// adjacent tetrahedron). Every column is sized and the stencils are coloured; the geometry columns are left at
// zero. Throws InputError for a face shared by more than two tetrahedra or a tetrahedron with a repeated node.
FaceDomains build_face_domains(const Cells& tets, Index n_nodes);

}  // namespace loom
