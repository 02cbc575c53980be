// The [[wall]] tables of a scene (rigid planes with a penalty contact, seed 001 §1.8), read into
// SceneSpec::walls: a plane by point and normal or a box; the body it acts on; the penalty; the slip.
#pragma once

#include "engine/scene/scene_spec.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

void read_wall(SceneSpec& scene, const TableReader& wall);

}  // namespace loom
