// Inflow through an inlet section ([[inlet]], seed 001 §4.4 and §1.8 of its spec: "new elements continuously
// pushed into the domain"). The section runs from `from` to `to`; n is its unit normal along the inflow and d(x) =
// (x - from) . n the signed distance downstream of it. While the inlet runs, one row of particles behind the
// section (d in [-h, 0)), `spacing` h apart along it, is driven at the velocity v (a prescribed displacement
// u = u_n + dt v). When the row reaches the section (d >= 0) it is released and a new row of fresh particles
// (u = 0, v = v, J = 1, unstressed) is added h behind it and joined to it by a strip of triangles. The material
// between the driven row and the section is a rigid strip moving at v, so the area downstream of the section grows
// by exactly |v . n| L per unit time (L the section's length); the body's whole area jumps by h L at each new row.
// At the start the body's particles on the section (its mesh must begin there) are the first released row, and the
// first new row is placed between h/2 and 3h/2 behind them such that the last row reaches the section at the end
// time: the inlet then closes by releasing it, and the poured area is |v . n| L T (to within |v . n| dt L).
#pragma once

#include <vector>

#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/pfem/particle_set.hpp"
#include "engine/methods/pfem/pfem_topology.hpp"

namespace loom {

struct InletFrame {
  Vec2 from, tangent, normal;  // unit tangent from -> to, unit normal along the inflow
  double length, spacing;
  double distance(const Vec2& x) const { return (x - from).dot(normal); }
};

InletFrame inlet_frame(const InletSpec& inlet, const PfemTopology& topo);

// The body's particles on the section (|d| within 1e-6 h, along it within [0, L]), ordered along it.
std::vector<Index> particles_on_section(const InletFrame& frame, const PfemTopology& topo, const Nodes<2>& nodes, Index body);

// Plans this step's inflow for every inlet (start, new rows, end) at the start of the step, t_n, on the previous
// mesh; adds to `change` (after any particle edits: new particles continue its numbering) and marks the inlets
// started or closed in `topo`. Throws RunError if an inlet's body has no particle on its section when it starts.
void plan_inflow(const std::vector<InletSpec>& inlets, double t_n, const Nodes<2>& nodes, PfemTopology& topo, ParticleSetChange& change);

// The driven rows' prescribed motion, added to boundary conditions just built (a row particle that a [[boundary]]
// also prescribes follows the inlet).
void add_inlet_rows(const std::vector<InletSpec>& inlets, const PfemTopology& topo, BoundaryConditions<2>& bc);

}  // namespace loom
