#!/usr/bin/env bash
# The cost of one static Newton step of the smoothed elements on tetrahedra against the mixed u-phi tetrahedron, on the
# homogeneous compression of scenes/homogeneous_compression_3d.toml (a box of Kuhn tetrahedra, Neo-Hooke, E = 10,
# nu = 0.3, one step of 10 % compression, three Newton iterations): per element the dofs, the factorisation per
# iteration, the assembly per call and the whole step, from the run's --profile timers. A study, not a test: run it
# on a quiet machine.
#
#   perf/smoothed_3d_step.sh [DIVISIONS] [LINEAR]     e.g. perf/smoothed_3d_step.sh "[34,17,17]" petsc
#
# DIVISIONS (default [26,13,13]: 5 292 nodes) are the box's cubes along x, y, z; LINEAR (default the scene's: UMFPACK for
# the mixed elements, CHOLMOD for es_u) is solver.linear. LOOM is the loom program (default build/loom).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
loom=${LOOM:-$here/build/loom}
divisions=${1:-"[26,13,13]"}
linear=${2:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for element in p1p1_uphi es_up fem_up es_u; do
  sets=(--set "body[0].element=\"$element\"" --set "body[0].mesh.divisions=$divisions" --set time.steps=1)
  case $element in es_up | fem_up) sets+=(--set body[0].alpha_stab=0.5) ;; esac
  [ -n "$linear" ] && sets+=(--set "solver.linear=\"$linear\"")
  "$loom" run "$here/scenes/homogeneous_compression_3d.toml" --quiet --profile --out "$out/$element" "${sets[@]}" >/dev/null
  python3 - "$out/$element" "$element" <<'PY'
import json, sys
folder, element = sys.argv[1], sys.argv[2]
t = json.load(open(f"{folder}/timings.json"))["timers"]
r = json.load(open(f"{folder}/run.json"))
total = lambda k: t.get(k, {}).get("total", 0.0)
calls = lambda k: max(t.get(k, {}).get("calls", 1), 1)
print(f"{element:10s} dofs {r['dofs']:>7}  Newton {r['newton_iterations']}  factorize {total('newton/solve/factorize') / calls('newton/solve/factorize'):7.3f} s"
      f"  solve {total('newton/solve') / calls('newton/solve'):7.3f} s  assemble {total('newton/assemble') / calls('newton/assemble'):6.3f} s"
      f"  step {total('newton'):7.2f} s  ({r['linear_solver']})")
PY
done
