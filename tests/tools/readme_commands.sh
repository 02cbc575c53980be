#!/usr/bin/env bash
# Runs the commands of README.md as written, so that the README stays true (ctest readme_commands, label
# scene). Usage: tests/tools/readme_commands.sh LOOM
#
# What is run (the same rules are in README.md, "Building and testing by hand"):
#  - every line of README.md that is indented by four spaces or lies inside a ``` block and starts with
#    `build/loom` (leading spaces allowed); a line `tools/setup.sh && build/loom ...` is run from its
#    `build/loom` on (setup is not repeated). A line ending in `\` continues on the next one;
#  - `build/loom` is replaced by LOOM; a `run` command gets `--out` into a temporary directory and `--quiet`.
#    An `--out DIR` of the line is replaced by a temporary directory named after DIR, and a `--restart DIR`
#    of a later line by the same one (without an --out: a restarted run writes where its checkpoint is), so
#    that a stop-and-restart pair of commands runs as written; the line's trailing comment stays a comment;
#  - the commands run one after the other from the repository root and must exit 0.
# Markers, in the line's trailing comment:
#  - `~N min` or `~N h` anywhere in the comment, written `(~N min)` or inside a longer parenthesis such as
#    `(coarse mesh, ~15 min)`: the command takes more than about half a minute; it is skipped. Mark every such
#    command so.
#  - `(exit N)`: the command is expected to exit with code N.
# Usage lines are written `loom ...` (without `build/`) and are not run. Every ```toml block is written to a
# temporary file and must pass `LOOM check`.
# The test fails naming the README line of every command that failed, with the end of its output.
set -uo pipefail
cd "$(dirname "$0")/../.."
loom=$(realpath "$1")
readme=README.md
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Command lines, one per record: "LINE<TAB>COMMAND" (continuations joined).
awk '
  /^[ \t]*```/ { fence = !fence; next }
  {
    line = $0
    if (pending != "") {
      sub(/^[ \t]+/, "", line); cmd = cmd " " line
      if (cmd ~ /\\[ \t]*$/) { sub(/\\[ \t]*$/, "", cmd); next }
      print start "\t" cmd; pending = ""; next
    }
    if (!fence && line !~ /^    /) next
    sub(/^[ \t]+/, "", line)
    sub(/^tools\/setup\.sh && /, "", line)
    if (line !~ /^build\/loom( |$)/) next
    if (line ~ /\\[ \t]*$/) { start = NR; cmd = line; sub(/\\[ \t]*$/, "", cmd); pending = 1; next }
    print NR "\t" line
  }' "$readme" > "$tmp/commands"

# ```toml blocks: "LINE" of the opening fence, then the block into its own file.
awk -v dir="$tmp" '
  /^```toml[ \t]*$/ { n++; f = dir "/block" n ".toml"; print NR > (dir "/blocks"); inside = 1; next }
  inside && /^```/ { inside = 0; close(f); next }
  inside { print > f }' "$readme"

failed=0 ran=0 skipped=0
fail() {  # fail LINE WHAT LOG
  echo "FAILED README.md:$1: $2"
  tail -n 20 "$3" | sed 's/^/    /'
  failed=$((failed + 1))
}

n=0
while IFS=$'\t' read -r line cmd; do
  n=$((n + 1))
  if [[ $cmd =~ \#.*~[0-9.]+[[:space:]]*(min|h)([^[:alnum:]]|$) ]]; then
    echo "skip README.md:$line (expensive): $cmd"
    skipped=$((skipped + 1))
    continue
  fi
  expect=0
  [[ $cmd =~ \(exit[[:space:]]+([0-9]+)\) ]] && expect=${BASH_REMATCH[1]}
  run=${cmd#build/loom}
  if [[ $run =~ ^[[:space:]]+run[[:space:]] ]]; then
    out="$tmp/out$n"
    if [[ $run =~ [[:space:]]--out[[:space:]]+([^[:space:]#]+) ]]; then out="$tmp/out_${BASH_REMATCH[1]//\//_}"; fi
    # Drop an --out of the line (its value is one word), then put ours right after `run SCENE`.
    run=$(sed -E 's/[[:space:]]--out[[:space:]]+[^[:space:]#]+//' <<< "$run")
    if [[ $run =~ [[:space:]]--restart[[:space:]]+([^[:space:]#]+) ]]; then
      restart="$tmp/out_${BASH_REMATCH[1]//\//_}"
      run=$(sed -E "s|[[:space:]]--restart[[:space:]]+[^[:space:]#]+| --restart '$restart'|" <<< "$run")
      run=$(sed -E "s|^([[:space:]]+run[[:space:]]+[^[:space:]#]+)|\\1 --quiet|" <<< "$run")
    else
      run=$(sed -E "s|^([[:space:]]+run[[:space:]]+[^[:space:]#]+)|\\1 --out '$out' --quiet|" <<< "$run")
    fi
  fi
  log="$tmp/log$n"
  start=${EPOCHREALTIME/./}
  bash -c "'$loom'$run" < /dev/null > "$log" 2>&1
  code=$?
  ms=$(( (${EPOCHREALTIME/./} - start) / 1000 ))
  seconds=$((ms / 1000)).$(((ms % 1000) / 100))
  ran=$((ran + 1))
  if [ "$code" -ne "$expect" ]; then
    fail "$line" "$cmd (exit $code, expected $expect)" "$log"
  else
    echo "ok   README.md:$line (${seconds} s): $cmd"
  fi
done < "$tmp/commands"

if [ -f "$tmp/blocks" ]; then
  k=0
  while read -r line; do
    k=$((k + 1))
    log="$tmp/checklog$k"
    if "$loom" check "$tmp/block$k.toml" > "$log" 2>&1; then
      echo "ok   README.md:$line (toml block passes loom check)"
    else
      fail "$line" "the toml block does not pass loom check" "$log"
    fi
  done < "$tmp/blocks"
fi

[ "$ran" -gt 0 ] || { echo "no command of README.md was found: the extraction is broken"; exit 1; }
echo "README commands: $ran run, $skipped skipped, $failed failed"
[ "$failed" -eq 0 ]
