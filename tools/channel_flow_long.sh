#!/usr/bin/env bash
# The channel flow (scenes/channel_flow_es.toml) on one of the paper's three meshes to t = 200 s, in three phases of
# growing step: the pouring at dt = 5e-3 s to step 6000 (30 s), the first spreading at 0.02 s to step 7500 (60 s),
# the creep to rest at 0.05 s to step 10300 (200 s). The pouring's step would take
# 10 times more steps over the 140 s of creep; the phases' result on n = 10 is 0.3 % from 5 ms steps throughout
# (docs/BENCHMARKS.md, "The paper's three meshes to 200 s"). Each phase restarts from the newest checkpoint (every 500
# steps), so a run interrupted anywhere continues when the script is run again with the same OUT. (time.adaptive_dt
# gives the same schedule in one run: docs/guide/walls_and_free_surfaces.md, Free-surface flows; the committed study was run with this script.)
# N is the mesh: h = 62.5 mm / N, the initial block [round(0.4 N), N] elements (the paper's 1300, 4800, 7300 triangles
# at the end: N = 10, 18, 22, the meshes this was run on; N = 4 fails while pouring). Run time on one core: about
# 15 min, 80 min and 2.5 h.
#   tools/channel_flow_long.sh OUT [N=22] [loom=build/loom]
set -u
usage="usage: tools/channel_flow_long.sh OUT [N] [loom]"
out=${1:?$usage}
n=${2:-22}
loom=${3:-build/loom}
[[ $n =~ ^[0-9]+$ ]] && [ "$n" -ge 10 ] && [ "$n" -le 100 ] ||
  { echo "tools/channel_flow_long.sh: N must be a whole number in [10, 100], not '$n'" >&2; exit 2; }
spacing=$(awk -v n="$n" 'BEGIN { printf "%.6g", 0.0625 / n }')
width=$(awk -v n="$n" 'BEGIN { printf "%d", int(0.4 * n + 0.5) }')
scene="$(dirname "$0")/../scenes/channel_flow_es.toml"
# time.stop_when.after = 1000 s: the scene's rest rule (front rate below 1e-4 m/s over 50 s) would stop the coarse
# mesh at about 140 s; the study compares the meshes at one instant.
sets=(--threads 1 --set solver.reuse_factor=true --set output.checkpoint_every=500 --set output.every=500
      --set time.stop_when.after=1000 --set "remesh.spacing=$spacing" --set "inlet[0].spacing=$spacing"
      --set "body[0].mesh.divisions=[$width,$n]")
# The step of the newest checkpoint (none: -1).
newest() {
  local latest at
  latest=$(ls "$out"/checkpoint_*.loom 2> /dev/null | sort | tail -n 1)
  [ -z "$latest" ] && { echo -1; return; }
  at=$(basename "$latest" .loom)
  echo $((10#${at#checkpoint_}))
}
phase() {  # dt, last step, extra sets
  local dt=$1 last=$2 resume=()
  shift 2
  local at
  at=$(newest)
  [ "$at" -ge "$last" ] && return 0
  [ "$at" -ge 0 ] && resume=(--restart "$out")
  "$loom" run "$scene" --out "$out" "${resume[@]}" "${sets[@]}" --set "time.dt=$dt" "$@" --stop-after "$last"
}
phase 5e-3 6000 || exit $?
phase 0.02 7500 || exit $?
phase 0.05 10300 --set output.every=100 || exit $?
