#!/usr/bin/python3
"""Highly constrained rubber block (seed 000 §5.1, scenes/constrained_block_fem.toml): force-displacement
curves of the three elements and of the p1p1_uphi stabilisation sweep (Fig 8), the pressure-oscillation
measure against alpha_s (Fig 9), and the tri6 / p1p1_uphi comparison (Fig 10) on the paper's 4x8 mesh and
refined ones.

Every curve is one `loom run` of a committed scene with --set overrides; nothing is tuned. All cases run the
FEM scene except tri6_eq24_ties: the PFEM scene with remeshing off (remesh.every > steps), i.e. tri6 with the
seed's eq-24 ties of boundary mid-nodes and nothing else of PFEM (the paper's FEM-TRI6 as read in docs/guide/scenes.md). Writes under
OUT (default docs/constrained_block/):
  curves.csv                 long format: case, element, alpha_s, mesh, step, u_pre, force, pressure_jump, uy_top_right, newton
  summary.csv                one row per run: final force and pressure jump, Newton iterations, converged
  reaction_vs_upre.png       Fig 8 / Fig 10 analogue: indenter force against u_pre, tri6 / p1p1_uphi (K/10)
  pressure_jump_vs_alpha.png Fig 9 analogue: final mean pressure jump across interior edges against alpha_s
  refinement.png             final force of p1p1_uphi (K/10) and tri6 against the mesh

Usage (from the repository root, after building build/loom):
  /usr/bin/python3 tools/constrained_block_study.py [--loom build/loom] [--out docs/constrained_block] [--fine]
Meshes are named as in the paper, rows x columns of element edges (4x8: divisions [8, 4]).
--fine adds the 16x32 meshes (tri6 takes about a minute there; p1p1_uphi stops early, see docs/guide/scenes.md).
Python 3 with Debian's numpy and matplotlib; no other dependency.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

SCENE = "scenes/constrained_block_fem.toml"
PFEM_SCENE = "scenes/constrained_block_pfem.toml"
NO_REMESH = ["remesh.every=1000"]  # more than the 200 steps: the PFEM scene never remeshes, the eq-24 ties stay
ALPHAS = ["1", "10", "100", "1e3", "1e4", "1e5"]  # MPa; K/10 = 1e4 (K = 1e5 MPa)
# Meshes are named as in the paper, rows x columns of element edges: "4x8" is divisions [8, 4].
def mesh_name(d):
    return f"{d[1]}x{d[0]}"


DU = 0.001  # mm of indentation per step (the scene's u_y = -0.001 t, dt = 1)
REFERENCE_FORCE = 6.5  # N, seed 000 §5.1 from its references [3, 21]


def run_case(loom, workdir, case, element, alpha, divisions, scene=SCENE, more=()):
    """Runs one case (more: further --set overrides); returns (rows, summary)."""
    out = os.path.join(workdir, case)
    args = [loom, "run", scene, "--out", out, "--quiet", "--set", "output.every=0",
            "--set", f"body[0].element={element}", "--set", f"body[0].mesh.divisions=[{divisions[0]},{divisions[1]}]"]
    if alpha is not None:
        args += ["--set", f"body[0].alpha_s={alpha}"]
    for m in more:
        args += ["--set", m]
    start = time.monotonic()
    proc = subprocess.run(args, capture_output=True, text=True)
    wall = time.monotonic() - start
    if proc.returncode not in (0, 1):  # 1: the run stopped early; its probes up to then are valid
        sys.exit(f"{' '.join(args)} failed with exit code {proc.returncode}:\n{proc.stderr}")
    with open(os.path.join(out, "probes.csv")) as f:
        probes = list(csv.DictReader(f))
    with open(os.path.join(out, "run.json")) as f:
        record = json.load(f)
    rows = []
    for p in probes:
        step = int(float(p["step"]))
        rows.append({"case": case, "element": element, "alpha_s": alpha or "", "mesh": mesh_name(divisions),
                     "step": step, "u_pre": DU * float(p["time"]), "force": -float(p["reaction"]),
                     "pressure_jump": float(p["pressure_jump"]), "uy_top_right": float(p["top_right"]),
                     "newton": int(float(p["newton"]))})
    summary = {"case": case, "element": element, "alpha_s": alpha or "", "mesh": mesh_name(divisions),
               "dofs": record["dofs"], "steps_done": record["steps_done"], "converged": record["converged"],
               "u_pre_final": rows[-1]["u_pre"], "force_final": rows[-1]["force"],
               "pressure_jump_final": rows[-1]["pressure_jump"], "newton_iterations": record["newton_iterations"]}
    print(f"{case:28s} u_pre {summary['u_pre_final']:.3f} mm  force {summary['force_final']:8.4f} N  "
          f"pressure jump {summary['pressure_jump_final']:8.4f} MPa  {'' if record['converged'] else 'STOPPED EARLY '}"
          f"({wall:.1f} s)", flush=True)
    return rows, summary


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in r.items()})


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--loom", default="build/loom")
    ap.add_argument("--out", default="docs/constrained_block")
    ap.add_argument("--fine", action="store_true", help="also run the 16x32 meshes")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)

    cases = []  # (case, element, alpha, divisions[, scene, overrides])
    for alpha in ALPHAS:
        cases.append((f"p1p1_uphi_alpha_{alpha}", "p1p1_uphi", alpha, (8, 4)))
    cases += [("tri6", "tri6", None, (8, 4)), ("tri6_eq24_ties", "tri6", None, (8, 4), PFEM_SCENE, NO_REMESH),
              ("p1", "p1", None, (8, 4))]
    meshes = [(16, 8)] + ([(32, 16)] if a.fine else [])
    for d in meshes:
        cases += [(f"p1p1_uphi_K10_{mesh_name(d)}", "p1p1_uphi", None, d), (f"tri6_{mesh_name(d)}", "tri6", None, d)]
    cases.append(("p1_8x16", "p1", None, (16, 8)))

    curves, summaries = [], []
    with tempfile.TemporaryDirectory() as work:
        for case in cases:
            rows, summary = run_case(a.loom, work, *case)
            curves += rows
            summaries.append(summary)
    write_csv(os.path.join(a.out, "curves.csv"), curves)
    write_csv(os.path.join(a.out, "summary.csv"), summaries)

    def curve(case):
        rs = [r for r in curves if r["case"] == case]
        return [r["u_pre"] for r in rs], [r["force"] for r in rs], [r["pressure_jump"] for r in rs]

    # 1. Force against indentation (Fig 8 sweep and Fig 10 comparison on the 4x8 mesh), the Fig 10 order as
    #    the ratio tri6 / p1p1_uphi (K/10) at every step, and p1 in its own panel.
    fig, (ax, ax_r, ax_p1) = plt.subplots(1, 3, figsize=(16, 5), gridspec_kw={"width_ratios": [2, 1.2, 1]})
    cmap = plt.get_cmap("viridis")
    for k, alpha in enumerate(ALPHAS):
        u, f, _ = curve(f"p1p1_uphi_alpha_{alpha}")
        label = f"p1p1_uphi, alpha_s = {alpha} MPa" + (" (K/10)" if alpha == "1e4" else "")
        ax.plot(u, f, color=cmap(k / (len(ALPHAS) - 1)), lw=2.2 if alpha == "1e4" else 1.3, label=label)
    u, f, _ = curve("tri6")
    ax.plot(u, f, "r--", lw=2, label="tri6")
    u, f, _ = curve("tri6_eq24_ties")
    ax.plot(u, f, "m-.", lw=2, label="tri6 with eq-24 ties (PFEM scene, no remeshing)")
    ax.axhline(REFERENCE_FORCE, color="grey", ls=":", lw=1)
    ax.annotate("6.5 N (references of seed 000 §5.1)", (0.005, REFERENCE_FORCE + 0.1), color="grey", fontsize=8)
    ax.set_xlabel("u_pre (mm)")
    ax.set_ylabel("indenter force (N per mm thickness)")
    ax.set_title("Constrained block, FEM, 4x8 shifted mesh")
    ax.set_xlim(0, 0.2)
    ax.set_ylim(0, None)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    _, f_ref, _ = curve("p1p1_uphi_alpha_1e4")
    for case, style, label in [("tri6", "r--", "tri6"), ("tri6_eq24_ties", "m-.", "tri6 with eq-24 ties")]:
        u, f, _ = curve(case)
        ax_r.plot(u[1:], [x / y for x, y in zip(f[1:], f_ref[1:])], style, lw=2, label=label)
    ax_r.axhline(1.0, color="C0", lw=1)
    ax_r.set_xlabel("u_pre (mm)")
    ax_r.set_ylabel("force / force of p1p1_uphi (K/10)")
    ax_r.set_title("Fig 10: tri6 against p1p1_uphi (K/10)")
    ax_r.set_xlim(0, 0.2)
    ax_r.grid(alpha=0.3)
    ax_r.legend(fontsize=8, loc="upper left")
    for case, style, label in [("p1", "k-", "p1 (locks)"), ("p1p1_uphi_alpha_1e4", "C0-", "p1p1_uphi K/10"), ("tri6", "r--", "tri6")]:
        u, f, _ = curve(case)
        ax_p1.plot(u, f, style, label=label)
    ax_p1.set_xlabel("u_pre (mm)")
    ax_p1.set_title("p1 for scale")
    ax_p1.set_xlim(0, 0.2)
    ax_p1.grid(alpha=0.3)
    ax_p1.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "reaction_vs_upre.png"), dpi=110)
    plt.close(fig)

    # 2. Pressure oscillation against alpha_s (final state).
    fig, ax = plt.subplots(figsize=(6, 4.5))
    xs = [float(x) for x in ALPHAS]
    ys = [curve(f"p1p1_uphi_alpha_{x}")[2][-1] for x in ALPHAS]
    ax.loglog(xs, ys, "o-", label="p1p1_uphi")
    ax.axhline(curve("tri6")[2][-1], color="r", ls="--", label="tri6")
    ax.axvline(1e4, color="grey", ls=":", lw=1)
    ax.annotate("K/10", (1.2e4, 1.0), color="grey", fontsize=8)
    ax.set_yticks([0.2, 0.3, 0.5, 1, 2, 3])
    ax.get_yaxis().set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax.set_xlabel("alpha_s (MPa)")
    ax.set_ylabel("mean |p1 - p2| across interior edges (MPa)")
    ax.set_title("Pressure jump at u_pre = 0.2 mm, 4x8 mesh")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "pressure_jump_vs_alpha.png"), dpi=110)
    plt.close(fig)

    # 3. Element comparison under refinement: the curves (a run that stopped early ends with an x) and the
    #    final force against the element edge (runs that stopped early left out).
    fig, (ax, ax_h) = plt.subplots(1, 2, figsize=(12, 5))
    uphi_case = lambda d: "p1p1_uphi_alpha_1e4" if d == (8, 4) else f"p1p1_uphi_K10_{mesh_name(d)}"
    tri6_case = lambda d: "tri6" if d == (8, 4) else f"tri6_{mesh_name(d)}"
    widths = {(8, 4): 2.2, (16, 8): 1.5, (32, 16): 0.9}
    for label, case_of, color, ls in [("p1p1_uphi (K/10)", uphi_case, "C0", "-"), ("tri6", tri6_case, "r", "--")]:
        hs, fs = [], []
        for d in [(8, 4)] + meshes:
            s = next(s for s in summaries if s["case"] == case_of(d))
            u, f, _ = curve(case_of(d))
            ax.plot(u, f, color=color, ls=ls, lw=widths[d], label=f"{label}, {mesh_name(d)}")
            if not s["converged"]:
                ax.plot(u[-1], f[-1], "x", color=color, ms=10, mew=2)
            else:
                hs.append(0.25 * 8 / d[0])
                fs.append(s["force_final"])
        ax_h.plot(hs, fs, "o" + ls, color=color, label=label)
    for axis in (ax, ax_h):
        axis.axhline(REFERENCE_FORCE, color="grey", ls=":", lw=1)
        axis.grid(alpha=0.3)
        axis.legend(fontsize=8, loc="lower right" if axis is ax else "best")
    ax.set_xlim(0, 0.2)
    ax.set_ylim(0, None)
    ax.set_xlabel("u_pre (mm)")
    ax.set_ylabel("indenter force (N per mm thickness)")
    ax.set_title("Refined meshes (x: last converged step)")
    ax_h.set_xscale("log", base=2)
    ax_h.invert_xaxis()
    ax_h.set_xlabel("element edge h (mm)")
    ax_h.set_ylabel("force at u_pre = 0.2 mm (N)")
    ax_h.set_title("Final force against the mesh")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "refinement.png"), dpi=110)
    plt.close(fig)
    print(f"wrote {a.out}/curves.csv, summary.csv, reaction_vs_upre.png, pressure_jump_vs_alpha.png, refinement.png")


if __name__ == "__main__":
    main()
