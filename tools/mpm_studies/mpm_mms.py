#!/usr/bin/python3
"""Manufactured solution of seed 003 §6.1 on the mixed MPM: runs the verification test that asserts the rates
(build/tests/verification/mpm_mms_test) with LOOM_MMS_CSV set, then plots its table.
Writes docs/mpm/mms_convergence.csv and docs/mpm/mms_convergence.png (about 10 s)."""
import csv
import os
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import loom_study

DOCS = loom_study.ROOT / "docs" / "mpm"
TEST = loom_study.ROOT / "build" / "tests" / "verification" / "mpm_mms_test"


def main():
    table = DOCS / "mms_convergence.csv"
    env = dict(os.environ, LOOM_MMS_CSV=str(table))
    p = subprocess.run([str(TEST), "--gtest_filter=*Converges*"], env=env, capture_output=True, text=True)
    print("\n".join(l for l in p.stdout.splitlines() if l.startswith("[mms") or "OK" in l or "FAIL" in l))
    if p.returncode != 0:
        raise SystemExit("the convergence test failed")
    rows = list(csv.DictReader(open(table)))
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.5))
    for stab, marker in [("ppp", "o"), ("asgs", "s"), ("osgs", "^")]:
        r = [x for x in rows if x["stabilisation"] == stab]
        h = [float(x["h"]) for x in r]
        ax[0].loglog(h, [float(x["error_u"]) for x in r], marker=marker, label=stab.upper())
        ax[1].loglog(h, [float(x["error_p"]) for x in r], marker=marker, label=stab.upper())
    for a, field, ref, slopes in [(ax[0], "displacement", 1e-3, [2]), (ax[1], "pressure", 1e-1, [1, 2])]:
        for s in slopes:
            h = [0.2, 0.015625]
            a.loglog(h, [ref * (x / 0.0625) ** s for x in h], "k--" if s == 2 else "k:", lw=0.8, label=f"slope {s}")
        a.set_xlabel("h (m)")
        a.set_ylabel(f"L2 error of the {field}")
        a.set_title(f"seed 003 §6.1, P1 grids: {field}")
        a.grid(alpha=0.3, which="both")
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(DOCS / "mms_convergence.png", dpi=120)
    print("wrote", table, "and", DOCS / "mms_convergence.png")


if __name__ == "__main__":
    main()
