#!/usr/bin/python3
"""The filament in operation: the base filament with damping over many revolutions on a grid of
speeds, frictions and depths (the grid of docs/contact.md, "Stick and Painlevé's paradox"). Runs
`rotbeam run` for every case and reports how each ended, its sticks and tangential impacts, and the
largest ledger residual of a revolution relative to its hub work and to its largest term (a
revolution whose hub work nearly cancels makes the first ratio large on a residual of round-off
size).

    bench/operation_grid.py [--rotbeam build/rotbeam] [--revolutions 20] [--jobs 2] [--set KEY=VALUE ...]
"""
import argparse
import concurrent.futures as cf
import csv
import json
import os
import subprocess
import sys
import tempfile

SPEEDS = [550, 850, 1200, 1800, 2500, 3500]
FRICTIONS = [0.1, 0.4, 0.7]
DEPTHS = [0.01, 0.03]


def run(args, rpm, mu, depth, folder):
    out = os.path.join(folder, f"{rpm}_{mu}_{depth}")
    sets = [f"beam.damping_ratio=0.03", f"simulation.revolutions={args.revolutions}", f"hub.speed_rpm={rpm}",
            f"surface.friction={mu}", f"surface.depth_fraction={depth}", 'output.history_revolutions="all"'] + args.set
    cmd = [args.rotbeam, "run", "-o", out, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    summary = json.load(open(os.path.join(out, "summary.json")))
    worst = worst_term = 0.0
    terms = ("hub_work_j", "friction_work_j", "surface_work_j", "damping_work_j", "impact_loss_j",
             "contact_dissipation_j", "energy_change_j")
    with open(os.path.join(out, "revolutions.csv")) as f:
        for row in csv.DictReader(r for r in f if not r.startswith("#")):
            hub = abs(float(row["hub_work_j"]))
            largest = max(abs(float(row[t])) for t in terms if t in row)
            if row["complete"] in ("true", "1") and hub > 0:
                worst = max(worst, abs(float(row["ledger_residual_j"])) / hub)
                worst_term = max(worst_term, abs(float(row["ledger_residual_j"])) / largest)
    kinds = {}
    with open(os.path.join(out, "events.csv")) as f:
        for row in csv.DictReader(r for r in f if not r.startswith("#")):
            k = row["kind"]
            if k == "impact" and row["detail"].startswith("tangential"):
                k = "tangential_impact"
            kinds[k] = kinds.get(k, 0) + 1
    failure = summary.get("failure")
    return dict(rpm=rpm, mu=mu, depth=depth, exit=p.returncode,
                ended=failure["kind"] if failure else "complete",
                theta=failure["theta_deg"] if failure else None,
                revolutions=summary["revolutions"], sticks=kinds.get("stick_start", 0),
                tangential=kinds.get("tangential_impact", 0), stick_time_s=summary.get("stick_time_s", 0.0),
                worst_ledger=worst, worst_ledger_term=worst_term)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rotbeam", default="build/rotbeam")
    ap.add_argument("--revolutions", type=int, default=20)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--set", action="append", default=[])
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as folder, cf.ThreadPoolExecutor(args.jobs) as pool:
        futures = [pool.submit(run, args, rpm, mu, depth, folder) for rpm in SPEEDS for mu in FRICTIONS for depth in DEPTHS]
        rows = [f.result() for f in futures]
    print(f"{'rpm':>5} {'mu':>4} {'depth':>5}  {'ended':<14} {'revs':>4} {'sticks':>6} {'tang.imp':>8} "
          f"{'stick ms':>9} {'ledger/hub':>10} {'ledger/term':>11}")
    for r in rows:
        ended = r["ended"] + (f" {r['theta']:.1f}°" if r["theta"] is not None else "")
        print(f"{r['rpm']:>5} {r['mu']:>4} {r['depth']:>5}  {ended:<14} {r['revolutions']:>4} {r['sticks']:>6} "
              f"{r['tangential']:>8} {1e3 * r['stick_time_s']:>9.3f} {r['worst_ledger']:>10.1e} "
              f"{r['worst_ledger_term']:>11.1e}")
    done = sum(r["ended"] == "complete" for r in rows)
    print(f"{done} of {len(rows)} complete; largest ledger residual of a revolution: "
          f"{max(r['worst_ledger'] for r in rows):.1e} of its hub work, "
          f"{max(r['worst_ledger_term'] for r in rows):.1e} of its largest term")
    return 0 if done == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
