// What the parts of the scene loader share: names as cross-references, and enum choices by name.
#pragma once

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/types.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

template <class E>
E pick(const std::string& v, std::initializer_list<std::pair<const char*, E>> table) {
  for (const auto& [name, value] : table)
    if (v == name) return value;
  return table.begin()->second;  // unreachable after schema validation
}

template <class Spec>
Index find_by_name(const std::vector<Spec>& items, const std::string& name) {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].name == name) return Index(i);
  return kNoIndex;
}

template <class Spec>
std::string names_of(const std::vector<Spec>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i.name;
  return s.empty() ? "(none)" : s;
}

// Names are keys of cross-references and columns of probes.csv: they must be non-empty.
inline std::string read_name(const TableReader& t) {
  std::string name = t.string("name");
  if (t.has("name") && name.empty()) t.error("name", "must not be empty");
  return name;
}

}  // namespace loom
