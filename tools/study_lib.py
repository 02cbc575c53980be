"""Helpers of tools/study: analytic references, the plots of a study, and the writer of docs/BENCHMARKS.md.
Debian's python3-numpy and python3-matplotlib (tools/setup.sh installs them)."""
import csv
import math
import os
import platform
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


# Analytic references: functions of the probe time t and the study's parameters.
def neo_hooke_plane_strain_compression_reaction(t, E, nu, W, H, rate):
    """Top reaction per unit thickness of a Neo-Hooke block (seed 000 eq 48-51) compressed between rollers
    by d = rate * H * t with a free right edge: F = diag(l1, l2, 1), l2 = 1 - d / H, P11(l1) = 0, reaction
    P22 W (tests/verification/homogeneous_compression_test.cpp derives it)."""
    mu = E / (2 * (1 + nu))
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    l2 = 1 - rate * t
    l1 = 1.0
    for _ in range(100):
        f = mu * l1 * l1 + lam * math.log(l1 * l2) - mu
        step = f / (2 * mu * l1 + lam / l1)
        l1 -= step
        if abs(step) < 1e-16 * l1:
            break
    J = l1 * l2
    return (mu * l2 + (lam * math.log(J) - mu) / l2) * W


def rolling_disk_x(t, g, theta):
    """Distance travelled by a uniform disk rolling without slip down an incline from rest: the
    acceleration is g sin(theta) / (1 + I / (m R^2)) with I = m R^2 / 2 (seed 004 eq 49)."""
    return g * math.sin(theta) * t * t / 3.0


def quadratic_fit(points):
    """Least-squares coefficients (c0, c1, c2) of c0 + c1 t + c2 t^2 through (t, y) points."""
    A = np.array([[1.0, t, t * t] for t, _ in points])
    y = np.array([v for _, v in points])
    return np.linalg.lstsq(A, y, rcond=None)[0]


def poured(t, area0, rate, pour, scale=1.0):
    """What an inlet has put in by time t: the initial area plus rate * t up to the pouring time, times `scale`
    (the density, for a mass)."""
    return scale * (area0 + rate * min(t, pour))


ANALYTIC = {"neo_hooke_plane_strain_compression_reaction": neo_hooke_plane_strain_compression_reaction,
            "rolling_disk_x": rolling_disk_x, "poured": poured}

# Sub-phases shown in the time breakdown, by self time (tools/study computes it), in this order.
PHASES = [("newton/assemble", "assemble"), ("newton/solve/factorize", "factorize"),
          ("newton/solve/back_substitute", "back-substitute"), ("newton/update", "update"),
          ("newton", "newton (other)"), ("newton/solve", "solve (other)"), ("apply_boundary_conditions", "loads"),
          ("commit", "commit"), ("probes", "probes"), ("output", "output"), ("output/write_vtu", "write vtu")]
COLOURS = plt.get_cmap("tab20").colors
MARKERS = "osD^vP*Xh<>"


def _series_order(cases):
    order = []
    for c in cases:
        if c.series not in order:
            order.append(c.series)
    return order


def _slope(x, y):
    x, y = np.log(np.asarray(x, float)), np.log(np.asarray(y, float))
    if len(set(x[-3:])) < 2:  # e.g. a time-step series: the dofs do not change
        return float("nan")
    return float(np.polyfit(x[-3:], y[-3:], 1)[0])


def _points(cases, series, q, xkey):
    xs, ys = [], []
    for c in cases:
        if c.series != series or not c.result or not c.result["run"]["converged"]:
            continue
        e = c.result["errors"].get(q)
        if e is None or not math.isfinite(e) or e <= 0:
            continue
        xs.append(c.result["run"]["wall_seconds"] if xkey == "wall" else c.result["run"]["dofs"])
        ys.append(e)
    return xs, ys


def plot_study(study, cases, outdir, self_times):
    name = study["name"]
    quantities = study["quantity"]
    series = _series_order(cases)
    for xkey, suffix, xlabel in (("wall", "work_precision", "wall time of the run [s]"), ("dofs", "error_dofs", "free dofs")):
        fig, axes = plt.subplots(1, len(quantities), figsize=(5.2 * len(quantities) + 1.2, 4.2), squeeze=False)
        for ax, q in zip(axes[0], quantities):
            for k, s in enumerate(series):
                xs, ys = _points(cases, s, q["name"], xkey)
                if not xs:
                    continue
                label = s
                if xkey == "dofs" and len(xs) >= 3 and math.isfinite(_slope(xs, ys)):
                    label += f" (slope {_slope(xs, ys):.2f})"
                ax.loglog(xs, ys, marker=MARKERS[k % len(MARKERS)], color=COLOURS[2 * (k % 10)], label=label)
            ax.set_xlabel(xlabel)
            rel = "relative " if q.get("relative", True) else ""
            ax.set_ylabel(f"{rel}error of {q['name']}")
            ax.set_title(q.get("title", q["name"]), fontsize=10)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
        fig.suptitle(f"{study['title']}: error against {'wall time' if xkey == 'wall' else 'dofs'}", fontsize=11)
        fig.tight_layout()
        fig.savefig(outdir / f"{name}_{suffix}.png", dpi=90)
        plt.close(fig)

    # Per-system time breakdown: self time of each phase as a share of the run's wall time.
    rows = [c for c in cases if c.result]
    fig, ax = plt.subplots(figsize=(9, 0.3 * len(rows) + 2.4))
    labels = [f"{c.series}  {c.label}" for c in rows]
    left = np.zeros(len(rows))
    present = set()
    for c in rows:
        present |= set(c.result["timings"]["timers"])
    for k, (timer, label) in enumerate(PHASES):
        if timer not in present:
            continue
        share = np.array([self_times(c.result["timings"]["timers"]).get(timer, 0.0) / max(c.result["run"]["wall_seconds"], 1e-12)
                          for c in rows]) * 100
        if not share.any():
            continue
        ax.barh(labels, share, left=left, color=COLOURS[k % len(COLOURS)], label=label)
        left += share
    for i, c in enumerate(rows):
        ax.text(min(left[i], 100) + 1, i, f"{c.result['run']['wall_seconds']:.3g} s", va="center", fontsize=7)
    ax.set_xlim(0, 118)
    ax.invert_yaxis()
    ax.set_xlabel("share of the run's wall time [%] (self time of each phase; the label: wall time)")
    ax.tick_params(axis="y", labelsize=7)
    ax.set_title(f"{study['title']}: where the time goes", fontsize=10)
    handles, names = ax.get_legend_handles_labels()
    fig.tight_layout(rect=(0, 0.5 / (0.3 * len(rows) + 2.4), 1, 1))
    fig.legend(handles, names, fontsize=7, ncol=6, loc="lower center", frameon=False)
    fig.savefig(outdir / f"{name}_breakdown.png", dpi=90)
    plt.close(fig)


# docs/BENCHMARKS.md
def _read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def _fmt(v, digits=4):
    try:
        x = float(v)
    except (TypeError, ValueError):
        return str(v)
    if not math.isfinite(x):
        return "-"
    return f"{x:.{digits}g}"


def _machine():
    cpu = platform.processor() or platform.machine()
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores"


def _study_section(study, outdir, lines):
    name = study["name"]
    doc = study["doc"]
    lines += [f"## {study['title']}", ""]
    lines += [f"Scene: `{study['scene']}`. Study: `{study['rel']}`.", ""]
    for key, head in (("setup", "Set-up"), ("reference", "Reference")):
        if key in doc:
            lines += [f"**{head}.** " + doc[key].strip(), ""]
    csv_path = outdir / name / f"{name}.csv"
    if not csv_path.exists():
        lines += [f"(no results yet: run `tools/study {study['rel']}`)", ""]
        return
    rows = _read_csv(csv_path)
    qn = [q["name"] for q in study["quantity"]]
    head = ["series", "case", "dofs", "steps"] + [f"{q}" for q in qn] + [f"error {q}" for q in qn] + ["Newton", "wall s", "solve+factorize s", "assemble s"]
    lines += ["| " + " | ".join(head) + " |", "|" + " --- |" * len(head)]
    for r in rows:
        conv = r["converged"] == "1"
        cells = [r["series"], r["case"], r["dofs"], r["steps"] if conv else f"{r['steps']} (failed)"]
        cells += [_fmt(r[q], 6) for q in qn] + [_fmt(r[f"{q}_error"], 3) for q in qn]
        cells += [r["newton_iterations"], _fmt(r["wall_s"], 3), _fmt(r.get("t:newton/solve", ""), 3), _fmt(r.get("t:newton/assemble", ""), 3)]
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    refs = {q["name"]: q for q in study["quantity"]}
    for q in qn:
        src = refs[q].get("source")
        if src:
            lines.append(f"- `{q}`: reference {src}")
    lines += [f"- Wall times: `run.json` wall_seconds, best of {study['repeat']} run(s), {study['threads']} thread(s); "
              "`solve+factorize` and `assemble` are totals of `timings.json` (`newton/solve`, `newton/assemble`).", ""]
    if "findings" in doc:
        lines += ["**Result.** " + doc["findings"].strip(), ""]
    lines += [f"![work-precision](benchmarks/{name}/{name}_work_precision.png)",
              f"![error against dofs](benchmarks/{name}/{name}_error_dofs.png)", "",
              f"![time breakdown](benchmarks/{name}/{name}_breakdown.png)", ""]
    for pic in study["picture"]:
        if (outdir / name / pic["file"]).exists():
            lines += [f"![{pic.get('title', pic['file'])}](benchmarks/{name}/{pic['file']})", "",
                      f"*{pic.get('caption', pic.get('title', ''))}*", ""]
    lines += ["Regenerate:", "", f"    tools/study {study['rel']}", "",
              f"Data: [`{name}.csv`](benchmarks/{name}/{name}.csv).", ""]


def _stress_section(outdir, lines, notes_path):
    lines += ["## Stress suite", ""]
    if notes_path.exists():
        lines += [notes_path.read_text().strip(), ""]
    csv_path = outdir / "stress" / "stress.csv"
    if not csv_path.exists():
        lines += ["(no results yet: `tools/study --all`, or `LOOM_STRESS_CSV=docs/benchmarks/stress/stress.csv ctest --test-dir build -L stress`)", ""]
        return
    rows = _read_csv(csv_path)
    groups = []
    for r in rows:
        if r["group"] not in groups:
            groups.append(r["group"])
    for g in groups:
        lines += [f"### {g}", "", "| case | outcome | exit | steps | detail | check |", "| --- | --- | --- | --- | --- | --- |"]
        for r in rows:
            if r["group"] == g:
                lines.append(f"| {r['case']} | {r['outcome']} | {r['exit']} | {r['steps']} | {r['detail']} | {r['check']} |")
        lines.append("")


def write_benchmarks_md(studies, outdir, md_path):
    tools = md_path.parent.parent / "tools" / "studies"
    lines = ["# Benchmarks: run time against error, and the stress suite", ""]
    intro = tools / "BENCHMARKS_intro.md"
    if intro.exists():
        lines += [intro.read_text().strip(), ""]
    lines += [f"Machine of the committed figures: {_machine()}.", ""]
    lines += ["Contents:", ""]
    for s in sorted(studies, key=lambda s: (s.get("order", 99), s["name"])):
        anchor = s["title"].lower()
        anchor = "".join(ch for ch in anchor if ch.isalnum() or ch in " -_").replace(" ", "-")
        lines.append(f"- [{s['title']}](#{anchor})")
    lines += ["- [Stress suite](#stress-suite)", ""]
    for s in sorted(studies, key=lambda s: (s.get("order", 99), s["name"])):
        _study_section(s, outdir, lines)
    _stress_section(outdir, lines, tools / "stress_notes.md")
    md_path.write_text("\n".join(lines).rstrip() + "\n")
