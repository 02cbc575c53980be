// Where a scene value came from: file, line and column (1-based), or the command line (--set).
#pragma once

#include <ostream>
#include <string>

namespace loom {

struct SourceRef {
  std::string file;  // scene file; empty for values set on the command line
  int line = 0;
  int column = 0;
};

inline std::ostream& operator<<(std::ostream& os, const SourceRef& s) {
  if (s.line == 0) return os << (s.file.empty() ? "command line (--set)" : s.file);
  return os << s.file << ":" << s.line << ":" << s.column;
}

}  // namespace loom
