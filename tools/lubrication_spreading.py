#!/usr/bin/python3
"""Shallow-layer (lubrication) model of a Bingham paste spreading in plane strain on a no-slip ground: the reference
history for scenes/bingham_collapse_es.toml and scenes/channel_flow_es.toml, whose arrested states it also gives.

Model (Liu & Mei 1989, Balmforth et al. 2006; a layer of thickness h(x, t) much thinner than long, inertia left out):
the shear stress at the base is tau_b = rho g h |h_x|; where it exceeds the yield stress tau0 the paste flows
below the yield surface at height Y = h - tau0 / (rho g |h_x|) and rides on it as a plug above, with the flux

    q = -sign(h_x) rho g |h_x| Y^2 (3 h - Y) / (6 mu),      h_t + q_x = 0,

and no flux where tau_b <= tau0. The layer stops in the state rho g h |h_x| = tau0 wherever it has flowed: from a
front at L, h = sqrt(2 tau0 (L - x) / (rho g)); its area A per unit width gives the front
L = [3 A / (2 sqrt(2 tau0 / (rho g)))]^(2/3) for a layer against a wall (the channel) and the half-width
L_f = [3 A / (4 sqrt(2 tau0 / (rho g)))]^(2/3) of a symmetric deposit of area A (the collapse).

Finite volumes on [0, length], explicit in time (the step is bounded by the diffusive limit of the flowing layer).
At x = 0 the flux is zero (a wall, or the symmetry line) or the inflow rate Q while t < pour.

    tools/lubrication_spreading.py collapse --tau0 20 --mu 10 --width 0.05 --height 0.1 --times 10,20,40,100
    tools/lubrication_spreading.py channel --tau0 50 --mu 50 --rate 0.001 --pour 28.4375 --width 0.025 --height 0.0625 --times 30,80
"""
import argparse
import math
import sys

import numpy as np

RHO, G = 2300.0, 9.81


def spread(h, dx, tau0, mu, inflow, times, rho=RHO, g=G):
    """Advances h through the given times; inflow(t) is the flux entering at x = 0. Yields (t, h) at each."""
    B = tau0 / (rho * g)
    t = 0.0
    for mark in times:
        while t < mark - 1e-12:
            hx = np.diff(h) / dx
            hf = 0.5 * (h[1:] + h[:-1])
            s = np.abs(hx) + 1e-300
            Y = np.maximum(hf - B / s, 0.0)
            q = -np.sign(hx) * rho * g / (6.0 * mu) * Y * Y * (3.0 * hf - Y) * s
            stable = 0.2 * dx * dx / (rho * g / (3.0 * mu) * max(hf.max(), 1e-6) ** 3)
            dt = min(stable, mark - t, 0.5)
            F = np.concatenate([[inflow(t)], q, [0.0]])
            h = np.maximum(h - dt * (F[1:] - F[:-1]) / dx, 0.0)
            t += dt
        yield t, h


def front_of(h, x, thin=1e-4):
    wet = x[h > thin]
    return wet.max() if wet.size else 0.0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("case", choices=["collapse", "channel"])
    p.add_argument("--tau0", type=float, required=True)
    p.add_argument("--mu", type=float, required=True)
    p.add_argument("--width", type=float, required=True, help="initial block: half-width (collapse) or width at the wall (channel)")
    p.add_argument("--height", type=float, required=True)
    p.add_argument("--rate", type=float, default=0.0, help="channel: inflow per unit width, m^2/s")
    p.add_argument("--pour", type=float, default=0.0, help="channel: pouring time, s")
    p.add_argument("--length", type=float, default=1.2)
    p.add_argument("--cells", type=int, default=1200)
    p.add_argument("--times", required=True, help="comma-separated output times, s")
    a = p.parse_args()
    x_edges = np.linspace(0.0, a.length, a.cells + 1)
    dx = x_edges[1] - x_edges[0]
    x = 0.5 * (x_edges[1:] + x_edges[:-1])
    h = np.where(x < a.width, a.height, 0.0)
    inflow = (lambda t: a.rate if t < a.pour else 0.0) if a.case == "channel" else (lambda t: 0.0)
    area = a.width * a.height + a.rate * a.pour
    c = math.sqrt(2.0 * a.tau0 / (RHO * G))
    arrested = (3.0 * (2 * area if a.case == "collapse" else area) / ((4.0 if a.case == "collapse" else 2.0) * c)) ** (2.0 / 3.0)
    print(f"# {a.case}: tau0 {a.tau0} Pa, mu {a.mu} Pa s, area {area:.6g} m^2 (of the half for the collapse), arrested front {arrested:.5f} m")
    print("time,front,height_at_0,area")
    for t, hh in spread(h, dx, a.tau0, a.mu, inflow, [float(v) for v in a.times.split(",")]):
        print(f"{t:.6g},{front_of(hh, x):.6f},{hh[0]:.6f},{hh.sum() * dx:.6g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
