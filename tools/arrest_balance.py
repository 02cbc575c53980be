#!/usr/bin/python3
"""Force balance of an arrested yield-stress deposit (the right half of a symmetric slump on a stick ground).

At rest the symmetry wall's thrust F_s = -integral sigma_xx dy over the centre section balances the ground's
friction F_b = integral tau_b dx. Lubrication theory takes the whole base at yield (F_b = tau0 x_f) and the centre
section lithostatic with sigma_xx = sigma_yy (F_s = rho g h_c^2 / 2); the two together give its arrested profile.
This tool reads a run's last frame and probes and says which of the two assumptions the computed deposit departs
from, and by how much:

  base      F_b / (tau0 x_f)                    1 when the whole base is at yield
  thrust    F_s / (rho g h_c^2 / 2)             1 for a lithostatic centre with no deviatoric normal stress
  budget    rho g h_c^2/2 - F_s, split exactly into five parts (and at rest, where F_s = F_b, rho g h_c^2 / 2 into
            seven with F_s + c split into the base's two below):
              height      rho g (h_c^2 - h_0^2) / 2          the section's top h_0 below the highest node h_c
              density     g int (rho - rho/J) y dy            the paste dilated (J > 1) weighs less per height
              vertical    int (W(y) + sigma_yy) dy            sigma_yy above or below the weight W(y) = g int_y rho/J
              extension   int (sigma_xx - sigma_yy) dy        the plug in extension (<= 2 tau0 h_0 at yield)
              wall        int -sigma_xx dy - F_s              the cell stresses a quarter cell off the wall against
                                                              the wall's force (resolution next to the wall)

The stresses along the centre section and the base come from the frame's cell stresses, sampled on lines a quarter
of a cell inside the body. It also prints the arrested half-width of the balance with the plug at yield in
extension over the whole depth (docs/free_surface.md): rho g h^2 / 2 - 2 tau0 h = tau0 (L - x), and the front
scaled to the half-area given, x_f (A / A_run)^(2/3) with A_run the run's area probe (half-widths go as A^(2/3)):
the front without the area the run gained (the u-p element's dilation) or lost, to compare runs on other meshes.

With --profile FILE it writes the same split section by section along the deposit (x, top, thrust of the cell
stresses, lithostatic thrusts for rho and rho / J, the weight and sigma_yy at the base, the extension term, and the
friction of the ground from x to the front as the cell shear a quarter cell up integrates it), which shows where
the deposit departs from the shallow balance d(thrust)/dx = tau_b.

usage: tools/arrest_balance.py RUN_DIR --tau0 20 [--rho 2300] [--g 9.81] [--area 0.005] [--step N] [--csv FILE]
       [--profile FILE]
(RUN_DIR holds probes.csv with wall_force probes symmetry_x and ground_x, and the frames *.vtu; without frames, as a
study's runs, only the walls' balance is given, with the probes front and height.)
"""
import argparse
import csv
import glob
import math
import os

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def read_frame(run_dir, step=None):
    """The frame of `step` (default: the last)."""
    frames = sorted(glob.glob(os.path.join(run_dir, "*.vtu")))
    if step is not None:
        frames = [f for f in frames if f.endswith(f"_{step:06d}.vtu")]
        if not frames:
            raise SystemExit(f"{run_dir}: no frame of step {step}")
    if not frames:
        return None, None
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(frames[-1])
    reader.Update()
    return frames[-1], reader.GetOutput()


def probes_at(run_dir, frame):
    """The probes of the frame's step (its file name ends in the step), or the last row without a frame."""
    with open(os.path.join(run_dir, "probes.csv")) as f:
        rows = list(csv.DictReader(f))
    row = rows[-1]
    if frame:
        step = int(os.path.splitext(frame)[0].rsplit("_", 1)[-1])
        row = next((r for r in rows if int(r["step"]) == step), None)
        if row is None:
            raise SystemExit(f"{run_dir}/probes.csv: no row of step {step}, the frame {frame}'s")
    return {k: float(v) for k, v in row.items()}


def sample_line(mesh, a, b, n):
    """Cell stresses (3x3) at n points from a to b; points outside the body are dropped."""
    line = vtk.vtkLineSource()
    line.SetPoint1(a[0], a[1], 0.0)
    line.SetPoint2(b[0], b[1], 0.0)
    line.SetResolution(n - 1)
    probe = vtk.vtkProbeFilter()
    probe.SetInputConnection(line.GetOutputPort())
    probe.SetSourceData(mesh)
    probe.Update()
    out = probe.GetOutput()
    pts = vtk_to_numpy(out.GetPoints().GetData())[:, :2]
    valid = vtk_to_numpy(out.GetPointData().GetArray(probe.GetValidPointMaskArrayName())).astype(bool)
    stress = vtk_to_numpy(out.GetPointData().GetArray("stress")).reshape(-1, 3, 3)
    jac = vtk_to_numpy(out.GetPointData().GetArray("J"))
    return pts[valid], stress[valid], jac[valid]


def section(mesh, x, hc, rho, g, n=400):
    """The vertical section at x: its top, thrust, lithostatic thrusts and the budget's parts (N/m)."""
    pts, s, jac = sample_line(mesh, (x, 1e-9), (x, hc), n)
    if len(pts) < 2:
        return None
    y, top = pts[:, 1], pts[:, 1].max()
    rho_cur = rho / jac
    # W(y) = g int_y^top rho/J dy', the weight above y per unit width (cumulative trapezoid from the top down)
    seg = 0.5 * (rho_cur[1:] + rho_cur[:-1]) * np.diff(y)
    W = g * np.concatenate([np.cumsum(seg[::-1])[::-1], [0.0]])
    return {
        "x": x, "top": top, "y": y, "s": s,
        "thrust": np.trapz(-s[:, 0, 0], y),
        "litho_nominal": rho * g * top**2 / 2,
        "litho_current": np.trapz(W, y),
        "vertical": np.trapz(W + s[:, 1, 1], y),
        "extension": np.trapz(s[:, 0, 0] - s[:, 1, 1], y),
        "weight": W[0], "base_syy": -s[0, 1, 1], "W": W,
        "upper_extension": np.mean(((s[:, 0, 0] - s[:, 1, 1]))[y > top / 2]),
    }


def boundary_areas(mesh):
    """Each node's share of the boundary's outward normal times length (as the walls' penalty measures it)."""
    x = vtk_to_numpy(mesh.GetPoints().GetData())[:, :2]
    if np.any(np.diff(vtk_to_numpy(mesh.GetCells().GetOffsetsArray())) != 3):
        raise SystemExit("arrest_balance: the frame's cells are not all 3-node triangles (es_pfem, pfem with p1)")
    tri = vtk_to_numpy(mesh.GetCells().GetConnectivityArray()).reshape(-1, 3)
    directed = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    _, inverse, count = np.unique(np.sort(directed, axis=1), axis=0, return_inverse=True, return_counts=True)
    directed = directed[count[inverse.ravel()] == 1]  # an edge of one triangle only: on the boundary
    area = np.zeros_like(x)
    for a, b in directed:  # counter-clockwise cells: the outward normal is the edge turned clockwise
        d = x[b] - x[a]
        area[a] += 0.5 * np.array([d[1], -d[0]])
        area[b] += 0.5 * np.array([d[1], -d[0]])
    return x, area


def corner_hold(mesh, Fs):
    """The stick ground's horizontal hold on the corner node (symmetry line and ground), N/m.

    The corner node touches both walls; its penalty springs, k_N times its boundary length on each wall, share the
    push of the paste towards the symmetry line. The ground's share is a thrust the symmetry wall's force does not
    count and the ground's total friction nets out: F_s + c is the thrust across the centre section, F_b + c the
    friction of the rest of the base. k_N follows from F_s and the wall nodes' penetrations; the ground's spring is
    taken as anchored on the symmetry line (where the corner node touched down at the start: the frame's displacement
    must put its reference position there, else it is reported), and both walls as having the same k_N (the default
    100 E / h; not so if either sets `penalty`)."""
    x, area = boundary_areas(mesh)
    on_wall = np.where(x[:, 0] <= 0.0)[0]
    if len(on_wall) == 0:
        return 0.0, None
    w = np.maximum(0.0, -area[on_wall, 0]) * -x[on_wall, 0]
    if w.sum() <= 0.0:
        return 0.0, None
    k = Fs / w.sum()  # k_N, N/m^3
    lowest = np.argmin(x[on_wall, 1])
    c = on_wall[lowest]
    if x[c, 1] > 0.0 or len(on_wall) < 2:
        return 0.0, None
    u = mesh.GetPointData().GetArray("displacement")
    if u is not None and np.linalg.norm(reference := x[c] - vtk_to_numpy(u)[c, :2]) > 1e-9:
        print(f"corner: the corner particle did not start at the origin (reference {reference}); its ground anchor, "
              "taken on the symmetry line, may be off")
    return k * max(0.0, -area[c, 1]) * -x[c, 0], {"share": k * w[lowest], "next": np.sort(x[on_wall, 1])[1], "k": k}


def write_profile(path, mesh, xf, hc, cell, xb, tau_b, rho, g, n=60):
    """The budget at n sections from the centre to a cell short of the front, with the friction beyond each."""
    # friction of the ground on the paste from x to the front: - int_x^xf tau_b (tau_b the cell shear near the base)
    seg = 0.5 * (tau_b[1:] + tau_b[:-1]) * np.diff(xb)
    beyond = np.concatenate([np.cumsum(seg[::-1])[::-1], [0.0]])
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["x", "top", "thrust", "litho_nominal", "litho_current", "vertical", "extension", "weight_base",
                    "syy_base", "friction_beyond"])
        for x in np.linspace(0.25 * cell, xf - cell, n):
            c = section(mesh, x, hc, rho, g)
            if c is None:
                continue
            w.writerow([f"{v:.6g}" for v in (x, c["top"], c["thrust"], c["litho_nominal"], c["litho_current"],
                                              c["vertical"], c["extension"], c["weight"], c["base_syy"],
                                              -np.interp(x, xb, beyond))])


def extension_corrected_half_width(tau0, rho, g, area):
    """Half-width L of rho g h^2/2 - 2 tau0 h = tau0 (L - x) holding the half-area `area` (bisection)."""
    k = rho * g

    def held(L):
        x = np.linspace(0.0, L, 4001)
        h = (2 * tau0 + np.sqrt(4 * tau0**2 + 2 * k * tau0 * (L - x))) / k
        return np.trapz(h, x), h[0]

    lo, hi = 1e-4, 100.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if held(mid)[0] < area else (lo, mid)
    return lo, held(lo)[1]


def print_area_scaled(xf, probes, area, L0, L1):
    """The front scaled to the half-area asked for, x_f (A / A_run)^(2/3) with A_run the probe `area` of the same
    step: an arrested shallow deposit's half-width goes as A^(2/3) (L_f above), so this is the front the deposit
    would have without the area it gained or lost (the u-p element's dilation under shear, the paste's elastic
    compression, a removal's loss), to compare runs whose areas differ."""
    if "area" not in probes or not probes["area"] > 0.0:
        return
    scaled = xf * (area / probes["area"]) ** (2.0 / 3.0)
    print(f"  scaled to the area: the run's half-area {probes['area']:.6g} m^2 ({100 * (probes['area'] / area - 1):+.2f} %), "
          f"x_f (A / A_run)^(2/3) = {scaled:.4f} m ({100 * (scaled / L0 - 1):+.1f} %, {100 * (scaled / L1 - 1):+.1f} %)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--tau0", type=float, required=True)
    ap.add_argument("--rho", type=float, default=2300.0)
    ap.add_argument("--g", type=float, default=9.81)
    ap.add_argument("--area", type=float, default=None, help="half-area for the shallow and corrected half-widths")
    ap.add_argument("--csv", default=None, help="write the centre section (y, stresses) here")
    ap.add_argument("--step", type=int, default=None, help="the frame of this step (default: the last)")
    ap.add_argument("--profile", default=None, help="write the budget section by section along x here")
    a = ap.parse_args()
    tau0, rho, g = a.tau0, a.rho, a.g
    frame, mesh = read_frame(a.run_dir, a.step)
    p = probes_at(a.run_dir, frame)
    if mesh is None:  # no frame (a study's run): the walls' balance from the probes front and height
        hc, xf = p["height"], p["front"]
        Fs, Fb = p["symmetry_x"], -p["ground_x"]
        print(f"{a.run_dir} (probes only): t = {p['time']:g} s, x_f = {xf:.4f} m, h_c = {1e3 * hc:.2f} mm")
        print(f"walls: F_s = {Fs:.4f}, F_b = {Fb:.4f} N/m; base F_b / (tau0 x_f) = {Fb / (tau0 * xf):.3f}; "
              f"thrust F_s / (rho g h_c^2 / 2) = {Fs / (rho * g * hc**2 / 2):.3f}")
        if a.area:
            L0 = (3 * a.area / (2 * math.sqrt(2 * tau0 / (rho * g)))) ** (2.0 / 3.0)
            L1, h1 = extension_corrected_half_width(tau0, rho, g, a.area)
            print(f"half-width: shallow {L0:.4f} m, extension-corrected {L1:.4f} m; computed {xf:.4f} m "
                  f"({100 * (xf / L0 - 1):+.1f} %, {100 * (xf / L1 - 1):+.1f} %)")
            print_area_scaled(xf, p, a.area, L0, L1)
        return
    x = vtk_to_numpy(mesh.GetPoints().GetData())[:, :2]
    hc, xf = x[:, 1].max(), x[:, 0].max()
    cell = math.sqrt(2.0 * xf * hc / max(1, mesh.GetNumberOfCells()))  # a cell's size, from the deposit's area

    # Centre section, a quarter of a cell off the symmetry line; the column's top is where the samples end.
    c = section(mesh, 0.25 * cell, hc, rho, g)
    y, s, top = c["y"], c["s"], c["top"]
    # Base, a quarter of a cell above the ground.
    bpts, bs, _ = sample_line(mesh, (0.0, 0.25 * cell), (xf, 0.25 * cell), 800)
    base_shear = bs[:, 0, 1]

    Fs, Fb = p.get("symmetry_x", float("nan")), -p.get("ground_x", float("nan"))
    litho_thrust = rho * g * hc**2 / 2
    parts = {
        "height": litho_thrust - c["litho_nominal"],
        "density": c["litho_nominal"] - c["litho_current"],
        "vertical": c["vertical"],
        "extension": c["extension"],
        "wall": c["thrust"] - Fs,
    }
    print(f"{frame}: t = {p['time']:g} s, x_f = {xf:.4f} m, h_c = {1e3 * hc:.2f} mm, speed {p.get('speed', float('nan')):.2e} m/s")
    print(f"walls: symmetry thrust F_s = {Fs:.4f} N/m, ground friction F_b = {Fb:.4f} N/m (balance {Fs - Fb:+.1e}), "
          f"ground normal {p.get('ground_y', float('nan')):.3f} N/m")
    print(f"base:   F_b / (tau0 x_f)          = {Fb / (tau0 * xf):.3f}   (cell shear a quarter cell up: mean "
          f"{base_shear.mean() / tau0:.3f} tau0 over {bpts[0, 0]:.3f}-{bpts[-1, 0]:.3f} m)")
    print(f"thrust: F_s / (rho g h_c^2 / 2)   = {Fs / litho_thrust:.3f}   (section of cell stresses: {c['thrust']:.4f} N/m)")
    print(f"  budget: rho g h_c^2 / 2 - F_s = {litho_thrust:.4f} - {Fs:.4f} = {litho_thrust - Fs:.4f} N/m "
          f"({100 * (1 - Fs / litho_thrust):.1f} % of it), from the section at x = {1e3 * c['x']:.2f} mm (top "
          f"h_0 = {1e3 * top:.2f} mm):")
    for name, v in parts.items():
        print(f"    {name:10s} {v:+.4f} N/m  ({100 * v / litho_thrust:+.1f} %)")
    print(f"    (sum {sum(parts.values()):+.4f}; extension bound 2 tau0 h_0 = {2 * tau0 * top:.4f}; mean (sigma_xx - "
          f"sigma_yy) / (2 tau0) over the upper half {c['upper_extension'] / (2 * tau0):.3f}; base sigma_yy "
          f"{c['base_syy']:.2f} Pa against the weight above it {c['weight']:.2f} Pa)")
    print(f"  effective yield stress of the shallow balance rho g h_c^2 / (2 x_f) = {litho_thrust / xf / tau0:.3f} tau0")
    hold, corner = corner_hold(mesh, Fs)
    if corner:
        y1 = corner["next"]
        strip = rho * g * hc * y1 / 2
        print(f"corner: the stick ground holds the corner node with c = {hold:.4f} N/m (the symmetry wall with "
              f"{corner['share']:.4f}); the centre section's thrust F_s + c = {Fs + hold:.4f} N/m "
              f"({(Fs + hold) / litho_thrust:.3f} of rho g h_c^2 / 2), the friction of the rest of the base F_b + c = "
              f"{Fb + hold:.4f} N/m = {(Fb + hold) / (tau0 * xf):.3f} tau0 x_f; k_N = {corner['k']:.9g} N/m^3 from F_s and the "
              f"wall's penetrations")
        print(f"  held strip: the bottom node row is held, so the thrust of the strip below the first node above the "
              f"corner (y_1 = {1e3 * y1:.2f} mm) reaches the ground without yielding: about rho g h_c y_1 / 2 = "
              f"{strip:.4f} N/m; (F_b + c - strip) / (tau0 x_f) = {(Fb + hold - strip) / (tau0 * xf):.3f}")
        # The whole of rho g h_c^2 / 2 in units of tau0 x_f: the budget's parts with the wall term split into the
        # corner's hold and what the cell stresses still miss, and the thrust F_s + c into the base's two parts.
        terms = [("height", parts["height"]), ("density", parts["density"]), ("vertical", parts["vertical"]),
                 ("extension", parts["extension"]), ("section", c["thrust"] - Fs - hold),
                 ("base layer", Fb + hold - strip), ("held strip", strip)]
        print(f"  rho g h_c^2 / (2 tau0 x_f) = {litho_thrust / (tau0 * xf):.3f} = "
              + " + ".join(f"{name} {v / (tau0 * xf):.3f}" for name, v in terms))
    if a.area:
        k = rho * g
        L0 = (3 * a.area / (2 * math.sqrt(2 * tau0 / k))) ** (2.0 / 3.0)
        L1, h1 = extension_corrected_half_width(tau0, rho, g, a.area)
        print(f"half-width: shallow {L0:.4f} m (h_c {1e3 * math.sqrt(2 * tau0 * L0 / k):.2f} mm), with the plug at yield in "
              f"extension {L1:.4f} m (h_c {1e3 * h1:.2f} mm); computed {xf:.4f} m ({100 * (xf / L0 - 1):+.1f} %, {100 * (xf / L1 - 1):+.1f} %)")
        print_area_scaled(xf, p, a.area, L0, L1)
    if a.profile:
        write_profile(a.profile, mesh, xf, hc, cell, bpts[:, 0], base_shear, rho, g)
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["y", "sigma_xx", "sigma_yy", "sigma_xy", "lithostatic", "extension_over_2tau0"])
            for yi, si, li in zip(y, s, c["W"]):
                w.writerow([f"{yi:.6g}", f"{si[0, 0]:.6g}", f"{si[1, 1]:.6g}", f"{si[0, 1]:.6g}", f"{-li:.6g}",
                            f"{(si[0, 0] - si[1, 1]) / (2 * tau0):.6g}"])


if __name__ == "__main__":
    main()
