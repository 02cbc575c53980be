#!/usr/bin/python3
"""The same quantity from several studies (one flow run by several methods) on one plot: relative error against
wall time, one line per study and series, from the studies' committed CSVs (docs/benchmarks/<study>/<study>.csv).

    tools/compare_studies.py QUANTITY OUT.png STUDY [STUDY...] [--title TITLE]

e.g. tools/compare_studies.py front docs/benchmarks/bingham_collapse_mpm/side_by_side_front.png \\
         bingham_collapse_es bingham_collapse_mpm
"""
import argparse
import csv
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def rows_of(study):
    with open(ROOT / "docs" / "benchmarks" / study / f"{study}.csv", newline="") as f:
        return list(csv.DictReader(f))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("quantity")
    ap.add_argument("out")
    ap.add_argument("studies", nargs="+")
    ap.add_argument("--title", default="")
    a = ap.parse_args()
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for study in a.studies:
        by_series = {}
        for r in rows_of(study):
            if r.get("converged") != "1" or not r.get(f"{a.quantity}_error"):
                continue
            by_series.setdefault(r["series"], []).append((float(r["wall_s"]), abs(float(r[f"{a.quantity}_error"])), r["case"]))
        for series, points in by_series.items():
            points.sort()
            ax.plot([p[0] for p in points], [p[1] for p in points], "o-", label=f"{study}: {series}")
            for t, e, case in points:
                ax.annotate(case, (t, e), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_xscale("log")
    ax.set_xlabel("wall time of the run [s]")
    ax.set_ylabel(f"relative error of {a.quantity}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title(a.title or f"{a.quantity}: " + ", ".join(a.studies), fontsize=9)
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
