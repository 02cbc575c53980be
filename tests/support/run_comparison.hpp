// Helpers of the tests that run loom more than one way and compare the runs (the PETSc back-end against the direct
// solvers, mpirun against one process); implemented in test_support.cpp.
#pragma once

#include <string>

#include "tests/support/test_support.hpp"

namespace loom::testing {

// The largest difference of two runs' probes over the run (step and time aside), relative to each probe's largest
// magnitude; a probe that is zero up to round-off in both (an area change of 1e-15) is compared absolutely, to 1e-12
// (beyond it: infinite). The names and row counts are expected equal (gtest expectations).
double probe_difference(const ProbeTable& a, const ProbeTable& b);

// `s` quoted for the shell.
std::string shell_quote(const std::string& s);

}  // namespace loom::testing
