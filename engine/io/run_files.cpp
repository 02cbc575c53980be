#include "engine/io/run_files.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/io/files.hpp"

namespace fs = std::filesystem;

namespace loom {
namespace {

// The step of a file named <prefix>NNNNNN<rest>, or -1.
int step_of(const std::string& name, const std::string& prefix) {
  if (name.size() < prefix.size() + 6 || name.compare(0, prefix.size(), prefix) != 0) return -1;
  int step = 0;
  for (std::size_t i = prefix.size(); i < prefix.size() + 6; ++i) {
    if (name[i] < '0' || name[i] > '9') return -1;
    step = 10 * step + (name[i] - '0');
  }
  return step;
}

bool is_frame(const fs::path& p) { return p.extension() == ".vtu" || p.extension() == ".vtp"; }

}  // namespace

void prepare_output_directory(const std::string& directory, const std::string& origin) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  LOOM_CHECK(!ec, InputError, origin << ": error: cannot create the output directory " << directory << ": " << ec.message());
  LOOM_CHECK(fs::is_directory(directory, ec), InputError, origin << ": error: the output directory " << directory << " is not a directory");
  // Permissions alone do not tell (root, read-only mounts): try to write.
  const std::string probe = directory + "/.loom_write_test";
  {
    std::ofstream out(probe);
    const int err = errno;
    LOOM_CHECK(out.good() && (out << "x").good(), InputError,
               origin << ": error: cannot write in the output directory " << directory << ": " << std::strerror(err ? err : EACCES));
  }
  std::remove(probe.c_str());
}

void remove_frames(const std::string& directory, const std::string& stem, int after_step, const std::vector<std::string>& kept) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory, ec)) {
    const std::string name = entry.path().filename().string();
    const int step = step_of(name, stem + "_");
    const bool listed = std::find(kept.begin(), kept.end(), name) != kept.end();
    if (step >= 0 && (step > after_step || (step == after_step && !listed)) && is_frame(entry.path())) fs::remove(entry.path(), ec);
    // Temporaries of a run that was killed outright.
    if (name.rfind(stem + "_", 0) == 0 && entry.path().extension() == ".tmp") fs::remove(entry.path(), ec);
  }
}

std::string checkpoint_path(const std::string& directory, int step) {
  std::ostringstream os;
  os << directory << "/checkpoint_" << std::setw(6) << std::setfill('0') << step << ".loom";
  return os.str();
}

void remove_checkpoints(const std::string& directory, int keep) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory, ec)) {
    const std::string name = entry.path().filename().string();
    const int step = step_of(name, "checkpoint_");
    if (step >= 0 && step != keep && (entry.path().extension() == ".loom" || entry.path().extension() == ".tmp"))
      fs::remove(entry.path(), ec);
  }
}

std::string find_checkpoint(const std::string& path) {
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return path;
  LOOM_CHECK(fs::is_directory(path, ec), InputError, "--restart " << path << ": error: no such file or directory");
  int best = -1;
  std::string found;
  for (const auto& entry : fs::directory_iterator(path, ec)) {
    const std::string name = entry.path().filename().string();
    const int step = step_of(name, "checkpoint_");
    if (step > best && entry.path().extension() == ".loom") best = step, found = entry.path().string();
  }
  LOOM_CHECK(best >= 0, InputError,
             "--restart " << path << ": error: no checkpoint in this directory (a run writes checkpoint_NNNNNN.loom files when "
                                     "[output] checkpoint_every > 0, or when it stops at --stop-after)");
  return found;
}

}  // namespace loom
