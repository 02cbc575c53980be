#!/usr/bin/python3
"""The height of the first row of particles above a ground line in loom frames (VTK .vtu).

A stick ground holds the particles on it, so the strip of paste between them and the next row reaches the ground
without yielding: a yield-stress deposit's base then carries about rho g h y_1 / 2 more than the yield stress
allows, y_1 the first row's height (docs/free_surface.md, section 3). This reads, for each particle on the ground
(|y - ground| below --tolerance), the highest particle an edge joins it to, and prints the points, the particles on
the ground, and the median and largest first-row height (mm), and the one at the particle nearest x = --at.

    tools/first_row.py OUT/bingham-collapse-es_002500.vtu [more frames] [--ground 0] [--at 0]
"""
import argparse
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def first_row(path, ground, tolerance):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid.GetNumberOfCells() == 0:
        sys.exit(f"{path}: no cells (not a loom frame?)")
    x = vtk_to_numpy(grid.GetPoints().GetData())[:, :2]
    on = np.abs(x[:, 1] - ground) < tolerance
    highest = {}
    for c in range(grid.GetNumberOfCells()):
        ids = grid.GetCell(c).GetPointIds()
        corners = [ids.GetId(k) for k in range(3)]  # tri6 cells: the corners are the particles
        for k in range(3):
            a, b = corners[k], corners[(k + 1) % 3]
            for p, q in ((a, b), (b, a)):
                if on[p] and not on[q]:
                    highest[p] = max(highest.get(p, 0.0), x[q, 1] - ground)
    if not highest:
        sys.exit(f"{path}: no particle within {tolerance} of the ground y = {ground}")
    return x, on, highest


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("frames", nargs="+")
    ap.add_argument("--ground", type=float, default=0.0, help="the ground line y = GROUND (m)")
    ap.add_argument("--tolerance", type=float, default=2e-5, help="a particle within this of the ground is on it (m)")
    ap.add_argument("--at", type=float, default=0.0, help="also the first row at the ground particle nearest x = AT")
    args = ap.parse_args()
    for path in args.frames:
        x, on, highest = first_row(path, args.ground, args.tolerance)
        ids = np.array(list(highest))
        h = np.array([highest[p] for p in ids])
        near = ids[np.argmin(np.abs(x[ids, 0] - args.at))]
        print(f"{path}: points {len(x)}, on the ground {int(on.sum())}, first row median {1e3 * np.median(h):.2f} mm, "
              f"largest {1e3 * h.max():.2f} mm, at x = {x[near, 0]:.4f} m {1e3 * highest[near]:.2f} mm")


if __name__ == "__main__":
    main()
