#include "engine/scene/diagnostics.hpp"

#include <sstream>

#include "engine/core/errors.hpp"

namespace loom {

std::string Diagnostics::report() const {
  std::ostringstream os;
  for (const auto& d : errors_) {
    os << d.where << ": error: ";
    if (!d.key.empty()) os << d.key << ": ";
    os << d.message << "\n";
  }
  return os.str();
}

void Diagnostics::throw_if_errors() const {
  if (!ok()) throw InputError(report());
}

}  // namespace loom
