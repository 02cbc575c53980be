#!/usr/bin/env bash
# One process against `mpirun -n 2` on this machine's two cores, whole runs of the step-44 block
# (scenes/block_3d.toml: mixed u-phi tetrahedra at nu = 0.4999, FGMRES + Schur fieldsplit with GAMG on u) with
# solver.linear = "petsc": the same mesh on 1 and 2 ranks (strong), and twice the mesh on 2 ranks (weak: the same dofs
# per rank). Per run: dofs, wall, assembly, preconditioner set-up and Krylov seconds (rank 0's timers), Krylov
# iterations, the peak resident memory of each rank, and the last uy_centre. docs/petsc.md quotes its output.
# Usage: perf/petsc/ranks_study.sh [LOOM] [N] [STEPS] [ROUNDS]
#   (default build/loom, N = 28 (9.8e4 dofs), 2 steps, 2 rounds alternated; about 6 minutes; run it on a quiet machine)
set -euo pipefail
cd "$(dirname "$0")/../.."
loom=${1:-build/loom}
n=${2:-28}
steps=${3:-2}
rounds=${4:-2}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_THREAD_LIMIT=1 OPENBLAS_NUM_THREADS=1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf "| case | ranks | mesh | dofs | wall s | assembly s | set-up s | Krylov s | iterations | peak RSS per rank MB | uy_centre |\n"
printf "|---|---:|---|---:|---:|---:|---:|---:|---:|---|---:|\n"
run() {  # case ranks divisions
  local name=$1 ranks=$2 divisions=$3 dir="$out/$1_$2"
  rm -rf "$dir" && mkdir -p "$dir"
  # Each rank's peak memory to its own file (the rank from Open MPI's environment).
  local cmd=(bash -c '/usr/bin/time -o "$0/rss.$OMPI_COMM_WORLD_RANK" -f %M "$@"' "$dir" "$loom" run scenes/block_3d.toml --quiet
             --threads 1 --out "$dir/out" --set "body[0].mesh.divisions=$divisions" --set time.steps="$steps" --set 'solver.linear="petsc"')
  if [ "$ranks" -gt 1 ]; then mpirun -n "$ranks" "${cmd[@]}" >/dev/null; else OMPI_COMM_WORLD_RANK=0 "${cmd[@]}" >/dev/null; fi
  python3 - "$dir" "$name" "$ranks" "$divisions" <<'PY'
import csv, glob, json, sys
d, name, ranks, divisions = sys.argv[1:]
r = json.load(open(d + "/out/run.json"))
t = json.load(open(d + "/out/timings.json"))["timers"]
s = lambda k: t[k]["total"] if k in t else 0.0
rss = "/".join(str(round(int(open(f).read().split()[-1]) / 1024)) for f in sorted(glob.glob(d + "/rss.*")))
rows = list(csv.reader(open(d + "/out/probes.csv")))
uy = rows[-1][rows[0].index("uy_centre")]
print(f"| {name} | {ranks} | {divisions} | {r['dofs']} | {r['wall_seconds']:.1f} | {s('newton/assemble'):.1f} | "
      f"{s('newton/solve/factorize'):.1f} | {s('newton/solve/back_substitute'):.1f} | {r['linear_iterations']} | {rss} | {uy} |")
PY
}
for round in $(seq "$rounds"); do
  run strong 1 "[$n,$n,$n]"
  run strong 2 "[$n,$n,$n]"
  run weak 2 "[$n,$n,$((2 * n + 1))]"
done
