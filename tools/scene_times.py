#!/usr/bin/env python3
"""The shipped scenes' exit codes and wall times in docs/guide/scenes.md, re-measured and rewritten in place.

Each row of the table names one scene (`scenes/X.toml`) with its exit code and wall time in seconds. This runs the
scenes as the page says (`loom run SCENE --quiet`, into a temporary directory that is removed) and rewrites those two
columns, so that a scene has one duration, measured, in one place. Rows whose recorded time is above --max-seconds
(or not a number, e.g. "hours") are left as they are and listed; --only takes a regular expression of scene names.

  tools/scene_times.py [--loom build/loom] [--max-seconds 120] [--only REGEX] [--dry-run]
  tools/scene_times.py --check      # every scenes/*.toml has exactly one row and every row an existing scene (no run)
"""
import argparse
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
PAGE = ROOT / "docs" / "guide" / "scenes.md"
ROW = re.compile(r"^\| `(scenes/[^`]+\.toml)` \|(.*)\| (\S+) \| ([^|]+) \|$")


def rows(lines):
    """(line index, scene, exit, wall) of every table row."""
    for i, line in enumerate(lines):
        m = ROW.match(line)
        if m:
            yield i, m.group(1), m.group(3), m.group(4).strip()


def check(lines):
    listed = [scene for _, scene, _, _ in rows(lines)]
    shipped = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "scenes").glob("*.toml"))
    problems = [f"{s}: no row in {PAGE.relative_to(ROOT)}" for s in shipped if s not in listed]
    problems += [f"{s}: a row, but no such scene" for s in sorted(set(listed)) if s not in shipped]
    problems += [f"{s}: {listed.count(s)} rows" for s in sorted(set(listed)) if listed.count(s) > 1]
    for p in problems:
        print(f"scene_times: {p}", file=sys.stderr)
    return 1 if problems else 0


def recorded_seconds(wall):
    m = re.match(r"~?([0-9.]+)", wall)
    return float(m.group(1)) if m else None


def formatted(seconds):
    return f"{seconds:.1f}" if seconds < 10 else f"{seconds:.0f}"


def measure(loom, scene, timeout):
    out = tempfile.mkdtemp(prefix="scene_times_")
    try:
        start = time.monotonic()
        try:
            rc = subprocess.run([loom, "run", scene, "--quiet", "--out", out], cwd=ROOT, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            return None, None
        return rc, time.monotonic() - start
    finally:
        shutil.rmtree(out, ignore_errors=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--loom", default=str(ROOT / "build" / "loom"))
    ap.add_argument("--max-seconds", type=float, default=120.0, help="skip rows recorded as taking longer")
    ap.add_argument("--only", default="", help="regular expression of the scenes to run")
    ap.add_argument("--dry-run", action="store_true", help="print the new rows, do not rewrite the page")
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    lines = PAGE.read_text().split("\n")
    if args.check:
        return check(lines)
    skipped = []
    for i, scene, old_exit, wall in list(rows(lines)):
        if args.only and not re.search(args.only, scene):
            continue
        recorded = recorded_seconds(wall)
        if recorded is None or recorded > args.max_seconds:
            skipped.append(f"{scene} ({wall})")
            continue
        rc, seconds = measure(args.loom, scene, timeout=max(10 * recorded, 60))
        if rc is None:
            print(f"{scene}: still running after {max(10 * recorded, 60):.0f} s (recorded {wall}), left as it is")
            continue
        new_wall = formatted(seconds)
        print(f"{scene}: exit {rc} (recorded {old_exit}), {new_wall} s (recorded {wall})")
        head = lines[i][: lines[i].rindex(f"| {old_exit} |")]
        lines[i] = f"{head}| {rc} | {new_wall} |"
    if skipped:
        print("left as recorded (above --max-seconds or not a number): " + ", ".join(skipped))
    if not args.dry_run:
        PAGE.write_text("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
