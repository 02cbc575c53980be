#!/usr/bin/python3
"""Moderately constrained rubber block, PFEM (seed 000 §5.2, scenes/moderate_block_pfem.toml): the Fig 17
study. For each mesh (16x16, 32x32), element (tri6, p1p1_uphi) and transfer (CPM, BTM-ISO0, BTM-ISO1,
BTM-ISO2), one `loom run` of the committed scene with --set overrides (16 runs); then, under OUT/VARIANT/:

  curves_<N>x<N>_<element>.csv  per step: u_y_mid, Newton iterations, connectivity changed (0/1), area
                                change of the remesh (mm^2) and body area, one column group per transfer
                                (empty after the last converged step)
  runs.csv                      one row per run: last converged step (and the paper's), why it stopped,
                                smoothness, Newton iterations per step, remeshes that changed the
                                connectivity, area change, wall time
  u_y_mid.png                   Fig 17 a-d analogue: u_y_mid against the step, x at the last converged step
  newton.png                    Newton iterations per step (moving mean over 25 steps)
  area.png                      body area against the step (the sum of the area changes of the remeshes)

Smoothness of a curve u_k (k = 0 .. n, the converged steps): S = sum_{k=1}^{n-1} (u_{k+1} - 2 u_k + u_{k-1})^2
/ (n - 1) in mm^2, the mean squared second difference; a jump of size d in one step adds about 2 d^2 / (n - 1).
S_common is the same over the steps that all four transfers of a panel converged (a fair comparison).

Variants (--variant):
  scene        the committed scene as it is (the default)
  top_fixed    the loaded part of the top held horizontally (u_x = 0 there, as in the 3D block of the
               seed's reference [3]) and inertia made negligible (density 1.1e-9: rubber in t/mm^3); see
               docs/moderate_block/README.md for why this reading is tried

Runs go to WORK/VARIANT/<mesh>_<element>_<transfer>/ (default WORK: build/moderate_block_runs); a run whose
run.json exists is not repeated unless --rerun, so the study can be run piecewise (--meshes 16, then
--meshes 32) and re-plotted with --plot-only. Runs are started with `nice`, one at a time.

Usage (from the repository root, after building build/loom):
  /usr/bin/python3 tools/moderate_block_study.py [--variant scene] [--meshes 16 32] [--plot-only]
Python 3 with Debian's numpy and matplotlib; no other dependency.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import time

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENE = "scenes/moderate_block_pfem.toml"
ELEMENTS = ["tri6", "p1p1_uphi"]
TRANSFERS = {"cpm": ("cpm", 0), "btm-iso0": ("btm", 0), "btm-iso1": ("btm", 1), "btm-iso2": ("btm", 2)}
COLOURS = {"cpm": "tab:red", "btm-iso0": "tab:orange", "btm-iso1": "tab:green", "btm-iso2": "tab:blue"}
# Fig 17: the runs that diverged and where; the others are shown to the end (1000 steps).
PAPER_DIVERGED = {(16, "tri6", "btm-iso0"): 971, (16, "p1p1_uphi", "btm-iso0"): 904,
                  (32, "tri6", "cpm"): 992, (32, "p1p1_uphi", "btm-iso0"): 747}
VARIANTS = {
    "scene": [],
    "top_fixed": ["--set", "boundary[load].displacement.x=0.0", "--set", "material[rubber].density=1.1e-9"],
}
STEPS = 1000


def run_name(mesh, element, transfer):
    return f"{mesh}x{mesh}_{element}_{transfer}"


def run_one(loom, variant, mesh, element, transfer, work, rerun):
    out = os.path.join(work, variant, run_name(mesh, element, transfer))
    if os.path.exists(os.path.join(out, "run.json")) and not rerun:
        return out
    scheme, iso = TRANSFERS[transfer]
    args = ["nice", loom, "run", SCENE, "--out", out, "--quiet", "--threads", "1", "--set", "output.every=100",
            "--set", f"body[0].mesh.divisions=[{mesh},{mesh}]", "--set", f"body[0].element={element}",
            "--set", f"map.scheme={scheme}", "--set", f"map.iso={iso}"] + VARIANTS[variant]
    print(f"{variant} {run_name(mesh, element, transfer)}: running ...", flush=True)
    start = time.monotonic()
    proc = subprocess.run(args, capture_output=True, text=True)
    if proc.returncode not in (0, 1):  # 1: the run stopped early; everything written up to then is valid
        sys.exit(f"{' '.join(args)} failed with exit code {proc.returncode}:\n{proc.stderr}")
    with open(os.path.join(out, "command.txt"), "w") as f:
        f.write(" ".join(args[1:]) + "\n")
    print(f"  {time.monotonic() - start:.0f} s, exit {proc.returncode}", flush=True)
    return out


def load_run(out):
    with open(os.path.join(out, "probes.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "run.json")) as f:
        record = json.load(f)
    cols = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    return cols, record


def smoothness(u):
    if len(u) < 3:
        return float("nan")
    d2 = u[2:] - 2 * u[1:-1] + u[:-2]
    return float(np.sum(d2 * d2) / len(d2))


def stop_reason(record):
    if record["converged"]:
        return "completed"
    f = record["failure"]
    if "intersects itself" in f:
        return "remesh: boundary polygon self-intersecting"
    if "inverted at the start" in f:
        return "Newton: cell inverted by the transfer"  # det F_n <= 0 at u = u_n on a fresh mesh
    if "inverted" in f:
        return "remesh: inverted cell"
    if "line search" in f:
        return "Newton: line search found no decrease"
    if "no convergence" in f:
        return "Newton: no convergence"
    return f[:60]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--loom", default="build/loom")
    ap.add_argument("--out", default="docs/moderate_block")
    ap.add_argument("--work", default="build/moderate_block_runs")
    ap.add_argument("--variant", default="scene", choices=sorted(VARIANTS))
    ap.add_argument("--meshes", type=int, nargs="+", default=[16, 32])
    ap.add_argument("--plot-only", action="store_true", help="use the runs in WORK, run nothing")
    ap.add_argument("--rerun", action="store_true")
    a = ap.parse_args()
    out_dir = os.path.join(a.out, a.variant)
    os.makedirs(out_dir, exist_ok=True)

    if not a.plot_only:
        for mesh in a.meshes:
            for element in ELEMENTS:
                for transfer in TRANSFERS:
                    run_one(a.loom, a.variant, mesh, element, transfer, a.work, a.rerun)

    # Everything present in WORK for this variant (both meshes if both were run).
    panels = []  # (mesh, element, {transfer: (cols, record)})
    for mesh in (16, 32):
        for element in ELEMENTS:
            runs = {}
            for transfer in TRANSFERS:
                d = os.path.join(a.work, a.variant, run_name(mesh, element, transfer))
                if os.path.exists(os.path.join(d, "run.json")):
                    runs[transfer] = load_run(d)
            if runs:
                panels.append((mesh, element, runs))
    if not panels:
        sys.exit("no runs found")

    summary = []
    for mesh, element, runs in panels:
        common = min(rec["last_converged_step"] for _, rec in runs.values())
        table = {"step": list(range(STEPS + 1))}
        for transfer, (c, rec) in runs.items():
            n = rec["last_converged_step"]
            step = c["step"].astype(int)
            keep = step <= n  # probes.csv rows of converged scene steps
            u = c["u_y_mid"][keep]
            for key, col in (("u_y_mid", "u_y_mid"), ("newton", "newton"), ("changed", "changed"),
                             ("area_change", "area_change"), ("area", "volume")):
                v = [""] * (STEPS + 1)
                for s, x in zip(step[keep], c[col][keep]):
                    v[s] = f"{x:.10g}"
                table[f"{key}_{transfer}"] = v
            its = c["newton"][keep][1:]
            dA = c["area_change"][keep][1:]
            summary.append({
                "mesh": f"{mesh}x{mesh}", "element": element, "transfer": transfer,
                "last_converged_step": n,
                "paper_last_step": PAPER_DIVERGED.get((mesh, element, transfer), STEPS),
                "stopped_by": stop_reason(rec),
                "u_y_mid_last": f"{u[-1]:.4f}",
                "smoothness_mm2": f"{smoothness(u):.4g}",
                "smoothness_common_mm2": f"{smoothness(u[:common + 1]):.4g}",
                "common_steps": common,
                "newton_per_step": f"{its.mean():.3f}",
                "newton_per_step_common": f"{its[:common].mean():.3f}",
                "newton_max": int(its.max()) if len(its) else 0,
                "remeshes_changed": int(c["changed"][keep][1:].sum()),
                "area_change_abs_sum_mm2": f"{np.abs(dA).sum():.4g}",
                "area_final_mm2": f"{c['volume'][keep][-1]:.2f}",
                "area_change_max_mm2": f"{dA.max() if len(dA) else 0:.4g}",
                "area_change_min_mm2": f"{dA.min() if len(dA) else 0:.4g}",
                "wall_s": f"{rec['wall_seconds']:.1f}",
            })
        path = os.path.join(out_dir, f"curves_{mesh}x{mesh}_{element}.csv")
        with open(path, "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            keys = list(table)
            w.writerow(keys)
            for k in range(STEPS + 1):
                w.writerow([table["step"][k]] + [table[key][k] for key in keys[1:]])
    with open(os.path.join(out_dir, "runs.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(summary[0]), lineterminator="\n")
        w.writeheader()
        w.writerows(summary)
    for s in summary:
        print(f"{s['mesh']:6s} {s['element']:10s} {s['transfer']:9s} last {s['last_converged_step']:5d} "
              f"(paper {s['paper_last_step']:4d}) {s['stopped_by']:42s} S {s['smoothness_mm2']:>9s} "
              f"S_common {s['smoothness_common_mm2']:>9s} ({s['common_steps']}) Newton/step {s['newton_per_step']} "
              f"changed {s['remeshes_changed']:4d} area {s['area_final_mm2']}")

    # Figures: one panel per (mesh, element), as Fig 17 a-d.
    def figure(name, ylabel, series):
        n = len(panels)
        cols = 2
        rows = (n + 1) // 2
        fig, axes = plt.subplots(rows, cols, figsize=(12, 4.2 * rows), squeeze=False)
        for ax, (mesh, element, runs) in zip(axes.flat, panels):
            for transfer, (c, rec) in runs.items():
                nlast = rec["last_converged_step"]
                keep = c["step"] <= nlast
                x, y = series(c, keep)
                ax.plot(x, y, color=COLOURS[transfer], lw=1.0, label=f"{transfer} (last {nlast})")
                if name == "u_y_mid" and len(x):
                    ax.plot(x[-1], y[-1], "x", color=COLOURS[transfer], ms=9, mew=2)
            paper = ", ".join(f"{t} {s}" for (m, e, t), s in PAPER_DIVERGED.items() if m == mesh and e == element)
            ax.set_title(f"{mesh}x{mesh} {element}" + (f" (paper: {paper} diverged)" if paper else ""), fontsize=10)
            ax.set_xlabel("time step")
            ax.set_ylabel(ylabel)
            ax.set_xlim(0, STEPS)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
        for ax in list(axes.flat)[n:]:
            ax.axis("off")
        fig.suptitle(f"moderate block PFEM ({a.variant}): {ylabel}", fontsize=11)
        fig.tight_layout()
        fig.savefig(os.path.join(out_dir, f"{name}.png"), dpi=110)
        plt.close(fig)

    def moving_mean(v, w=25):
        if len(v) < w:
            return v
        return np.convolve(v, np.ones(w) / w, mode="same")

    figure("u_y_mid", "u_y_mid (mm)", lambda c, k: (c["step"][k], c["u_y_mid"][k]))
    figure("newton", "Newton iterations per step (moving mean, 25 steps)",
           lambda c, k: (c["step"][k][1:], moving_mean(c["newton"][k][1:])))
    figure("area", "body area (mm^2)", lambda c, k: (c["step"][k], c["volume"][k]))


if __name__ == "__main__":
    main()
