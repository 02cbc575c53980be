// Tetrahedral meshes for 3D benchmarks: a box cut into Kuhn tetrahedra or meshed as a body-centred cubic lattice,
// the extrusion of a 2D mesh, an interior distortion, and the mid-nodes of 10-node tetrahedra.
#pragma once

#include <cstdint>

#include "engine/mesh/mesh_data.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace loom {

struct BoxSpec {
  Vec3 origin = Vec3::Zero();
  Vec3 size = Vec3::Ones();
  int nx = 1, ny = 1, nz = 1;
};

// An nx x ny x nz lattice of hexahedra, each cut into the six Kuhn tetrahedra around its diagonal from the
// lowest to the highest corner (every tetrahedron is a path 000 -> e_i -> e_i + e_j -> 111 through the cube).
// Every cube is cut the same way, so the faces of neighbouring cubes match (a conforming mesh).
TetMeshData generate_box(const BoxSpec& spec);

// The body-centred cubic lattice of the same box: the cube corners, numbered as generate_box's nodes, then the cube
// centres (i fastest, then j, then k). Its tetrahedra are the lattice's Delaunay cells, congruent and far from
// degenerate (3 r_in / R = 0.949, dihedral angles 60-90 degrees): across every interior cube face, the four around
// the segment between the two centres; on the box's faces, each pyramid of a centre over a face is cut in two along
// the face's diagonal from its lowest-numbered corner (its five points are cospherical: either cut is Delaunay).
// Unlike the Kuhn box, whose every cube's eight corners are cospherical, a Delaunay triangulation of these points
// is unique inside the box, so a remesh of a body at rest or in motion does not churn between equivalent meshes.
TetMeshData generate_bcc_box(const BoxSpec& spec);

// Each triangle of `mesh` (quadrilaterals are cut along their diagonal from the lowest-numbered corner)
// swept over `layers` layers of thickness depth / layers in z from z = 0, each prism cut into three
// tetrahedra. The cut of a prism's side face joins the higher-numbered bottom corner of its edge to the
// lower-numbered top corner, a rule that depends only on the edge, so neighbouring prisms agree.
TetMeshData extrude(const MeshData& mesh, double depth, int layers);

// Moves interior nodes (those on no boundary face) by a random vector of length up to `fraction` of the node's
// smallest altitude over its tetrahedra (deterministic for a given seed). Returns the smallest ratio of a
// tetrahedron's volume after to before: <= 0 means one inverted (fraction too large).
double distort_interior_nodes(TetMeshData& mesh, double fraction, std::uint64_t seed);

// Adds one node at the midpoint of every edge (numbered in order of first appearance over the cells).
Tet10MeshData tet10_from_tet4(const TetMeshData& mesh);

}  // namespace loom
