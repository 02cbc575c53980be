#!/usr/bin/env bash
# The thin Bingham collapse (scenes/bingham_collapse_es.toml with tau0 = 5 Pa, mu = 3 Pa s, the ground graded to
# 1.25 mm) run until it comes to rest (the front 5.6 % short of lubrication theory's arrested half-width; 3.7 % on a
# ground graded to 0.625 mm, GROUND_SPACING below): the first 10 s at the
# scene's dt = 2e-3 s, then in steps of 1e-2 s with Newton's line search to a residual of 1e-6 (hours on one core;
# docs/BENCHMARKS.md, thin collapse). mu = 3 Pa s spreads the sheet 10/3 times faster than the scene's 10 Pa s: the
# shallow-layer model has no inertia, so its history at mu = 3 is the one at mu = 10 at 10/3 the time, and its
# arrested state does not depend on mu. The walls' penalty is E / h of the graded ground (8e7 instead of 100 E / h:
# penetration about 5 micrometres, 0.4 % of the ground's spacing; fewer Newton iterations, docs/free_surface.md).
# A step that fails through all its cut-backs is retried from the last checkpoint in steps of 8e-3 s (the next
# failures in 6e-3, 5e-3 and again 1e-2 s), so that the remeshes fall at other states: two sizes alone can both fail
# at their own steps after one checkpoint, and the retries then repeat the same two runs.
# The first 10 s use the line search too (the scene's residual_relative = 1e-8): without it Newton cycles between
# the yield kinks of the fine rows at the ground (25 iterations, residual stuck at 1e-3 to 1e-2 of the first) and
# a step in two to four was cut back; over steps 2250-2750 of the run with a 15 mm ramp it takes 3 cut-backs against
# 251 and a third of the Newton iterations (docs/free_surface.md, "The first 10 s"). The runs of docs/BENCHMARKS.md
# before 2026-12-03 ran the first 10 s without it (this script as of commit cc36664).
# A run interrupted (or failed) in its first 10 s continues from its last checkpoint when the script is run again.
# GROUND_SPACING (m, default 1.25e-3) grades the ground to a finer first row; the walls' penalty stays E / h of it, so
# that the penetration stays the same fraction of the ground's spacing (the held strip below the first row is first
# order in that row's height: docs/free_surface.md). SPACING_RAMP (m, default 0: one body spacing, 5 mm) is the distance
# over which the ground's spacing grows to the body's; over one body spacing the first row stays about 4.7 times the
# ground's spacing at 1.25 mm (wall[].spacing_ramp in docs/guide/scene_keys.md). DIVISIONS (default 10: the scene's h = 5 mm) is the
# body mesh's n, divisions [n, 2n] of the 0.05 m x 0.1 m half-column (h = 50 mm / n); the ground's spacing and ramp
# are lengths and stay as given.
#   tools/thin_collapse_long.sh OUT [until_seconds=150] [loom=build/loom] [ground_spacing=1.25e-3] [spacing_ramp=0]
#                               [divisions=10]
set -u
usage="usage: tools/thin_collapse_long.sh OUT [until_seconds] [loom] [ground_spacing] [spacing_ramp] [divisions]"
out=${1:?$usage}
until=${2:-150}
loom=${3:-build/loom}
ground=${4:-0.00125}
ramp=${5:-0}
divisions=${6:-10}
[[ $until =~ ^[0-9]+$ ]] && [ "$until" -gt 10 ] || { echo "tools/thin_collapse_long.sh: until_seconds must be a whole number above 10, not '$until'" >&2; exit 2; }
[[ $divisions =~ ^[0-9]+$ ]] && [ "$divisions" -ge 2 ] || { echo "tools/thin_collapse_long.sh: divisions must be a whole number of at least 2, not '$divisions'" >&2; exit 2; }
# E = 1e5 Pa (the scene's paste): the penalty E / h, 8e7 at the default 1.25 mm.
penalty=$(awk -v h="$ground" 'BEGIN { if (h + 0 <= 0 || h + 0 > 0.005) exit 1; printf "%.6g", 1e5 / h }') ||
  { echo "tools/thin_collapse_long.sh: ground_spacing must be a length in metres in (0, 0.005], not '$ground'" >&2; exit 2; }
scene="$(dirname "$0")/../scenes/bingham_collapse_es.toml"
sets=(--set 'material[0].tau0=5.0' --set 'material[0].viscosity=3.0' --set "wall[0].spacing=$ground"
      --set "wall[0].penalty=$penalty" --set "wall[1].penalty=$penalty" --set time.steps=400000
      --set 'time.stop_when={ probe = "front", rate_below = 2e-5, over = 30.0, after = 60.0 }'
      --set output.checkpoint_every=250 --set output.every=2500 --threads 1 --quiet)
# The scene's own ramp unless one is asked for: a run without it stays the run it was.
[ "$ramp" != 0 ] && sets+=(--set "wall[0].spacing_ramp=$ramp")
[ "$divisions" != 10 ] && sets+=(--set "body[0].mesh.divisions=[$divisions,$((2 * divisions))]")
# Steps of the long stage: from step 5000 at 10 s, 100 per second.
last=$((5000 + (until - 10) * 100))
# The step of the last checkpoint (none: -1): below 5000 the first stage is not done.
latest=$(ls "$out"/checkpoint_*.loom 2> /dev/null | sort | tail -n 1)
at=-1
if [ -n "$latest" ]; then
  at=$(basename "$latest" .loom)
  at=$((10#${at#checkpoint_}))
fi
if [ "$at" -lt 5000 ]; then
  resume=()
  [ "$at" -ge 0 ] && resume=(--restart "$out")
  "$loom" run "$scene" --out "$out" "${resume[@]}" --stop-after 5000 --set solver.line_search=true "${sets[@]}" || exit $?
fi
dts=(1e-2 8e-3 6e-3 5e-3)
n=${#dts[@]}
for attempt in $(seq 0 40); do
  dt=${dts[$((attempt % n))]}
  "$loom" run "$scene" --out "$out" --restart "$out" --set time.dt=$dt --stop-after $last \
    --set solver.line_search=true --set solver.residual_relative=1e-6 "${sets[@]}"
  rc=$?
  [ $rc -ne 1 ] && exit $rc  # 0: reached the step or settled; 2: bad input
  echo "thin_collapse_long: retrying from the last checkpoint of $out in steps of ${dts[$(((attempt + 1) % n))]} s" >&2
done
exit 1
