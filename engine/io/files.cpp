#include "engine/io/files.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>

#include "engine/core/errors.hpp"

namespace loom {

std::string temporary_name(const std::string& path) { return path + ".tmp"; }

void write_file_atomic(const std::string& path, const std::string& content) {
  const std::string tmp = temporary_name(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    LOOM_CHECK(out, RunError, "cannot write " << tmp);
    out << content;
    out.flush();
    LOOM_CHECK(out, RunError, "cannot write " << tmp);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  LOOM_CHECK(!ec, RunError, "cannot rename " << tmp << " to " << path << ": " << ec.message());
}

std::string file_stem(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) c = '_';
  return s;
}

}  // namespace loom
