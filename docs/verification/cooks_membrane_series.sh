#!/bin/sh
# Refinement series of the Cook's membrane scenes with the P1 element, as CSV on stdout:
#   docs/verification/cooks_membrane_series.sh linear    [LOOM] > docs/verification/cooks_membrane_linear_p1.csv
#   docs/verification/cooks_membrane_series.sh neo_hooke [LOOM] > docs/verification/cooks_membrane_neo_hooke_p1.csv
# Run from the repository root; LOOM defaults to build/loom. Every row is one `loom run` of the committed
# scene with --set overrides (divisions n x n, pattern, material); dofs are the free dofs of run.json.
#   linear:    scenes/cooks_membrane_linear.toml as committed (E = 250, nu = 0.4999; reference u_y(C) = 7.771,
#              u_y(M) = 7.405) and with E = 70, nu = 1/3 (reference u_y(C) = 32.28; no u_y(M) reference).
#   neo_hooke: scenes/cooks_membrane_neo_hooke.toml as committed (E = 70, nu = 0.499; reference u_y(C) = 0.2761).
# References: ../shared/REFERENCES.md.
set -eu
MODE=${1:?usage: cooks_membrane_series.sh linear|neo_hooke [LOOM]}
LOOM=${2:-build/loom}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
case "$MODE" in
  linear) SCENE=scenes/cooks_membrane_linear.toml
          CASES="0.4999:250:7.771:7.405 0.3333333333333333:70:32.28:" ;;
  neo_hooke) SCENE=scenes/cooks_membrane_neo_hooke.toml
             CASES="0.499:70:0.2761:" ;;
  *) echo "unknown series '$MODE'" >&2; exit 2 ;;
esac
echo "nu,E,pattern,n,dofs,uy_C,uy_M,ratio_C,ratio_M,newton"
for case in $CASES; do
  nu=$(echo "$case" | cut -d: -f1) E=$(echo "$case" | cut -d: -f2)
  refC=$(echo "$case" | cut -d: -f3) refM=$(echo "$case" | cut -d: -f4)
  for pattern in right alternating; do
    for n in 4 8 16 32 64 128; do
      "$LOOM" run "$SCENE" --out "$TMP/run" --quiet --set "material[0].nu=$nu" --set "material[0].E=$E" \
        --set "body[0].mesh.divisions=[$n,$n]" --set "body[0].mesh.pattern=\"$pattern\"" --set output.every=0 >/dev/null
      dofs=$(sed -n 's/.*"dofs": *\([0-9]*\).*/\1/p' "$TMP/run/run.json")
      iterations=$(sed -n 's/.*"newton_iterations": *\([0-9]*\).*/\1/p' "$TMP/run/run.json")
      tail -n 1 "$TMP/run/probes.csv" | awk -F, -v nu="$nu" -v E="$E" -v p="$pattern" -v n="$n" -v d="$dofs" \
        -v rc="$refC" -v rm="$refM" -v it="$iterations" '{
          rM = (rm == "") ? "" : sprintf("%.6f", $4 / rm);
          printf "%s,%s,%s,%d,%d,%.10g,%.10g,%.6f,%s,%d\n", (nu + 0 < 0.4 ? "1/3" : nu), E, p, n, d, $3, $4, $3 / rc, rM, it }'
    done
  done
done
