#!/usr/bin/env bash
# tools/thin_collapse_long.sh's control flow, with a stub in place of loom that records each call (a real run takes
# hours): bad arguments exit 2 before any run; a fresh output directory runs the first 10 s (5000 steps, with the
# line search) and then the long stage; one whose last checkpoint is below step 5000 continues the first stage from
# it (--restart) rather than starting the long stage's steps of 1e-2 s at the wrong time; one at or past step 5000
# goes straight to the long stage; a failed long stage (exit 1) is retried in steps of 8e-3 s, then 6e-3 s; a finer
# body mesh (the sixth argument) reaches both stages.
# Usage: check_thin_collapse_long.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The stub: appends its arguments to calls.txt; exits with the code in stub_rc (one line per call, 0 when used up).
cat > "$work/loom" <<'EOF'
#!/usr/bin/env bash
dir=$(dirname "$0")
echo "$*" >> "$dir/calls.txt"
n=$(wc -l < "$dir/calls.txt")
rc=$(sed -n "${n}p" "$dir/stub_rc" 2> /dev/null)
exit "${rc:-0}"
EOF
chmod +x "$work/loom"
fail() { echo "thin_collapse_long.sh: $1"; [ -f "$work/calls.txt" ] && cat "$work/calls.txt"; exit 1; }
# run OUT RC...: a fresh record, the stub's exit codes, the script's own exit code in $rc.
run() {
  local out=$1; shift
  rm -f "$work/calls.txt"; printf '%s\n' "$@" > "$work/stub_rc"
  rc=0; tools/thin_collapse_long.sh "$out" 150 "$work/loom" > "$work/log" 2>&1 || rc=$?
}
calls() { [ -f "$work/calls.txt" ] && wc -l < "$work/calls.txt" || echo 0; }
call() { sed -n "${1}p" "$work/calls.txt"; }

for bad in "5" "ten"; do
  rc=0; tools/thin_collapse_long.sh "$work/x" "$bad" "$work/loom" > "$work/log" 2>&1 || rc=$?
  [ "$rc" -eq 2 ] && [ "$(calls)" -eq 0 ] || fail "until_seconds '$bad': exit $rc, $(calls) runs (expected 2, none)"
done
rc=0; tools/thin_collapse_long.sh "$work/x" 150 "$work/loom" 0.01 > "$work/log" 2>&1 || rc=$?
[ "$rc" -eq 2 ] && [ "$(calls)" -eq 0 ] || fail "ground_spacing 0.01: exit $rc, $(calls) runs (expected 2, none)"
rc=0; tools/thin_collapse_long.sh "$work/x" 150 "$work/loom" 0.00125 0 1 > "$work/log" 2>&1 || rc=$?
[ "$rc" -eq 2 ] && [ "$(calls)" -eq 0 ] || fail "divisions 1: exit $rc, $(calls) runs (expected 2, none)"

# Fresh: the first stage from the scene (no --restart), then the long stage to step 5000 + 140 * 100.
mkdir -p "$work/fresh"
run "$work/fresh" 0 0
[ "$rc" -eq 0 ] && [ "$(calls)" -eq 2 ] || fail "fresh: exit $rc, $(calls) runs (expected 0, 2)"
call 1 | grep -q -- '--stop-after 5000 --set solver.line_search=true' || fail "fresh: the first run is not the first stage"
call 1 | grep -q -- '--restart' && fail "fresh: the first stage restarts"
call 2 | grep -q -- "--restart $work/fresh --set time.dt=1e-2 --stop-after 19000" || fail "fresh: the second run is not the long stage"
call 1 | grep -q -- 'body\[0\].mesh' && fail "fresh: the scene's body mesh is overridden by default"

# A finer body mesh: divisions [n, 2n] in both stages.
rm -rf "$work/fine" && mkdir -p "$work/fine"
rm -f "$work/calls.txt"; printf '0\n0\n' > "$work/stub_rc"
rc=0; tools/thin_collapse_long.sh "$work/fine" 150 "$work/loom" 0.00125 0.015 15 > "$work/log" 2>&1 || rc=$?
[ "$rc" -eq 0 ] && [ "$(calls)" -eq 2 ] || fail "fine: exit $rc, $(calls) runs (expected 0, 2)"
for i in 1 2; do
  call $i | grep -q -- '--set body\[0\].mesh.divisions=\[15,30\]' || fail "fine: run $i is not on divisions [15, 30]"
  call $i | grep -q -- '--set wall\[0\].spacing_ramp=0.015' || fail "fine: run $i has not the 15 mm ramp"
done

# Interrupted in the first stage: it is continued from its checkpoint, then the long stage.
mkdir -p "$work/early" && touch "$work/early/checkpoint_000250.loom" "$work/early/checkpoint_002842.loom"
run "$work/early" 0 0
[ "$rc" -eq 0 ] && [ "$(calls)" -eq 2 ] || fail "early: exit $rc, $(calls) runs (expected 0, 2)"
call 1 | grep -q -- "--restart $work/early --stop-after 5000 --set solver.line_search=true" || fail "early: the first stage is not continued"

# Past the first stage: the long stage only; a failure is retried from the checkpoint in steps of 8e-3 s.
mkdir -p "$work/late" && touch "$work/late/checkpoint_005000.loom"
run "$work/late" 1 0
[ "$rc" -eq 0 ] && [ "$(calls)" -eq 2 ] || fail "late: exit $rc, $(calls) runs (expected 0, 2)"
call 1 | grep -q -- '--set time.dt=1e-2 ' || fail "late: the first run is not the long stage"
call 2 | grep -q -- '--set time.dt=8e-3 ' || fail "late: the retry is not in steps of 8e-3 s"

# Failures in two sizes go on to a third: the retries do not repeat the same two runs.
run "$work/late" 1 1 0
[ "$rc" -eq 0 ] && [ "$(calls)" -eq 3 ] || fail "late, two failures: exit $rc, $(calls) runs (expected 0, 3)"
call 3 | grep -q -- '--set time.dt=6e-3 ' || fail "late: the second retry is not in steps of 6e-3 s"

# Bad input from loom (exit 2) ends the script with it, in either stage.
run "$work/fresh" 2
[ "$rc" -eq 2 ] && [ "$(calls)" -eq 1 ] || fail "bad input: exit $rc, $(calls) runs (expected 2, 1)"
echo "thin_collapse_long ok"
