#!/usr/bin/env python3
"""loom's run-time policies against the C library's and libgomp's defaults: each case run alternately as loom runs
it (A) and with one environment assignment that turns a policy off (B), on one thread. Prints the CPU seconds (user
+ system) of each, the system share, the largest resident size and the ratio B / A, and checks that the two runs'
probes.csv agree (the policies decide where memory comes from and which thread runs a region of one, not what is
computed; they have been identical byte for byte).

  perf/policy_ab.py --env LOOM_MALLOC=system      # freed memory given back to the system (engine/core/allocator.hpp)
  perf/policy_ab.py --env LOOM_OPENMP=libgomp     # CHOLMOD's OpenMP regions through libgomp (openmp_regions_of_one.cpp)
  perf/policy_ab.py --env ... [--loom build/loom] [--rounds 2] [--only NAME] [--steps N] [--tolerance 1e-9]

Exit 1 if a probe of a pair differs by more than --tolerance (1e-9) of its column's largest magnitude: the same
run up to round-off, which an alignment-sensitive kernel on another machine could leave. CPU time, not wall time,
is compared: it is what the policies change and the other core's load moves it less. Results: perf/README.md,
"Freed memory stays in the heap" and "OpenMP regions of one thread".
"""
import argparse
import csv
import filecmp
import os
import subprocess
import sys
import tempfile

FINE_CHANNEL = ["time.dt=5e-3", "remesh.spacing=0.00284091", "inlet[0].spacing=0.00284091",
                "body[0].mesh.divisions=[9,22]"]

# name, scene, --set overrides: a case per method and back-end, each long enough (several seconds) to time.
CASES = [
    ("channel_n22_es_pfem_umfpack", "scenes/channel_flow_es.toml", FINE_CHANNEL + ["time.steps=150"]),
    ("collapse_10k_es_pfem_umfpack", "perf/scenes/es_pfem_free_surface_10k.toml", ["time.steps=10"]),
    ("moderate_block_pfem", "scenes/moderate_block_pfem.toml", ["time.steps=500"]),
    ("cooks_neo_hooke_p1_cholmod_256", "scenes/cooks_membrane_neo_hooke.toml",
     ["body[0].mesh.divisions=[256,256]", "time.steps=4"]),
    ("cantilever_mpm_10k", "perf/compare/cantilever_mpm.toml", []),
]


def run(loom, scene, sets, out, assignment):
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_THREAD_LIMIT="1")
    for name in ("LOOM_MALLOC", "LOOM_OPENMP"):
        env.pop(name, None)
    if assignment:
        name, _, value = assignment.partition("=")
        env[name] = value
    cmd = [loom, "run", scene, "--threads", "1", "--quiet", "--out", out, "--set", "output.every=0"]
    for s in sets:
        cmd += ["--set", s]
    with open(out + ".stderr", "w+") as err:
        proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)  # this child's own usage (ru_maxrss in kB)
        proc.returncode = os.waitstatus_to_exitcode(status)
        if proc.returncode != 0:
            err.seek(0)
            sys.exit(f"policy_ab: {' '.join(cmd)} exited {proc.returncode}:\n{err.read()}")
    return usage.ru_utime + usage.ru_stime, usage.ru_stime, usage.ru_maxrss / 1024.0


def compare(path_a, path_b):
    """(byte-identical?, the largest difference of a probe between the two runs relative to its column's largest
    magnitude; infinite if the tables differ in shape)."""
    if filecmp.cmp(path_a, path_b, shallow=False):
        return True, 0.0
    with open(path_a) as fa, open(path_b) as fb:
        rows_a, rows_b = list(csv.reader(fa)), list(csv.reader(fb))
    if len(rows_a) != len(rows_b) or rows_a[0] != rows_b[0]:
        return False, float("inf")
    worst = 0.0
    for c in range(len(rows_a[0])):
        col_a = [float(r[c]) for r in rows_a[1:]]
        col_b = [float(r[c]) for r in rows_b[1:]]
        scale = max(max(map(abs, col_a), default=0.0), 1e-300)
        worst = max(worst, max((abs(x - y) for x, y in zip(col_a, col_b)), default=0.0) / scale)
    return False, worst


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--env", required=True, help="NAME=VALUE: the assignment of run B")
    ap.add_argument("--loom", default="build/loom")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--only", help="run only the case of this name")
    ap.add_argument("--steps", type=int, help="time.steps of every case (shorter smoke runs)")
    ap.add_argument("--tolerance", type=float, default=1e-9,
                    help="largest difference of a probe between A and B, relative to its column's largest magnitude")
    a = ap.parse_args()
    if "=" not in a.env:
        sys.exit(f"policy_ab: --env {a.env}: expected NAME=VALUE")
    cases = [c for c in CASES if not a.only or c[0] == a.only]
    if not cases:
        sys.exit(f"policy_ab: no case named {a.only}")
    print("| case | run | CPU s (best of %d) | system share | max RSS MB | CPU ratio B / A |" % a.rounds)
    print("| --- | --- | --- | --- | --- | --- |")
    differ = False
    identical = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene, sets in cases:
            if a.steps:
                sets = [x for x in sets if not x.startswith("time.steps=")] + [f"time.steps={a.steps}"]
            best = {}
            for r in range(a.rounds):
                for policy in (("A", "B") if r % 2 == 0 else ("B", "A")):
                    out = os.path.join(tmp, f"{name}_{policy}_{r}")
                    cpu, system, rss = run(a.loom, scene, sets, out, a.env if policy == "B" else None)
                    if policy not in best or cpu < best[policy][0]:
                        best[policy] = (cpu, system, rss)
                pair = [os.path.join(tmp, f"{name}_{p}_{r}", "probes.csv") for p in ("A", "B")]
                same, gap = compare(*pair)
                identical.append(same)
                if gap > a.tolerance:
                    print(f"policy_ab: {name} round {r}: probes differ between A and B by {gap:.1e} of a column's "
                          f"largest value", file=sys.stderr)
                    differ = True
            ratio = best["B"][0] / best["A"][0]
            for policy in ("A", "B"):
                cpu, system, rss = best[policy]
                label = "loom" if policy == "A" else a.env
                print(f"| {name} | {label} | {cpu:.2f} | {100 * system / cpu:.0f} % | {rss:.0f} | "
                      f"{'%.2f' % ratio if policy == 'B' else ''} |", flush=True)
    print(f"probes byte-identical in {sum(identical)} of {len(identical)} pairs" +
          ("" if differ else f", the others within {a.tolerance:g}"))
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
