#!/usr/bin/python3
"""Particle-Newmark MPM (Aulisa & Capodaglio, scenes/rolling_disk_mpm.toml and scenes/cantilever_mpm_particle.toml):
the runs behind the data files that the two studies (tools/studies/rolling_disk_mpm.toml,
tools/studies/cantilever_mpm_particle.toml) do not write, and the files themselves. Every run is one
`loom run SCENE --threads 1 --set ...` of a committed scene; the exact overrides of each are in the CSVs.

  cantilever   tip histories over 8 s of particle Newmark (J = 2, 3; J = 4 with --j4, about 11 minutes more)
               and of grid Newmark on the same beam (scenes/cantilever_mpm_grid_newmark.toml: 16 x 16 quad4 with
               1 920 particles, 32 x 32 with 1 920, 7 680, 30 720), the linear check (E x 100, gravity held) and
               the energy lost against dt, grid, particles, soft stiffness, Newton tolerance and beta ->
               docs/benchmarks/cantilever_mpm_particle/cantilever_mpm_particle_tip_history.csv (time, tip u_y
               and energy of the plotted runs), cantilever_mpm_particle_tip_history.png,
               cantilever_mpm_particle_runs.csv (one row per run, with its command). About 20 minutes on one
               thread without --j4.
  rolling      the start-up of the rolling disk: the paper's set-up with a_0 = g (time.initial_acceleration =
               "equilibrium") and with the disk touching the ground, J = 1..4, E = 4.2e6 with the C_c of the
               authors' table; the disk's rotation at J = 1 (frames every 5 steps, read with python3-vtk9: about
               250 MB a run); the rigid-disk estimates; the split of eq 52 into t <= 0.5 s and t > 0.5 s for the
               study's cases (from rolling_disk_mpm_histories.csv) -> docs/benchmarks/rolling_disk_mpm/
               rolling_disk_mpm_startup.csv. About 12 minutes on one thread.
  histories W  collects the centre's x(t), y(t) of every case of a kept rolling-disk study run
               (tools/study tools/studies/rolling_disk_mpm.toml --work W --keep) ->
               docs/benchmarks/rolling_disk_mpm/rolling_disk_mpm_histories.csv.

Runs go to --work (default out/study/particle_newmark); a run whose run.json exists is reused, so the script can
be re-run to re-plot. LOOM=path overrides build/loom.

    tools/mpm_studies/particle_newmark_evidence.py cantilever [--j4]
    tools/mpm_studies/particle_newmark_evidence.py rolling
    tools/mpm_studies/particle_newmark_evidence.py histories WORK
"""
import argparse
import csv
import glob
import json
import math
import os
import pathlib
import re
import subprocess

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
LOOM = os.environ.get("LOOM", str(ROOT / "build" / "loom"))
BENCH = ROOT / "docs" / "benchmarks"

G, THETA, DT, STEPS, BETA = 9.81, math.pi / 4, 0.01, 250, 0.3
S = G * math.sin(THETA)  # the slope's component of gravity
A_ROLL = 2.0 * S / 3.0  # 4.6245 m/s^2
# Centre height that puts the generated disk (outer ring at r = 1.600853663..., core 1.4, 300 on its rim, factor
# 1.14) on the ground y = -1.6, as perf/bench_particle_newmark.cpp places it.
TOUCH = 0.0008536641936229

BEAM_J = {3: ["grid.refinements=3", "body[0].particles.core_height=0.2", "body[0].particles.n_height=40",
              "body[0].particles.factor=1.2"],
          4: ["grid.refinements=4", "body[0].particles.core_height=0.225", "body[0].particles.n_height=80",
              "body[0].particles.factor=1.224"]}
GRAVITY_OFF = 'body_force.y="t < 0.399 ? -9.81 : 0"'


def run(work, name, scene, sets, frames=False):
    """One loom run (skipped when WORK/name/run.json exists); returns (run.json, probes columns, wall s)."""
    out = pathlib.Path(work) / name
    info_path = out / "run.json"
    if not info_path.exists():
        cmd = [LOOM, "run", str(ROOT / "scenes" / scene), "--out", str(out), "--quiet", "--threads", "1"]  # an absolute scene stays
        for s in list(sets) + ([] if frames else ["output.every=0"]):
            cmd += ["--set", s]
        env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
        print(" ".join(cmd), flush=True)
        p = subprocess.run(cmd, capture_output=True, text=True, env=env)
        if p.returncode == 2:
            raise SystemExit(f"bad input: {' '.join(cmd)}\n{p.stderr}")
    info = json.loads(info_path.read_text())
    with open(out / "probes.csv") as f:
        rows = list(csv.DictReader(f))
    cols = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    return info, cols, info["wall_seconds"]


def command(scene, sets):
    return "build/loom run scenes/" + scene + "".join(f" --set '{s}'" for s in sets)


# Cantilever ------------------------------------------------------------------------------------------------------
def tip_decay(t, u):
    """First and last minimum of the tip's u_y (local minima below the mean after release) and the mean period
    between the minima after the first (the first is the sag under gravity)."""
    mean = u[t > 0.4].mean()
    mins = [i for i in range(1, len(u) - 1) if u[i] < u[i - 1] and u[i] <= u[i + 1] and u[i] < mean]
    period = (t[mins[-1]] - t[mins[1]]) / (len(mins) - 2) if len(mins) > 2 else float("nan")
    return mins[0], mins[-1], period


CANT_HEADER = ["run", "converged", "steps", "last_converged_time", "wall_s", "tip_first_min", "t_first_min",
               "tip_last_min", "t_last_min", "last_over_first_min", "period_s", "energy_at_0.4s", "energy_end",
               "energy_end_over_0.4s", "energy_lost_by_2s", "energy_lost_by_3.2s", "mean_tip_uy", "static_tip_uy", "command"]

# The reference of the linear check: the same beam (E x 100, Neo-Hooke, plane strain) in loom's static fem with
# tri6 on the alternating pattern, n_x x n_y = 40 x 16 ... 320 x 128; its tip (0.625, 0) is the MPM beam's
# (0.125, 0). The scene is written to the work directory.
STATIC_BEAM = """[scene]
name = "cantilever_static_tri6"
method = "fem"
description = "The cantilever of the particle-Newmark studies with E x 100, static under its weight, tri6"

[time]
integrator = "static"
dt = 1.0
steps = 1

[solver]
residual_relative = 1e-10

[[material]]
name = "rubber"
model = "neo_hooke"
E = 1.74e8
nu = 0.4
density = 10000

[[body]]
name = "beam"
material = "rubber"
element = "tri6"
mesh = { generator = "rectangle", origin = [0.0, -0.125], size = [0.625, 0.25], divisions = [40, 16], pattern = "alternating" }

[body_force]
y = -9.81

[[boundary]]
name = "wall"
region = { box = [[0.0, -0.125], [0.0, 0.125]] }
displacement = { x = 0, y = 0 }

[[probe]]
name = "tip_uy"
kind = "point"
at = [0.625, 0.0]
component = "y"
"""


def cantilever(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = BENCH / "cantilever_mpm_particle"
    p, g = "cantilever_mpm_particle.toml", "cantilever_mpm_grid_newmark.toml"
    # (name, scene, overrides, label of a plotted history or None)
    runs = [("particle_J2", p, [], "particle Newmark J = 2 (8 x 8 quad9, 23 040 particles)"),
            ("particle_J3", p, BEAM_J[3], "particle Newmark J = 3 (16 x 16 quad9, 70 008 particles)")]
    if args.j4:
        runs.append(("particle_J4", p, BEAM_J[4], "particle Newmark J = 4 (32 x 32 quad9, 178 790 particles)"))
    runs += [("grid_16x16", g, [], "grid Newmark 16 x 16 quad4, 1 920 particles"),
             ("grid_32x32", g, ["grid.divisions=[32,32]", "body[0].mesh.divisions=[40,16]"],
              "grid Newmark 32 x 32 quad4, 7 680 particles"),
             ("grid_32x32_1920", g, ["grid.divisions=[32,32]"], None),
             ("grid_32x32_30720", g, ["grid.divisions=[32,32]", "body[0].mesh.divisions=[80,32]"], None),
             # The linear check: E x 100 (Neo-Hooke at a deflection of L / 300), gravity held for the 1000 steps.
             ("linear_J2", p, ["material[0].E=1.74e8", "body_force.y=-9.81"], None),
             ("linear_J3", p, ["material[0].E=1.74e8", "body_force.y=-9.81"] + BEAM_J[3], None),
             # Where the energy goes (J = 2 unless named; the loss by t = 3.2 s).
             ("dt0.004", p, ["time.dt=0.004", "time.steps=2000", GRAVITY_OFF], None),
             ("dt0.002", p, ["time.dt=0.002", "time.steps=1600", GRAVITY_OFF], None),
             ("J3grid_J2particles", p, ["time.steps=400", "grid.refinements=3"], None),
             ("J2grid_J3particles", p, ["time.steps=400"] + BEAM_J[3][1:], None),
             ("soft_stiffness_1e-12", p, ["time.steps=400", "mpm.soft_stiffness.c1=1e-12", "mpm.soft_stiffness.c2=1e-12"], None),
             ("soft_stiffness_1e-4", p, ["time.steps=400", "mpm.soft_stiffness.c1=1e-4", "mpm.soft_stiffness.c2=1e-4"], None),
             ("soft_stiffness_off", p, ["mpm.soft_stiffness.c1=0", "mpm.soft_stiffness.c2=0"], None),
             ("newton_1e-11", p, ["time.steps=400", "solver.residual_relative=1e-11"], None)]
    # beta = 1/4 (2 beta = gamma) is refused by the scene checks since it was run here: the particles' energy grew
    # 6.8-fold in 125 steps (the double eigenvalue -1 the refusal names).

    rows, hist = [], {}
    for name, scene, sets, label in runs:
        info, c, wall = run(args.work, name, scene, sets)
        t, u, e = c["time"], c["tip_uy"], c["energy"]
        dt = t[1] - t[0]
        k = {tt: int(round(tt / dt)) for tt in (0.4, 2.0, 3.2)}
        row = {"run": name, "converged": int(info["converged"]), "steps": info["steps_done"],
               "last_converged_time": f"{info['last_converged_time']:.4g}", "wall_s": f"{wall:.4g}",
               "command": command(scene, sets) + " --threads 1"}
        if name.startswith("linear"):
            row["mean_tip_uy"] = f"{u[1:].mean():.6g}"
        elif len(e) > k[0.4]:
            row["energy_at_0.4s"] = f"{e[k[0.4]]:.6g}"
            row["energy_end"] = f"{e[-1]:.6g}"
            row["energy_end_over_0.4s"] = f"{e[-1] / e[k[0.4]]:.4f}"
            for tt in (2.0, 3.2):
                if len(e) > k[tt]:
                    row[f"energy_lost_by_{tt:g}s"] = f"{1 - e[k[tt]] / e[k[0.4]]:.4f}"
            if t[-1] > 7.9:
                i0, i1, period = tip_decay(t, u)
                row.update({"tip_first_min": f"{u[i0]:.6g}", "t_first_min": f"{t[i0]:.4g}", "tip_last_min": f"{u[i1]:.6g}",
                            "t_last_min": f"{t[i1]:.4g}", "last_over_first_min": f"{u[i1] / u[i0]:.4f}", "period_s": f"{period:.4f}"})
        rows.append(row)
        if label:
            hist[name] = (label, t, u, e)
    static_scene = pathlib.Path(args.work) / "cantilever_static_tri6.toml"
    static_scene.write_text(STATIC_BEAM)
    for n in (40, 80, 160, 320):
        sets = [f"body[0].mesh.divisions=[{n},{n * 2 // 5}]"]
        info, c, wall = run(args.work, f"static_tri6_{n}x{n * 2 // 5}", str(static_scene), sets)
        rows.append({"run": f"static_tri6_{n}x{n * 2 // 5}", "converged": int(info["converged"]), "steps": info["steps_done"],
                     "wall_s": f"{wall:.4g}", "static_tip_uy": f"{c['tip_uy'][-1]:.6g}",
                     "command": f"build/loom run SCENE --set '{sets[0]}' --threads 1 (SCENE: the static tri6 beam of "
                                "tools/mpm_studies/particle_newmark_evidence.py)"})
    with open(out / "cantilever_mpm_particle_runs.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=CANT_HEADER)
        w.writeheader()
        w.writerows(rows)

    names = list(hist)
    t = hist[names[0]][1]
    with open(out / "cantilever_mpm_particle_tip_history.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time"] + [f"{n}_tip_uy" for n in names] + [f"{n}_energy" for n in names])
        for i in range(len(t)):
            w.writerow([f"{t[i]:.6g}"] + [f"{hist[n][2][i]:.8g}" for n in names] + [f"{hist[n][3][i]:.8g}" for n in names])

    fig, ax = plt.subplots(2, 1, figsize=(10, 7.5), sharex=True)
    for k, n in enumerate(names):
        label, tt, u, e = hist[n]
        style = "-" if n.startswith("particle") else "--"
        ax[0].plot(tt, u, style, color=f"C{k}", lw=0.9, label=label)
        k04 = int(round(0.4 / (tt[1] - tt[0])))
        ax[1].plot(tt[k04:], e[k04:] / e[k04], style, color=f"C{k}", lw=0.9, label=label)
    ax[0].axvline(0.4, color="k", lw=0.5, ls=":")
    ax[0].set_ylabel("tip u_y [m] (particle at (0.125, 0))")
    ax[1].legend(fontsize=7, loc="lower left")
    ax[1].set_ylabel("E(t) / E(0.4 s), kinetic + elastic")
    ax[1].set_xlabel("t [s] (gravity off from t = 0.4 s; dt = 0.008)")
    for a in ax:
        a.grid(alpha=0.3)
    fig.suptitle("Cantilever of Aulisa & Capodaglio §6.2: free vibration after gravity is removed at t = 0.4 s", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "cantilever_mpm_particle_tip_history.png", dpi=90)
    print("wrote", out / "cantilever_mpm_particle_runs.csv", out / "cantilever_mpm_particle_tip_history.csv",
          out / "cantilever_mpm_particle_tip_history.png")


# Rolling disk ----------------------------------------------------------------------------------------------------
def eq52_parts(t, x):
    """Eq 52 (mean over the steps of |x - x_exact| / x_exact), its part from t <= 0.5 s and from t > 0.5 s (the
    two add up to it), and the acceleration fitted on t in [1, 2.5] s."""
    ref = S * t[1:] ** 2 / 3.0
    e = np.abs(x[1:] - ref) / ref
    n = len(e)
    early = e[t[1:] <= 0.5 + 1e-12].sum() / n
    m = (t >= 1.0 - 1e-12) & (t <= 2.5 + 1e-12)
    late = 2.0 * np.polyfit(t[m], x[m], 2)[0] if m.sum() >= 3 else float("nan")
    return e.mean(), early, e.mean() - early, late


ROLL_HEADER = ["run", "J", "C_c", "gap", "a_0", "converged", "steps", "fall_time_s", "eq52", "eq52_t_le_0.5s",
               "eq52_t_gt_0.5s", "late_acceleration", "late_acceleration_error", "centre_y_min", "centre_y_max",
               "R_alpha_over_a", "wall_s", "command"]


def rigid_rows():
    """The rigid-disk estimates of the start-up: Newmark (gamma = 1/2, beta = 0.3) from a_0 = 0 under the rolling
    acceleration, and a free fall through the gap (sliding at g sin(theta)) ended by a sticky impact (v -> 2/3 v,
    angular momentum about the contact point) followed by rolling, evaluated at t_i = i dt (exact kinematics)."""
    t = np.arange(STEPS + 1) * DT
    rows = []
    x = 0.5 * A_ROLL * t ** 2 - 0.5 * A_ROLL * DT * t + BETA * A_ROLL * DT ** 2
    x[0] = 0.0
    e, early, rest, _ = eq52_parts(t, x)
    rows.append({"run": "rigid disk rolling, Newmark from a_0 = 0", "gap": 0, "a_0": "0", "eq52": f"{e:.4g}",
                 "eq52_t_le_0.5s": f"{early:.4g}", "eq52_t_gt_0.5s": f"{rest:.4g}", "late_acceleration": f"{A_ROLL:.6g}"})
    for modulus, base in (("4.2e6", 0.2), ("4.2e8", 0.3)):
        for J in (1, 2, 3, 4):
            gap = base / 2 ** (J - 1)
            tf = math.sqrt(2 * gap / (G * math.cos(THETA)))
            x = np.where(t < tf, 0.5 * S * t ** 2,
                         0.5 * S * tf ** 2 + (2 / 3) * S * tf * (t - tf) + 0.5 * A_ROLL * (t - tf) ** 2)
            e, early, rest, _ = eq52_parts(t, x)
            rows.append({"run": f"rigid disk, fall through the gap then sticky impact (E = {modulus} gaps)", "J": J,
                         "gap": f"{gap:.6g}", "fall_time_s": f"{tf:.4f}", "eq52": f"{e:.4g}", "eq52_t_le_0.5s": f"{early:.4g}",
                         "eq52_t_gt_0.5s": f"{rest:.4g}", "late_acceleration": f"{A_ROLL:.6g}"})
    return rows


def disk_rotation(outdir):
    """R alpha / a: alpha and a twice the t^2 coefficients of parabolas fitted on t in [1, 2.5] s through the angle
    of the best-fit rotation of all particles and their mean x displacement (the run's frames, every 5 steps)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    ts, phis, xs, prev, acc = [], [], [], None, 0.0
    for f in sorted(glob.glob(str(outdir / "*_particles.vtp"))):
        step = int(re.search(r"_(\d+)_particles\.vtp$", f).group(1))
        r = vtkXMLPolyDataReader()
        r.SetFileName(f)
        r.Update()
        poly = r.GetOutput()
        x = vtk_to_numpy(poly.GetPoints().GetData())[:, :2]
        X = x - vtk_to_numpy(poly.GetPointData().GetArray("displacement"))[:, :2]
        Xc, xc = X - X.mean(0), x - x.mean(0)
        phi = math.atan2((Xc[:, 0] * xc[:, 1] - Xc[:, 1] * xc[:, 0]).sum(), (Xc * xc).sum())
        acc = phi if prev is None else acc + (phi - prev + math.pi) % (2 * math.pi) - math.pi
        prev = phi
        ts.append(step * DT)
        phis.append(acc)
        xs.append(x.mean(0)[0] - X.mean(0)[0])
    t, phi, x = np.array(ts), np.array(phis), np.array(xs)
    m = (t >= 1.0 - 1e-9) & (t <= 2.5 + 1e-9)
    alpha = 2.0 * np.polyfit(t[m], phi[m], 2)[0]
    a = 2.0 * np.polyfit(t[m], x[m], 2)[0]
    return 1.6 * abs(alpha) / a


def rolling(args):
    out = BENCH / "rolling_disk_mpm"
    scene = "rolling_disk_mpm.toml"
    rows = rigid_rows()

    # The study's cases, from the committed histories.
    hist_path = out / "rolling_disk_mpm_histories.csv"
    if hist_path.exists():
        cases = {}
        with open(hist_path) as f:
            for r in csv.DictReader(f):
                cases.setdefault((r["series"], r["case"]), []).append((float(r["time"]), float(r["centre_x"]), float(r["centre_y"])))
        for (series, case), v in cases.items():
            a = np.array(v)
            e, early, rest, late = eq52_parts(a[:, 0], a[:, 1])
            J = int(case.split("=")[1])
            cc = 0.5 if series in ("E = 4.2e6", "E = 4.2e8") else {1: 0.0, 2: 0.0, 3: 0.0, 4: 0.3}[J]
            gap = (0.3 if series == "E = 4.2e8" else 0.2) / 2 ** (J - 1)
            rows.append({"run": f"study: {series}", "J": J, "C_c": cc, "gap": f"{gap:.6g}", "a_0": "0", "converged": 1,
                         "steps": len(v) - 1, "eq52": f"{e:.4g}", "eq52_t_le_0.5s": f"{early:.4g}", "eq52_t_gt_0.5s": f"{rest:.4g}",
                         "late_acceleration": f"{late:.6g}", "late_acceleration_error": f"{late / A_ROLL - 1:+.4f}",
                         "centre_y_min": f"{a[:, 2].min():.4g}", "centre_y_max": f"{a[:, 2].max():.4g}",
                         "command": "tools/study tools/studies/rolling_disk_mpm.toml"})

    def case_sets(J, cc, y):
        return [f"grid.refinements={J}", f"mpm.receding_contact={cc}", f"body[0].particles.centre=[0.0, {y}]",
                f"probe[0].at=[0.0, {y}]", f"probe[1].at=[0.0, {y}]"]

    runs = []
    for J in (1, 2, 3, 4):
        cc = {1: 0.0, 2: 0.0, 3: 0.0, 4: 0.3}[J]
        gap = 0.2 / 2 ** (J - 1)
        runs.append(("a_0 = g (equilibrium), E = 4.2e6, C_c of the authors' table", f"equilibrium_J{J}", J, cc, gap, "g",
                     case_sets(J, cc, gap) + ['time.initial_acceleration="equilibrium"'], False))
        runs.append(("touching the ground, E = 4.2e6, C_c of the authors' table", f"touching_J{J}", J, cc, 0.0, "0",
                     case_sets(J, cc, TOUCH), False))
    runs.append(("the paper's set-up, E = 4.2e6, C_c = 1", "cc1_J1", 1, 1.0, 0.2, "0", ["mpm.receding_contact=1.0"], False))
    runs.append(("touching the ground, E = 4.2e6, C_c = 0.5", "touching_cc0.5_J3", 3, 0.5, 0.0, "0", case_sets(3, 0.5, TOUCH), False))
    runs += [("rotation, E = 4.2e6, C_c = 0.5", "rotation_soft_cc0.5_J1", 1, 0.5, 0.2, "0", [], True),
             ("rotation, E = 4.2e6, C_c = 0", "rotation_soft_cc0_J1", 1, 0.0, 0.2, "0", ["mpm.receding_contact=0.0"], True),
             ("rotation, E = 4.2e8, C_c = 0.5", "rotation_stiff_cc0.5_J1", 1, 0.5, 0.3, "0",
              ["material[0].E=4.2e8", "mpm.soft_stiffness.c1=1e-5", "mpm.soft_stiffness.c2=1e-9",
               "body[0].particles.centre=[0.0, 0.3]", "probe[0].at=[0.0, 0.3]", "probe[1].at=[0.0, 0.3]"], True)]
    for label, name, J, cc, gap, a0, sets, frames in runs:
        if frames:
            sets = sets + ["output.every=5"]
        info, c, wall = run(args.work, name, scene, sets, frames=frames)
        e, early, rest, late = eq52_parts(c["time"], c["centre_x"])
        row = {"run": label, "J": J, "C_c": cc, "gap": f"{gap:.6g}", "a_0": a0, "converged": int(info["converged"]),
               "steps": info["steps_done"], "centre_y_min": f"{c['centre_y'].min():.4g}",
               "centre_y_max": f"{c['centre_y'].max():.4g}", "wall_s": f"{wall:.4g}",
               "command": command(scene, sets) + " --threads 1"}
        if info["converged"]:
            row.update({"eq52": f"{e:.4g}", "eq52_t_le_0.5s": f"{early:.4g}", "eq52_t_gt_0.5s": f"{rest:.4g}",
                        "late_acceleration": f"{late:.6g}", "late_acceleration_error": f"{late / A_ROLL - 1:+.4f}"})
        if frames:
            row["R_alpha_over_a"] = f"{disk_rotation(pathlib.Path(args.work) / name):.3f}"
        rows.append(row)
    with open(out / "rolling_disk_mpm_startup.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=ROLL_HEADER)
        w.writeheader()
        w.writerows(rows)
    print("wrote", out / "rolling_disk_mpm_startup.csv")


def histories(args):
    """Centre histories of the kept study runs (tools/study names a run directory series_case)."""
    out = BENCH / "rolling_disk_mpm" / "rolling_disk_mpm_histories.csv"
    import tomllib
    with open(ROOT / "tools" / "studies" / "rolling_disk_mpm.toml", "rb") as f:
        study = tomllib.load(f)
    with open(out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["series", "case", "step", "time", "centre_x", "centre_y", "newton"])
        for series in study["series"]:
            for J in series["values"]:
                d = pathlib.Path(args.work) / "runs" / re.sub(r"[^A-Za-z0-9_.=-]+", "_", f"{series['label']}_J={J}")
                with open(d / "probes.csv") as g:
                    for r in csv.DictReader(g):
                        w.writerow([series["label"], f"J={J}", r["step"], r["time"], f"{float(r['centre_x']):.9g}",
                                    f"{float(r['centre_y']):.9g}", r["newton"]])
    print("wrote", out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("part", choices=["cantilever", "rolling", "histories"])
    ap.add_argument("study_work", nargs="?", help="histories: the --work directory of a kept rolling-disk study run")
    ap.add_argument("--work", default=str(ROOT / "out" / "study" / "particle_newmark"))
    ap.add_argument("--j4", action="store_true", help="cantilever: also J = 4 (about 11 minutes on one thread)")
    args = ap.parse_args()
    if args.part == "histories":
        if not args.study_work:
            ap.error("histories needs the study's work directory")
        args.work = args.study_work
        histories(args)
    else:
        pathlib.Path(args.work).mkdir(parents=True, exist_ok=True)
        {"cantilever": cantilever, "rolling": rolling}[args.part](args)


if __name__ == "__main__":
    main()
