#include "engine/io/pvd_writer.hpp"

#include <sstream>

#include "engine/io/files.hpp"

namespace loom {

void PvdWriter::add(double time, const std::string& file, int part) {
  entries_.push_back({time, file, part});
  rewrite();
}

void PvdWriter::restore(std::vector<Entry> entries) {
  entries_ = std::move(entries);
  rewrite();
}

void PvdWriter::rewrite() const {
  std::ostringstream os;
  os.precision(15);
  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (const auto& e : entries_)
    os << "    <DataSet timestep=\"" << e.time << "\" group=\"\" part=\"" << e.part << "\" file=\"" << e.file << "\"/>\n";
  os << "  </Collection>\n</VTKFile>\n";
  write_file_atomic(path(), os.str());
}

}  // namespace loom
