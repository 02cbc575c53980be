// The [[inlet]] tables of a scene (inflow through a section, seed 001 §4.4), read into SceneSpec::inlets.
#pragma once

#include "engine/scene/scene_spec.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

void read_inlet(SceneSpec& scene, const TableReader& inlet);

}  // namespace loom
