// The scene keys of seed 004's MPM (Aulisa & Capodaglio): [mpm] (scheme, soft stiffness, receding
// contact), a body's generated particles (body[].particles), Newmark's beta and gamma, and the checks
// that tie them to the grid, the element and the integrator.
#pragma once

#include "engine/scene/scene_spec.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

// time.beta and time.gamma (newmark only; unconditional stability 2 beta >= gamma >= 1/2).
void read_newmark_parameters(const TableReader& time, TimeSpec& t);

// Options of method mpm on a body (seed 003): particles per cell of its mesh, and the stabilisation of p1p1_up.
void read_mpm_body(const SceneSpec& s, const TableReader& t, BodySpec& b);

// body[].particles: the disk or beam generator of the paper's appendix.
void read_particle_generator(const TableReader& body, BodySpec& b);

// [mpm] and the checks of scheme = "particle_newmark" against the rest of the scene (after everything is read).
void read_mpm_options(SceneSpec& s, const TableReader& root);

}  // namespace loom
