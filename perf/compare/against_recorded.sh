#!/bin/bash
# loom's time per step at 10 240 particles on one thread, as a fraction of CB-Geo's quoted 73.7 ms, measured so that
# the shared machine's drift (2-4x between days, 20-30 % within an hour) cancels: the build that was timed beside
# CB-Geo (commit cbbf122: 10.8 ms a step then) and the build under test run the cantilever in alternation, and
# loom's time is the median ratio of neighbouring runs times 10.8 ms.
#   perf/compare/against_recorded.sh [ROUNDS=7] [LOOM=build/loom] [OLD_LOOM]
# Without OLD_LOOM the recorded build is made once in a git worktree ($LOOM_RECORDED_DIR, default
# /tmp/loom_cbbf122; `cmake --build --target loom`, about 10 minutes on two cores).
set -euo pipefail
ROUNDS=${1:-7}; LOOM=${2:-build/loom}; OLD=${3:-}
cd "$(dirname "$0")/../.."
RECORDED=cbbf122 RECORDED_MS=10.8 CBGEO_MS=73.7
if [ -z "$OLD" ]; then
  dir=${LOOM_RECORDED_DIR:-/tmp/loom_$RECORDED}
  if [ ! -x "$dir/build/loom" ]; then
    [ -d "$dir" ] || git worktree add --detach "$dir" "$RECORDED" > /dev/null
    cmake -S "$dir" -B "$dir/build" -DCMAKE_BUILD_TYPE=Release > /dev/null
    cmake --build "$dir/build" -j "$(nproc)" --target loom > /dev/null
  fi
  OLD=$dir/build/loom
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "round build wall_s"
for r in $(seq "$ROUNDS"); do
  for b in "$OLD" "$LOOM"; do
    "$b" run perf/compare/cantilever_mpm.toml --out "$out/run" --threads 1 --quiet > /dev/null
    echo "$r $([ "$b" = "$OLD" ] && echo recorded || echo tested) $(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['wall_seconds'])" "$out/run/run.json")"
  done
done | tee "$out/rows"
python3 - "$out/rows" "$RECORDED_MS" "$CBGEO_MS" <<'PY'
import sys, statistics as st
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
w = {}
for r, b, s in rows: w.setdefault(b, []).append(float(s))
ratios = [n / o for o, n in zip(w["recorded"], w["tested"])]
ms, cb = float(sys.argv[2]) * st.median(ratios), float(sys.argv[3])
print(f"median wall of 120 steps: recorded {st.median(w['recorded']):.3f} s, tested {st.median(w['tested']):.3f} s")
print("tested / recorded, per round:", " ".join(f"{x:.3f}" for x in ratios), f"median {st.median(ratios):.3f}")
print(f"per step, scaled to the recorded build's {sys.argv[2]} ms: {ms:.2f} ms = 1/{cb / ms:.1f} of CB-Geo's {cb} ms")
PY
