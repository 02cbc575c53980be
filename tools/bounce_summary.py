#!/usr/bin/python3
"""Bounces of a falling body from a run's probes.csv (the bouncing disk of Aulisa & Capodaglio's B4).

Reads the centre's height probe (default centre_y, a displacement from the start) and, if present, a mechanical
energy probe (default energy), and prints: the first lowest point (time, height) against the free fall's contact
time sqrt(2 gap / g); each rebound's top (time, height, the fraction of the drop it regains); and the energy at each
top and its change per bounce (a body that bounces without loss keeps it; the drop's m g h is the scale).

usage: tools/bounce_summary.py RUN_DIR [RUN_DIR ...] [--probe centre_y] [--energy energy] [--gap 1.36] [--g 9.81]
       [--csv FILE]   (one row per run: impact time, first rebound fraction, energy lost by the first top)
       [--plot FILE --labels "A;B;..."]   (the centre's height and the mechanical energy against time, one line per run)
"""
import argparse
import csv
import math
import os


def read(run_dir):
    with open(os.path.join(run_dir, "probes.csv")) as f:
        return list(csv.DictReader(f))


def extrema(t, y):
    lows = [k for k in range(1, len(y) - 1) if y[k] < y[k - 1] and y[k] <= y[k + 1]]
    tops = [k for k in range(1, len(y) - 1) if y[k] > y[k - 1] and y[k] >= y[k + 1]]
    return lows, tops


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--probe", default="centre_y")
    ap.add_argument("--energy", default="energy")
    ap.add_argument("--gap", type=float, default=1.36, help="fall height to the first contact (m)")
    ap.add_argument("--g", type=float, default=9.81)
    ap.add_argument("--csv", default=None)
    ap.add_argument("--plot", default=None)
    ap.add_argument("--labels", default=None)
    a = ap.parse_args()
    t_contact = math.sqrt(2 * a.gap / a.g)
    rows = []
    for run in a.runs:
        r = read(run)
        t = [float(x["time"]) for x in r]
        y = [float(x[a.probe]) for x in r]
        e = [float(x[a.energy]) for x in r] if a.energy in r[0] else None
        lows, tops = extrema(t, y)
        # Rattling on the surface is not a bounce: a top counts when it regains at least a tenth of the drop.
        tops = [k for k in tops if y[k] - min(y) > 0.1 * a.gap]
        print(f"{run}: {len(t) - 1} steps to t = {t[-1]:g} s")
        if not lows:
            print("  no lowest point")
            continue
        k0 = lows[0]
        print(f"  first lowest point t = {t[k0]:.4f} s (free fall to contact {t_contact:.4f} s), height {y[k0]:+.4f} m")
        drop = -y[k0]
        for n, k in enumerate(tops):
            line = f"  top {n + 1}: t = {t[k]:.4f} s, height {y[k]:+.4f} m, regains {100 * (y[k] - y[k0]) / drop:.1f} % of the drop"
            if e:
                line += f", energy {e[k]:+.2f} J" + (f" ({e[k] - e[tops[n - 1]]:+.2f} since the last top)" if n else "")
            print(line)
        if not tops:
            print("  no rebound: the body stays on the surface (largest height after the first contact "
                  f"{max(y[k0:]):+.4f} m)")
        if e:
            print(f"  energy at the end {e[-1]:+.2f} J")
        rows.append([run, t[k0], (y[tops[0]] - y[k0]) / drop if tops else 0.0, e[tops[0]] if (e and tops) else float("nan")])
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        labels = a.labels.split(";") if a.labels else a.runs
        fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
        for run, label in zip(a.runs, labels):
            r = read(run)
            t = [float(x["time"]) for x in r]
            ax1.plot(t, [float(x[a.probe]) for x in r], label=label, lw=1)
            if a.energy in r[0]:
                ax2.plot(t, [float(x[a.energy]) for x in r], label=label, lw=1)
        ax1.set_ylabel(f"{a.probe} (m)")
        ax2.set_ylabel("mechanical energy (J)")
        ax2.set_xlabel("t (s)")
        ax1.legend(fontsize=7)
        ax1.grid(alpha=0.3), ax2.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=110)
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["run", "first_low_time", "first_rebound_fraction", "energy_at_first_top"])
            w.writerows(rows)


if __name__ == "__main__":
    main()
