// `--set key.path=value`: changes a parsed scene before validation, so that overridden values are
// checked like any other. Arrays of tables are addressed by index or by name: `body[0].mesh.divisions`
// and `body[block].mesh.divisions` name the same entry when the first [[body]] has name = "block".
// The value is read as TOML (`[16, 16]`, `1e-3`, `true`, `"text"`); a value that is not valid TOML is
// taken as a string (`--set time.integrator=static`).
#pragma once

#include <string>

#include <toml++/toml.h>

namespace loom {

// Throws InputError naming the argument if the path cannot be resolved.
void apply_override(toml::table& root, const std::string& assignment);

}  // namespace loom
