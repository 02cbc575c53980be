// The ParaView collection file `<scene>.pvd`: one DataSet entry per frame, rewritten atomically after
// each frame so that it always lists exactly the frames that exist.
#pragma once

#include <string>
#include <vector>

namespace loom {

class PvdWriter {
 public:
  PvdWriter() = default;
  PvdWriter(std::string directory, std::string name) : directory_(std::move(directory)), name_(std::move(name)) {}
  // Records a frame file (relative to the directory) and rewrites the collection.
  void add(double time, const std::string& file, int part = 0);
  std::string path() const { return directory_ + "/" + name_ + ".pvd"; }

  struct Entry {
    double time;
    std::string file;
    int part;
  };
  const std::vector<Entry>& entries() const { return entries_; }
  // A restarted run: the frames its checkpoint had written; rewrites the collection.
  void restore(std::vector<Entry> entries);

 private:
  void rewrite() const;
  std::string directory_, name_;
  std::vector<Entry> entries_;
};

}  // namespace loom
