#!/usr/bin/python3
"""The surface profile h(x) of a yield-stress deposit in a loom frame against the arrested shallow layer.

A Bingham layer on a no-slip ground stops where the yield stress holds the hydrostatic gradient, tau0 = rho g h
|dh/dx|, so an arrested deposit whose front is at x_f has h(x) = sqrt(2 tau0 (x_f - x) / (rho g)) (plane strain;
lubrication theory, e.g. Liu & Mei 1989). The profile of the frame is the highest boundary point in each of `--bins`
columns of equal width (points of the mesh at their current position). Written: a CSV of x, h of the frame, the
arrested profile through the frame's own front and, with --length, the one through lubrication theory's arrested
front L (what a deposit that spread all the way would show), and a PNG.

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


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("frame", help="a .vtu frame of a pfem or es_pfem run")
    ap.add_argument("--tau0", type=float, required=True)
    ap.add_argument("--rho", type=float, required=True)
    ap.add_argument("--g", type=float, default=9.81)
    ap.add_argument("--length", type=float, default=0.0, help="lubrication theory's arrested front, m (optional)")
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
    with open(a.out + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["x", "h", "h_arrested_own_front", "h_arrested_L"])
        for row in zip(xs, hs, own, full):
            w.writerow([f"{v:.6g}" for v in row])
    # The fit in the part of the deposit away from its ends: the middle 80 % of its length.
    mid = [(h, o) for x, h, o in zip(xs, hs, own) if 0.1 * front <= x <= 0.9 * front]
    rms = math.sqrt(sum((h - o) ** 2 for h, o in mid) / len(mid)) if mid else float("nan")
    print(f"front {front:.4f} m; height at x = {xs[0]:.4f}: {hs[0]:.5f} m (arrested through the own front {own[0]:.5f}"
          + (f", through L = {a.length}: {full[0]:.5f}" if a.length > 0 else "") + f"); rms over 10-90 % of the length {rms:.2e} m")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 3))
    ax.plot(xs, hs, "o", ms=3, label="loom (highest boundary point per column)")
    ax.plot(xs, own, "-", label="arrested layer through the same front")
    if a.length > 0:
        xl = np.linspace(0.0, a.length, 200)
        ax.plot(xl, np.sqrt(c * (a.length - xl)), "--", label=f"arrested layer, lubrication L = {a.length} m")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("h (m)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=120)


if __name__ == "__main__":
    main()
