#!/bin/bash
# The whole-run two-thread speed-up of the cantilever as a user runs it (no solver key), in interleaved runs: each
# round runs NEW on 1 thread, NEW on 2, OLD on 1 and OLD on 2 (OLD: a build before a change of the default), so that
# the machine's drift hits the four alike; reported: the median over rounds of each, NEW's own 2-thread speed-up per
# round, and NEW against OLD on one thread (what the change costs a one-thread run).
#   perf/compare/default_speedup.sh [K=25 (100 000 particles)] [ROUNDS=5] [NEW=build/loom] [OLD=NEW]
set -euo pipefail
K=${1:-25}; ROUNDS=${2:-5}; NEW=${3:-build/loom}; OLD=${4:-$NEW}
cd "$(dirname "$0")/../.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "round build threads wall_s linear_solver"
for r in $(seq "$ROUNDS"); do
  for cfg in "new 1" "new 2" "old 1" "old 2"; do
    set -- $cfg
    loom=$NEW; [ "$1" = old ] && loom=$OLD
    "$loom" run perf/compare/cantilever_mpm.toml --out "$out/run" --threads "$2" --quiet \
      --set "body[0].mesh.divisions=[$((5 * K)),$K]" --set "grid.divisions=[$((21 * K)),$((5 * K))]" > /dev/null
    echo "$r $1 $2 $(/usr/bin/env python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print(r['wall_seconds'], r['linear_solver'])" "$out/run/run.json")"
  done
done | tee "$out/rows"
/usr/bin/env python3 - "$out/rows" <<'PY'
import sys, statistics as st
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
w = {}
for r, build, thr, s, solver in rows: w.setdefault((build, thr), []).append(float(s))
for k, v in sorted(w.items()): print(f"median {k[0]} {k[1]} thread(s): {st.median(v):8.3f} s")
for build in ("new", "old"):
    own = [a / b for a, b in zip(w[(build, "1")], w[(build, "2")])]
    print(f"{build}: 2-thread speed-up per round", " ".join(f"{x:.2f}" for x in own), f"median {st.median(own):.2f}")
cost = [a / b for a, b in zip(w[("new", "1")], w[("old", "1")])]
print("new / old on one thread, per round", " ".join(f"{x:.3f}" for x in cost), f"median {st.median(cost):.3f}")
PY
