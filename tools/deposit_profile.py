#!/usr/bin/python3
"""The surface profile h(x) of a yield-stress deposit in a loom frame against the arrested shallow layer.

A Bingham layer on a no-slip ground stops where the yield stress holds the hydrostatic gradient, tau0 = rho g h
|dh/dx|, so an arrested deposit whose front is at x_f has h(x) = sqrt(2 tau0 (x_f - x) / (rho g)) (plane strain;
lubrication theory, e.g. Liu & Mei 1989). The profile of the frame is the highest boundary point in each of `--bins`
columns of equal width (points of the mesh at their current position). Written: a CSV of x, h of the frame, the
arrested profile through the frame's own front and, with --length, the one through lubrication theory's arrested
front L (what a deposit that spread all the way would show), and a PNG.

With --extension AREA also the arrested layer whose plug is held at yield in extension over its whole depth (a
thick deposit; the shallow theory drops this term): the part downstream of x balances its thrust, less the
extension's 2 tau0 h, against the ground's friction at yield, rho g h^2 / 2 - 2 tau0 h = tau0 (L_e - x), so
h(x) = [2 tau0 + sqrt(4 tau0^2 + 2 rho g tau0 (L_e - x))] / (rho g), with L_e such that the area under it is AREA:
int_0^L h = [2 tau0 L + ((4 tau0^2 + 2 rho g tau0 L)^(3/2) - 8 tau0^3) / (3 rho g tau0)] / (rho g).

    tools/deposit_profile.py OUT/scene_001234.vtu --tau0 20 --rho 2300 --length 0.3166 --out docs/benchmarks/x/profile
"""
import argparse
import csv
import math
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def boundary_points(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetOutput().GetNumberOfCells() == 0:
        sys.exit(f"{path}: no cells (not a loom frame?)")
    # The edges used by one triangle only: VTK's boundary edges of the frame's surface (tri6 cells come out linear).
    surface = vtk.vtkGeometryFilter()
    surface.SetInputConnection(reader.GetOutputPort())
    edges = vtk.vtkFeatureEdges()
    edges.SetInputConnection(surface.GetOutputPort())
    edges.BoundaryEdgesOn()
    edges.FeatureEdgesOff()
    edges.ManifoldEdgesOff()
    edges.NonManifoldEdgesOff()
    edges.Update()
    return vtk_to_numpy(edges.GetOutput().GetPoints().GetData())[:, :2]


def extension_profile(tau0, rho, g, area):
    """L_e and h(x) of the arrested layer with the plug at yield in extension holding `area` (see the docstring)."""
    rg = rho * g

    def held(length):
        return (2.0 * tau0 * length + ((4.0 * tau0**2 + 2.0 * rg * tau0 * length) ** 1.5 - 8.0 * tau0**3) / (3.0 * rg * tau0)) / rg

    lo, hi = 0.0, 1.0
    while held(hi) < area:
        hi *= 2.0
    for _ in range(200):  # the area grows monotonically with L: bisection to round-off
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if held(mid) < area else (lo, mid)
    length = 0.5 * (lo + hi)
    return length, lambda x: (2.0 * tau0 + math.sqrt(4.0 * tau0**2 + 2.0 * rg * tau0 * max(length - x, 0.0))) / rg


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("frame", help="a .vtu frame of a pfem or es_pfem run")
    ap.add_argument("--tau0", type=float, required=True)
    ap.add_argument("--rho", type=float, required=True)
    ap.add_argument("--g", type=float, default=9.81)
    ap.add_argument("--length", type=float, default=0.0, help="lubrication theory's arrested front, m (optional)")
    ap.add_argument("--extension", type=float, default=0.0, metavar="AREA",
                    help="also the arrested layer with the plug at yield in extension holding AREA m^2 (optional)")
    ap.add_argument("--bins", type=int, default=40)
    ap.add_argument("--out", required=True, help="path without extension: OUT.csv and OUT.png")
    a = ap.parse_args()

    p = boundary_points(a.frame)
    front = p[:, 0].max()
    edges = np.linspace(p[:, 0].min(), front, a.bins + 1)
    k = np.clip(np.searchsorted(edges, p[:, 0], side="right") - 1, 0, a.bins - 1)
    xs, hs = [], []
    for b in range(a.bins):
        sel = k == b
        if sel.any():
            top = np.argmax(np.where(sel, p[:, 1], -np.inf))
            xs.append(p[top, 0])
            hs.append(p[top, 1])
    c = 2.0 * a.tau0 / (a.rho * a.g)
    own = [math.sqrt(c * max(front - x, 0.0)) for x in xs]
    full = [math.sqrt(c * max(a.length - x, 0.0)) for x in xs] if a.length > 0 else [float("nan")] * len(xs)
    if a.extension > 0:
        length_e, h_e = extension_profile(a.tau0, a.rho, a.g, a.extension)
        ext = [h_e(x) for x in xs]
    else:
        ext = [float("nan")] * len(xs)
    with open(a.out + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["x", "h", "h_arrested_own_front", "h_arrested_L", "h_arrested_extension"])
        for row in zip(xs, hs, own, full, ext):
            w.writerow([f"{v:.6g}" for v in row])

    # The fit in the part of the deposit away from its ends: the middle 80 % of its length.
    def rms(model):
        mid = [(h, m) for x, h, m in zip(xs, hs, model) if 0.1 * front <= x <= 0.9 * front]
        return math.sqrt(sum((h - m) ** 2 for h, m in mid) / len(mid)) if mid else float("nan")

    print(f"front {front:.4f} m; height at x = {xs[0]:.4f}: {hs[0]:.5f} m (arrested through the own front {own[0]:.5f}"
          + (f", through L = {a.length}: {full[0]:.5f}" if a.length > 0 else "") + f"); rms over 10-90 % of the length {rms(own):.2e} m")
    if a.extension > 0:
        print(f"with the plug in extension: L_e = {length_e:.4f} m, height at x = {xs[0]:.4f}: {ext[0]:.5f} m; "
              f"rms over 10-90 % of the length {rms(ext):.2e} m")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 3))
    ax.plot(xs, hs, "o", ms=3, label="loom (highest boundary point per column)")
    ax.plot(xs, own, "-", label="arrested layer through the same front")
    if a.length > 0:
        xl = np.linspace(0.0, a.length, 200)
        ax.plot(xl, np.sqrt(c * (a.length - xl)), "--", label=f"arrested layer, lubrication L = {a.length} m")
    if a.extension > 0:
        xe = np.linspace(0.0, length_e, 200)
        ax.plot(xe, [h_e(x) for x in xe], ":", label=f"arrested, plug in extension, L_e = {length_e:.3f} m")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("h (m)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=120)


if __name__ == "__main__":
    main()
