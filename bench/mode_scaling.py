#!/usr/bin/python3
"""Whole-pass cost against the mode count, and the accuracy each variant reaches.

Runs `rotbeam run` on the base case (or a case given with --set) for n = 5, 10, 20, 30 modes with
the adaptive scheme's variants, in one run so that the ratios compare like with like on a shared
machine:

  plain        simulation.integrating_factor = false (Dormand-Prince 5(4) on q, q')
  factor       the default: the integrating factor (linear modal oscillation propagated exactly)
  factor+clear the default plus simulation.end_when_clear = true (the pass ends once no touch can
               happen before the end angle)

For each it reports the median CPU time of the CLI process over --repeats runs (user + system, from
the child's resource usage: process start, the modal integrals and the output files included),
steps, right-hand-side evaluations, and the errors of the last separation angle [deg] and of the
normal impulse [relative] against a reference run at rtol 1e-12, atol 1e-15 (with the integrating
factor: at 5 and 10 modes it agrees with the plain scheme's rtol-1e-12 run to 3e-11 deg and 2.5e-8
deg; docs/performance.md). Plain runs above --plain-max-modes are skipped (they take minutes).

Usage: bench/mode_scaling.py [--modes 5,10,20,30] [--repeats 3] [--set key=value ...]
                             [--rotbeam build/rotbeam] [--plain-max-modes 10] [--json]
"""
import argparse
import json
import os
import pathlib
import resource
import statistics
import subprocess
import sys
import tempfile

REPO = pathlib.Path(__file__).resolve().parent.parent


def run_cli(rotbeam, sets, out):
    """Runs one pass; returns (cpu seconds of the child, summary dict)."""
    cmd = [str(rotbeam), "run", "--quiet", "-o", str(out)]
    for s in sets:
        cmd += ["--set", s]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise SystemExit(f"mode_scaling: {' '.join(cmd)} exited {proc.returncode}: {proc.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    with open(out / "summary.json") as f:
        return cpu, json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--modes", default="5,10,20,30")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--set", action="append", default=[], help="a configuration override for every run")
    ap.add_argument("--rotbeam", default=str(REPO / "build" / "rotbeam"))
    ap.add_argument("--plain-max-modes", type=int, default=10)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    if args.repeats < 1:
        raise SystemExit("mode_scaling: --repeats must be at least 1")
    modes = [int(m) for m in args.modes.split(",") if m]
    variants = [("plain", ["simulation.integrating_factor=false"]), ("factor", []),
                ("factor+clear", ["simulation.end_when_clear=true"])]
    rows = []
    with tempfile.TemporaryDirectory(prefix="rotbeam-scaling-") as tmp:
        tmp = pathlib.Path(tmp)
        for n in modes:
            base = args.set + [f"beam.modes={n}"]
            print(f"n = {n}: reference (rtol 1e-12) ...", file=sys.stderr, flush=True)
            _, ref = run_cli(args.rotbeam, base + ["simulation.rtol=1e-12", "simulation.atol=1e-15"], tmp / f"ref{n}")
            for name, extra in variants:
                if name == "plain" and n > args.plain_max_modes:
                    continue
                cpus = []
                for k in range(args.repeats):
                    print(f"n = {n}: {name} run {k + 1}/{args.repeats} ...", file=sys.stderr, flush=True)
                    cpu, s = run_cli(args.rotbeam, base + extra, tmp / f"{name}{n}")
                    cpus.append(cpu)
                rows.append({
                    "modes": n, "variant": name, "cpu_s": statistics.median(cpus), "steps": s["steps"],
                    "rhs_evaluations": s["rhs_evaluations"], "impacts": s["impacts"], "impacts_ref": ref["impacts"],
                    "last_separation_error_deg": s["last_separation_deg"] - ref["last_separation_deg"],
                    "impulse_error": s["normal_impulse_n_s"] / ref["normal_impulse_n_s"] - 1.0,
                    "ended_clear_deg": s.get("ended_clear_deg"),
                })
    if args.json:
        json.dump(rows, sys.stdout, indent=1)
        print()
        return
    print(f"| n | variant | CPU [s] (median of {args.repeats}) | steps | RHS | impacts (ref) | "
          "last separation error [deg] | impulse error [rel] | ended at [deg] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        ended = "" if r["ended_clear_deg"] is None else f"{r['ended_clear_deg']:.2f}"
        print(f"| {r['modes']} | {r['variant']} | {r['cpu_s']:.3f} | {r['steps']} | {r['rhs_evaluations']} | "
              f"{r['impacts']} ({r['impacts_ref']}) | {r['last_separation_error_deg']:.1e} | "
              f"{r['impulse_error']:.1e} | {ended} |")


if __name__ == "__main__":
    main()
