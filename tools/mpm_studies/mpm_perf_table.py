#!/usr/bin/python3
"""Markdown tables of the MPM benchmarks (perf/bench_locate_points, bench_transfers, bench_mpm_step) from their
Google Benchmark JSON output. Usage:
    mpm_perf_table.py locate.json transfers.json step.json
(medians if the benchmarks ran with --benchmark_repetitions). Prints particles per second of locate, projection and interpolation, and milliseconds per step by system."""
import json
import sys

SYSTEMS = ["locate_particles", "activate_grid", "project_to_grid", "apply_grid_loads", "newton/assemble", "newton/solve",
           "newton", "interpolate_to_particles", "probes"]


def load(path):
    """The medians when the run had --benchmark_repetitions, else the single runs."""
    runs = json.load(open(path))["benchmarks"]
    medians = [b for b in runs if b.get("aggregate_name") == "median"]
    return medians or [b for b in runs if b.get("run_type", "iteration") == "iteration"]


def split(name):
    base, particles, threads = name.split("/")[:3]
    return base.replace("BM_", ""), int(particles), int(threads)


def main():
    locate, transfers, step = (load(p) for p in sys.argv[1:4])
    print("| kernel | particles (requested / actual) | threads | ms per call | particles per second |")
    print("| --- | --- | --- | --- | --- |")
    for b in locate + transfers:
        kernel, n, t = split(b["name"])
        print(f"| {kernel} | {n} / {int(b['particles'])} | {t} | {b['real_time']:.3f} | {b['items_per_second'] / 1e6:.1f} M |")
    print()
    print("| grid | particles | threads | ms per step | Newton per step | " + " | ".join(SYSTEMS) + " |")
    print("| --- | --- | --- | --- | --- | " + " | ".join("---" for _ in SYSTEMS) + " |")
    for b in step:
        kernel, n, t = split(b["name"])
        grid = "quad4" if kernel.endswith("Quad") else "tri3"  # BM_MpmStepQuad: the same on a quad4 grid
        per_step = b["real_time"] / 4  # bench_mpm_step runs 4 steps per iteration
        cells = " | ".join(f"{b[s + '_ms']:.2f}" for s in SYSTEMS)
        print(f"| {grid} | {int(b['particles'])} | {t} | {per_step:.1f} | {b['newton_per_step']:.2f} | {cells} |")


if __name__ == "__main__":
    main()
