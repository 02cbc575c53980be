#!/usr/bin/python3
"""Dynamic Cook's membrane on the mixed MPM (seed 003 §6.2, Fig 6): u_y(A) histories for 3, 12 and 33
particles per cell (ASGS) and for PPP, ASGS, OSGS at 33 particles per cell, plus the unstabilised run that
fails early. Writes docs/mpm/cooks_dynamic.csv (histories), cooks_dynamic_runs.csv (one row per run) and
cooks_dynamic.png. About 7 minutes on two idle cores; --quick runs 40 steps with fewer particles."""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import loom_study

DOCS = loom_study.ROOT / "docs" / "mpm"
OUT = loom_study.ROOT / "out" / "study" / "cooks_dynamic"


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    runs = [("asgs", 3), ("asgs", 12), ("asgs", 33), ("ppp", 33), ("osgs", 33), ("none", 33)]
    sets_common = ["output.every=0"] + (["time.steps=40"] if args.quick else [])
    histories, summary = [], []
    for stab, ppc in runs:
        if args.quick:
            ppc = min(ppc, 6)
        label = f"{stab}-{ppc}"
        code, info, rows, wall, err = loom_study.run(
            "cooks_membrane_mpm_dynamic.toml", OUT / label,
            sets_common + [f'body[0].stabilisation="{stab}"', f"body[0].particles_per_cell={ppc}"])
        iters = [float(r["newton"]) for r in rows[1:]]
        mean_iters = sum(iters) / len(iters) if iters else float("nan")
        failure = info["failure"].replace("\n", " ")
        print(f"{label:9s} exit {code}  steps {info['steps_done']}/{info['steps_requested']}  last converged step "
              f"{info['last_converged_step']}  Newton/step {mean_iters:.1f}  {wall:.0f} s  {failure}")
        summary.append([stab, ppc, code, info["steps_done"], info["last_converged_step"], f"{mean_iters:.2f}", f"{wall:.1f}",
                        failure])
        for r in rows:
            histories.append([stab, ppc, r["step"], r["time"], r["uy_A"], r["newton"], r["kinetic_energy"], r["elastic_energy"]])
    suffix = "_quick" if args.quick else ""
    loom_study.write_csv(DOCS / f"cooks_dynamic{suffix}.csv",
                         ["stabilisation", "particles_per_cell", "step", "time", "uy_A", "newton", "kinetic_energy", "elastic_energy"],
                         histories)
    loom_study.write_csv(DOCS / f"cooks_dynamic_runs{suffix}.csv",
                         ["stabilisation", "particles_per_cell", "exit_code", "steps_done", "last_converged_step",
                          "newton_per_step", "wall_s", "failure"], summary)

    def series(stab, ppc):
        t = [float(h[3]) for h in histories if h[0] == stab and int(h[1]) == ppc]
        u = [float(h[4]) for h in histories if h[0] == stab and int(h[1]) == ppc]
        return t, u

    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
    for stab, ppc in runs[:3]:
        ppc = min(ppc, 6) if args.quick else ppc
        ax[0].plot(*series(stab, ppc), label=f"ASGS, {ppc} particles per cell")
    for stab, ppc in runs[2:]:
        ppc = min(ppc, 6) if args.quick else ppc
        t, u = series(stab, ppc)
        name = {"asgs": "ASGS", "ppp": "PPP", "osgs": "OSGS", "none": "no stabilisation"}[stab]
        if stab == "none":
            ax[1].plot(t, u, "k:", label=f"{name} (fails at t = {t[-1] + 0.025:.3f} s)")
            ax[1].plot(t[-1:], u[-1:], "kx")
        else:
            ax[1].plot(t, u, label=f"{name}, {ppc} particles per cell")
    for a, title in zip(ax, ["particles per cell (ASGS)", "stabilisations"]):
        a.set_xlabel("t (s)")
        a.set_title(f"h = 0.1, dt = 0.025: {title}")
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    ax[0].set_ylabel("u_y(A) (m)")
    fig.tight_layout()
    fig.savefig(DOCS / f"cooks_dynamic{suffix}.png", dpi=120)
    print("wrote", DOCS / f"cooks_dynamic{suffix}.png")


if __name__ == "__main__":
    main()
