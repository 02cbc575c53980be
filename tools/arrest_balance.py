#!/usr/bin/python3
"""Force balance of an arrested yield-stress deposit (the right half of a symmetric slump on a stick ground).

At rest the symmetry wall's thrust F_s = -integral sigma_xx dy over the centre section balances the ground's
friction F_b = integral tau_b dx. Lubrication theory takes the whole base at yield (F_b = tau0 x_f) and the centre
section lithostatic with sigma_xx = sigma_yy (F_s = rho g h_c^2 / 2); the two together give its arrested profile.
This tool reads a run's last frame and probes and says which of the two assumptions the computed deposit departs
from, and by how much:

  base      F_b / (tau0 x_f)                    1 when the whole base is at yield
  thrust    F_s / (rho g h_c^2 / 2)             1 for a lithostatic centre with no deviatoric normal stress
  split     rho g h_c^2/2 - F_s = integral (rho g (h - y) + sigma_yy) dy   (the centre lighter than lithostatic)
                                + integral (sigma_xx - sigma_yy) dy          (the plug in extension, <= 2 tau0 h_c)

The stresses along the centre section and the base come from the frame's cell stresses, sampled on lines a quarter
of a cell inside the body. It also prints the arrested half-width of the balance with the plug at yield in
extension over the whole depth (docs/free_surface.md): rho g h^2 / 2 - 2 tau0 h = tau0 (L - x).

usage: tools/arrest_balance.py RUN_DIR --tau0 20 [--rho 2300] [--g 9.81] [--area 0.005] [--csv FILE]
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


def last_frame(run_dir):
    frames = sorted(glob.glob(os.path.join(run_dir, "*.vtu")))
    if not frames:
        return None, None
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(frames[-1])
    reader.Update()
    return frames[-1], reader.GetOutput()


def last_probes(run_dir):
    with open(os.path.join(run_dir, "probes.csv")) as f:
        rows = list(csv.DictReader(f))
    return {k: float(v) for k, v in rows[-1].items()}


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
    return pts[valid], stress[valid]


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


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--tau0", type=float, required=True)
    ap.add_argument("--rho", type=float, default=2300.0)
    ap.add_argument("--g", type=float, default=9.81)
    ap.add_argument("--area", type=float, default=None, help="half-area for the shallow and corrected half-widths")
    ap.add_argument("--csv", default=None, help="write the centre section (y, stresses) here")
    a = ap.parse_args()
    tau0, rho, g = a.tau0, a.rho, a.g
    frame, mesh = last_frame(a.run_dir)
    p = last_probes(a.run_dir)
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
        return
    x = vtk_to_numpy(mesh.GetPoints().GetData())[:, :2]
    hc, xf = x[:, 1].max(), x[:, 0].max()
    cell = math.sqrt(2.0 * xf * hc / max(1, mesh.GetNumberOfCells()))  # a cell's size, from the deposit's area

    # Centre section, a quarter of a cell off the symmetry line; the column's top is where the samples end.
    xs = 0.25 * cell
    pts, s = sample_line(mesh, (xs, 1e-9), (xs, hc), 400)
    y, top = pts[:, 1], pts[:, 1].max()
    litho = rho * g * (top - y)
    thrust_section = np.trapz(-s[:, 0, 0], y)
    lighter = np.trapz(litho + s[:, 1, 1], y)
    extension = np.trapz(s[:, 0, 0] - s[:, 1, 1], y)
    # Base, a quarter of a cell above the ground.
    bpts, bs = sample_line(mesh, (0.0, 0.25 * cell), (xf, 0.25 * cell), 800)
    base_shear = bs[:, 0, 1]

    Fs, Fb = p.get("symmetry_x", float("nan")), -p.get("ground_x", float("nan"))
    litho_thrust = rho * g * hc**2 / 2
    print(f"{frame}: t = {p['time']:g} s, x_f = {xf:.4f} m, h_c = {1e3 * hc:.2f} mm, speed {p.get('speed', float('nan')):.2e} m/s")
    print(f"walls: symmetry thrust F_s = {Fs:.4f} N/m, ground friction F_b = {Fb:.4f} N/m (balance {Fs - Fb:+.1e}), "
          f"ground normal {p.get('ground_y', float('nan')):.3f} N/m")
    print(f"base:   F_b / (tau0 x_f)          = {Fb / (tau0 * xf):.3f}   (cell shear a quarter cell up: mean "
          f"{base_shear.mean() / tau0:.3f} tau0 over {bpts[0, 0]:.3f}-{bpts[-1, 0]:.3f} m)")
    print(f"thrust: F_s / (rho g h_c^2 / 2)   = {Fs / litho_thrust:.3f}   (section of cell stresses: {thrust_section:.4f} N/m)")
    print(f"  lithostatic {litho_thrust:.4f} - thrust {Fs:.4f} = {litho_thrust - Fs:.4f} N/m. The section's cell stresses (top "
          f"{1e3 * top:.2f} mm at x = {1e3 * xs:.2f} mm; they need not balance the nodal forces exactly): lighter than "
          f"lithostatic by {lighter:.4f}, the plug's extension {extension:.4f} (2 tau0 h = {2 * tau0 * top:.4f}), mean "
          f"(sigma_xx - sigma_yy) / (2 tau0) over the upper half {np.mean(((s[:, 0, 0] - s[:, 1, 1]) / (2 * tau0))[y > top / 2]):.3f}")
    print(f"  effective yield stress of the shallow balance rho g h_c^2 / (2 x_f) = {litho_thrust / xf / tau0:.3f} tau0")
    if a.area:
        k = rho * g
        L0 = (3 * a.area / (2 * math.sqrt(2 * tau0 / k))) ** (2.0 / 3.0)
        L1, h1 = extension_corrected_half_width(tau0, rho, g, a.area)
        print(f"half-width: shallow {L0:.4f} m (h_c {1e3 * math.sqrt(2 * tau0 * L0 / k):.2f} mm), with the plug at yield in "
              f"extension {L1:.4f} m (h_c {1e3 * h1:.2f} mm); computed {xf:.4f} m ({100 * (xf / L0 - 1):+.1f} %, {100 * (xf / L1 - 1):+.1f} %)")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["y", "sigma_xx", "sigma_yy", "sigma_xy", "lithostatic", "extension_over_2tau0"])
            for yi, si, li in zip(y, s, litho):
                w.writerow([f"{yi:.6g}", f"{si[0, 0]:.6g}", f"{si[1, 1]:.6g}", f"{si[0, 1]:.6g}", f"{-li:.6g}",
                            f"{(si[0, 0] - si[1, 1]) / (2 * tau0):.6g}"])


if __name__ == "__main__":
    main()
