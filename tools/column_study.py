#!/usr/bin/env python3
"""Seed 003's 3D columns solved with loom's FEM on several meshes: the reference for the 3D MPM.

Runs scenes/column_bending_fem.toml (3 s) and column_twisting_fem.toml (0.5 s) at h = 0.5, 0.333, 0.25, 0.1667,
0.125 (divisions [2,2,12] .. [8,8,48]) with the mixed tetrahedron or tet10, and prints per case: the first extremum
of u_x(A) (time, value), the first period (from the first zero crossing of u_x(A) to the third), the largest
|E - E_0| / E_0 of the total energy, Newton iterations and wall time; then, for each column, every run's
distance to the last run given (the finest): max_t |u_h(A) - u_ref(A)| over the run and its RMS over time,
relative to max_t |u_ref(A)|. Each run's probes.csv stays in WORK/<case>/.

  tools/column_study.py [--loom build/loom] [--work DIR] [--cases NAME,...] [--threads T] [--end T] [--dt DT]

Case names: bending_tet10_h0.5, ..., twisting_p1p1_uphi_h0.125. The twisting column runs with the scene's
settings (tet10: dt = 5e-4 and the constant-acceleration predictor); --dt overrides dt for every case.
docs/fem_3d.md's tables: --cases bending_tet10_h0.5,bending_tet10_h0.333,bending_tet10_h0.25 (about 40 minutes),
--cases twisting_tet10_h0.5,twisting_tet10_h0.333,twisting_tet10_h0.25,twisting_tet10_h0.1667.
"""
import argparse, csv, math, os, subprocess, sys, time

MESHES = {"h0.5": "[2,2,12]", "h0.333": "[3,3,18]", "h0.25": "[4,4,24]", "h0.1667": "[6,6,36]", "h0.125": "[8,8,48]"}


def cases():
    out = []
    for column in ("bending", "twisting"):
        for element in ("p1p1_uphi", "tet10"):
            for h, div in MESHES.items():
                out.append((f"{column}_{element}_{h}", column, element, div))
    return out


def crossings(t, u):
    return [t[i - 1] + (t[i] - t[i - 1]) * (-u[i - 1]) / (u[i] - u[i - 1]) for i in range(2, len(u)) if u[i - 1] * u[i] < 0]


def summarise(path):
    rows = list(csv.DictReader(open(path)))
    t = [float(r["time"]) for r in rows]
    ux = [float(r["ux_A"]) for r in rows]
    E = [float(r["total"]) for r in rows]
    newton = sum(float(r["newton"]) for r in rows)
    k = max(range(len(ux)), key=lambda i: abs(ux[i]) if t[i] < (crossings(t, ux) or [t[-1]])[0] else -1)
    z = crossings(t, ux)
    period = z[2] - z[0] if len(z) >= 3 else float("nan")  # first zero to the third: one whole swing
    drift = max(abs(e - E[0]) / E[0] for e in E)
    return {"t_end": t[-1], "peak_t": t[k], "peak_ux": ux[k], "first_zero": z[0] if z else float("nan"), "period": period,
            "energy_drift": drift, "newton": newton, "steps": len(rows) - 1}


def history(path):
    rows = list(csv.DictReader(open(path)))
    return {round(float(r["time"]), 9): (float(r["ux_A"]), float(r["uy_A"]), float(r["uz_A"])) for r in rows}


def distance(run, ref):
    """max and RMS over the common output times of |u_run(A) - u_ref(A)|, relative to max |u_ref(A)|."""
    times = sorted(set(run) & set(ref))
    d = [math.dist(run[t], ref[t]) for t in times]
    scale = max(math.hypot(*ref[t]) for t in times)
    return max(d) / scale, math.sqrt(sum(x * x for x in d) / len(d)) / scale, times[-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--loom", default="build/loom")
    ap.add_argument("--work", default="/tmp/loom_column_study")
    ap.add_argument("--end", type=float, default=0.0, help="end time (default: 3 s bending, 0.5 s twisting)")
    ap.add_argument("--dt", type=float, default=0.0, help="time step (default: the scene's)")
    ap.add_argument("--cases", default="")
    ap.add_argument("--threads", default="2")
    a = ap.parse_args()
    by_name = {c[0]: c for c in cases()}
    chosen = [by_name[n] for n in a.cases.split(",")] if a.cases else cases()  # in the order given
    done = []
    print("case,steps,t_end,peak_t,peak_ux_A,first_zero,period,max_energy_drift,newton,wall_s")
    for name, column, element, div in chosen:
        out = os.path.join(a.work, name)
        os.makedirs(out, exist_ok=True)
        dt = a.dt or (5e-4 if column == "twisting" and element == "tet10" else 1e-3)
        end = a.end or (3.0 if column == "bending" else 0.5)
        cmd = [a.loom, "run", f"scenes/column_{column}_fem.toml", "--out", out, "--quiet", "--threads", a.threads,
               "--set", f"body[0].element=\"{element}\"", "--set", f"body[0].mesh.divisions={div}",
               "--set", f"time.dt={dt}", "--set", f"time.steps={round(end / dt)}", "--set", "output.every=100000"]
        start = time.time()
        r = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.time() - start
        if r.returncode not in (0, 1):
            print(f"{name},error {r.returncode}: {r.stderr.strip()[:200]}", flush=True)
            continue
        s = summarise(os.path.join(out, "probes.csv"))
        print(f"{name},{s['steps']},{s['t_end']:.4f},{s['peak_t']:.4f},{s['peak_ux']:.5f},{s['first_zero']:.4f},{s['period']:.4f},"
              f"{s['energy_drift']:.2e},{s['newton']:.0f},{wall:.1f}", flush=True)
        done.append((name, column, os.path.join(out, "probes.csv")))
    for column in ("bending", "twisting"):
        runs = [(n, p) for n, c, p in done if c == column]
        if len(runs) < 2:
            continue
        ref_name, ref = runs[-1][0], history(runs[-1][1])
        print(f"\ncase,max_t |u(A) - u_ref(A)| / max |u_ref(A)|,RMS over time,up to t (ref: {ref_name})")
        for n, p in runs[:-1]:
            mx, rms, t_end = distance(history(p), ref)
            print(f"{n},{mx:.4f},{rms:.4f},{t_end:.4f}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
