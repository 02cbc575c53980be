// The scene keys of seed 001's formulations: the material hencky_perzyna (tau0, viscosity) and the
// elements es_up, es_u, fem_up, fem_u (alpha_stab), with the checks that tie them together.
#pragma once

#include "engine/scene/scene_spec.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

// tau0 and viscosity of a [[material]] table (errors if given to another model).
void read_hencky_perzyna(MaterialSpec& m, const TableReader& t);

// alpha_stab of a [[body]], and the element-material pairing: es_*/fem_* take hencky_perzyna or
// linear_elastic; a finite tau0 needs an element that carries the history.
void read_smoothed_body(const SceneSpec& s, const TableReader& t, BodySpec& b);

}  // namespace loom
