#!/usr/bin/env python3
"""Runs loom's step loop on a ladder of problem sizes at 1 and 2 threads and prints the time per step split by
system (from each run's timings.json): the side-by-side benchmark of perf/compare/README.md.

    perf/compare/step_times.py cantilever [--loom build/loom] [--threads 1,2] [--repeat 3] [--csv out.csv]
    perf/compare/step_times.py fem | pfem | all
    perf/compare/step_times.py cantilever --loom OLD_LOOM,build/loom     (two builds, runs interleaved)
    perf/compare/step_times.py cantilever --linear auto,cholmod_bisected (two linear solvers, interleaved)

Problems (each a scene and the --set lists of its sizes):
  cantilever  perf/compare/cantilever_mpm.toml: the 10 m x 1 m linear elastic beam, implicit MPM with grid
              Newmark, quad4 cells, 4 particles per cell; 1 440, 10 240, 40 960, 100 000 particles; 120 steps
  fem         scenes/cooks_membrane_neo_hooke.toml (one static load step, Newton): 1e3, 1e4, 1e5 cells
  pfem        scenes/moderate_block_pfem.toml (remeshed every step): 16 x 16 to 64 x 64 divisions, 20 steps
Each configuration runs --repeat times; the run with the median wall time is reported. With several
binaries (--loom A,B) their runs alternate, so that a slow period of the machine hits both alike, and each
row names its binary. Times are wall
clock of loom's own timers, per step = the run's wall time (set-up included) over its steps; "other" is the
part of the wall time in none of the listed systems; "non-solver" is the share of the Newton iterations spent
outside the linear solver (assembly and update).
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def cantilever():
    scene = os.path.join(ROOT, "perf/compare/cantilever_mpm.toml")
    for k in (3, 8, 16, 25):
        yield f"{160 * k * k} particles", scene, [f"body[0].mesh.divisions=[{5 * k},{k}]", f"grid.divisions=[{21 * k},{5 * k}]"]


def fem():
    scene = os.path.join(ROOT, "scenes/cooks_membrane_neo_hooke.toml")
    for n in (22, 71, 224):  # 2 n^2 triangles: about 1e3, 1e4, 1e5 cells
        yield f"{2 * n * n} cells", scene, [f"body[0].mesh.divisions=[{n},{n}]"]


def pfem():
    scene = os.path.join(ROOT, "scenes/moderate_block_pfem.toml")
    for n in (16, 32, 64):
        yield f"{2 * n * n} cells", scene, [f"body[0].mesh.divisions=[{n},{n}]", "time.steps=20"]


PROBLEMS = {"cantilever": cantilever, "fem": fem, "pfem": pfem}
# Systems reported (timer names); nested ones are shown apart from their parent.
COLUMNS = ["locate_particles", "activate_grid", "project_to_grid", "remesh/triangulate", "remesh", "newton/assemble",
           "newton/solve/factorize/analyze", "newton/solve/factorize", "newton/solve/back_substitute", "interpolate_to_particles"]


def run_once(loom, scene, sets, threads, out):
    cmd = [loom, "run", scene, "--out", out, "--threads", str(threads), "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    cmd += ["--set", "output.every=0"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "timings.json")) as f:
        t = json.load(f)
    steps, newton = 0, 0
    with open(os.path.join(out, "probes.csv")) as f:
        rows = list(csv.DictReader(f))
    steps = int(rows[-1]["step"]) if rows else 0
    if rows and "newton" in rows[0]:
        newton = sum(int(float(r["newton"])) for r in rows[1:])
    return t, max(steps, 1), newton


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("problem", choices=list(PROBLEMS) + ["all"])
    ap.add_argument("--loom", default=os.path.join(ROOT, "build/loom"), help="loom binary, or several separated by commas")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--linear", default="", help="solver.linear values to compare (separated by commas; default: the scene's)")
    ap.add_argument("--csv", help="also write the rows to this file")
    args = ap.parse_args()
    problems = list(PROBLEMS) if args.problem == "all" else [args.problem]
    rows = []
    header = f"{'problem':10s} {'size':>18s} {'thr':>3s} {'ms/step':>8s} {'newton':>6s} {'analyses':>8s}  " + \
        " ".join(f"{c.split('/')[-1][:10]:>10s}" for c in COLUMNS) + f" {'other':>6s} {'non-solver':>10s}   (share of the step, %; non-solver: of newton)"
    print(header)
    for problem in problems:
        for label, scene, sets in PROBLEMS[problem]():
            # Each variant: a binary and a solver.linear value (None: the scene's own).
            binaries = [(b, lin) for b in args.loom.split(",") for lin in (args.linear.split(",") if args.linear else [None])]
            base = {}
            for threads in (int(x) for x in args.threads.split(",")):
                runs = {b: [] for b in binaries}
                for _ in range(args.repeat):
                    for b in binaries:
                        with tempfile.TemporaryDirectory() as out:
                            runs[b].append(run_once(b[0], scene, sets + ([f"solver.linear={b[1]}"] if b[1] else []), threads, out))
                for b in binaries:
                    runs[b].sort(key=lambda r: r[0]["wall"])
                for b in binaries:
                    t, steps, newton = runs[b][len(runs[b]) // 2]
                    timers, wall = t["timers"], t["wall"]
                    ms = 1e3 * wall / steps
                    share = {c: 100.0 * timers[c]["total"] / wall if c in timers else None for c in COLUMNS}
                    # A parent's share without its listed children.
                    for parent, child in (("newton/solve/factorize", "newton/solve/factorize/analyze"), ("remesh", "remesh/triangulate")):
                        if share[parent] is not None and share[child] is not None:
                            share[parent] -= share[child]
                    listed = sum(v for v in share.values() if v is not None)
                    analyses = timers.get("newton/solve/factorize/analyze", {}).get("calls", 0)
                    # The share of the Newton iterations spent outside the linear solver (assembly, update).
                    non_solver = 100.0 * (1.0 - timers["newton/solve"]["total"] / timers["newton"]["total"]) if "newton" in timers else 0.0
                    base.setdefault(b, ms)
                    name = f"  {b[0]}" + (f" {b[1]}" if b[1] else "") if len(binaries) > 1 else ""
                    print(f"{problem:10s} {label:>18s} {threads:3d} {ms:8.2f} {newton / steps:6.2f} {analyses:4d}/{steps:<4d} " +
                          " ".join(f"{v:10.1f}" if v is not None else f"{'-':>10s}" for v in share.values()) +
                          f" {100.0 - listed:6.1f} {non_solver:10.1f}" + (f"   speed-up {base[b] / ms:.2f}" if threads != 1 else "") + name)
                    sys.stdout.flush()
                    rows.append({"binary": b[0], "linear": b[1] or "", "problem": problem, "size": label, "threads": threads, "ms_per_step": round(ms, 3),
                                 "newton_per_step": round(newton / steps, 3), "analyses": analyses, "steps": steps,
                                 "non_solver_share": round(non_solver, 2),
                                 **{c: round(v, 2) if v is not None else "" for c, v in share.items()}})
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)


if __name__ == "__main__":
    main()
