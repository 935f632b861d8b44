#!/usr/bin/python3
"""A brush's mean force against its number of filaments, and its cost (docs/brush.md, docs/performance.md).

Runs `rotbeam brush` on examples/brush.toml's filament (550 rpm, 2 % depth, ζ = 0.05) with one row and
brush.length_scatter (default 0.05) for N = 1, 2, 5, 10, 20, 50, 100, 200 filaments and several seeds,
and reports per N: the mean normal force per filament (mean over the seeds and their spread), the
fraction of filaments that reach the surface, and the wall time of the 100-filament brush (median over
the seeds; the acceptance target is 2 minutes on a 2-core machine).

With scatter the per-filament mean is a sample mean over the lengths drawn: it converges to the
expectation over the length distribution as N grows, its seed-to-seed spread falling like 1/√N.

Usage: bench/brush_scaling.py [--counts 1,2,5,10,20,50,100,200] [--seeds 1,2,3] [--scatter 0.05]
                              [--rotbeam build/rotbeam] [--jobs 0] [--json]
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

REPO = pathlib.Path(__file__).resolve().parent.parent


def run_brush(rotbeam, n, seed, scatter, jobs, out):
    cmd = [str(rotbeam), "brush", str(REPO / "examples" / "brush.toml"), "--quiet", "--json", "-o", str(out),
           "--jobs", str(jobs), "--set", f"brush.filaments={n}", "--set", "brush.rows=1",
           "--set", f"brush.length_scatter={scatter}", "--set", f"brush.seed={seed}"]
    start = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: exit {done.returncode}: {done.stderr.strip()}")
    return wall, json.loads(done.stdout)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--counts", default="1,2,5,10,20,50,100,200")
    p.add_argument("--seeds", default="1,2,3")
    p.add_argument("--scatter", type=float, default=0.05)
    p.add_argument("--rotbeam", default=str(REPO / "build" / "rotbeam"))
    p.add_argument("--jobs", type=int, default=0)
    p.add_argument("--json", action="store_true")
    a = p.parse_args()
    counts = [int(x) for x in a.counts.split(",")]
    seeds = [int(x) for x in a.seeds.split(",")]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in counts:
            per, reach, walls = [], [], []
            for seed in seeds:
                wall, s = run_brush(a.rotbeam, n, seed, a.scatter, a.jobs, pathlib.Path(tmp) / f"b{n}-{seed}")
                per.append(s["mean_normal_force_n"] / n)
                reach.append(s["reaching_filaments"] / n)
                walls.append(wall)
            rows.append({"filaments": n, "mean_force_per_filament_n": statistics.mean(per),
                         "spread_n": statistics.pstdev(per), "reaching_fraction": statistics.mean(reach),
                         "median_wall_s": statistics.median(walls)})
            if not a.json:
                r = rows[-1]
                print(f"N = {n:4d}: mean normal force per filament {r['mean_force_per_filament_n']:.5f} N "
                      f"(seed spread {r['spread_n']:.5f} N), {100 * r['reaching_fraction']:.0f} % reach the surface, "
                      f"median wall {r['median_wall_s']:.1f} s", flush=True)
    if a.json:
        print(json.dumps(rows, indent=2))


if __name__ == "__main__":
    main()
