#include "engine/io/probe_writer.hpp"

#include <cstdlib>
#include <iomanip>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/io/files.hpp"

namespace loom {
namespace {

std::string header(const std::vector<std::string>& names) {
  std::string h = "step,time";
  for (const auto& n : names) h += "," + n;
  return h;
}

}  // namespace

void ProbeWriter::open(const std::string& path, const std::vector<std::string>& names) {
  path_ = path;
  out_.open(path, std::ios::trunc);
  LOOM_CHECK(out_, RunError, "cannot write " << path);
  out_ << header(names) << "\n" << std::flush;
}

void ProbeWriter::reopen(const std::string& path, const std::vector<std::string>& names, int through_step) {
  std::ifstream in(path);
  LOOM_CHECK(in, InputError, path << ": error: cannot read the probes of the run to continue");
  std::string line, kept;
  std::getline(in, line);
  LOOM_CHECK(line == header(names), InputError,
             path << ": error: its columns (" << line << ") are not this scene's probes (" << header(names) << ")");
  kept = line + "\n";
  int rows = 0;
  while (std::getline(in, line)) {
    const int step = std::atoi(line.c_str());
    if (step > through_step) break;
    kept += line + "\n";
    ++rows;
  }
  LOOM_CHECK(rows == through_step + 1, InputError,
             path << ": error: holds " << rows << " rows up to step " << through_step << ", expected " << through_step + 1
                  << " (steps 0.." << through_step << ")");
  in.close();
  write_file_atomic(path, kept);
  path_ = path;
  out_.open(path, std::ios::app);
  LOOM_CHECK(out_, RunError, "cannot write " << path);
}

void ProbeWriter::write(int step, double time, const std::vector<double>& values) {
  out_ << step << "," << std::setprecision(12) << time;
  out_ << std::setprecision(15);
  for (double v : values) out_ << "," << v;
  out_ << "\n" << std::flush;
  LOOM_CHECK(out_, RunError, "cannot write " << path_);
}

}  // namespace loom
