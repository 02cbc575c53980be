// The scene keys of the plastic materials of a [[material]] table: hencky_perzyna's tau0 and viscosity,
// drucker_prager's friction and dilatancy angles, cohesion and cone, with the checks that each is given to its model.
#pragma once

#include "engine/scene/scene_spec.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

// dimension: the scene's (drucker_prager's cone defaults to plane strain in 2D, to the compression cone in 3D).
void read_plasticity(MaterialSpec& m, const TableReader& t, int dimension);

}  // namespace loom
