#include "engine/core/errors.hpp"

#include <cstdlib>
#include <iostream>

namespace loom::detail {

void assertion_failed(const char* expr, const char* file, int line, const std::string& msg) {
  std::cerr << "loom: internal assertion failed: " << expr << " at " << file << ":" << line;
  if (!msg.empty()) std::cerr << ": " << msg;
  std::cerr << std::endl;
  std::abort();
}

}  // namespace loom::detail
