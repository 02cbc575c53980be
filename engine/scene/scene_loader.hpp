// Parse -> validate -> typed spec (STYLE §6). Every error of the scene is collected and reported at once
// as an InputError (exit code 2): syntax, unknown keys, types, ranges, references, combinations.
#pragma once

#include <string>
#include <vector>

#include "engine/scene/scene_spec.hpp"

namespace loom {

SceneSpec load_scene(const std::string& file, const std::vector<std::string>& overrides = {});
// Same, from text in memory; `file` only labels messages.
SceneSpec load_scene_text(const std::string& text, const std::string& file,
                          const std::vector<std::string>& overrides = {});

}  // namespace loom
