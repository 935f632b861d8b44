#!/usr/bin/python3
"""How far the default tolerance's metrics lie from a tight run (docs/configuration.md).

Runs each case at the default tolerance and at rtol = 1e-12, atol = 1e-15, and prints whether the
counts agree and the relative difference of the friction work, contact time, normal impulse, last
separation and peak force, then the worst of each.

    bench/default_tolerance.py [--rotbeam build/rotbeam]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

CASES = [[], ["hub.speed_rpm=3000"], ["hub.speed_rpm=800", "surface.depth_fraction=0.005"],
         ["hub.speed_rpm=5000", "surface.friction=1"], ["hub.speed_rpm=1200", "initial.modal_velocity=[1,0,0,0,0]"],
         ["hub.speed_rpm=2000", "surface.depth_fraction=0.03", "surface.friction=0"],
         ["hub.speed_rpm=1000", "impact.restitution=0.5", "surface.depth_fraction=0.01"],
         ["hub.speed_rpm=4000", "surface.depth_fraction=0.005", "surface.friction=0.7"]]
KEYS = ["friction_work_j", "contact_time_s", "normal_impulse_n_s", "last_separation_deg", "peak_normal_force_n"]
TIGHT = ["simulation.rtol=1e-12", "simulation.atol=1e-15"]


def summary(rotbeam, sets):
    with tempfile.TemporaryDirectory() as folder:
        cmd = [rotbeam, "run", "-o", folder, "--quiet"]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, capture_output=True, check=False)
        with open(os.path.join(folder, "summary.json")) as f:
            return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rotbeam", default="build/rotbeam")
    args = ap.parse_args()
    worst = {k: (0.0, "") for k in KEYS}
    for case in CASES:
        name = " ".join(case) or "base case"
        a, b = summary(args.rotbeam, case), summary(args.rotbeam, case + TIGHT)
        same = a["impacts"] == b["impacts"] and a["contact_episodes"] == b["contact_episodes"]
        cells = []
        for k in KEYS:
            r = abs(a[k] - b[k]) / abs(b[k]) if b[k] else abs(a[k] - b[k])
            cells.append(f"{k} {r:.1e}")
            if r > worst[k][0]:
                worst[k] = (r, name)
        print(f"{name}: {'counts equal' if same else 'COUNTS DIFFER'}; " + ", ".join(cells))
    print("worst: " + "; ".join(f"{k} {v:.1e} ({where})" for k, (v, where) in worst.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
