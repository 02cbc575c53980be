// A column is one contiguous array of one field of a store (DESIGN §2, STYLE §2).
// A column that no system of the scene uses is never allocated: resize() leaves it empty, and
// describe() shows it as absent, so `loom info` tells what a scene pays for.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/core/errors.hpp"
#include "engine/core/prefetch.hpp"
#include "engine/core/types.hpp"

namespace loom {

template <class T>
class Column {
 public:
  using value_type = T;

  // Marks the column as used (or not) by the scene; an unused column holds no memory.
  void use(bool on = true) {
    used_ = on;
    if (!on) std::vector<T>().swap(values_);
  }
  bool used() const { return used_; }

  void resize(Index n, const T& fill = T()) {
    if (used_) values_.resize(static_cast<std::size_t>(n), fill);
  }
  // For flat columns holding `stride` values per entity (connectivity, shape gradients).
  void resize_strided(Index n, int stride, const T& fill = T()) {
    if (used_) values_.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(stride), fill);
  }
  void assign(Index n, const T& value) {
    if (used_) values_.assign(static_cast<std::size_t>(n), value);
  }

  T& operator[](Index i) {
    LOOM_ASSERT(i >= 0 && static_cast<std::size_t>(i) < values_.size(), "column index " << i << " out of range");
    return values_[static_cast<std::size_t>(i)];
  }
  const T& operator[](Index i) const {
    LOOM_ASSERT(i >= 0 && static_cast<std::size_t>(i) < values_.size(), "column index " << i << " out of range");
    return values_[static_cast<std::size_t>(i)];
  }

  Index size() const { return static_cast<Index>(values_.size()); }
  bool empty() const { return values_.empty(); }
  T* data() { return values_.data(); }
  const T* data() const { return values_.data(); }
  auto begin() { return values_.begin(); }
  auto end() { return values_.end(); }
  auto begin() const { return values_.begin(); }
  auto end() const { return values_.end(); }
  std::vector<T>& values() { return values_; }
  const std::vector<T>& values() const { return values_; }
  std::size_t bytes() const { return values_.capacity() * sizeof(T); }

 private:
  std::vector<T> values_;
  bool used_ = false;
};

// Prefetches entry i of a column, or of a per-entity vector, if it holds one (engine/core/prefetch.hpp).
template <class T>
void prefetch_row(const Column<T>& column, Index i) {
  if (i < column.size()) prefetch_object(column[i]);
}
template <class T>
void prefetch_row(const std::vector<T>& values, Index i) {
  if (std::size_t(i) < values.size()) prefetch_object(values[std::size_t(i)]);
}

}  // namespace loom
