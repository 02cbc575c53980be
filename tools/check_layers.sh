#!/usr/bin/env bash
# Layers point one way (STYLE §1): the engine core never includes systems/; only engine/methods (the
# recipes) and engine/cli (the program) may. Exits non-zero and lists the offending lines otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."
bad=$(grep -rnE '#include[[:space:]]+"systems/' engine --include='*.hpp' --include='*.cpp' | grep -vE '^engine/(methods|cli)/' || true)
if [ -n "$bad" ]; then
  echo "engine core includes systems/ (only engine/methods and engine/cli may):"
  echo "$bad"
  exit 1
fi
vtk=$(grep -rlE '#include[[:space:]]+<vtk' engine systems --include='*.hpp' --include='*.cpp' | grep -v '^engine/io/vtk_writer.cpp$' || true)
if [ -n "$vtk" ]; then
  echo "VTK headers outside engine/io/vtk_writer.cpp:"
  echo "$vtk"
  exit 1
fi
echo "layers ok"
