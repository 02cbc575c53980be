#!/usr/bin/env python3
"""Seed 003's 3D columns (§6.3 bending, §6.4 twisting) with loom's mixed u-p MPM on tet4 grids, against a FEM reference.

Runs scenes/column_bending_mpm.toml and column_twisting_mpm.toml for the cases given (grid spacing h, material points
per cell, stabilisation) and prints per case: the time reached (a failed run stops early), the first extremum of
u_x(A), the largest |E - E_0| / E_0 of the total energy and |L - L_0| / |L_0| of the angular momentum, Newton
iterations a step, wall time, and, with a reference, the distance of u(A) to the reference history:
max_t |u(A) - u_ref(A)| / max_t |u_ref(A)| over the run, and |u(A) - u_ref(A)| / |u_ref(A)| where |u_ref(A)| peaks
in the first swing (bending: t <= 0.6 s, the first peak at 0.44 s; twisting: t <= 0.06 s, the first quarter turn).
Each run's probes.csv stays in WORK/<case>/.

  tools/column_mpm_study.py --cases NAME,... [--loom build/loom] [--work DIR] [--threads T] [--end T]
                            [--reference-bending CSV] [--reference-twisting CSV]
  tools/column_mpm_study.py --runs DIR,... --column bending|twisting [--reference-... CSV]   # summarise runs made
                            # elsewhere (tools/study --work W --keep), without running anything

Case names: <column>_<stabilisation>_h<h>_n<points per cell>, e.g. twisting_asgs_h0.25_n24, bending_ppp_h0.25_n4;
h is 0.25, 0.1667 or 0.125 (the paper's Table 1 grids), points per cell 1, 4, 14 or 24. The reference CSVs are
probes.csv files of the FEM runs (scenes/column_bending_fem.toml, column_twisting_fem.toml; tools/column_study.py).
docs/mpm_3d.md's tables come from this script.
"""
import argparse, csv, json, math, os, subprocess, sys, time

GRIDS = {"0.25": 4, "0.1667": 6, "0.125": 8}  # cubes per metre


def parse(name):
    column, stab, h, n = name.split("_")
    return column, stab, h[1:], int(n[1:])


def overrides(column, stab, h, n, end):
    k = GRIDS[h]
    grid = f"[{8 * k},{2 * k},{7 * k}]" if column == "bending" else f"[{4 * k},{4 * k},{7 * k}]"
    steps = int(round(end / 1e-3))
    return [f'body[0].stabilisation="{stab}"', f"body[0].particles_per_cell={n}", f"body[0].mesh.divisions=[{k},{k},{6 * k}]",
            f"grid.divisions={grid}", f"time.steps={steps}", "output.every=0"]


def read(path):
    rows = list(csv.DictReader(open(path)))
    return rows


def history(rows):
    return {round(float(r["time"]), 9): (float(r["ux_A"]), float(r["uy_A"]), float(r["uz_A"])) for r in rows}


def distances(run, ref, window):
    times = sorted(set(run) & set(ref))
    if not times:
        return float("nan"), float("nan")
    scale = max(math.hypot(*ref[t]) for t in times)
    full = max(math.dist(run[t], ref[t]) for t in times) / scale
    peak_t = max((t for t in ref), key=lambda t: math.hypot(*ref[t]) if t <= window else -1)  # the first swing's peak
    at_peak = math.dist(run[peak_t], ref[peak_t]) / math.hypot(*ref[peak_t]) if peak_t in run else float("nan")
    return full, at_peak


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--loom", default="build/loom")
    ap.add_argument("--work", default="/tmp/loom_column_mpm_study")
    ap.add_argument("--cases", default="")
    ap.add_argument("--runs", default="", help="summarise these run directories instead of running cases")
    ap.add_argument("--column", default="", help="with --runs: bending or twisting")
    ap.add_argument("--threads", default="1")
    ap.add_argument("--end", type=float, default=0.0, help="end time (default: 3 s bending, 0.5 s twisting)")
    ap.add_argument("--reference-bending", default="")
    ap.add_argument("--reference-twisting", default="")
    a = ap.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    print("case,exit,t_end,peak_t,peak_ux_A,max_energy_drift,max_L_drift,newton_per_step,wall_s,dist_full,dist_first_peak")
    jobs = [(os.path.basename(d.rstrip("/")), a.column, d) for d in a.runs.split(",")] if a.runs else \
           [(name, parse(name)[0], os.path.join(a.work, name)) for name in a.cases.split(",")]
    for name, column, out in jobs:
        if a.runs:
            info = json.load(open(os.path.join(out, "run.json")))
            code, wall = (0 if info.get("completed") else 1), info.get("wall_seconds", float("nan"))
        else:
            _, stab, h, n = parse(name)
            end = a.end or (3.0 if column == "bending" else 0.5)
            os.makedirs(out, exist_ok=True)
            scene = os.path.join(here, "..", "scenes", f"column_{column}_mpm.toml")
            cmd = [a.loom, "run", scene, "--out", out, "--threads", a.threads, "--quiet"]
            for o in overrides(column, stab, h, n, end):
                cmd += ["--set", o]
            t0 = time.time()
            code = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=open(os.path.join(out, "stderr.txt"), "w")).returncode
            wall = time.time() - t0
        rows = read(os.path.join(out, "probes.csv"))
        t = [float(r["time"]) for r in rows]
        ux = [float(r["ux_A"]) for r in rows]
        E = [float(r["total"]) for r in rows]
        Lname = "Ly" if column == "bending" else "Lz"
        L = [float(r[Lname]) for r in rows]
        window = 0.6 if column == "bending" else 0.06  # the first swing: bending's first peak, twisting's first quarter turn
        k = max(range(len(ux)), key=lambda i: abs(ux[i]) if t[i] <= window else -1)
        drift = max(abs(e - E[0]) / E[0] for e in E)
        Ldrift = max(abs(l - L[0]) / abs(L[0]) for l in L)
        newton = sum(float(r["newton"]) for r in rows) / max(1, len(rows) - 1)
        ref_path = a.reference_bending if column == "bending" else a.reference_twisting
        full, at_peak = distances(history(rows), history(read(ref_path)), window) if ref_path else (float("nan"), float("nan"))
        print(f"{name},{code},{t[-1]:.3f},{t[k]:.3f},{ux[k]:.4f},{drift:.2e},{Ldrift:.2e},{newton:.2f},{wall:.0f},{full:.4f},{at_peak:.4f}",
              flush=True)


if __name__ == "__main__":
    sys.exit(main())
