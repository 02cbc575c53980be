// Particle insertion on tetrahedra (methods pfem and es_pfem with scene.dimension = 3): 2D's insertion
// (particle_edits.hpp) read in 3D. Before the remesh, a particle is put at the midpoint of every edge of the previous
// mesh longer than insert_above * h0, at most one edge per tetrahedron and remesh (the longest first, so that no
// tetrahedron has to be cut along two edges at once; the next remeshes take the others), and each tetrahedron around
// the edge is split in two at it (the previous mesh stays valid for the remesh to take its surface from). Every nodal
// column of the new particle is the mean of the edge's ends (an affine state stays exact); it starts with no mass, and
// the remesh shares the split tetrahedra's mass out (new_triangle_mass.hpp). Edges with an end whose motion or load is
// prescribed are not split. Particles are appended after the others, so nothing that holds particle indices is
// renumbered: the cells must be linear (tet10's mid-nodes follow the particles; the scene checks refuse it).
// No removal yet.
#pragma once

#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/pfem/pfem_topology.hpp"

namespace loom {

// Returns the number of particles inserted.
Index insert_particles_3d(double insert_above, PfemTopology3d& topo, FemModelT<3>& m);

// h0 per body: the mean edge length of its initial mesh (each tetrahedron's six edges; interior edges counted once per
// tetrahedron around them).
std::vector<double> initial_spacing_3d(const PfemTopology3d& topo, const Nodes<3>& nodes);

}  // namespace loom
