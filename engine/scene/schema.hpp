// The scene schema: every key a scene may hold, with its type, default, range and meaning.
// The validator checks scenes against it, the loader takes defaults from it, and `loom schema` and the
// user guide's key table (docs/guide/scene_keys.md) are printed from it, so the three cannot drift apart (STYLE §6).
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace loom {

enum class ValueKind {
  table,        // [name] or an inline table
  table_array,  // [[name]]
  string,
  choice,       // a string out of a fixed list
  real,         // a number (an integer is accepted)
  integer,
  boolean,
  expression,   // a number or a muparser expression string in t, x, y
  vec2,         // [a, b] of numbers
  ivec2,        // [i, j] of integers
  box,          // [[xmin, ymin], [xmax, ymax]]
};

const char* value_kind_name(ValueKind k);

struct KeySpec {
  std::string path;           // schema path: "time.dt", "body[].mesh.size" ([] marks an array of tables)
  ValueKind kind = ValueKind::string;
  bool required = false;
  std::string unless;         // required only when this sibling key is absent ("file" for the generators' keys)
  std::string default_value;  // as shown to users; empty: no default
  std::string doc;
  std::vector<std::string> choices;
  std::optional<double> lower, upper;  // numeric range
  bool lower_open = false, upper_open = false;

  KeySpec& require() { required = true; return *this; }
  KeySpec& require_unless(std::string sibling) { required = true; unless = std::move(sibling); return *this; }
  KeySpec& by_default(std::string v) { default_value = std::move(v); return *this; }
  KeySpec& one_of(std::vector<std::string> c) { choices = std::move(c); return *this; }
  KeySpec& above(double v) { lower = v; lower_open = true; return *this; }
  KeySpec& at_least(double v) { lower = v; lower_open = false; return *this; }
  KeySpec& below(double v) { upper = v; upper_open = true; return *this; }
  KeySpec& at_most(double v) { upper = v; upper_open = false; return *this; }

  std::string range_text() const;  // "> 0", "in [0, 0.45]", "" if unbounded
};

const std::vector<KeySpec>& scene_schema();
const KeySpec* find_key_spec(const std::string& schema_path);

// `loom schema`: one block per key. markdown = true prints the README table instead.
void print_schema(std::ostream& os, bool markdown);

}  // namespace loom
