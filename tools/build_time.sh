#!/usr/bin/env bash
# Where a fresh build's time goes: configures an empty build directory whose compiler and linker are wrapped by a
# timer, builds it, and prints the compile and link seconds by part of the tree (engine, systems, tests by folder,
# perf) and the slowest translation units. The sum of the compile times over the cores' count bounds the wall time
# from below; -j1 gives times free of contention with the build's own jobs.
#
#   tools/build_time.sh [BUILD_DIR (default /tmp/loom_build_time)] [JOBS (default 1)] [TARGET (default all)]
#   tools/build_time.sh --report LOG      # only the summary of an earlier run's log
set -euo pipefail
cd "$(dirname "$0")/.."
report() {
  python3 - "$1" <<'PY'
import collections, sys
rows = [l.split() for l in open(sys.argv[1]) if len(l.split()) == 4]
part = collections.Counter()
count = collections.Counter()
units = []
for start, end, kind, out in rows:
    d = float(end) - float(start)
    target = out.split("CMakeFiles/")[1].split(".dir/")[0] if "CMakeFiles/" in out else out.split("/")[-1]
    if kind == "link":
        group = "libraries" if target.startswith(("lib", "../lib")) or target.endswith((".a", ".so")) else "programs"
    elif target.startswith("loom_") or target == "loom":
        group = "libraries and loom"
    elif "/__/" in out:
        group = "copies in each program"  # a source of the engine compiled again for every test program
    elif target.endswith("_test"):
        group = "test programs"
    else:
        group = "benchmarks and tools"
    part[(group, kind)] += d
    count[(group, kind)] += 1
    units.append((d, kind, out.split("/")[-1]))
total = sum(part.values())
print(f"{len(rows)} compiles and links, {total:.0f} s in all")
for (group, kind), s in sorted(part.items(), key=lambda kv: -kv[1]):
    print(f"  {group:22s} {kind:8s} {count[(group, kind)]:4d} units {s:8.0f} s  {100 * s / total:5.1f} %")
print("slowest:")
for d, kind, name in sorted(units, reverse=True)[:15]:
    print(f"  {d:6.1f} s  {kind:8s} {name}")
PY
}
if [ "${1:-}" = "--report" ]; then report "$2"; exit 0; fi
dir=${1:-/tmp/loom_build_time}
jobs=${2:-1}
target=${3:-all}
log="$dir.times"
rm -rf "$dir" "$log"
wrapper="$dir.wrap"
cat > "$wrapper" <<W
#!/usr/bin/env bash
start=\$(date +%s.%N); "\$@"; rc=\$?; end=\$(date +%s.%N)
out=""; prev=""; for a in "\$@"; do [ "\$prev" = "-o" ] && out="\$a"; prev="\$a"; done
case " \$* " in *" -c "*) kind=compile ;; *) kind=link ;; esac
echo "\$start \$end \$kind \$out" >> "$log"
exit \$rc
W
chmod +x "$wrapper"
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER="$wrapper" -DCMAKE_CXX_LINKER_LAUNCHER="$wrapper" > /dev/null
start=$(date +%s)
cmake --build "$dir" -j "$jobs" --target "$target" > "$dir.log" 2>&1
echo "fresh build of $target with -j $jobs: $(( $(date +%s) - start )) s wall (log $dir.log, times $log)"
report "$log"
