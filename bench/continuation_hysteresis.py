#!/usr/bin/python3
"""Brute-force sweeps up and down in the hub speed, each speed started from the previous speed's final
state (its section state at the end of its steady-state search), to confirm a fold that `rotbeam
continue` located (docs/continuation.md): going up, the orbit of the branch persists to the fold and
then jumps; going down, the other orbit persists past it — hysteresis.

Usage: bench/continuation_hysteresis.py [--config examples/casing-rub.toml] [--speeds 1068,1070,…]
Prints, per speed and direction, the last revolution's peak normal force and impacts and whether the
steady state was reached. Needs the rotbeam Python package (PYTHONPATH=build/python).
"""
import argparse
import pathlib
import sys

import rotbeam

REPO = pathlib.Path(__file__).resolve().parent.parent


def run(config, rpm, q=None, qd=None):
    o = {"hub.speed_rpm": rpm, "simulation.until_steady": True, "simulation.revolutions": 200,
         "simulation.multipliers": False}
    if q is not None:
        o.update({"initial.start": "flexible", "initial.modal_displacement": q, "initial.modal_velocity": qd})
    r = rotbeam.run(config, o)
    n = r.summary["config"]["beam"]["modes"]
    # The run ends at a section (θ0 + 360° k): its last row is the state the next speed starts from.
    q = [float(r.history[f"q{i}_m"][-1]) for i in range(1, n + 1)]
    qd = [float(r.history[f"qd{i}_m_s"][-1]) for i in range(1, n + 1)]
    return q, qd, r.summary


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--config", default=str(REPO / "examples" / "casing-rub.toml"))
    ap.add_argument("--speeds", default="1068,1070,1072,1073,1073.5,1074,1074.5,1075,1076,1078",
                    help="ascending speeds [rpm]; swept up, then down")
    a = ap.parse_args()
    speeds = [float(s) for s in a.speeds.split(",")]
    for label, order in (("up", speeds), ("down", speeds[::-1])):
        q = qd = None
        for s in order:
            q, qd, summary = run(a.config, s, q, qd)
            lr = summary.get("last_revolution") or {}
            st = summary["steady_state"]
            print(f"{label:4s} {s:9.2f} rpm  peak force {lr.get('peak_normal_force_n', float('nan')):.5f} N  "
                  f"impacts {lr.get('impacts')}  steady {st['reached']} (period {st['period_revolutions']})", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
