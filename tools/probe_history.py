#!/usr/bin/env python3
"""Several runs' probe histories side by side, sampled every --every seconds, and when each run's probe came to rest.

    tools/probe_history.py n10=OUT10/probes.csv n18=OUT18/probes.csv --probes front,height,area --every 1 --csv H.csv
    tools/probe_history.py n18=OUT18/probes.csv --arrest front --within 1e-4

The CSV has a column time and one column <probe>_<label> per probe and run (empty past a run's end), at the rows
whose time is a multiple of --every (to 1e-9 s). With --arrest, each run's last value of that probe is printed with
the time from which the probe stays within --within of it (its arrest, by that tolerance) and the run's last time;
a run whose probe moved by more than --within over its last --window seconds is reported as still moving.
With --plot, the first of --probes against time for every run (every row, not only the samples), beside
--model CSV (a time column and that probe's; '#' lines skipped: tools/lubrication_spreading.py's output) and
horizontal --level VALUE=LABEL lines:

    tools/probe_history.py n18=OUT18/probes.csv --probes front --plot F.png --model lub.csv --level 0.770=shallow
"""
import argparse
import csv
import sys


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows or "time" not in rows[0]:
        sys.exit(f"probe_history: {path}: no probes.csv (no 'time' column)")
    return rows


def sampled(rows, every):
    out = {}
    for r in rows:
        t = float(r["time"])
        k = round(t / every)
        if abs(t - k * every) < 1e-9:
            out[k] = r
    return out


def arrest(rows, probe, within, window):
    if probe not in rows[0]:
        sys.exit(f"probe_history: no probe '{probe}' (columns: {', '.join(rows[0])})")
    t = [float(r["time"]) for r in rows]
    v = [float(r[probe]) for r in rows]
    last = v[-1]
    since = t[0]
    for k in range(len(v) - 1, -1, -1):
        if abs(v[k] - last) > within:
            since = t[k + 1] if k + 1 < len(t) else t[-1]
            break
    moving = any(abs(v[k] - last) > within for k in range(len(v)) if t[k] >= t[-1] - window)
    return last, since, t[-1], moving


def plot(path, runs, probe, model, levels):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 3.5))
    for label, rows in runs:
        ax.plot([float(r["time"]) for r in rows], [float(r[probe]) for r in rows], "-", lw=1.2, label=label)
    if model:
        with open(model) as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
        if not rows or probe not in rows[0]:
            sys.exit(f"probe_history: {model}: no column '{probe}'")
        ax.plot([float(r["time"]) for r in rows], [float(r[probe]) for r in rows], "k--", lw=1, label="model")
    for spec, style in zip(levels, [":", "-.", (0, (1, 3)), (0, (5, 5))] * len(levels)):
        value, _, label = spec.partition("=")
        ax.axhline(float(value), color="grey", lw=0.9, ls=style, label=label or value)
    ax.set_xlabel("t (s)")
    ax.set_ylabel(probe)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+", help="LABEL=path/to/probes.csv")
    ap.add_argument("--probes", default="front", help="comma-separated probe columns for the CSV")
    ap.add_argument("--every", type=float, default=1.0, help="sampling interval in seconds")
    ap.add_argument("--csv", help="write the sampled histories here")
    ap.add_argument("--arrest", help="report when this probe came to rest in each run")
    ap.add_argument("--within", type=float, default=1e-4, help="tolerance of --arrest, in the probe's unit")
    ap.add_argument("--window", type=float, default=10.0, help="seconds at the end a resting probe must not move")
    ap.add_argument("--plot", help="write a PNG of the first of --probes against time")
    ap.add_argument("--model", help="with --plot: a CSV with time and the probe's column to draw beside the runs")
    ap.add_argument("--level", action="append", default=[], help="with --plot: VALUE=LABEL, a horizontal line")
    a = ap.parse_args()
    runs = []
    for spec in a.runs:
        label, sep, path = spec.partition("=")
        if not sep or not label:
            sys.exit(f"probe_history: '{spec}' is not LABEL=path")
        runs.append((label, read(path)))
    if a.csv:
        probes = a.probes.split(",")
        for label, rows in runs:
            missing = [p for p in probes if p not in rows[0]]
            if missing:
                sys.exit(f"probe_history: run {label} has no probe {', '.join(missing)}")
        samples = [(label, sampled(rows, a.every)) for label, rows in runs]
        keys = sorted(set().union(*(s.keys() for _, s in samples)))
        with open(a.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["time"] + [f"{p}_{label}" for p in probes for label, _ in samples])
            for k in keys:
                w.writerow([f"{k * a.every:g}"] + [s[k][p] if k in s else "" for p in probes for _, s in samples])
    if a.plot:
        probe = a.probes.split(",")[0]
        for label, rows in runs:
            if probe not in rows[0]:
                sys.exit(f"probe_history: run {label} has no probe {probe}")
        plot(a.plot, runs, probe, a.model, a.level)
    if a.arrest:
        for label, rows in runs:
            last, since, end, moving = arrest(rows, a.arrest, a.within, a.window)
            state = "STILL MOVING" if moving else f"within {a.within:g} of it from t = {since:.2f} s"
            print(f"{label}: {a.arrest} {last:.6g} at t = {end:.2f} s; {state}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
