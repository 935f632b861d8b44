#!/usr/bin/python3
"""A brush as a population against the filament route (docs/brush.md, docs/performance.md).

For each filament design: N filaments with 5 % length scatter, 2 % diameter scatter and 1° phase
jitter, run by `rotbeam brush` filament by filament and as a population on the same draws; reports
the wall time of each, the representatives the population ran, the population's error against the
filament route in the mean normal force, tangential force, hub torque and power, and the error the
population estimated for itself. Then the population alone on --large filaments.

Usage: bench/brush_population.py [--filaments 1000] [--large 100000] [--rotbeam build/rotbeam]
                                  [--designs base,stiff] [--out DIR] [--skip-filaments]
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys
import time

REPO = pathlib.Path(__file__).resolve().parent.parent

# Filament designs on examples/brush.toml: its wire, and a shorter, stiffer one at another speed and depth.
DESIGNS = {
    "base": [],
    "stiff": ["beam.length_m=0.05", "beam.diameter_m=0.0006", "hub.speed_rpm=900", "surface.depth_fraction=0.04",
              "surface.friction=0.25"],
}
SCATTER = ["brush.rows=1", "brush.length_scatter=0.05", "brush.diameter_scatter=0.02", "brush.phase_jitter_deg=1"]


def run(rotbeam, out, sets):
    if out.exists():
        shutil.rmtree(out)
    cmd = [rotbeam, "brush", str(REPO / "examples" / "brush.toml"), "-o", str(out), "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    start = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode not in (0, 11):
        sys.exit(f"{' '.join(cmd)}: exit {done.returncode}\n{done.stderr}")
    return wall, json.loads((out / "summary.json").read_text())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--filaments", type=int, default=1000)
    ap.add_argument("--large", type=int, default=100000)
    ap.add_argument("--rotbeam", default=str(REPO / "build" / "rotbeam"))
    ap.add_argument("--designs", default="base,stiff")
    ap.add_argument("--out", default="brush-population")
    ap.add_argument("--skip-filaments", action="store_true", help="run the population only")
    a = ap.parse_args()
    out = pathlib.Path(a.out)
    out.mkdir(exist_ok=True)
    keys = [("mean_normal_force_n", "mean_normal_force"), ("mean_tangential_force_n", "mean_tangential_force"),
            ("mean_hub_torque_n_m", "mean_hub_torque"), ("mean_hub_power_w", "mean_hub_torque")]
    for name in a.designs.split(","):
        sets = DESIGNS[name] + SCATTER + [f"brush.filaments={a.filaments}"]
        wp, p = run(a.rotbeam, out / f"{name}-population", sets + ['brush.method="population"'])
        est = p["population"]["estimated_error"]
        print(f"{name}: {a.filaments} filaments ({p['reaching_filaments']} reach), population: "
              f"{p['population']['representatives']} runs ({p['population']['exact_filaments']} filaments on their own), "
              f"{wp:.1f} s, converged {p['population']['converged']}")
        if not a.skip_filaments:
            wf, f = run(a.rotbeam, out / f"{name}-filaments", sets)
            print(f"  filament route: {f['distinct_filaments']} distinct, {wf:.1f} s; population / filaments wall {wp / wf:.3f}")
            for k, e in keys:
                err = (p[k] - f[k]) / f[k]
                print(f"  {k:26s} filaments {f[k]:.6g}  population {p[k]:.6g}  error {err:+.2e}  estimated {est[e]:.2e}"
                      f"  true/estimated {abs(err) / est[e]:.2f}")
        else:
            for k, e in keys:
                print(f"  {k:26s} population {p[k]:.6g}  estimated {est[e]:.2e}")
    if a.large:
        sets = DESIGNS["base"] + SCATTER + [f"brush.filaments={a.large}", 'brush.method="population"']
        wl, l = run(a.rotbeam, out / "large-population", sets)
        print(f"large: {a.large} filaments by population: {l['population']['representatives']} representatives, "
              f"{wl:.1f} s, mean normal force {l['mean_normal_force_n']:.6g} N, estimated error "
              f"{l['population']['estimated_error']['mean_normal_force']:.2e}")


if __name__ == "__main__":
    main()
