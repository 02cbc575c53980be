#!/usr/bin/env bash
# Runs the default test suite once per OpenBLAS kernel family that this CPU can execute, to find tests that
# pass only with the kernels this machine happens to pick. Debian's OpenBLAS chooses its kernels at run time
# (DYNAMIC_ARCH); an Intel Xeon and an AMD EPYC pick different ones, and their round-off differs, which
# CHOLMOD and UMFPACK pass on to every factorization. OPENBLAS_CORETYPE forces a family, so one machine can
# play several. A test that fails under one family asserts something that does not hold within round-off.
# Usage: tools/portability_check.sh [ctest arguments]     (about 1.5 min per family on two cores)
# Environment: LOOM_CORETYPES (default: every family below that the CPU supports).
set -uo pipefail
cd "$(dirname "$0")/.."
flags=$(grep -m1 '^flags' /proc/cpuinfo)
has() { [[ " $flags " == *" $1 "* ]]; }
families=(Prescott Nehalem Sandybridge Haswell Zen SkylakeX)
supported=()
for f in "${families[@]}"; do
  case $f in
    Sandybridge) has avx || continue ;;
    Haswell | Zen) has avx2 && has fma || continue ;;
    SkylakeX) has avx512f && has avx512bw && has avx512dq && has avx512vl || continue ;;
  esac
  supported+=("$f")
done
read -r -a chosen <<< "${LOOM_CORETYPES:-${supported[*]}}"
status=0
summary=""
for f in "${chosen[@]}"; do
  log=$(mktemp)
  start=$(date +%s)
  OPENBLAS_CORETYPE=$f ctest --test-dir build -j "${LOOM_JOBS:-$(nproc)}" -LE "stress|study|portability" "$@" >"$log" 2>&1
  rc=$?
  failed=$(grep -E '^\s+[0-9]+ - .*\((Failed|SEGFAULT|Timeout|Subprocess aborted|Exception)' "$log" | sed 's/^ *[0-9]* - //' | tr '\n' ';')
  line="$f: $(grep -E 'tests passed' "$log" | head -1) ($(( $(date +%s) - start )) s)${failed:+ FAILED: $failed}"
  echo "$line"
  summary+="$line"$'\n'
  [ $rc -ne 0 ] && status=1
  rm -f "$log"
done
echo "--- portability summary (OPENBLAS_CORETYPE)"
printf '%s' "$summary"
exit $status
