#!/usr/bin/env python3
"""Whole-run timing of many revolutions: wall time, peak resident memory and the per-revolution
energy ledger of `rotbeam run --set simulation.revolutions=N` for several N, to show that time
grows linearly with N, memory stays bounded, and the ledger closes in every revolution.

    /usr/bin/python3 bench/revolutions_scaling.py build/rotbeam [N ...] [--set key=value ...]

Defaults: N = 10 100 1000 on the base case with beam.damping_ratio = 0.01 (contact in every
revolution). Each run writes into a temporary folder that is removed afterwards.
"""
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time


def measure(binary, n, sets):
    out = tempfile.mkdtemp(prefix="rotbeam-revolutions-")
    try:
        cmd = ["/usr/bin/time", "-v", binary, "run", "--quiet", "-o", os.path.join(out, "run"),
               "--set", f"simulation.revolutions={n}"]
        for s in sets:
            cmd += ["--set", s]
        t0 = time.monotonic()
        p = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.monotonic() - t0
        if p.returncode != 0:
            sys.exit(f"revolutions = {n}: exit {p.returncode}\n{p.stderr[-2000:]}")
        rss_kb = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr).group(1))
        worst = 0.0
        rows = over = 0
        with open(os.path.join(out, "run", "revolutions.csv")) as f:
            for r in csv.DictReader(f):
                rows += 1
                hub = abs(float(r["hub_work_j"]))
                closing = (float(r["hub_work_j"]) + float(r["friction_work_j"]) + float(r["damping_work_j"])
                           + float(r["impact_loss_j"]) - float(r["energy_change_j"]))
                relative = abs(closing) / hub if hub > 0 else abs(closing)
                worst = max(worst, relative)
                over += relative > 1e-8
        size = sum(os.path.getsize(os.path.join(out, "run", f)) for f in os.listdir(os.path.join(out, "run")))
        return wall, rss_kb / 1024.0, rows, worst, over, size / 1e6
    finally:
        shutil.rmtree(out, ignore_errors=True)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    binary = sys.argv[1]
    counts, sets, args = [], [], sys.argv[2:]
    while args:
        a = args.pop(0)
        if a == "--set":
            sets.append(args.pop(0))
        else:
            counts.append(int(a))
    counts = counts or [10, 100, 1000]
    sets = sets or ["beam.damping_ratio=0.01"]
    print(f"case: {' '.join(sets)}")
    print(f"{'revolutions':>11}  {'wall [s]':>9}  {'s/revolution':>12}  {'peak RSS [MB]':>13}  "
          f"{'output [MB]':>11}  {'worst ledger / hub work':>23}  {'revolutions over 1e-8':>21}")
    for n in counts:
        wall, rss, rows, worst, over, size = measure(binary, n, sets)
        if rows != n:
            sys.exit(f"revolutions = {n}: revolutions.csv has {rows} rows")
        print(f"{n:>11}  {wall:>9.2f}  {wall / n:>12.4f}  {rss:>13.1f}  {size:>11.1f}  {worst:>23.2e}  {over:>21d}", flush=True)


if __name__ == "__main__":
    main()
