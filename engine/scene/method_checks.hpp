// What each method implements, checked on a loaded scene: keys and combinations that only one method
// supports ([grid], newmark, p1p1_up, particles, prescribed pressures and energy probes: mpm; euler_backward,
// consistent mass, several bodies and volume probes: fem and pfem). Errors are reported at the key that asks for more.
#pragma once

#include "engine/scene/diagnostics.hpp"
#include "engine/scene/scene_spec.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

void check_method_support(const SceneSpec& scene, const TableReader& root, Diagnostics& diag);

}  // namespace loom
