// Structural check of a parsed scene against the schema: unknown keys (with a suggestion), wrong types,
// values out of range or not among the choices, missing required keys. Semantic checks (references
// between tables, parameter combinations) are the loader's.
#pragma once

#include <string>

#include <toml++/toml.h>

#include "engine/scene/diagnostics.hpp"

namespace loom {

void validate_against_schema(const toml::table& root, const std::string& file, Diagnostics& diag);

// Source position of a toml node; values inserted by --set have none and read as the command line.
SourceRef source_of(const toml::node& node, const std::string& file);

}  // namespace loom
