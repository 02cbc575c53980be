#!/usr/bin/python3
"""Nodal pressure of the static Cook's membrane on the mixed MPM (seed 003 Fig 5): the grid pressure of the
last frame for no stabilisation, PPP, ASGS and OSGS on 24 x 24 cells (3 particles per cell, nu = 0.5),
drawn on the background grid. Without stabilisation the pressure jumps from node to node (Fig 5a).
Writes docs/mpm/cooks_static_pressure.png (about 10 s)."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.tri as mtri
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

import loom_study

DOCS = loom_study.ROOT / "docs" / "mpm"
OUT = loom_study.ROOT / "out" / "study" / "cooks_pressure"
N = 24


def grid_pressure(directory):
    last = sorted(directory.glob("*_grid.vtu"))[-1]
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(str(last))
    r.Update()
    g = r.GetOutput()
    xy = vtk_to_numpy(g.GetPoints().GetData())[:, :2]
    cells = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, 3)
    return xy, cells, vtk_to_numpy(g.GetPointData().GetArray("mean_stress"))


def main():
    fig, axes = plt.subplots(1, 4, figsize=(15, 4.6))
    for ax, stab in zip(axes, ["none", "ppp", "asgs", "osgs"]):
        out = OUT / stab
        code, _, probes, _, _ = loom_study.run("cooks_membrane_mpm_static.toml", out,
                                               [f'body[0].stabilisation="{stab}"', f"grid.divisions=[{N},{N}]",
                                                f"body[0].mesh.divisions=[{N},{N}]", "output.every=1"])
        xy, cells, p = grid_pressure(out)
        used = np.unique(cells)
        lim = np.percentile(np.abs(p[used]), 99)
        tpc = ax.tripcolor(mtri.Triangulation(xy[:, 0], xy[:, 1], cells), p, shading="gouraud", cmap="coolwarm",
                           vmin=-lim, vmax=lim)
        fig.colorbar(tpc, ax=ax, shrink=0.8)
        name = "no stabilisation" if stab == "none" else stab.upper()
        ax.set_title(f"{name}: u_y(A) = {float(probes[-1]['uy_A']):.4f}\nmean nodal jump {float(probes[-1]['pressure_jump']):.3g} Pa",
                     fontsize=9)
        ax.set_aspect("equal")
        ax.set_axis_off()
        print(f"{stab}: exit {code}, p in [{p[used].min():.3g}, {p[used].max():.3g}] Pa")
    fig.suptitle(f"Static Cook's membrane, nodal pressure p (sigma = s + p I) on {N} x {N} grid cells, 3 particles per cell")
    fig.tight_layout()
    fig.savefig(DOCS / "cooks_static_pressure.png", dpi=110)
    print("wrote", DOCS / "cooks_static_pressure.png")


if __name__ == "__main__":
    main()
