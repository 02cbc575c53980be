// The history of seed 001's integration domains across a remesh (es_pfem, seed 001 §3.5):
//  - a domain whose edge survives (same two end nodes; a triangle domain: same corners) keeps its b^e_n;
//  - a new one takes the isochoric part of the nearest old domain's b^e (closest midpoint, CPM),
//    b_bar = (det b^e)^(-1/3) b^e, and the volumetric part from the particles' nodal J (eq 56):
//    b^e = (J^k)^(2/3) b_bar, J^k = the mean of J^l over the domain's pressure nodes (an edge's two ends).
//  - a triangle keeps its reference area if it survives. A new one, in a dynamic run (lumped masses), gets the mass of
//    the removed triangles whose region it covers (and a share of what its corners lost otherwise), so that the
//    body's mass stays what it was (new_triangle_mass.hpp), and a new domain takes its volume ratio from its
//    triangles, sum A_n / sum A_0, so that its b^e agrees with the mass it holds; without lumped masses (static runs) a new triangle gets A_n / J_e with J_e the mean nodal
//    J of its corners and a new domain the nodal J of its ends (the spec's reading of eqs 42, 48 and 56, ambiguity
//    21). docs/free_surface.md shows why the nodal reading lets the mass drift in a flow that remeshes every step.
// In 3D (D = 3) read face for edge and tetrahedron for triangle: the same rules, keys of three (four) sorted nodes.
// The spec applies the projection to every edge at every remesh; loom keeps surviving edges as they are, so
// that remeshing a resting body changes nothing (an idle remesh must not creep) and the projection acts only
// where the mesh changed. docs/es_fem.md says why.
#pragma once

#include <array>
#include <map>
#include <vector>

#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// What the old mesh leaves for the transfer: per domain key (sorted end nodes, or sorted corners) its b^e_n,
// the midpoints and b^e of all old domains, and the reference areas of the old triangles.
template <int D>
struct DomainSnapshot {
  using Key = std::array<Index, D + 1>;  // a cell's sorted corners; an edge (face) leaves the last slot kNoIndex
  std::map<Key, Index> domain_of;  // key -> index into midpoint / be
  std::vector<Vec<D>> midpoint;
  std::vector<Mat3> be;
  std::vector<Index> body;  // a new domain takes its history from the nearest old domain of its own body
  std::map<Key, double> reference_area;  // sorted corners -> A_0 of a triangle of a domain block
};

struct DomainTransferStats {
  Index kept = 0, projected = 0;
  double new_material_mass = 0.0;  // with density: of the cells that filled gaps (material added, not carried)
};

template <int D>
DomainSnapshot<D> snapshot_domains(const std::vector<Edges<D>>& edges, const std::vector<Cells>& cells);

// After the particles were renumbered (old_to_new[i]: new index of particle i, kNoIndex if removed): the keys
// follow; a domain or triangle that lost a node can no longer survive (its history stays for the nearest-domain
// transfer).
template <int D>
void renumber_domain_snapshot(const std::vector<Index>& old_to_new, DomainSnapshot<D>& snapshot);

// Rebuilds `edges` on the new `cells` (geometry at x_n) and fills their history and the triangles' reference
// areas from the snapshot; nodes.J_node must be in use. With `density` (per body), nodes.lumped_mass must hold each
// particle's mass before the remesh (the mass-conserving reading above). `gap_cells` (per block, per cell) flags new
// triangles that fill a gap outside the previous boundary (two surfaces that met): they held no material, so they
// take new material, A_0 = A_n / J_e, and no share of the lost mass (the remesh probe's area change says how much).
template <int D>
DomainTransferStats transfer_domains(const DomainSnapshot<D>& old, const Nodes<D>& nodes, std::vector<Cells>& cells,
                                     const std::vector<char>& j_projection, std::vector<Edges<D>>& edges,
                                     const std::vector<double>* density = nullptr, const std::vector<std::vector<char>>* gap_cells = nullptr);

}  // namespace loom
