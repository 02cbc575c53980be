// Typed access to one table of a scene that has passed the schema check. Defaults come from the schema,
// so the loader never repeats them. A value of the wrong type was already reported by the validator: the
// reader then returns the default without a second message.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "engine/core/types.hpp"
#include "engine/scene/diagnostics.hpp"
#include "engine/scene/scene_spec.hpp"

namespace loom {

class TableReader {
 public:
  TableReader(const toml::table* table, std::string schema_path, std::string display_path, const std::string& file,
              Diagnostics& diag);

  bool present() const { return table_ != nullptr; }
  bool has(const std::string& key) const;

  std::string string(const std::string& key) const;
  double real(const std::string& key) const;
  std::optional<double> optional_real(const std::string& key) const;
  long long integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  Vec2 vec2(const std::string& key) const;
  std::array<long long, 2> ivec2(const std::string& key) const;
  std::array<Vec2, 2> box(const std::string& key) const;
  // The i-th number of a vector value (its default's when absent), of corner `corner` of a box value.
  double component(const std::string& key, int i) const;
  double box_component(const std::string& key, int corner, int i) const;
  std::optional<ExpressionSpec> expression(const std::string& key) const;

  TableReader table(const std::string& key) const;          // absent table: present() == false
  std::vector<TableReader> array(const std::string& key) const;

  SourceRef where(const std::string& key) const;  // position of the key's value
  SourceRef where() const;                        // position of this table
  std::string path(const std::string& key) const;  // display path, e.g. body[0].mesh.size
  const std::string& path() const { return display_; }
  void error(const std::string& key, const std::string& message) const;

 private:
  const toml::node* node(const std::string& key) const;
  const std::string& default_text(const std::string& key) const;

  const toml::table* table_;
  std::string schema_, display_;
  const std::string& file_;
  Diagnostics& diag_;
};

}  // namespace loom
