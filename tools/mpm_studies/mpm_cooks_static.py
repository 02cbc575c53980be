#!/usr/bin/python3
"""Static Cook's membrane on the mixed MPM (seed 003 §6.2, Fig 4): u_y(A) against the grid refinement
(8 ... 128 cells per side, 3 particles per cell, nu = 0.5) for no stabilisation, PPP, ASGS and OSGS, with
Newton iterations at the scene's tolerance (1e-8) and at 1e-4 (closer to the seed's counts: ASGS about 4,
OSGS about 8) and the mean nodal pressure jump (seed Fig 5a). Writes docs/mpm/cooks_static.csv and .png
(a few minutes on two cores)."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import loom_study

DOCS = loom_study.ROOT / "docs" / "mpm"
OUT = loom_study.ROOT / "out" / "study" / "cooks_static"
REFERENCE = 0.2758  # REFERENCES.md, nu = 0.5 (the seed quotes 0.275)


def main():
    rows = []
    for stab in ["none", "ppp", "asgs", "osgs"]:
        for n in [8, 16, 32, 64, 128]:
            sets = [f'body[0].stabilisation="{stab}"', f"grid.divisions=[{n},{n}]", f"body[0].mesh.divisions=[{n},{n}]", "output.every=0"]
            code, info, probes, wall, _ = loom_study.run("cooks_membrane_mpm_static.toml", OUT / f"{stab}-{n}", sets)
            last = probes[-1]
            loose = ""
            if stab in ("asgs", "osgs"):
                _, _, p4, _, _ = loom_study.run("cooks_membrane_mpm_static.toml", OUT / f"{stab}-{n}-loose", sets + ["solver.residual_relative=1e-4"])
                loose = p4[-1]["newton"]
            uy = float(last["uy_A"])
            print(f"{stab:4s} n = {n:3d}: u_y(A) = {uy:.5f} ({100 * (uy / REFERENCE - 1):+.2f} %), Newton {last['newton']} "
                  f"(at 1e-4: {loose or '-'}), pressure jump {float(last['pressure_jump']):.4g}, {wall:.1f} s, exit {code}")
            rows.append([stab, n, 48.0 / n, f"{uy:.6f}", f"{100 * (uy / REFERENCE - 1):.3f}", last["newton"], loose,
                         last["pressure_jump"], info["dofs"], f"{wall:.2f}"])
    loom_study.write_csv(DOCS / "cooks_static.csv", ["stabilisation", "cells_per_side", "h_x", "uy_A", "error_percent", "newton",
                                                     "newton_at_1e-4", "pressure_jump", "dofs", "wall_s"], rows)
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.5))
    for stab, marker in [("none", "x"), ("ppp", "o"), ("asgs", "s"), ("osgs", "^")]:
        r = [x for x in rows if x[0] == stab]
        n = [x[1] for x in r]
        label = "no stabilisation" if stab == "none" else stab.upper()
        ax[0].semilogx(n, [float(x[3]) for x in r], marker=marker, label=label, base=2)
        ax[1].loglog(n, [float(x[7]) for x in r], marker=marker, label=label, base=2)
    ax[0].axhline(REFERENCE, color="k", lw=0.8, label="reference 0.2758 (nu = 0.5)")
    ax[0].axhline(0.275, color="k", ls=":", lw=0.8, label="seed 003: 0.275")
    ax[0].axhspan(0.98 * REFERENCE, 1.02 * REFERENCE, color="0.9", label="reference +- 2 %")
    ax[0].set_ylabel("u_y(A) (m)")
    ax[0].set_title("Static Cook's membrane, 3 particles per cell")
    ax[1].set_ylabel("mean |p_a - p_b| over grid sides (Pa)")
    ax[1].set_title("Nodal pressure oscillation")
    for a in ax:
        a.set_xlabel("grid cells per side")
        a.grid(alpha=0.3, which="both")
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(DOCS / "cooks_static.png", dpi=120)
    print("wrote", DOCS / "cooks_static.png")


if __name__ == "__main__":
    main()
