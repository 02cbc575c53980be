#!/usr/bin/python3
"""Moderate block (seed 000 §5.2) with walls: the runs behind the section "With walls (2026-11)" of
docs/moderate_block/README.md that are not the element/transfer study of tools/moderate_block_study.py.

Each run is the scene's reading (50 x 50 mm, K = 501, G = 3.2296 MPa, rho = 1.1e-3 g/mm^3, dead load on
0 <= x <= 25 ramped to 30 MPa over 1000 steps of 0.01 ms, p1p1_uphi 16 x 16 unless stated) with one thing
changed: the method (fem: the same mesh, no remeshing), the integrator (static: no inertia, same load
steps), how x = 0 and y = 0 are held (dir: u = 0 on the nodes that start there; wall: a frictionless wall
only; both: the two together, as scenes/moderate_block_pfem.toml), the loaded length, the load, the top held
horizontally, the density or the wall penalty. The scenes are written from the template below (so that fem
runs have no [remesh]), into WORK/scenes/; runs go to WORK/<name>/ and are not repeated if their run.json
exists. Writes into docs/moderate_block/walls/:

  reading_runs.csv     one row per run: what it changes, last converged step, why it stopped, u_y_mid at
                       steps 100..1000, largest penetration, remeshes that changed the connectivity
  reading_curves.csv   u_y_mid per step of every run (empty after its last converged step)
  reading_u_y_mid.png  u_y_mid against the step, four panels

Usage (from the repository root, after building build/loom; about 3 minutes on one core, one run at a time):
  /usr/bin/python3 tools/moderate_block_reading_study.py [--work /tmp/moderate_reading] [--plot-only]
Python 3 with Debian's numpy and matplotlib.
"""
import argparse
import csv
import json
import os
import subprocess
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "docs", "moderate_block", "walls")


def scene_text(method="pfem", integ="euler_backward", sym="both", bot="both", load="half"):
    s = f'''[scene]
name = "moderate-block"
method = "{method}"
units = "mm ms g N MPa"

[time]
integrator = "{integ}"
dt = 0.01
steps = 1000
mass = "lumped"

[solver]
max_iterations = 25
line_search = true
max_cutbacks = 4

[[material]]
name = "rubber"
model = "neo_hooke"
K = 501.0
G = 3.2296
density = 1.1e-3

[[body]]
name = "block"
material = "rubber"
element = "p1p1_uphi"
mesh = {{ generator = "rectangle", origin = [0.0, 0.0], size = [50.0, 50.0], divisions = [16, 16], pattern = "shifted" }}
'''
    if sym in ("wall", "both"):
        s += '\n[[wall]]\nname = "symmetry"\npoint = [0.0, 0.0]\nnormal = [1.0, 0.0]\n'
    if bot in ("wall", "both"):
        s += '\n[[wall]]\nname = "support"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\n'
    if sym in ("dir", "both"):
        s += '\n[[boundary]]\nname = "symmetry_bc"\nregion = { box = [[0.0, 0.0], [0.0, 50.0]] }\ndisplacement = { x = 0.0 }\n'
    if bot in ("dir", "both"):
        s += '\n[[boundary]]\nname = "bottom_bc"\nregion = { box = [[0.0, 0.0], [50.0, 0.0]] }\ndisplacement = { y = 0.0 }\n'
    xl = 25.0 if load == "half" else 50.0
    s += f'\n[[boundary]]\nname = "load"\nregion = {{ box = [[0.0, 50.0], [{xl}, 50.0]] }}\ntraction = {{ y = "-30 * t / 10" }}\n'
    if method == "pfem":
        s += '\n[remesh]\nalpha = 2.5\nlchar = "local"\n\n[map]\nscheme = "cpm"\n'

    def probe(name, body):
        return f'\n[[probe]]\nname = "{name}"\n{body}\n'

    s += probe("u_y_mid", 'kind = "point"\nat = [0.0, 50.0]\ncomponent = "y"')
    s += probe("u_y_edge", 'kind = "point"\nat = [25.0, 50.0]\ncomponent = "y"')
    s += probe("u_x_corner", 'kind = "point"\nat = [50.0, 50.0]\ncomponent = "x"')
    s += probe("volume", 'kind = "volume"')
    if sym in ("wall", "both") or bot in ("wall", "both"):
        s += probe("penetration", 'kind = "penetration"')
    if sym in ("dir", "both"):
        s += probe("symmetry_reaction", 'kind = "reaction"\nboundary = "symmetry_bc"\ncomponent = "x"')
    s += probe("xmin", 'kind = "extent"\ncomponent = "x"\nbound = "min"')
    s += probe("ymin", 'kind = "extent"\ncomponent = "y"\nbound = "min"')
    if method == "pfem":
        s += probe("changed", 'kind = "remesh"\nquantity = "changed"')
    s += probe("newton", 'kind = "newton"')
    s += '\n[output]\nevery = 50\n'
    return s


# name: (scene options, extra --set, group, what it shows)
RUNS = [
    ("fem_static_16", dict(method="fem", integ="static", sym="dir", bot="dir"), [], "fem static",
     "FEM, static, u = 0 on the lines"),
    ("fem_static_32", dict(method="fem", integ="static", sym="dir", bot="dir"), ["body[0].mesh.divisions=[32,32]"],
     "fem static", "FEM, static, 32x32"),
    ("fem_static_16_tri6", dict(method="fem", integ="static", sym="dir", bot="dir"), ["body[0].element=\"tri6\""],
     "fem static", "FEM, static, tri6"),
    ("fem_static_32_tri6", dict(method="fem", integ="static", sym="dir", bot="dir"),
     ["body[0].element=\"tri6\"", "body[0].mesh.divisions=[32,32]"], "fem static", "FEM, static, 32x32 tri6"),
    ("fem_static_whole", dict(method="fem", integ="static", sym="dir", bot="dir", load="whole"), [], "whole top",
     "FEM, static, whole top loaded"),
    ("fem_dyn_walls", dict(method="fem", sym="wall", bot="wall"), [], "fem dynamic",
     "FEM, dynamic, walls only"),
    ("fem_dyn_dir", dict(method="fem", sym="dir", bot="dir"), [], "fem dynamic", "FEM, dynamic, u = 0 on the lines"),
    ("fem_dyn_whole", dict(method="fem", sym="dir", bot="dir", load="whole"), [], "whole top",
     "FEM, dynamic, whole top loaded"),
    ("fem_period", dict(method="fem", sym="dir", bot="dir"),
     ["boundary[load].traction.y=-0.3", "time.integrator=\"bossak\"", "time.alpha=0.0", "time.steps=1500",
      "output.every=0"], None, "FEM, 0.3 MPa applied at once, Newmark (alpha_B = 0): the first period"),
    ("pfem_walls", dict(sym="wall", bot="wall"), [], "pfem", "PFEM, walls only (the draft)"),
    ("pfem_walls_tri6", dict(sym="wall", bot="wall"), ["body[0].element=\"tri6\""], "pfem",
     "PFEM, walls only, tri6"),
    ("pfem_walls_iso2", dict(sym="wall", bot="wall"), ["map.scheme=\"btm\"", "map.iso=2"], "pfem",
     "PFEM, walls only, BTM-ISO2"),
    ("pfem_walls_32", dict(sym="wall", bot="wall"), ["body[0].mesh.divisions=[32,32]"], "pfem",
     "PFEM, walls only, 32x32"),
    ("pfem_scene", dict(), [], "pfem", "PFEM, u = 0 and walls (the scene)"),
    ("pfem_support_wall", dict(sym="both", bot="wall"), [], "pfem",
     "PFEM, symmetry u = 0 and wall, support a wall only"),
    ("pfem_scene_k3e3", dict(), ["wall[symmetry].penalty=3e3", "wall[support].penalty=3e3"], "pfem",
     "PFEM, the scene, penalty 3e3 (10 x default)"),
    ("pfem_scene_k1e4", dict(), ["wall[symmetry].penalty=1e4", "wall[support].penalty=1e4"], "pfem",
     "PFEM, the scene, penalty 1e4"),
    ("pfem_quasistatic", dict(), ["material[rubber].density=1.1e-9"], "set-up", "PFEM, the scene, rho = 1.1e-9"),
    ("pfem_whole", dict(load="whole"), [], "whole top", "PFEM, the scene, whole top loaded"),
    ("pfem_3mpa", dict(), ["boundary[load].traction.y=\"-3 * t / 10\""], "set-up", "PFEM, the scene, 3 MPa"),
    ("pfem_top_held", dict(), ["boundary[load].displacement.x=0.0"], "set-up",
     "PFEM, the scene, loaded part held horizontally"),
    ("pfem_top_held_qs", dict(), ["boundary[load].displacement.x=0.0", "material[rubber].density=1.1e-9"], "set-up",
     "PFEM, loaded part held, rho = 1.1e-9"),
]


def stop_reason(rec):
    if rec.get("converged"):
        return "completed"
    f = rec.get("failure", "")
    for key, text in (("singular", "tangent singular"), ("inverted at the start", "cell inverted by the transfer"),
                      ("line search", "line search: no decrease"), ("no convergence", "Newton: no convergence"),
                      ("intersects itself", "boundary self-intersecting")):
        if key in f:
            return text
    return f[:60]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--loom", default="build/loom")
    ap.add_argument("--work", default="/tmp/moderate_reading")
    ap.add_argument("--plot-only", action="store_true")
    a = ap.parse_args()
    os.makedirs(os.path.join(a.work, "scenes"), exist_ok=True)
    results = {}
    for name, opts, sets, group, what in RUNS:
        out = os.path.join(a.work, name)
        if not a.plot_only and not os.path.exists(os.path.join(out, "run.json")):
            scene = os.path.join(a.work, "scenes", name + ".toml")
            with open(scene, "w") as f:
                f.write(scene_text(**opts))
            args = ["nice", a.loom, "run", scene, "--out", out, "--quiet", "--threads", "1"]
            for s in sets:
                args += ["--set", s]
            print(name, "...", flush=True)
            p = subprocess.run(args, capture_output=True, text=True)
            if p.returncode not in (0, 1):
                sys.exit(f"{' '.join(args)}: exit {p.returncode}\n{p.stderr}")
        rows = list(csv.DictReader(open(os.path.join(out, "probes.csv"))))
        rec = json.load(open(os.path.join(out, "run.json")))
        results[name] = (rows, rec)

    steps = (100, 200, 300, 400, 500, 600, 800, 1000)
    with open(os.path.join(HERE, "reading_runs.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["run", "what", "last_converged_step", "stopped_by"] + [f"u_y_mid_{s}" for s in steps]
                   + ["u_y_mid_last", "penetration_max_mm", "remeshes_changed"])
        for name, opts, sets, group, what in RUNS:
            rows, rec = results[name]
            n = rec["last_converged_step"]
            u = [float(r["u_y_mid"]) for r in rows[:n + 1]]
            pen = max((float(r.get("penetration") or 0) for r in rows[:n + 1]), default=0.0)
            ch = sum(int(float(r.get("changed") or 0)) for r in rows[1:n + 1])
            w.writerow([name, what, n, stop_reason(rec)] + [f"{u[s]:.3f}" if s <= n else "" for s in steps]
                       + [f"{u[-1]:.3f}", f"{pen:.4f}", ch if "changed" in rows[0] else ""])
    with open(os.path.join(HERE, "reading_curves.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        names = [r[0] for r in RUNS if r[3] is not None]
        w.writerow(["step"] + names)
        for s in range(1001):
            row = [s]
            for name in names:
                rows, rec = results[name]
                row.append(f"{float(rows[s]['u_y_mid']):.6g}" if s <= rec["last_converged_step"] else "")
            w.writerow(row)

    panels = [("fem static", "static FEM (no inertia, no remeshing)", "upper right"),
              ("fem dynamic", "dynamic FEM (no remeshing)", "upper right"),
              ("pfem", "PFEM, the reading: walls only vs u = 0 and walls", "upper right"),
              ("set-up", "PFEM, candidate set-ups of the paper", "lower left"),
              ("whole top", "whole top loaded", "lower left")]
    fig, axes = plt.subplots(3, 2, figsize=(12, 12))
    for ax, (group, title, legend_at) in zip(axes.flat, panels):
        for name, opts, sets, g, what in RUNS:
            if g != group:
                continue
            rows, rec = results[name]
            n = rec["last_converged_step"]
            x = np.arange(n + 1)
            y = np.array([float(r["u_y_mid"]) for r in rows[:n + 1]])
            line, = ax.plot(x, y, lw=1.0, label=f"{what} (last {n})")
            ax.plot(x[-1], y[-1], "x", color=line.get_color(), ms=8, mew=2)
        if group == "whole top":
            K, G = 501.0, 3.2296
            lam_l = K - 2 * G / 3
            P = np.linspace(0.01, 30, 300)
            lam = []
            v = np.array([1.0, 1.0])
            for p in P:  # homogeneous plane strain compression of the loom neo_hooke, lateral stress free
                for _ in range(50):
                    a1, l2 = v
                    J = a1 * l2
                    r = np.array([lam_l * np.log(J) / a1 + G * (a1 - 1 / a1), lam_l * np.log(J) / l2 + G * (l2 - 1 / l2) + p])
                    Jm = np.array([[lam_l * (1 - np.log(J)) / a1**2 + G * (1 + 1 / a1**2), lam_l / (a1 * l2)],
                                   [lam_l / (a1 * l2), lam_l * (1 - np.log(J)) / l2**2 + G * (1 + 1 / l2**2)]])
                    v = v - np.linalg.solve(Jm, r)
                lam.append(v[1])
            ax.plot(P / 30 * 1000, 50 * (np.array(lam) - 1), "k--", lw=0.8, label="homogeneous (exact, static)")
            ax.axvline(18.34 / 30 * 1000, color="grey", lw=0.6, ls=":")
            ax.text(18.34 / 30 * 1000 + 5, -45, "Biot\n18.3 MPa", fontsize=7)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("step (load = 0.03 MPa x step)")
        ax.set_ylabel("u_y_mid (mm)")
        ax.set_xlim(0, 1000)
        ax.set_ylim(-52, 2)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc=legend_at)
    axes.flat[-1].axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "reading_u_y_mid.png"), dpi=100)
    rows, rec = results["fem_period"]
    t = np.array([float(r["time"]) for r in rows])
    u = np.array([float(r["u_y_mid"]) for r in rows])
    amp = np.abs(np.fft.rfft(u - u.mean()))
    freq = np.fft.rfftfreq(len(u), t[1] - t[0])
    k = 1 + int(np.argmax(amp[1:]))
    print(f"fem_period: dominant period {1 / freq[k]:.2f} ms (mean u_y_mid {u.mean():.3f} mm, extreme {u.min():.3f} mm)")
    for name, opts, sets, group, what in RUNS:
        rows, rec = results[name]
        print(f"{name:20s} last {rec['last_converged_step']:5d} {stop_reason(rec):28s} "
              f"u_y_mid end {float(rows[rec['last_converged_step']]['u_y_mid']):8.2f}")


if __name__ == "__main__":
    main()
