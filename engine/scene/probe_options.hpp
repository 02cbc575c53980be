// The [[probe]] tables of a scene: kind, what each kind reads (boundary, component, at or group, body,
// bound, quantity, energy) and the combinations that make no sense, read into SceneSpec::probes.
#pragma once

#include "engine/scene/scene_spec.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

// Appends the probe of table `t` to s.probes; errors go to the reader's diagnostics.
void read_probe(SceneSpec& s, const TableReader& t);

}  // namespace loom
