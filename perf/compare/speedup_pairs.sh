#!/bin/bash
# The whole-step two-thread speed-up of the cantilever, measured in interleaved runs: each round runs
# auto on 1 thread, cholmod_bisected on 2, cholmod_bisected on 1 and auto on 2, one after the other, so that
# the machine's drift (2-3x between hours on a shared VM) hits the four alike; the speed-up of a round is
# the ratio of two neighbouring runs, and the median over rounds is reported.
#   perf/compare/speedup_pairs.sh [K=25 (100 000 particles)] [ROUNDS=5] [LOOM=build/loom]
set -euo pipefail
K=${1:-25}; ROUNDS=${2:-5}; LOOM=${3:-build/loom}
cd "$(dirname "$0")/../.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "round linear threads wall_s"
for r in $(seq "$ROUNDS"); do
  for cfg in "auto 1" "cholmod_bisected 2" "cholmod_bisected 1" "auto 2"; do
    set -- $cfg
    "$LOOM" run perf/compare/cantilever_mpm.toml --out "$out/run" --threads "$2" --quiet \
      --set "body[0].mesh.divisions=[$((5 * K)),$K]" --set "grid.divisions=[$((21 * K)),$((5 * K))]" --set "solver.linear=\"$1\"" > /dev/null
    echo "$r $1 $2 $(/usr/bin/env python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['wall_seconds'])" "$out/run/run.json")"
  done
done | tee "$out/rows"
/usr/bin/env python3 - "$out/rows" <<'PY'
import sys, statistics as st
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
w = {}
for r, lin, thr, s in rows: w.setdefault((lin, thr), []).append(float(s))
med = {k: st.median(v) for k, v in w.items()}
for k, v in sorted(med.items()): print(f"median {k[0]:17s} {k[1]} thread(s): {v:8.3f} s")
pairs = [a / b for a, b in zip(w[("auto", "1")], w[("cholmod_bisected", "2")])]
own = [a / b for a, b in zip(w[("cholmod_bisected", "1")], w[("cholmod_bisected", "2")])]
print("cholmod_bisected on 2 threads over auto on 1, per round:", " ".join(f"{x:.2f}" for x in pairs), f"median {st.median(pairs):.2f}")
print("cholmod_bisected 2 over 1 thread, per round:           ", " ".join(f"{x:.2f}" for x in own), f"median {st.median(own):.2f}")
PY
