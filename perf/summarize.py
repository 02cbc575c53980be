#!/usr/bin/python3
"""Turns the JSON output of bench_assemble, bench_newton_step and bench_linear_solver (run with --benchmark_repetitions and
--benchmark_out_format=json) into the Markdown tables of perf/README.md. Figures are medians over the
repetitions; `cv` is the largest coefficient of variation (stddev / mean) of the times in a row.

    perf/summarize.py assemble.json newton.json linear.json

Files from the same program are merged (run the same program twice, e.g. with and without
OMP_THREAD_LIMIT, and summarize the two separately).
"""
import json
import sys
from collections import defaultdict


def load(path):
    with open(path) as f:
        data = json.load(f)
    runs = defaultdict(dict)  # run_name -> aggregate -> entry
    for b in data["benchmarks"]:
        if b.get("run_type") == "aggregate":
            runs[b["run_name"]][b["aggregate_name"]] = b
    return data["context"], runs


def context_line(path, ctx):
    load_avg = ", ".join(f"{x:.2f}" for x in ctx.get("load_avg", []))
    line = f"`{path}`: {ctx['date']}, load average at start {load_avg}"
    if "others_cores" in ctx:  # added by a runner that watched the machine (see README)
        line += f", other processes used {ctx['others_cores']:.3f} cores during the run"
    return line


def parts(run_name):
    # BM_Family/capture/arg1/arg2.../real_time|manual_time
    p = run_name.split("/")
    return p[0], p[1], [int(x) for x in p[2:] if x.isdigit()]


def cv(aggregates, field="real_time"):
    return aggregates["cv"][field] if "cv" in aggregates else float("nan")


def assemble_tables(runs):
    out = []
    table = defaultdict(dict)  # cells -> (mode, threads) -> (Mcells/s, cv)
    loops = defaultdict(dict)  # cells -> loop -> (Mcells/s, cv)
    material = {}
    for name, a in runs.items():
        family, capture, args = parts(name)
        if family == "BM_Assemble":
            table[args[0]][(capture, args[1])] = (a["median"]["items_per_second"] / 1e6, cv(a))
        elif family == "BM_CellLoop":
            loops[args[0]][capture] = (a["median"]["items_per_second"] / 1e6, cv(a))
        elif family == "BM_NeoHooke":
            material[capture] = (1e9 / a["median"]["items_per_second"], cv(a))

    out.append("| cells | residual 1 thr | residual 2 thr | speed-up | residual+tangent 1 thr | residual+tangent 2 thr | speed-up | max cv |")
    out.append("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n in sorted(table):
        row = table[n]
        r1, r2, t1, t2 = (row.get(k, (float("nan"), float("nan"))) for k in
                          [("residual", 1), ("residual", 2), ("tangent", 1), ("tangent", 2)])
        worst = max(x[1] for x in (r1, r2, t1, t2))
        out.append(f"| {n} | {r1[0]:.2f} | {r2[0]:.2f} | {r2[0] / r1[0]:.2f} | {t1[0]:.2f} | {t2[0]:.2f} | "
                   f"{t2[0] / t1[0]:.2f} | {100 * worst:.1f} % |")
    out.append("")
    out.append("(million cells per second, median of the repetitions)")
    out.append("")

    if loops:
        names = ["residual_natural", "residual_colour", "tangent_kernel_natural", "tangent_natural", "tangent_colour",
                 "tangent_colour_helper", "tangent_colour_helper_kind"]
        out.append("| cells | residual natural | residual colour | assemble_system residual | tangent kernel only | "
                   "+ scatter, natural order | colour order | + for_each_in | + dof-kind check | assemble_system tangent | max cv |")
        out.append("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for n in sorted(loops):
            row = loops[n]
            v = [row.get(k, (float("nan"), float("nan"))) for k in names]
            r1 = table[n].get(("residual", 1), (float("nan"), 0.0))
            t1 = table[n].get(("tangent", 1), (float("nan"), 0.0))
            worst = max(x[1] for x in v + [r1, t1])
            out.append(f"| {n} | {v[0][0]:.2f} | {v[1][0]:.2f} | {r1[0]:.2f} | {v[2][0]:.2f} | {v[3][0]:.2f} | "
                       f"{v[4][0]:.2f} | {v[5][0]:.2f} | {v[6][0]:.2f} | {t1[0]:.2f} | {100 * worst:.1f} % |")
        out.append("")
        out.append("(million cells per second, one thread; columns left to right add one ingredient of assemble_system)")
        out.append("")

    if material:
        out.append("| NeoHooke call (one point) | ns | cv |")
        out.append("|---|---:|---:|")
        for k in ["stress", "stress_tangent", "stress_tangent_in_plane"]:
            if k in material:
                out.append(f"| {k} | {material[k][0]:.1f} | {100 * material[k][1]:.1f} % |")
        out.append("")
    return "\n".join(out)


def newton_tables(runs):
    rows = []
    for name, a in runs.items():
        family, solver, args = parts(name)
        if family != "BM_NewtonStep":
            continue
        m = a["median"]
        rows.append((solver, args[0], args[1], args[2], m, cv(a)))
    rows.sort(key=lambda r: (r[0], r[1], -r[2], -r[3]))
    out = ["| solver | cells | dofs | threads tbb/solver | total ms | assemble | factorize | back-subst. | scatter + update | "
           "outside solver | first factorize (with analysis) | cv |",
           "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for solver, n, tbb, st, m, c in rows:
        out.append(f"| {solver} | {n} | {int(m['dofs'])} | {tbb}/{st} | {m['real_time']:.2f} | {m['assemble_ms']:.2f} | "
                   f"{m['factorize_ms']:.2f} | {m['back_substitute_ms']:.2f} | {m['scatter_ms'] + m['update_ms']:.3f} | "
                   f"{100 * m['outside_solver']:.0f} % | {m['first_factorize_ms']:.1f} | {100 * c:.1f} % |")
    out.append("")
    out.append("(ms per Newton iteration, median of the repetitions; the median of each column is taken separately)")
    return "\n".join(out)


def linear_tables(runs):
    order = ["cholmod_supernodal", "cholmod_simplicial", "cholmod_auto", "cholmod_supernodal_metis", "umfpack",
             "umfpack_no_refine", "eigen_ldlt"]
    rows = []
    for name, a in runs.items():
        family, backend, args = parts(name)
        if family == "BM_LinearSolve":
            rows.append((args[0], args[1], backend, a["median"], cv(a)))
    rows.sort(key=lambda r: (r[0], r[1], order.index(r[2]) if r[2] in order else 99))
    out = ["| cells | solver threads | back-end | factorize + solve ms | factorize | solve | nnz(L) | Gflop | residual of the solve | cv |",
           "|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|"]
    for n, st, backend, m, c in rows:
        lnz = f"{m['lnz'] / 1e6:.2f} M" if "lnz" in m else ""
        gflop = f"{m['gflop']:.3f}" if "gflop" in m else ""
        out.append(f"| {n} | {st} | {backend} | {m['real_time']:.2f} | {m['factorize_ms']:.2f} | {m['solve_ms']:.2f} | "
                   f"{lnz} | {gflop} | {m['relative_residual']:.0e} | {100 * c:.1f} % |")
    out.append("")
    out.append("(ms, median of the repetitions; residual of the solve = norm(K du + r) / norm(r))")
    return "\n".join(out)


def main(paths):
    # Files of one program (e.g. chunks run with different --benchmark_filter) are merged into one table.
    by_program = defaultdict(list)
    for path in paths:
        ctx, runs = load(path)
        by_program[ctx["executable"].split("/")[-1]].append((path, ctx, runs))
    for program, files in by_program.items():
        merged = {}
        for path, ctx, runs in files:
            print(f"- {context_line(path, ctx)}")
            merged.update(runs)
        print()
        families = {parts(n)[0] for n in merged}
        if "BM_NewtonStep" in families:
            print(newton_tables(merged))
        elif "BM_LinearSolve" in families:
            print(linear_tables(merged))
        else:
            print(assemble_tables(merged))
        print()


if __name__ == "__main__":
    main(sys.argv[1:])
