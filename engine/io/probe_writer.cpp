#include "engine/io/probe_writer.hpp"

#include <iomanip>

#include "engine/core/errors.hpp"

namespace loom {

void ProbeWriter::open(const std::string& path, const std::vector<std::string>& names) {
  path_ = path;
  out_.open(path, std::ios::trunc);
  LOOM_CHECK(out_, RunError, "cannot write " << path);
  out_ << "step,time";
  for (const auto& n : names) out_ << "," << n;
  out_ << "\n" << std::flush;
}

void ProbeWriter::write(int step, double time, const std::vector<double>& values) {
  out_ << step << "," << std::setprecision(12) << time;
  out_ << std::setprecision(15);
  for (double v : values) out_ << "," << v;
  out_ << "\n" << std::flush;
  LOOM_CHECK(out_, RunError, "cannot write " << path_);
}

}  // namespace loom
