// Collects every error found in a scene so that all are reported at once (STYLE §6); each names the
// source position and the key path (e.g. `body[0].mesh.divisions`).
#pragma once

#include <string>
#include <vector>

#include "engine/scene/source.hpp"

namespace loom {

struct Diagnostic {
  SourceRef where;
  std::string key;  // display path, with array indices
  std::string message;
};

class Diagnostics {
 public:
  void error(const SourceRef& where, const std::string& key, const std::string& message) {
    errors_.push_back({where, key, message});
  }
  bool ok() const { return errors_.empty(); }
  const std::vector<Diagnostic>& errors() const { return errors_; }
  // One line per error: "file:line:col: error: key: message".
  std::string report() const;
  // Throws InputError with report() if any error was recorded.
  void throw_if_errors() const;

 private:
  std::vector<Diagnostic> errors_;
};

}  // namespace loom
