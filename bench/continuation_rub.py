#!/usr/bin/python3
"""Continuation against brute force on the rub of examples/casing-rub.toml (docs/continuation.md):
`rotbeam continue` over hub.speed_rpm from A to B, and a brute-force sweep (`rotbeam sweep`, each speed
run to its steady state or 200 revolutions) over the same range, in one sitting on the same machine.

Reports both wall times and their ratio, the continuation's orbits (stable and unstable), branches,
special points and map evaluations, and how many brute-force speeds settled; then, for every
brute-force speed that settled with period 1 inside a stretch of the branch, the relative distance
of its last revolution's peak force from the branch's (interpolated).

Usage: bench/continuation_rub.py [--range 1000:1060] [--speeds 13] [--out DIR] [--rotbeam build/rotbeam]
                                 [--jobs 0]
"""
import argparse
import csv
import json
import pathlib
import shutil
import subprocess
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent


def timed(cmd):
    t0 = time.monotonic()
    done = subprocess.run(cmd, capture_output=True, text=True)
    return time.monotonic() - t0, done


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--range", default="1000:1060", help="A:B (rpm)")
    ap.add_argument("--speeds", type=int, default=13, help="brute-force speeds over the range")
    ap.add_argument("--out", default="continuation-bench", help="a folder for both runs (made)")
    ap.add_argument("--rotbeam", default=str(REPO / "build" / "rotbeam"))
    ap.add_argument("--jobs", default="0")
    a = ap.parse_args()
    lo, hi = (float(v) for v in a.range.split(":"))
    out = pathlib.Path(a.out)
    for sub in ("branch", "sweep"):
        shutil.rmtree(out / sub, ignore_errors=True)
    out.mkdir(parents=True, exist_ok=True)
    case = str(REPO / "examples" / "casing-rub.toml")
    tc, c = timed([a.rotbeam, "continue", case, "--parameter", "hub.speed_rpm", "--from", f"{lo:g}", "--to",
                   f"{hi:g}", "-o", str(out / "branch"), "--jobs", a.jobs, "--quiet"])
    if c.returncode not in (0,):
        print(c.stdout, c.stderr, file=sys.stderr)
    tb, b = timed([a.rotbeam, "sweep", case, "--vary", f"hub.speed_rpm={lo:g}:{hi:g}:{a.speeds}", "-o",
                   str(out / "sweep"), "--jobs", a.jobs, "--quiet"])
    if b.returncode != 0:
        print(b.stdout, b.stderr, file=sys.stderr)
        return 1
    s = json.loads((out / "branch" / "summary.json").read_text())
    with open(out / "branch" / "branch.csv") as f:
        rows = list(csv.DictReader(f))
    with open(out / "sweep" / "sweep.csv") as f:
        sweep = list(csv.DictReader(f))
    kinds = {}
    for p in s["special_points"]:
        kinds[p["kind"]] = kinds.get(p["kind"], 0) + 1
    settled = [r for r in sweep if float(r["steady_after_revolutions"] or 0) > 0]
    print(f"range {lo:g}–{hi:g} rpm, examples/casing-rub.toml")
    print(f"continuation: {tc:.1f} s, {s['points']} orbits ({s['stable_points']} stable), {len(s['branches'])} branches, "
          f"{s['map_evaluations']} map evaluations; special points {kinds or 'none'}")
    print(f"brute force:  {tb:.1f} s, {len(sweep)} speeds, {len(settled)} settled within 200 revolutions")
    print(f"continuation / brute force: {tc / tb:.2f}")
    # The brute-force peak force against the branch's at the same speed (where one branch covers it once).
    x = np.array([float(r["parameter"]) for r in rows if r["branch"] == "0"])
    y = np.array([float(r["peak_normal_force_n"]) for r in rows if r["branch"] == "0"])
    if x.size > 1 and np.all(np.diff(x) > 0):
        for r in settled:
            v = float(r["hub.speed_rpm"])
            if x[0] <= v <= x[-1]:
                yb = float(r["last_revolution_peak_normal_force_n"])
                print(f"  {v:8.2f} rpm: brute force {yb:.6f} N, branch {np.interp(v, x, y):.6f} N, "
                      f"relative {abs(yb / np.interp(v, x, y) - 1):.1e} (interpolated between points)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
