// Inflow through a disc in 3D ([[inlet]] with scene.dimension = 3; seed 001 §4.6: material "pushed in" at a nozzle's
// outlet). The 2D scheme of inlet_flow.hpp with layers for rows:
//  - the section is the disc of radius r about c(t) normal to the inflow velocity v (n = v / |v|), where c moves at the
//    section velocity w (perpendicular to n: a nozzle moving along a print path) while the inlet runs;
//  - at the start, the body's particles on the disc's plane within r are the first layer and the body's surface
//    triangles with all three corners in it its pattern (the body's mesh must begin at the section);
//  - a new layer is a copy of the layer in front, `spacing` h upstream (x - h n): one fresh particle (u = 0, J = 1,
//    unstressed, moving at v + w) per particle of the front, joined to it by three tetrahedra per pattern triangle
//    (a prism over the triangle, cut by the rule of extrude: the diagonal of the side quadrilateral over the edge (p, q),
//    p < q, joins q to the copy of p, so that neighbouring prisms agree); those tetrahedra are the previous mesh's new
//    material and their mass, rho V / 4, goes to their corners;
//  - the newest layer is driven at v + w (a prescribed displacement u = u_n + dt (v + w)); once its mean distance
//    downstream of the moving disc, (x - c(t)) . n, is >= 0 it is released and a new layer added behind it.
// The first new layer is placed between h/2 and 3h/2 upstream such that the last reaches the disc at the end time,
// when the inlet closes, so that the poured volume is |v| A T (A the area of the pattern) to within |v| dt A. The driven
// prism between the newest layer and the one in front moves rigidly: the volume downstream of the disc grows at |v| A.
#pragma once

#include <vector>

#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/pfem/pfem_topology.hpp"

namespace loom {

struct InletDisc {
  Vec3 centre, normal;  // at the time asked for; the unit normal along the inflow
  Vec3 velocity;        // of the driven layer: inflow plus section velocity
  double radius, spacing, speed;  // speed: |inflow velocity|
  double distance(const Vec3& x) const { return (x - centre).dot(normal); }
};

// The inlet's disc at time t (its centre moved by section_velocity over the part of [start, start + duration] before t).
InletDisc inlet_disc(const InletSpec& inlet, const PfemTopology3d& topo, double t);

// The body's particles on the disc: within 1e-6 h of its plane and r (1 + 1e-9) of its centre, in index order.
std::vector<Index> particles_on_disc(const InletDisc& disc, const PfemTopology3d& topo, const Nodes<3>& nodes, Index body);

// The surface triangles of the body's current mesh with every corner in `layer` (sorted).
std::vector<std::array<Index, 3>> layer_pattern(const PfemTopology3d& topo, Index body, const std::vector<Index>& layer);

// Before a run: every inlet's disc holds a triangle of its body's initial surface, lies on the side of the body the
// velocity points away from, and is at least two spacings in radius (InputError naming the scene's key otherwise).
void check_inlet_discs(const SceneSpec& scene, const PfemTopology3d& topo, const Nodes<3>& nodes);

// Starts, advances and closes the inlets at t_n, before the remesh: new layers' particles appended (nodes, node_body,
// topology), their tetrahedra added to the previous mesh (topo.tets, surface, neighbours) and, with lumped masses, their
// mass to their corners. Returns the number of particles added; `released` is set when a layer was released without a
// new one (the inlet closed: the boundary conditions change). Throws RunError if an inlet's body has no pattern on its
// disc when it starts.
Index pour_inlets_3d(const std::vector<InletSpec>& inlets, double t_n, PfemTopology3d& topo, FemModelT<3>& m, bool& released);

// The driven layers' prescribed motion, added to boundary conditions just built (a driven particle that a [[boundary]]
// also prescribes follows the inlet).
void add_inlet_layers(const std::vector<InletSpec>& inlets, const PfemTopology3d& topo, BoundaryConditions<3>& bc);

}  // namespace loom
