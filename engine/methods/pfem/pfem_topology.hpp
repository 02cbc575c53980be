// What a PFEM run keeps between remeshes besides the stores (methods pfem and es_pfem): per body its particles,
// the corner triangles and boundary polygon of the current mesh (the next remesh's constraints), the spacing
// that particle insertion and removal measure edges against, the dead-load traction edges of the initial mesh,
// and the state of each inlet.
//
// The particles are the leading nodes [0, n_points) of the Nodes store: they keep their index and every nodal
// column across remeshes while the particle set is unchanged; TRI6 mid-nodes are appended after them. (DESIGN §2
// puts persistent particles in Points: keeping them as the leading nodes avoids copying every nodal column twice
// per step and a second index space; Points stays the store of MPM's material points.) Inserting or removing
// particles renumbers them (engine/methods/pfem/particle_set.hpp).
#pragma once

#include <array>
#include <type_traits>
#include <vector>

#include "engine/core/types.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "systems/remesh/remesh_types.hpp"

namespace loom {

// An inlet while it runs: the row of particles driven at its velocity (ordered along the section), and whether
// it has started and ended.
struct InletState {
  std::vector<Index> row;
  bool started = false, closed = false;
};

struct PfemTopology {
  Index n_points = 0;                              // nodes [0, n_points) are the particles
  std::vector<std::vector<Index>> points_of_body;  // global node indices of each body's particles
  std::vector<std::vector<Index>> triangles;       // per body: corner connectivity (global indices)
  std::vector<std::vector<Edge>> boundary;         // per body: boundary polygon (global indices)
  std::vector<double> spacing;                     // per body: h0 (remesh.spacing, or the initial mean edge length)
  std::vector<TractionEdge<2>> tractions;          // loaded edges of the initial mesh, on corners (dead loads)
  std::vector<InletState> inlets;                  // per [[inlet]]
};

// The same on tetrahedra (method pfem with scene.dimension = 3): per body the particles, the corner tetrahedra and the
// outward surface faces of the current mesh (the next remesh's "old mesh", spec 3d-free-surface §3), and the
// dead-load traction faces of the initial mesh on corners, and the state of each inlet (its driven layer in `row`).
// Particle insertion and inflow; no removal.
struct PfemTopology3d {
  Index n_points = 0;
  std::vector<std::vector<Index>> points_of_body;
  std::vector<std::vector<Index>> tets;                      // per body: corner connectivity (global indices), 4 per cell
  std::vector<std::vector<std::array<Index, 3>>> surface;    // per body: faces used by one tetrahedron, outward
  std::vector<std::vector<std::array<Index, 4>>> neighbours;  // per body: tet_face_neighbours of tets (cell indices in the body)
  std::vector<TractionFace> tractions;                       // loaded faces of the initial mesh, on corners (dead loads)
  std::vector<double> spacing;                               // per body: h0 of particle insertion (as PfemTopology's)
  std::vector<InletState> inlets;                            // per [[inlet]]
};

// The topology a D-dimensional pfem run keeps.
template <int D>
using PfemTopologyOf = std::conditional_t<D == 2, PfemTopology, PfemTopology3d>;

}  // namespace loom
