// Helpers shared by the files that build the scene schema (engine/scene/schema.cpp and the key groups it calls).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/scene/schema.hpp"

namespace loom {

inline KeySpec key(std::string path, ValueKind kind, std::string doc) {
  KeySpec k;
  k.path = std::move(path);
  k.kind = kind;
  k.doc = std::move(doc);
  return k;
}

using K = ValueKind;

// [[wall]], [[inlet]], [remesh], [map]: the keys of mesh-based free-surface runs (schema_free_surface.cpp).
void add_free_surface_keys(std::vector<KeySpec>& s);
// [solver]: Newton's tolerances and cut-backs, the linear solver (schema_solver.cpp).
void add_solver_keys(std::vector<KeySpec>& s);

}  // namespace loom
