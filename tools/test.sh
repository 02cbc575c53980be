#!/usr/bin/env bash
# Runs loom's default test suite: sets up (installs missing Debian packages, builds the program, the tests and
# the benchmarks into build/) if needed, then ctest without the long labels (stress, study). Extra arguments go to
# ctest, e.g.
#   tools/test.sh -L unit          tools/test.sh -R Patch
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh --all
ctest --test-dir build --output-on-failure -j "${LOOM_JOBS:-$(nproc)}" -LE "stress|study" "$@"
