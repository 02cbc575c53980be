// Files are written to a temporary name and renamed, so that a killed run never leaves a corrupt file
// (DESIGN §6).
#pragma once

#include <string>

namespace loom {

// Writes `content` to `path` atomically (temporary file in the same directory, then rename).
void write_file_atomic(const std::string& path, const std::string& content);
std::string temporary_name(const std::string& path);
// A scene name made safe as a file-name stem: characters other than letters, digits, - _ . become _.
std::string file_stem(const std::string& name);

}  // namespace loom
