#!/usr/bin/env bash
# Runs the commands of README.md and of the user guide (docs/guide/*.md) as written, so that they stay true
# (ctest readme_commands, label scene). Usage: tests/tools/readme_commands.sh LOOM
#
# What is run (the same rules are in docs/guide/building.md, "Building and testing by hand"), file by file:
#  - every line of README.md and docs/guide/*.md that is indented by four spaces or lies inside a ``` block and
#    starts with `build/loom` (leading spaces allowed); a line `tools/setup.sh && build/loom ...` is run from its
#    `build/loom` on (setup is not repeated). A line ending in `\` continues on the next one;
#  - `build/loom` is replaced by LOOM; a `run` command gets `--out` into a temporary directory and `--quiet`.
#    An `--out DIR` of the line is replaced by a temporary directory named after DIR, and a `--restart DIR`
#    of a later line of the same file by the same one (without an --out: a restarted run writes where its
#    checkpoint is), so that a stop-and-restart pair of commands runs as written; the line's trailing comment
#    stays a comment;
#  - the commands run one after the other from the repository root and must exit 0.
# Markers, in the line's trailing comment:
#  - `~N min` or `~N h` anywhere in the comment, written `(~N min)` or inside a longer parenthesis such as
#    `(coarse mesh, ~15 min)`: the command takes more than about half a minute; it is skipped. Mark every such
#    command so.
#  - `(exit N)`: the command is expected to exit with code N.
# Usage lines are written `loom ...` (without `build/`) and are not run. Every ```toml block is written to a
# temporary file and must pass `LOOM check`. In every ```toml (or unmarked) block, a comment listing the choices of
# a key, `key = "value"   # a | b | c` (each choice may carry a remark in parentheses), must list exactly the
# choices of the key's "one of ..." in `LOOM schema --markdown` (tests/tools/readme_choices.py).
# The test fails naming FILE:LINE of every command, block or choice list that failed, with the end of its output.
set -uo pipefail
cd "$(dirname "$0")/../.."
loom=$(realpath "$1")
files=(README.md docs/guide/*.md)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

failed=0 ran=0 skipped=0 checked=0
fail() {  # fail FILE:LINE WHAT LOG
  echo "FAILED $1: $2"
  tail -n 20 "$3" | sed 's/^/    /'
  failed=$((failed + 1))
}

run_file() {  # run_file FILE DIR: the commands and toml blocks of FILE, DIR its scratch directory
  local readme=$1 dir=$2 line cmd n k expect run out restart log start code ms seconds
  mkdir "$dir"

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
    }' "$readme" > "$dir/commands"

  # ```toml blocks: "LINE" of the opening fence, then the block into its own file.
  awk -v dir="$dir" '
    /^```toml[ \t]*$/ { n++; f = dir "/block" n ".toml"; print NR > (dir "/blocks"); inside = 1; next }
    inside && /^```/ { inside = 0; close(f); next }
    inside { print > f }' "$readme"

  n=0
  while IFS=$'\t' read -r line cmd; do
    n=$((n + 1))
    if [[ $cmd =~ \#.*~[0-9.]+[[:space:]]*(min|h)([^[:alnum:]]|$) ]]; then
      echo "skip $readme:$line (expensive): $cmd"
      skipped=$((skipped + 1))
      continue
    fi
    expect=0
    [[ $cmd =~ \(exit[[:space:]]+([0-9]+)\) ]] && expect=${BASH_REMATCH[1]}
    run=${cmd#build/loom}
    if [[ $run =~ ^[[:space:]]+run[[:space:]] ]]; then
      out="$dir/out$n"
      if [[ $run =~ [[:space:]]--out[[:space:]]+([^[:space:]#]+) ]]; then out="$dir/out_${BASH_REMATCH[1]//\//_}"; fi
      # Drop an --out of the line (its value is one word), then put ours right after `run SCENE`.
      run=$(sed -E 's/[[:space:]]--out[[:space:]]+[^[:space:]#]+//' <<< "$run")
      if [[ $run =~ [[:space:]]--restart[[:space:]]+([^[:space:]#]+) ]]; then
        restart="$dir/out_${BASH_REMATCH[1]//\//_}"
        run=$(sed -E "s|[[:space:]]--restart[[:space:]]+[^[:space:]#]+| --restart '$restart'|" <<< "$run")
        run=$(sed -E "s|^([[:space:]]+run[[:space:]]+[^[:space:]#]+)|\\1 --quiet|" <<< "$run")
      else
        run=$(sed -E "s|^([[:space:]]+run[[:space:]]+[^[:space:]#]+)|\\1 --out '$out' --quiet|" <<< "$run")
      fi
    fi
    log="$dir/log$n"
    start=${EPOCHREALTIME/./}
    bash -c "'$loom'$run" < /dev/null > "$log" 2>&1
    code=$?
    ms=$(( (${EPOCHREALTIME/./} - start) / 1000 ))
    seconds=$((ms / 1000)).$(((ms % 1000) / 100))
    ran=$((ran + 1))
    if [ "$code" -ne "$expect" ]; then
      fail "$readme:$line" "$cmd (exit $code, expected $expect)" "$log"
    else
      echo "ok   $readme:$line (${seconds} s): $cmd"
    fi
  done < "$dir/commands"

  if [ -f "$dir/blocks" ]; then
    k=0
    while read -r line; do
      k=$((k + 1))
      log="$dir/checklog$k"
      checked=$((checked + 1))
      if "$loom" check "$dir/block$k.toml" > "$log" 2>&1; then
        echo "ok   $readme:$line (toml block passes loom check)"
      else
        fail "$readme:$line" "the toml block does not pass loom check" "$log"
      fi
    done < "$dir/blocks"
  fi
}

f=0
for readme in "${files[@]}"; do
  f=$((f + 1))
  run_file "$readme" "$tmp/$f"
done

# The choice lists in the comments of the scene examples against the schema's "one of" lists.
lists=0
if "$loom" schema --markdown > "$tmp/schema.md" 2> "$tmp/schema.log"; then
  python3 tests/tools/readme_choices.py "$tmp/schema.md" "${files[@]}" > "$tmp/choices.log" 2>&1
  code=$?
  cat "$tmp/choices.log"
  lists=$(grep -c '^ok   ' "$tmp/choices.log")
  bad=$(grep -c '^FAILED ' "$tmp/choices.log")
  if [ "$code" -ne 0 ] && [ "$bad" -eq 0 ]; then bad=1; fi  # the check itself broke
  failed=$((failed + bad))
else
  fail schema "LOOM schema --markdown failed" "$tmp/schema.log"
fi

[ "$ran" -gt 0 ] || { echo "no command of ${files[*]} was found: the extraction is broken"; exit 1; }
echo "README and guide commands (${#files[@]} files): $ran run, $skipped skipped, $checked toml blocks checked, $lists choice lists as the schema, $failed failed"
[ "$failed" -eq 0 ]
