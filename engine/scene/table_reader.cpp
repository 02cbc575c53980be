#include "engine/scene/table_reader.hpp"

#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/scene/schema.hpp"
#include "engine/scene/schema_validator.hpp"

namespace loom {
namespace {

std::optional<double> as_number(const toml::node* n) {
  if (!n) return std::nullopt;
  if (n->is_integer()) return double(n->as_integer()->get());
  if (n->is_floating_point()) return n->as_floating_point()->get();
  return std::nullopt;
}

std::string unquote(const std::string& s) {
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') return s.substr(1, s.size() - 2);
  return s;
}

// Defaults of array type are written in TOML syntax in the schema ("[0.0, 0.0]").
toml::table parse_default(const std::string& text) { return toml::parse("v = " + text); }

}  // namespace

TableReader::TableReader(const toml::table* table, std::string schema_path, std::string display_path,
                         const std::string& file, Diagnostics& diag)
    : table_(table), schema_(std::move(schema_path)), display_(std::move(display_path)), file_(file), diag_(diag) {}

bool TableReader::has(const std::string& key) const { return node(key) != nullptr; }

const toml::node* TableReader::node(const std::string& key) const { return table_ ? table_->get(key) : nullptr; }

const std::string& TableReader::default_text(const std::string& key) const {
  const std::string sp = schema_.empty() ? key : schema_ + "." + key;
  const KeySpec* spec = find_key_spec(sp);
  LOOM_ASSERT(spec, "key " << sp << " is read by the loader but missing from the schema");
  return spec->default_value;
}

std::string TableReader::path(const std::string& key) const { return display_.empty() ? key : display_ + "." + key; }

SourceRef TableReader::where(const std::string& key) const {
  const toml::node* n = node(key);
  return n ? source_of(*n, file_) : where();
}

SourceRef TableReader::where() const {
  if (!table_) return {file_, 0, 0};
  SourceRef s = source_of(*table_, file_);
  if (s.line == 0 && display_.empty()) s = {file_, 1, 1};
  return s;
}

void TableReader::error(const std::string& key, const std::string& message) const {
  diag_.error(key.empty() ? where() : where(key), key.empty() ? display_ : path(key), message);
}

std::string TableReader::string(const std::string& key) const {
  const toml::node* n = node(key);
  if (n && n->is_string()) return n->as_string()->get();
  return unquote(default_text(key));
}

double TableReader::real(const std::string& key) const {
  if (auto v = as_number(node(key))) return *v;
  const std::string& d = default_text(key);
  return d.empty() ? 0.0 : std::stod(d);
}

std::optional<double> TableReader::optional_real(const std::string& key) const { return as_number(node(key)); }

long long TableReader::integer(const std::string& key) const {
  const toml::node* n = node(key);
  if (n && n->is_integer()) return n->as_integer()->get();
  const std::string& d = default_text(key);
  return d.empty() ? 0 : std::stoll(d);
}

bool TableReader::boolean(const std::string& key) const {
  const toml::node* n = node(key);
  if (n && n->is_boolean()) return n->as_boolean()->get();
  return default_text(key) == "true";
}

Vec2 TableReader::vec2(const std::string& key) const {
  const toml::node* n = node(key);
  toml::table fallback;
  if (!n || !n->is_array() || n->as_array()->size() < 2) {  // 3D vectors: their x and y
    const std::string& d = default_text(key);
    if (d.empty()) return Vec2::Zero();
    fallback = parse_default(d);
    n = fallback.get("v");
  }
  const auto& a = *n->as_array();
  return Vec2(as_number(&a[0]).value_or(0.0), as_number(&a[1]).value_or(0.0));
}

std::array<long long, 2> TableReader::ivec2(const std::string& key) const {
  const toml::node* n = node(key);
  if (n && n->is_array() && n->as_array()->size() >= 2 && (*n->as_array())[0].is_integer() && (*n->as_array())[1].is_integer())
    return {(*n->as_array())[0].as_integer()->get(), (*n->as_array())[1].as_integer()->get()};
  return {1, 1};
}

std::array<Vec2, 2> TableReader::box(const std::string& key) const {
  std::array<Vec2, 2> b{Vec2::Zero(), Vec2::Zero()};
  const toml::node* n = node(key);
  if (!n || !n->is_array() || n->as_array()->size() != 2) return b;
  for (std::size_t i = 0; i < 2; ++i) {
    const auto* corner = (*n->as_array())[i].as_array();
    if (!corner || corner->size() < 2) return b;
    b[i] = Vec2(as_number(&(*corner)[0]).value_or(0.0), as_number(&(*corner)[1]).value_or(0.0));
  }
  return b;
}

double TableReader::component(const std::string& key, int i) const {
  const toml::node* n = node(key);
  toml::table fallback;
  if (!n || !n->is_array() || int(n->as_array()->size()) <= i) {
    const std::string& d = default_text(key);
    if (d.empty()) return 0.0;
    fallback = parse_default(d);
    n = fallback.get("v");
    if (!n || !n->is_array() || int(n->as_array()->size()) <= i) return 0.0;
  }
  return as_number(&(*n->as_array())[std::size_t(i)]).value_or(0.0);
}

double TableReader::box_component(const std::string& key, int corner, int i) const {
  const toml::node* n = node(key);
  if (!n || !n->is_array() || n->as_array()->size() != 2) return 0.0;
  const auto* c = (*n->as_array())[std::size_t(corner)].as_array();
  if (!c || int(c->size()) <= i) return 0.0;
  return as_number(&(*c)[std::size_t(i)]).value_or(0.0);
}

std::optional<ExpressionSpec> TableReader::expression(const std::string& key) const {
  const toml::node* n = node(key);
  ExpressionSpec e;
  e.key = path(key);
  if (n && n->is_string()) {
    e.text = n->as_string()->get();
  } else if (auto v = as_number(n)) {
    std::ostringstream os;
    os.precision(17);
    os << *v;
    e.text = os.str();
  } else {
    return std::nullopt;
  }
  e.where = source_of(*n, file_);
  return e;
}

TableReader TableReader::table(const std::string& key) const {
  const toml::node* n = node(key);
  const std::string sp = schema_.empty() ? key : schema_ + "." + key;
  return TableReader(n ? n->as_table() : nullptr, sp, path(key), file_, diag_);
}

std::vector<TableReader> TableReader::array(const std::string& key) const {
  std::vector<TableReader> r;
  const toml::node* n = node(key);
  if (!n || !n->is_array_of_tables()) return r;
  const std::string sp = (schema_.empty() ? key : schema_ + "." + key) + "[]";
  const auto& arr = *n->as_array();
  for (std::size_t i = 0; i < arr.size(); ++i)
    r.emplace_back(arr[i].as_table(), sp, path(key) + "[" + std::to_string(i) + "]", file_, diag_);
  return r;
}

}  // namespace loom
