#include "engine/scene/overrides.hpp"

#include <cctype>
#include <vector>

#include "engine/core/errors.hpp"

namespace loom {
namespace {

struct Segment {
  std::string name;
  bool subscripted = false;
  std::string subscript;
};

std::vector<Segment> split_path(const std::string& path, const std::string& arg) {
  std::vector<Segment> segs(1);
  bool in_bracket = false;
  for (char c : path) {
    if (in_bracket) {
      if (c == ']') in_bracket = false;
      else segs.back().subscript += c;
    } else if (c == '[') {
      LOOM_CHECK(!segs.back().subscripted && !segs.back().name.empty(), InputError, "--set " << arg << ": misplaced '['");
      segs.back().subscripted = in_bracket = true;
    } else if (c == '.') {
      segs.emplace_back();
    } else {
      LOOM_CHECK(!segs.back().subscripted, InputError, "--set " << arg << ": expected '.' after ']'");
      segs.back().name += c;
    }
  }
  LOOM_CHECK(!in_bracket, InputError, "--set " << arg << ": missing ']'");
  for (const auto& s : segs) LOOM_CHECK(!s.name.empty(), InputError, "--set " << arg << ": empty key in path '" << path << "'");
  return segs;
}

bool is_integer_text(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

toml::table& entry_of(toml::table& parent, const Segment& seg, const std::string& arg) {
  toml::node* n = parent.get(seg.name);
  LOOM_CHECK(n && n->is_array_of_tables(), InputError, "--set " << arg << ": '" << seg.name << "' is not an array of tables in the scene");
  auto& arr = *n->as_array();
  if (is_integer_text(seg.subscript)) {
    const std::size_t i = std::stoul(seg.subscript);
    LOOM_CHECK(i < arr.size(), InputError,
               "--set " << arg << ": " << seg.name << "[" << i << "] does not exist (the scene has " << arr.size() << ")");
    return *arr[i].as_table();
  }
  for (auto& e : arr) {
    const toml::node* name = e.as_table()->get("name");
    if (name && name->is_string() && name->as_string()->get() == seg.subscript) return *e.as_table();
  }
  throw InputError("--set " + arg + ": no [[" + seg.name + "]] has name = \"" + seg.subscript + "\"");
}

}  // namespace

void apply_override(toml::table& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  LOOM_CHECK(eq != std::string::npos && eq > 0, InputError, "--set " << assignment << ": expected key.path=value");
  const std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  const auto segs = split_path(path, assignment);

  toml::table* t = &root;
  for (std::size_t k = 0; k + 1 < segs.size(); ++k) {
    const Segment& s = segs[k];
    if (s.subscripted) {
      t = &entry_of(*t, s, assignment);
      continue;
    }
    toml::node* n = t->get(s.name);
    if (!n) n = t->insert_or_assign(s.name, toml::table{}).first->second.as_table();
    LOOM_CHECK(n->is_table(), InputError, "--set " << assignment << ": '" << s.name << "' is not a table");
    t = n->as_table();
  }
  const Segment& last = segs.back();
  LOOM_CHECK(!last.subscripted, InputError, "--set " << assignment << ": the path must end at a key, not at a table");

  // Node copies do not carry source positions, so the validator reports the command line for this value.
  try {
    toml::table parsed = toml::parse("v = " + text);
    parsed.get("v")->visit([&](const auto& value) { t->insert_or_assign(last.name, value); });
  } catch (const toml::parse_error&) {
    t->insert_or_assign(last.name, text);
  }
}

}  // namespace loom
