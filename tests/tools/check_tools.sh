#!/usr/bin/env bash
# Smoke test of tools/study and tools/render (ctest label scene): a two-case study into a temporary
# directory, then checks that the CSV has its columns and rows, that every plot and the picture are PNG
# files, that tools/profile_folded reads a --profile run, that tools/arrest_balance.py reads walls as loom
# does, that tools/first_row.py measures a mesh's first row, that tools/probe_history.py samples and dates
# arrests and that tools/compare_studies.py plots two studies on one axes. Usage: check_tools.sh LOOM
set -euo pipefail
cd "$(dirname "$0")/../.."
loom=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
tools/study tests/tools/smoke_study.toml --loom "$loom" --out "$out" 2>"$out/log" || { cat "$out/log"; exit 1; }
csv="$out/smoke/smoke.csv"
head -1 "$csv" | grep -q '^study,series,case,param,dofs,cells,steps,threads,converged,wall_s,process_s,newton_iterations,cutbacks,reaction,reaction_reference,reaction_error,ux_right,ux_right_reference,ux_right_error,t:' \
  || { echo "unexpected CSV header: $(head -1 "$csv")"; exit 1; }
[ "$(wc -l < "$csv")" -eq 3 ] || { echo "expected 2 rows in $csv"; cat "$csv"; exit 1; }
# The analytic error is round-off; the finest case is its own reference (error 0).
awk -F, 'NR > 1 && ($16 > 1e-10 || $9 != 1) { bad = 1 } END { exit bad }' "$csv" || { echo "wrong errors in $csv"; cat "$csv"; exit 1; }
for f in smoke_work_precision.png smoke_error_dofs.png smoke_breakdown.png smoke_J.png; do
  head -c 8 "$out/smoke/$f" | od -An -c | grep -q 'P   N   G' || { echo "$f is not a PNG"; exit 1; }
done
# tools/compare_studies.py: one quantity of several studies on one plot, from their committed CSVs.
tools/compare_studies.py front "$out/side_by_side.png" bingham_collapse_es bingham_collapse_mpm > /dev/null \
  || { echo "compare_studies failed"; exit 1; }
head -c 8 "$out/side_by_side.png" | od -An -c | grep -q 'P   N   G' || { echo "side_by_side.png is not a PNG"; exit 1; }
"$loom" run scenes/homogeneous_compression.toml --out "$out/profiled" --quiet --profile --set output.every=0
tools/profile_folded "$out/profiled/timings.json" > "$out/folded" || { echo "profile_folded failed"; exit 1; }
grep -q '^step 1;newton;iteration 1;solve;factorize [0-9]*$' "$out/folded" \
  || { echo "profile_folded: no 'step 1;newton;iteration 1;solve;factorize' stack; its output:"; head -20 "$out/folded"; exit 1; }
# tools/arrest_balance.py rebuilds the symmetry wall's force from a frame's penetrations: the penalty it infers must
# be the scene's default k_N = 100 E / h (E = 1e5 Pa, h = 5 mm), or its corner correction would be wrong. loom
# measures the boundary lengths at the start of a step, the tool in the frame: they agree on a body at rest (here
# the column with a yield stress it cannot exceed, settled by Bossak's damping: 6e-5 apart after 6 s).
"$loom" run scenes/bingham_collapse_es.toml --out "$out/collapse" --quiet --set 'material[0].tau0=1e4' --set time.dt=0.05 \
  --set time.steps=120 --set output.every=120
tools/arrest_balance.py "$out/collapse" --tau0 1e4 --area 0.005 --csv "$out/section.csv" > "$out/balance" \
  || { echo "arrest_balance failed"; exit 1; }
k=$(sed -n 's/.*k_N = \([0-9.e+]*\) N\/m^3.*/\1/p' "$out/balance")
python3 -c "import sys; sys.exit(0 if abs(float('$k') / 2e9 - 1) < 1e-3 else 1)" \
  || { echo "arrest_balance: k_N = $k, expected 2e9"; cat "$out/balance"; exit 1; }
# The centre section's CSV holds the section the budget integrates: its columns give back the printed section
# thrust (- int sigma_xx dy) and vertical term (int (W + sigma_yy) dy, W the weight above: "lithostatic" is -W).
python3 - "$out/section.csv" "$out/balance" <<'PY' || { echo "arrest_balance --csv: not the budget's section"; head "$out/section.csv"; cat "$out/balance"; exit 1; }
import csv, re, sys
rows = list(csv.DictReader(open(sys.argv[1])))
text = open(sys.argv[2]).read()
y, sxx, syy, lith = ([float(r[k]) for r in rows] for k in ("y", "sigma_xx", "sigma_yy", "lithostatic"))
trapz = lambda f: sum(0.5 * (f[i] + f[i + 1]) * (y[i + 1] - y[i]) for i in range(len(y) - 1))
thrust = float(re.search(r"section of cell stresses: ([-0-9.]+) N/m", text).group(1))
vertical = float(re.search(r"vertical +([-+0-9.]+) N/m", text).group(1))
ok = len(rows) > 100 and abs(trapz([-v for v in sxx]) - thrust) < 2e-4 and abs(trapz([a - b for a, b in zip(syy, lith)]) - vertical) < 2e-4
sys.exit(0 if ok else 1)
PY
# The front scaled to the area asked for, x_f (0.005 / A_run)^(2/3), A_run the last row's area probe.
python3 - "$out/balance" "$out/collapse/probes.csv" <<'PY' || { echo "arrest_balance: wrong front scaled to the area"; cat "$out/balance"; exit 1; }
import csv, re, sys
text = open(sys.argv[1]).read()
row = list(csv.DictReader(open(sys.argv[2])))[-1]
xf = float(re.search(r"computed ([0-9.]+) m", text).group(1))
scaled = float(re.search(r"x_f \(A / A_run\)\^\(2/3\) = ([0-9.]+) m", text).group(1))
expected = xf * (0.005 / float(row["area"])) ** (2 / 3)
sys.exit(0 if abs(scaled - expected) < 1e-4 and abs(float(row["area"]) / 0.005 - 1) > 1e-4 else 1)
PY
# tools/first_row.py on the same resting column, its mesh's rows h = 5 mm apart: 11 particles on the ground and the
# first row 5 mm above every one of them, less the column's own elastic shortening under its weight (rho g H / E
# = 2.3 % at the base: 4.90 mm).
frame=$(ls "$out"/collapse/*.vtu | tail -1)
tools/first_row.py "$frame" > "$out/first_row" || { echo "first_row failed"; exit 1; }
sed -n 's/.*on the ground \([0-9]*\), first row median \([0-9.]*\) mm, largest \([0-9.]*\) mm.*/\1 \2 \3/p' "$out/first_row" |
  awk '{ ok = ($1 == 11 && $2 > 4.85 && $3 < 4.95 && $3 - $2 < 0.03) } END { exit !ok }' \
  || { echo "first_row: expected 11 ground particles and a first row 4.85-4.95 mm above them:"; cat "$out/first_row"; exit 1; }
# tools/probe_history.py: two runs side by side at every second (the shorter one's column empty past its end), and the
# arrest of a front that stops at t = 2 s against one still moving.
printf 'step,time,front\n0,0,1.0\n1,0.5,1.5\n2,1,2.0\n3,1.5,2.5\n4,2,3.0\n5,2.5,3.0\n6,3,3.0\n' > "$out/a.csv"
printf 'step,time,front\n0,0,1.0\n1,1,1.2\n2,2,1.4\n' > "$out/b.csv"
tools/probe_history.py a="$out/a.csv" b="$out/b.csv" --csv "$out/history.csv" --arrest front --within 1e-6 --window 1.0 > "$out/arrest" \
  || { echo "probe_history failed"; exit 1; }
printf 'time,front_a,front_b\n0,1.0,1.0\n1,2.0,1.2\n2,3.0,1.4\n3,3.0,\n' | diff - <(tr -d '\r' < "$out/history.csv") \
  || { echo "probe_history: wrong CSV"; exit 1; }
grep -q '^a: front 3 at t = 3.00 s; within 1e-06 of it from t = 2.00 s$' "$out/arrest" && grep -q '^b: .*STILL MOVING$' "$out/arrest" \
  || { echo "probe_history: wrong arrest:"; cat "$out/arrest"; exit 1; }
echo "tools ok"
