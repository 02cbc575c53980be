// A checkpoint: one binary file holding named blobs -- every column of every store, the step and time, the
// writer state -- so that `loom run SCENE --restart DIR` continues a run as if it had never stopped (same
// probes.csv, bit for bit). Layout: "LOOMCKPT", format version, blob count, then per blob its name, element
// size, element count and raw bytes, and an FNV-1a checksum of all of it. Files are written atomically
// (temporary name, then rename). The layout is that of this build: a checkpoint is read back by the same
// loom version on the same kind of machine, not archived.
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include "engine/core/errors.hpp"
#include "engine/store/column.hpp"

namespace loom {

// What a checkpoint stores as raw bytes: numbers, and fixed-size Eigen vectors and matrices of them (plain
// arrays of coefficients; Eigen declares their copy constructors, so they are not "trivially copyable").
template <class T, class = void>
struct is_plain_data : std::is_arithmetic<T> {};
template <class T>
struct is_plain_data<T, std::void_t<typename T::Scalar, decltype(T::SizeAtCompileTime)>>
    : std::bool_constant<std::is_arithmetic_v<typename T::Scalar> && (T::SizeAtCompileTime > 0) &&
                         sizeof(T) == sizeof(typename T::Scalar) * std::size_t(T::SizeAtCompileTime)> {};

class CheckpointWriter {
 public:
  template <class T>
  void vector(const std::string& name, const std::vector<T>& v) {
    static_assert(is_plain_data<T>::value);
    blob(name, sizeof(T), v.size(), v.data());
  }
  // A column with its allocation flag: an unused column is recorded as unused (and empty).
  template <class T>
  void column(const std::string& name, const Column<T>& c) {
    value(name + "#used", char(c.used() ? 1 : 0));
    vector(name, c.values());
  }
  template <class T>
  void value(const std::string& name, const T& v) {
    static_assert(is_plain_data<T>::value);
    blob(name, sizeof(T), 1, &v);
  }
  void text(const std::string& name, const std::string& s) { blob(name, 1, s.size(), s.data()); }
  // Every column of a store (anything with for_each_column(name, column)), under `prefix/`.
  template <class Store>
  void store(const std::string& prefix, const Store& s) {
    s.for_each_column([&](const char* name, const auto& c) { column(prefix + "/" + name, c); });
  }

  std::string bytes() const;
  void write(const std::string& path) const;  // atomically

 private:
  void blob(const std::string& name, std::size_t element_size, std::size_t count, const void* data);
  std::string body_;
  std::uint32_t count_ = 0;
};

class CheckpointReader {
 public:
  // Throws InputError naming the file if it cannot be read, is not a checkpoint, is truncated or corrupt.
  explicit CheckpointReader(const std::string& path);
  const std::string& path() const { return path_; }
  bool has(const std::string& name) const { return blobs_.count(name) > 0; }

  template <class T>
  void vector(const std::string& name, std::vector<T>& v) const {
    const Blob& b = find(name, sizeof(T));
    v.resize(b.count);
    if (b.count) std::memcpy(static_cast<void*>(v.data()), b.data, b.count * sizeof(T));
  }
  template <class T>
  void column(const std::string& name, Column<T>& c) const {
    // A column the checkpoint does not name is one its version did not have (particles/be before history materials
    // reached the particles): unused.
    const bool used = has(name + "#used") && value<char>(name + "#used") != 0;
    LOOM_CHECK(used == c.used(), InputError,
               path_ << ": error: the checkpoint " << (used ? "holds" : "does not hold") << " column " << name
                     << ", which this scene " << (used ? "does not use" : "uses")
                     << ": the scene differs from the one the checkpoint was written for");
    if (used) vector(name, c.values());
  }
  template <class T>
  T value(const std::string& name) const {
    const Blob& b = find(name, sizeof(T));
    LOOM_CHECK(b.count == 1, InputError, path_ << ": error: checkpoint entry " << name << " is not a single value");
    T v;
    std::memcpy(static_cast<void*>(&v), b.data, sizeof(T));
    return v;
  }
  std::string text(const std::string& name) const {
    const Blob& b = find(name, 1);
    return std::string(b.data, b.count);
  }
  template <class Store>
  void store(const std::string& prefix, Store& s) const {
    s.for_each_column([&](const char* name, auto& c) { column(prefix + "/" + name, c); });
  }
  // A restored store must fit the scene's model (the same mesh, the same particles): InputError naming
  // what differs otherwise.
  void expect_size(const std::string& what, std::size_t restored, std::size_t model) const {
    expect(restored == model, "holds " + std::to_string(restored) + " " + what + ", the scene's model " + std::to_string(model));
  }
  void expect(bool ok, const std::string& what) const {
    LOOM_CHECK(ok, InputError,
               path_ << ": error: the checkpoint " << what
                     << ": the scene (its mesh, particles or grid) differs from the one the checkpoint was written for");
  }

 private:
  struct Blob {
    std::size_t element_size = 0, count = 0;
    const char* data = nullptr;
  };
  const Blob& find(const std::string& name, std::size_t element_size) const;
  std::string path_, content_;
  std::map<std::string, Blob> blobs_;
};

}  // namespace loom
