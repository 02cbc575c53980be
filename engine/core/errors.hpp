// Two kinds of check, never mixed (STYLE §7):
//  - LOOM_ASSERT: programming contracts, compiled out in release builds;
//  - LOOM_CHECK / typed exceptions: run-time and user errors, always on.
// InputError (bad scene or command line, exit 2) and RunError (a run that failed, exit 1) are the two
// exception families the program turns into exit codes.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace loom {

// Bad input: the program exits with code 2. The message is complete (file:line:column, key, what).
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run that could not go on (Newton gave up, anomaly in a system): exit code 1.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {
[[noreturn]] void assertion_failed(const char* expr, const char* file, int line, const std::string& msg);
}

}  // namespace loom

#ifdef NDEBUG
#define LOOM_ASSERT(expr, msg) ((void)0)
#else
#define LOOM_ASSERT(expr, msg)                                                            \
  do {                                                                                    \
    if (!(expr)) {                                                                        \
      std::ostringstream loom_assert_os_;                                                 \
      loom_assert_os_ << msg;                                                             \
      ::loom::detail::assertion_failed(#expr, __FILE__, __LINE__, loom_assert_os_.str()); \
    }                                                                                     \
  } while (false)
#endif

// Throws ErrorType with the streamed message when expr is false.
#define LOOM_CHECK(expr, ErrorType, msg) \
  do {                                   \
    if (!(expr)) {                       \
      std::ostringstream loom_check_os_; \
      loom_check_os_ << msg;             \
      throw ErrorType(loom_check_os_.str()); \
    }                                    \
  } while (false)
