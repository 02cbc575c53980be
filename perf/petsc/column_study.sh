#!/usr/bin/env bash
# The mixed u-p MPM system of the twisting column (scenes/column_twisting_mpm.toml) on the paper's three grids, solved
# by UMFPACK and by solver.linear = "petsc" (FGMRES + Schur-complement fieldsplit, GAMG on u), fresh and with the
# preconditioner kept (solver.reuse_factor): unknowns, Newton solves, Krylov iterations per solve, preconditioner
# set-ups, wall seconds, and u_x(A) at the last step against UMFPACK's. docs/petsc.md quotes its output.
# Usage: perf/petsc/column_study.sh [LOOM] [STEPS]   (default build/loom, 10 steps; about 6 minutes on two cores)
set -euo pipefail
cd "$(dirname "$0")/../.."
loom=${1:-build/loom}
steps=${2:-10}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf "| h | grid | dofs | solver | Newton solves | iterations per solve | set-ups | wall s | u_x(A) |\n|---|---|---:|---|---:|---:|---:|---:|---:|\n"
for level in "0.25 [16,16,28] [4,4,24]" "0.1667 [24,24,42] [6,6,36]" "0.125 [32,32,56] [8,8,48]"; do
  read -r h grid body <<<"$level"
  for solver in umfpack petsc petsc_reuse; do
    linear=${solver%_reuse}
    reuse=false; [ "$solver" = petsc_reuse ] && reuse=true
    "$loom" run scenes/column_twisting_mpm.toml --quiet --threads 1 --out "$out/$solver" --set time.steps="$steps" \
      --set "grid.divisions=$grid" --set "body[0].mesh.divisions=$body" --set "solver.linear=\"$linear\"" \
      --set "solver.reuse_factor=$reuse" >/dev/null
    python3 - "$out/$solver" "$h" "$grid" "$solver" <<'PY'
import json, sys, csv
d, h, grid, solver = sys.argv[1:]
r = json.load(open(d + "/run.json"))
rows = list(csv.reader(open(d + "/probes.csv")))
ux = rows[-1][rows[0].index("ux_A")] if "ux_A" in rows[0] else rows[-1][2]
n = r["newton_iterations"]
per = r["linear_iterations"] / n if r["linear_iterations"] else 0
print(f"| {h} | {grid} | {r['dofs']} | {solver} | {n} | {per:.0f} | {r['preconditioner_set_ups']} | {r['wall_seconds']:.1f} | {ux} |")
PY
  done
done
