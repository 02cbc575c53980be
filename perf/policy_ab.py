#!/usr/bin/env python3
"""loom's run-time policies against the C library's and libgomp's defaults: each case run alternately as loom runs
it (A) and with one environment assignment that turns a policy off (B), on one thread. Prints the CPU seconds (user
+ system) of each, the system share, the largest resident size and the ratio B / A, and checks that the two runs'
probes.csv are identical byte for byte (the policies decide where memory comes from and which thread runs a region
of one, never what is computed).

  perf/policy_ab.py --env LOOM_MALLOC=system      # freed memory given back to the system (engine/core/allocator.hpp)
  perf/policy_ab.py --env LOOM_OPENMP=libgomp     # CHOLMOD's OpenMP regions through libgomp (openmp_regions_of_one.cpp)
  perf/policy_ab.py --env ... [--loom build/loom] [--rounds 2] [--only NAME]

Exit 1 if any pair's probes differ. CPU time, not wall time, is compared: it is what the policies change and the
other core's load moves it less. Results: perf/README.md, "Freed memory stays in the heap" and "OpenMP regions of
one thread".
"""
import argparse
import filecmp
import os
import subprocess
import sys
import tempfile

FINE_CHANNEL = ["time.dt=5e-3", "remesh.spacing=0.00284091", "inlet[0].spacing=0.00284091", "body[0].mesh.divisions=[9,22]"]

# name, scene, --set overrides: a case per method and back-end, each long enough (several seconds) to time.
CASES = [
    ("channel_n22_es_pfem_umfpack", "scenes/channel_flow_es.toml", FINE_CHANNEL + ["time.steps=150"]),
    ("collapse_10k_es_pfem_umfpack", "perf/scenes/es_pfem_free_surface_10k.toml", ["time.steps=10"]),
    ("moderate_block_pfem", "scenes/moderate_block_pfem.toml", ["time.steps=500"]),
    ("cooks_neo_hooke_p1_cholmod_256", "scenes/cooks_membrane_neo_hooke.toml", ["body[0].mesh.divisions=[256,256]", "time.steps=4"]),
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


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--env", required=True, help="NAME=VALUE: the assignment of run B")
    ap.add_argument("--loom", default="build/loom")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--only", help="run only the case of this name")
    a = ap.parse_args()
    if "=" not in a.env:
        sys.exit(f"policy_ab: --env {a.env}: expected NAME=VALUE")
    cases = [c for c in CASES if not a.only or c[0] == a.only]
    if not cases:
        sys.exit(f"policy_ab: no case named {a.only}")
    print("| case | run | CPU s (best of %d) | system share | max RSS MB | CPU ratio B / A |" % a.rounds)
    print("| --- | --- | --- | --- | --- | --- |")
    differ = False
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene, sets in cases:
            best = {}
            for r in range(a.rounds):
                for policy in (("A", "B") if r % 2 == 0 else ("B", "A")):
                    out = os.path.join(tmp, f"{name}_{policy}_{r}")
                    cpu, system, rss = run(a.loom, scene, sets, out, a.env if policy == "B" else None)
                    if policy not in best or cpu < best[policy][0]:
                        best[policy] = (cpu, system, rss)
                pair = [os.path.join(tmp, f"{name}_{p}_{r}", "probes.csv") for p in ("A", "B")]
                if not filecmp.cmp(*pair, shallow=False):
                    print(f"policy_ab: {name} round {r}: probes differ between A and B", file=sys.stderr)
                    differ = True
            ratio = best["B"][0] / best["A"][0]
            for policy in ("A", "B"):
                cpu, system, rss = best[policy]
                label = "loom" if policy == "A" else a.env
                print(f"| {name} | {label} | {cpu:.2f} | {100 * system / cpu:.0f} % | {rss:.0f} | "
                      f"{'%.2f' % ratio if policy == 'B' else ''} |", flush=True)
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
