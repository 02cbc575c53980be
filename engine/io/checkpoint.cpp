#include "engine/io/checkpoint.hpp"

#include <fstream>
#include <sstream>

#include "engine/io/files.hpp"

namespace loom {
namespace {

constexpr char kMagic[8] = {'L', 'O', 'O', 'M', 'C', 'K', 'P', 'T'};
constexpr std::uint32_t kFormat = 1;

std::uint64_t fnv1a(const char* data, std::size_t n) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(data[i])) * 1099511628211ull;
  return h;
}

template <class T>
void put(std::string& out, T v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

}  // namespace

void CheckpointWriter::blob(const std::string& name, std::size_t element_size, std::size_t count, const void* data) {
  put(body_, std::uint32_t(name.size()));
  body_ += name;
  put(body_, std::uint64_t(element_size));
  put(body_, std::uint64_t(count));
  body_.append(static_cast<const char*>(data), element_size * count);
  ++count_;
}

std::string CheckpointWriter::bytes() const {
  std::string out(kMagic, sizeof kMagic);
  put(out, kFormat);
  put(out, count_);
  out += body_;
  put(out, fnv1a(out.data(), out.size()));
  return out;
}

void CheckpointWriter::write(const std::string& path) const { write_file_atomic(path, bytes()); }

CheckpointReader::CheckpointReader(const std::string& path) : path_(path) {
  std::ifstream in(path, std::ios::binary);
  LOOM_CHECK(in, InputError, path << ": error: cannot read the checkpoint");
  std::ostringstream all;
  all << in.rdbuf();
  content_ = all.str();
  const std::size_t header = sizeof kMagic + 2 * sizeof(std::uint32_t), tail = sizeof(std::uint64_t);
  LOOM_CHECK(content_.size() >= header + tail && content_.compare(0, sizeof kMagic, kMagic, sizeof kMagic) == 0, InputError,
             path << ": error: not a loom checkpoint");
  std::uint64_t sum = 0;
  std::memcpy(&sum, content_.data() + content_.size() - tail, tail);
  LOOM_CHECK(sum == fnv1a(content_.data(), content_.size() - tail), InputError,
             path << ": error: the checkpoint is truncated or corrupt (checksum mismatch)");
  std::uint32_t format = 0, count = 0;
  std::memcpy(&format, content_.data() + sizeof kMagic, sizeof format);
  std::memcpy(&count, content_.data() + sizeof kMagic + sizeof format, sizeof count);
  LOOM_CHECK(format == kFormat, InputError, path << ": error: checkpoint format " << format << ", this loom reads format " << kFormat);
  std::size_t at = header;
  const std::size_t end = content_.size() - tail;
  auto take = [&](void* dst, std::size_t n) {
    LOOM_CHECK(at + n <= end, InputError, path << ": error: the checkpoint is truncated");
    std::memcpy(dst, content_.data() + at, n);
    at += n;
  };
  for (std::uint32_t k = 0; k < count; ++k) {
    std::uint32_t name_size = 0;
    take(&name_size, sizeof name_size);
    LOOM_CHECK(at + name_size <= end, InputError, path << ": error: the checkpoint is truncated");
    std::string name(content_.data() + at, name_size);
    at += name_size;
    std::uint64_t element_size = 0, n = 0;
    take(&element_size, sizeof element_size);
    take(&n, sizeof n);
    LOOM_CHECK(element_size == 0 || n <= (end - at) / element_size, InputError, path << ": error: the checkpoint is truncated");
    blobs_[name] = Blob{std::size_t(element_size), std::size_t(n), content_.data() + at};
    at += std::size_t(element_size * n);
  }
}

const CheckpointReader::Blob& CheckpointReader::find(const std::string& name, std::size_t element_size) const {
  auto it = blobs_.find(name);
  LOOM_CHECK(it != blobs_.end(), InputError,
             path_ << ": error: the checkpoint has no entry " << name << ": the scene differs from the one it was written for, or the checkpoint was written by another loom build "
                      "(a checkpoint is read back by the build that wrote it)");
  LOOM_CHECK(it->second.element_size == element_size, InputError,
             path_ << ": error: checkpoint entry " << name << " has elements of " << it->second.element_size << " bytes, expected "
                   << element_size << " (written by another loom build?)");
  return it->second;
}

}  // namespace loom
