// The PFEM keys of a scene, [remesh] and [map] (seed 000 §3), read into SceneSpec::pfem; both tables are
// errors for any other method.
#pragma once

#include "engine/scene/scene_spec.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

void read_pfem_options(SceneSpec& scene, const TableReader& root);

}  // namespace loom
