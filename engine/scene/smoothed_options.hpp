// The scene keys of seed 001's elements es_up, es_u, fem_up, fem_u (alpha_stab), with the checks that tie them to
// their materials (the materials' own keys: material_options.hpp).
#pragma once

#include "engine/scene/scene_spec.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

// alpha_stab of a [[body]], and the element-material pairing: es_*/fem_* take hencky_perzyna or
// linear_elastic; a finite tau0 needs an element that carries the history.
void read_smoothed_body(const SceneSpec& s, const TableReader& t, BodySpec& b);

}  // namespace loom
