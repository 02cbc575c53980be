#include "engine/scene/schema_validator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "engine/scene/schema.hpp"

namespace loom {
namespace {

std::string parent_of(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? std::string() : path.substr(0, dot);
}
std::string last_of(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? path : path.substr(dot + 1);
}

const std::map<std::string, std::vector<const KeySpec*>>& children_by_parent() {
  static const auto m = [] {
    std::map<std::string, std::vector<const KeySpec*>> r;
    for (const auto& k : scene_schema()) r[parent_of(k.path)].push_back(&k);
    return r;
  }();
  return m;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string suggestion(const std::string& parent, const std::string& key) {
  auto it = children_by_parent().find(parent);
  if (it == children_by_parent().end()) return {};
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, key.size() / 3) + 1;
  for (const KeySpec* k : it->second) {
    const std::string name = last_of(k->path);
    const std::size_t d = edit_distance(key, name);
    if (d < best_d) best_d = d, best = name;
  }
  return best.empty() ? std::string() : " (did you mean '" + best + "'?)";
}

std::string known_keys(const std::string& parent) {
  auto it = children_by_parent().find(parent);
  if (it == children_by_parent().end()) return {};
  std::string s;
  for (const KeySpec* k : it->second) s += (s.empty() ? "" : ", ") + last_of(k->path);
  return s;
}

std::string describe(const toml::node& n) {
  std::ostringstream os;
  if (n.is_table()) return "a table";
  if (n.is_array()) return "an array of " + std::to_string(n.as_array()->size()) + " values";
  if (n.is_string()) return "the string \"" + n.as_string()->get() + "\"";
  if (n.is_boolean()) return n.as_boolean()->get() ? "true" : "false";
  if (n.is_integer()) return "the integer " + std::to_string(n.as_integer()->get());
  if (n.is_floating_point()) {
    // A whole number is shown with its decimal point: "expected integer, got 2" would read as a riddle.
    const double v = n.as_floating_point()->get();
    os << "the floating-point number " << v;
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15) os << ".0";
    return os.str();
  }
  return "a date or time";
}

bool is_number(const toml::node& n) { return n.is_integer() || n.is_floating_point(); }
double number_of(const toml::node& n) {
  return n.is_integer() ? double(n.as_integer()->get()) : n.as_floating_point()->get();
}
// An array of `size` numbers (integers): a point or a count per axis, size = scene.dimension.
bool is_number_pair(const toml::node& n, bool integers, std::size_t size) {
  const auto* a = n.as_array();
  if (!a || a->size() != size) return false;
  for (const auto& e : *a)
    if (integers ? !e.is_integer() : !is_number(e)) return false;
  return true;
}

class Validator {
 public:
  Validator(const std::string& file, Diagnostics& diag, int dimension) : file_(file), diag_(diag), dimension_(dimension) {}

  void table(const toml::table& t, const std::string& schema, const std::string& display) {
    for (auto&& [k, node] : t) {
      const std::string key(k.str());
      const std::string schema_path = schema.empty() ? key : schema + "." + key;
      const std::string display_path = display.empty() ? key : display + "." + key;
      const KeySpec* spec = find_key_spec(schema_path);
      if (!spec) {
        std::string msg = "unknown key" + suggestion(schema, key);
        if (msg == "unknown key") {
          const std::string known = known_keys(schema);
          if (!known.empty()) msg += "; known keys here: " + known;
        }
        diag_.error(key_source(k, node), display_path, msg);
        continue;
      }
      value(node, *spec, schema_path, display_path);
    }
    auto it = children_by_parent().find(schema);
    if (it == children_by_parent().end()) return;
    for (const KeySpec* k : it->second)
      if (k->required && !t.contains(last_of(k->path)) && (k->unless.empty() || !t.contains(k->unless))) {
        SourceRef where = source_of(t, file_);
        if (where.line == 0 && schema.empty()) where = {file_, 1, 1};
        diag_.error(where, display.empty() ? last_of(k->path) : display + "." + last_of(k->path),
                    std::string("missing required ") + (k->kind == ValueKind::table ? "table" : k->kind == ValueKind::table_array ? "array of tables" : "key") +
                        (k->unless.empty() ? "" : " (or " + k->unless + ")"));
      }
  }

 private:
  SourceRef key_source(const toml::key& k, const toml::node& node) const {
    if (k.source().begin.line > 0) return {file_, int(k.source().begin.line), int(k.source().begin.column)};
    return source_of(node, file_);
  }

  void wrong_type(const toml::node& n, const KeySpec& spec, const std::string& display) {
    std::string expected = value_kind_name(spec.kind);
    if (spec.kind == ValueKind::vec2 || spec.kind == ValueKind::ivec2 || spec.kind == ValueKind::box) {
      const std::string d = std::to_string(dimension_);
      expected = spec.kind == ValueKind::vec2    ? "array of " + d + " numbers"
                 : spec.kind == ValueKind::ivec2 ? "array of " + d + " integers"
                                                 : "array of 2 arrays of " + d + " numbers";
      expected += " (scene.dimension = " + d + ")";
    }
    diag_.error(source_of(n, file_), display, "expected " + expected + ", got " + describe(n));
  }

  // TOML has nan and inf literals, and integers beyond the int the loader reads them into.
  bool representable(const toml::node& n, double v, const KeySpec& spec, const std::string& display) {
    std::ostringstream os;
    if (!std::isfinite(v)) {
      os << "must be a finite number, got " << v;
    } else if (n.is_integer() && (spec.kind == ValueKind::integer || spec.kind == ValueKind::ivec2) &&
               (v > std::numeric_limits<int>::max() || v < std::numeric_limits<int>::min())) {
      os << "must be at most " << std::numeric_limits<int>::max() << " in magnitude, got " << n.as_integer()->get();
    } else {
      return true;
    }
    diag_.error(source_of(n, file_), display, os.str());
    return false;
  }
  // Every number inside an array value (vec2, box) must be finite.
  void finite_elements(const toml::node& n, const KeySpec& spec, const std::string& display) {
    if (const auto* a = n.as_array()) {
      for (const auto& e : *a) finite_elements(e, spec, display);
    } else if (is_number(n)) {
      representable(n, number_of(n), spec, display);
    }
  }

  void range(const toml::node& n, double v, const KeySpec& spec, const std::string& display) {
    if (!representable(n, v, spec, display)) return;
    const bool low = spec.lower && (spec.lower_open ? v <= *spec.lower : v < *spec.lower);
    const bool high = spec.upper && (spec.upper_open ? v >= *spec.upper : v > *spec.upper);
    if (low || high) {
      std::ostringstream os;
      os << "must be " << spec.range_text() << ", got " << v;
      diag_.error(source_of(n, file_), display, os.str());
    }
  }

  void value(const toml::node& n, const KeySpec& spec, const std::string& schema, const std::string& display) {
    switch (spec.kind) {
      case ValueKind::table:
        if (!n.is_table()) return wrong_type(n, spec, display);
        return table(*n.as_table(), schema, display);
      case ValueKind::table_array: {
        if (!n.is_array_of_tables()) return wrong_type(n, spec, display);
        const auto& arr = *n.as_array();
        for (std::size_t i = 0; i < arr.size(); ++i)
          table(*arr[i].as_table(), schema + "[]", display + "[" + std::to_string(i) + "]");
        return;
      }
      case ValueKind::string:
        if (!n.is_string()) wrong_type(n, spec, display);
        return;
      case ValueKind::choice: {
        if (!n.is_string()) return wrong_type(n, spec, display);
        const std::string& v = n.as_string()->get();
        if (std::find(spec.choices.begin(), spec.choices.end(), v) == spec.choices.end()) {
          std::string list;
          for (const auto& c : spec.choices) list += (list.empty() ? "" : ", ") + c;
          diag_.error(source_of(n, file_), display, "\"" + v + "\" is not one of: " + list);
        }
        return;
      }
      case ValueKind::real:
        if (!is_number(n)) return wrong_type(n, spec, display);
        return range(n, number_of(n), spec, display);
      case ValueKind::integer:
        if (!n.is_integer()) return wrong_type(n, spec, display);
        return range(n, number_of(n), spec, display);
      case ValueKind::boolean:
        if (!n.is_boolean()) wrong_type(n, spec, display);
        return;
      case ValueKind::expression:
        if (!n.is_string() && !is_number(n)) wrong_type(n, spec, display);
        return;
      case ValueKind::vec2:
        if (!is_number_pair(n, false, std::size_t(dimension_))) return wrong_type(n, spec, display);
        return finite_elements(n, spec, display);
      case ValueKind::ivec2:
        if (!is_number_pair(n, true, std::size_t(dimension_))) return wrong_type(n, spec, display);
        for (const auto& e : *n.as_array()) range(e, number_of(e), spec, display);
        return;
      case ValueKind::box: {
        const auto* a = n.as_array();
        const auto D = std::size_t(dimension_);
        if (!a || a->size() != 2 || !is_number_pair((*a)[0], false, D) || !is_number_pair((*a)[1], false, D))
          return wrong_type(n, spec, display);
        return finite_elements(n, spec, display);
      }
    }
  }

  const std::string& file_;
  Diagnostics& diag_;
  int dimension_;  // vectors and boxes have this many numbers
};

}  // namespace

SourceRef source_of(const toml::node& node, const std::string& file) {
  const auto& s = node.source();
  if (s.begin.line == 0) return {};
  return {file, int(s.begin.line), int(s.begin.column)};
}

void validate_against_schema(const toml::table& root, const std::string& file, Diagnostics& diag) {
  // The dimension decides how many numbers a vector takes; an invalid one is reported by its own key (and
  // vectors are then checked as 2D).
  const auto* d = root["scene"]["dimension"].as_integer();
  const int dimension = d && d->get() == 3 ? 3 : 2;
  Validator(file, diag, dimension).table(root, "", "");
}

}  // namespace loom
