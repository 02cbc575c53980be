"""Helpers of the study scripts: run the loom program on a scene with overrides and read what it wrote."""
import csv
import json
import os
import pathlib
import subprocess
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
LOOM = os.environ.get("LOOM", str(ROOT / "build" / "loom"))


def run(scene, out, sets=(), threads=None):
    """Runs `loom run scene --out out --set ...`; returns (exit code, run.json dict, probes rows, wall s, stderr)."""
    cmd = [LOOM, "run", str(ROOT / "scenes" / scene), "--quiet", "--out", str(out)]
    for s in sets:
        cmd += ["--set", s]
    if threads:
        cmd += ["--threads", str(threads)]
    start = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - start
    if p.returncode == 2:
        raise RuntimeError(f"bad input: {' '.join(cmd)}\n{p.stderr}")
    info = json.loads((pathlib.Path(out) / "run.json").read_text())
    with open(pathlib.Path(out) / "probes.csv") as f:
        rows = list(csv.DictReader(f))
    return p.returncode, info, rows, wall, p.stderr


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    print("wrote", path)
