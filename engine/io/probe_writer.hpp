// probes.csv: `step,time,<probe>...`, one row per step, flushed at once so that a killed or failed run
// keeps every row it reached.
#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace loom {

class ProbeWriter {
 public:
  ProbeWriter() = default;
  // Opens (truncates) the file and writes the header.
  void open(const std::string& path, const std::vector<std::string>& names);
  // A restarted run: keeps the header and the rows of steps up to `through_step` of an existing file
  // (InputError if its header is not `step,time,<names>`) and appends after them.
  void reopen(const std::string& path, const std::vector<std::string>& names, int through_step);
  void write(int step, double time, const std::vector<double>& values);
  bool is_open() const { return out_.is_open(); }

 private:
  std::ofstream out_;
  std::string path_;
};

}  // namespace loom
