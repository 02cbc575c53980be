// Material points of a tetrahedral body mesh, for the 3D MPM (seed 003 §6.3-6.4): in each tetrahedron the
// points of a symmetric rule (engine/mesh/tetrahedron_rules.hpp), each carrying its weight's share of the cell's
// volume and mass. The rule's exactness carries over to the body: a rule of degree k reproduces every moment of
// order <= k of the body's volume (mass, centre of mass for k >= 1, inertia tensor for k >= 2).
#pragma once

#include <vector>

#include "engine/core/types.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace loom {

struct TetParticles {
  std::vector<Vec3> X;         // reference positions
  std::vector<double> volume;  // V_p, L^3
  std::vector<double> mass;    // m_p = density V_p
};

// per_cell: a count tetrahedron_rule has (1, 4, 14, 24; InputError otherwise). InputError for a tetrahedron of
// non-positive volume, naming it.
TetParticles place_tet_particles(const TetMeshData& mesh, int per_cell, double density);

}  // namespace loom
