#!/usr/bin/python3
"""The rub map of docs/surfaces.md: examples/casing-rub.toml (a filament in a two-lobe casing, 0.1 mm
clearance, 0.3 mm lobes, μ = 0.02, ζ = 0.02, each speed run to its steady state or 200 revolutions)
swept over hub speed, then drawn over the Campbell diagram (rub_map.png).

Reports per speed the last revolution's peak |y_t|/L, peak contact force, normal impulse, friction
work and impacts, whether the steady state was reached, the cases stopped on a diagnosed failure,
and the sweep's wall time.

Usage: bench/rub_map.py [--speeds 500:6000:50] [--out DIR] [--rotbeam build/rotbeam] [--jobs 0]
                        [--picture docs/images/rub_map.png]
"""
import argparse
import csv
import json
import pathlib
import shutil
import subprocess
import sys
import time

REPO = pathlib.Path(__file__).resolve().parent.parent


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--speeds", default="500:6000:50", help="the hub speeds, A:B:N (rpm)")
    ap.add_argument("--out", default="rub-map", help="the sweep's folder (made; refused if it holds another sweep)")
    ap.add_argument("--rotbeam", default=str(REPO / "build" / "rotbeam"))
    ap.add_argument("--jobs", default="0")
    ap.add_argument("--picture", help="copy rub_map.png here as well")
    a = ap.parse_args()
    out = pathlib.Path(a.out)
    cmd = [a.rotbeam, "sweep", str(REPO / "examples" / "casing-rub.toml"), "--vary", f"hub.speed_rpm={a.speeds}",
           "-o", str(out), "--jobs", a.jobs, "--quiet"]
    start = time.perf_counter()
    done = subprocess.run(cmd)
    wall = time.perf_counter() - start
    if done.returncode not in (0, 1):  # 1: some case stopped on a diagnosed failure, named in the map
        sys.exit(f"{' '.join(cmd)}: exit {done.returncode}")
    rows = list(csv.DictReader(open(out / "sweep.csv")))
    print(f"{len(rows)} speeds in {wall:.0f} s")
    print(f"{'rpm':>6} {'status':>8} {'steady':>6} {'|y|/L':>7} {'F peak N':>9} {'I mN s':>8} {'W_f mJ':>8} {'impacts':>7}")
    for r in rows:
        steady = ""
        if r["status"] in ("done", "resumed"):
            s = json.loads((out / r["folder"] / "summary.json").read_text())
            st = s.get("steady_state") or {}
            steady = f"{st.get('after_revolutions')}" if st.get("reached") else "no"

        def num(k, scale=1.0):
            return f"{float(r[k]) * scale:.4g}" if r[k] else "-"
        print(f"{float(r['hub.speed_rpm']):6.0f} {r['status']:>8} {steady:>6} "
              f"{num('last_revolution_max_tip_deflection_ratio'):>7} {num('last_revolution_peak_normal_force_n'):>9} "
              f"{num('last_revolution_normal_impulse_n_s', 1e3):>8} {num('last_revolution_friction_work_j', 1e3):>8} "
              f"{num('last_revolution_impacts'):>7}")
    subprocess.run([a.rotbeam, "plot", str(out), "-o", str(out / "pictures")], check=True)
    if a.picture:
        shutil.copyfile(out / "pictures" / "rub_map.png", a.picture)
        print(f"wrote {a.picture}")


if __name__ == "__main__":
    main()
