#!/usr/bin/env bash
# Installs loom's Debian 12 dependencies (idempotent) and builds the loom program into build/.
# Usage: tools/setup.sh [--no-build | --all]   Environment: LOOM_BUILD_TYPE (default Release), LOOM_JOBS.
#   (default)   the program build/loom only: what running a scene needs (about 8 minutes fresh on two cores)
#   --all       everything: the program, the test programs and the benchmarks (tools/test.sh asks for this)
#   --no-build  the packages only
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
  --no-build) target=none ;;
  --all) target=all ;;
  "") target=loom ;;
  *) echo "setup: unknown option $1 (--no-build, --all)" >&2; exit 2 ;;
esac


# xvfb: tools/render draws off-screen through an X server of its own (Debian's VTK 9.1 renders through X).
# Packages are installed without their Recommends, so every recommended package that a test uses is listed:
# xauth (xvfb-run needs it; only recommended by xvfb). libpetsc-real-dev (with Open MPI, hypre, MUMPS: about 50 packages,
# 200 MB) builds the plugin of solver.linear = "petsc" (docs/petsc.md); loom builds without it.
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libtbb-dev libcgal-dev libsuitesparse-dev libopenblas0-pthread
  libvtk9-dev libbenchmark-dev libgtest-dev libgmock-dev libtomlplusplus-dev libmuparser-dev libgmsh-dev
  python3 python3-numpy python3-matplotlib python3-vtk9 xvfb xauth
  libpetsc-real-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

[ "$target" = none ] && exit 0
cmake -S . -B build -DCMAKE_BUILD_TYPE="${LOOM_BUILD_TYPE:-Release}" >/dev/null
cmake --build build -j "${LOOM_JOBS:-$(nproc)}" --target "$target"
