#!/usr/bin/env bash
# Compares the probes.csv and VTK frames of two loom binaries, scene by scene, byte for byte: the check that a change
# (a refactoring, a new option that is off by default) keeps every existing result as it was.
#
#   tools/compare_probes.sh OLD_LOOM NEW_LOOM [scene.toml...]     (default: every scenes/*.toml)
#
# Each scene is run by both binaries (`loom run SCENE --out DIR --quiet --stop-after N`) into separate
# temporary directories, one after the other, and the two probes.csv files are compared with cmp. One
# line per scene: name, steps compared (the last step in probes.csv; old/new if they differ), wall seconds of each run, and
# "identical" or "DIFFERS" (then the first differing line of each file). A run that fails with exit
# code 1 (a scene that diverges) keeps the rows it reached: those are compared and the line says so.
# A run that times out or fails otherwise (bad input: exit 2, a signal) makes the scene an ERROR.
# Exit status: 0 every scene identical, 1 some scene differs or is an ERROR, 2 bad usage.
#
# probes.csv holds 15 significant digits (engine/io/probe_writer.cpp), so the VTK frames both runs wrote
# (.vtu/.vtp, binary doubles) are compared byte for byte as well: identical frames mean bit-for-bit equal
# fields. To compare only the scenes an older binary knows, list them, e.g.
#   tools/compare_probes.sh OLD NEW $(git ls-tree --name-only OLD_COMMIT scenes/ | grep toml$)
#
# Environment:
#   LOOM_COMPARE_STEPS    stop each run after this step (--stop-after; default 40; 0: run to the end).
#                         A scene with fewer steps simply runs to its end.
#   LOOM_COMPARE_TIMEOUT  time limit of each run, seconds (default 300).
#   LOOM_COMPARE_KEEP     1: keep the temporary output directories (their path is printed).
set -euo pipefail

usage() {
  echo "usage: $0 OLD_LOOM NEW_LOOM [scene.toml...]" >&2
  exit 2
}
[ $# -ge 2 ] || usage
old=$1 new=$2
shift 2
for bin in "$old" "$new"; do
  [ -x "$bin" ] || { echo "$0: $bin is not an executable" >&2; exit 2; }
done

repo=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -gt 0 ]; then
  scenes=("$@")
else
  scenes=("$repo"/scenes/*.toml)
fi
for scene in "${scenes[@]}"; do
  [ -f "$scene" ] || { echo "$0: no scene $scene" >&2; exit 2; }
done

steps=${LOOM_COMPARE_STEPS:-40}
limit=${LOOM_COMPARE_TIMEOUT:-300}
[[ $steps =~ ^[0-9]+$ ]] || { echo "$0: LOOM_COMPARE_STEPS must be a whole number, not '$steps'" >&2; exit 2; }
[[ $limit =~ ^[1-9][0-9]*$ ]] || { echo "$0: LOOM_COMPARE_TIMEOUT must be a positive number of seconds" >&2; exit 2; }
stop=()
if [ "$steps" -gt 0 ]; then stop=(--stop-after "$steps"); fi

work=$(mktemp -d "${TMPDIR:-/tmp}/compare_probes.XXXXXX")
if [ "${LOOM_COMPARE_KEEP:-0}" = 1 ]; then
  echo "outputs in $work"
else
  trap 'rm -rf "$work"' EXIT
fi

# run BIN SCENE DIR: runs one scene into DIR; sets rc (exit code; 124 on time-out) and secs (wall seconds).
run() {
  local start end
  mkdir -p "$3"
  start=$(date +%s.%N)
  rc=0
  # SIGTERM makes loom stop after the current step; KILL if it does not within 30 s more.
  timeout -k 30 "$limit" "$1" run "$2" --out "$3" --quiet "${stop[@]}" >"$3.log" 2>&1 || rc=$?
  end=$(date +%s.%N)
  secs=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
}

# last_step FILE: the step of the last row of a probes.csv ("-" if none); its rows are steps 0, 1, ...
last_step() { if [ -f "$1" ] && [ "$(wc -l <"$1")" -gt 1 ]; then tail -n 1 "$1" | cut -d, -f1; else echo "-"; fi; }

# first_difference A B: number of the first line that differs (or exists in only one file); 0 if none.
first_difference() {
  awk 'FILENAME == ARGV[1] { a[FNR] = $0; n = FNR; next }
       { m = FNR; if (!(FNR in a) || a[FNR] != $0) { print FNR; found = 1; exit } }
       END { if (!found) print (n > m ? m + 1 : 0) }' "$1" "$2"
}

line_of() { sed -n "$2p" "$1" | grep . || echo "(no such line)"; }

printf '%-40s %7s %8s %8s  %s\n' scene steps "old s" "new s" result
status=0
index=0
for scene in "${scenes[@]}"; do
  index=$((index + 1))
  name=$(basename "$scene" .toml)
  dir="$work/$index-$name"
  run "$old" "$scene" "$dir/old"; old_rc=$rc old_secs=$secs
  run "$new" "$scene" "$dir/new"; new_rc=$rc new_secs=$secs
  a="$dir/old/probes.csv" b="$dir/new/probes.csv"

  notes=()
  error=0
  for side in old new; do
    code=${side}_rc
    case ${!code} in
      0) ;;
      1) notes+=("$side run failed (exit 1): compared the rows it wrote") ;;
      124) notes+=("$side run timed out after ${limit}s"); error=1 ;;
      *) notes+=("$side run exit ${!code}"); error=1 ;;
    esac
  done
  if [ ! -f "$a" ] || [ ! -f "$b" ]; then
    notes+=("no probes.csv from $([ -f "$a" ] || echo "old ")$([ -f "$b" ] || echo new)")
    error=1
  fi

  counted=$(last_step "$b")
  if [ "$(last_step "$a")" != "$counted" ]; then counted="$(last_step "$a")/$counted"; fi
  frames=0 frames_differ=()
  if [ "$error" = 0 ]; then
    for f in "$dir"/old/*.vtu "$dir"/old/*.vtp; do
      [ -f "$f" ] || continue
      frames=$((frames + 1))
      cmp -s "$f" "$dir/new/$(basename "$f")" || frames_differ+=("$(basename "$f")")
    done
  fi
  if [ "$error" = 0 ] && cmp -s "$a" "$b" && [ ${#frames_differ[@]} = 0 ]; then
    result="identical (probes, $frames frames)"
  elif [ "$error" = 0 ]; then
    result=DIFFERS
  else
    result=ERROR
  fi
  [ "${result%% *}" = identical ] || status=1
  printf '%-40s %7s %8s %8s  %s\n' "$name" "$counted" "$old_secs" "$new_secs" "$result"
  for note in "${notes[@]+"${notes[@]}"}"; do echo "    $note"; done
  if [ ${#frames_differ[@]} -gt 0 ]; then echo "    frames that differ: ${frames_differ[*]}"; fi
  if [ "$result" = DIFFERS ] && ! cmp -s "$a" "$b"; then
    line=$(first_difference "$a" "$b")
    if [ "$line" = 0 ]; then
      echo "    the files differ in bytes but not in lines (a missing final newline?)"
    else
      echo "    first difference, line $line:"
      echo "    old: $(line_of "$a" "$line")"
      echo "    new: $(line_of "$b" "$line")"
    fi
  fi
  if [ "$result" = ERROR ]; then
    for side in old new; do
      if [ -s "$dir/$side.log" ]; then tail -n 3 "$dir/$side.log" | sed "s/^/    $side log: /"; fi
    done
  fi
done
exit "$status"
