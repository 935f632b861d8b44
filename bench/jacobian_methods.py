#!/usr/bin/python3
"""The revolution map's Jacobian two ways (simulation.jacobian): central differences of the map (4n
runs of a revolution) and the variational equations with saltation matrices (one run). For each
case the steady orbit is found by brute force, then its Floquet multipliers are computed by each
method; the cost of the multipliers is the run's wall time less that of the same run without them.
Then the whole shooting search (Newton on the map, its Jacobian by each method) is timed.

Usage: bench/jacobian_methods.py [--repeat 3] [--cases 0,1,…]
Prints, per case: the multipliers' cost by each method (median of the repeats), their ratio, the
largest multiplier by each method and their largest difference, and the shooting search's time by
each method. Needs the rotbeam Python package (PYTHONPATH=build/python).
"""
import argparse
import pathlib
import statistics

import rotbeam

REPO = pathlib.Path(__file__).resolve().parent.parent

CASES = {
    "3 modes, impacts (800 rpm, e 0.6, mu 0.1, zeta 0.02)": (None, {
        "beam.modes": 3, "beam.damping_ratio": 0.02, "surface.friction": 0.1, "hub.speed_rpm": 800,
        "impact.restitution": 0.6}),
    "base case, zeta 0.03 (5 modes, impacts and sliding)": (None, {"beam.damping_ratio": 0.03}),
    "casing rub at 1003 rpm (examples/casing-rub.toml)": (str(REPO / "examples" / "casing-rub.toml"),
                                                           {"hub.speed_rpm": 1003}),
    "3 modes, frictionless Hertz contact (800 rpm)": (None, {
        "beam.modes": 3, "beam.damping_ratio": 0.02, "surface.friction": 0.0, "hub.speed_rpm": 800,
        "contact.model": "hertz"}),
}


def run(config, overrides):
    o = {"simulation.until_steady": True, "simulation.revolutions": 400, "simulation.steady_tolerance": 1e-9}
    o.update(overrides)
    return rotbeam.run(config, o).summary


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cases", default="", help="indices of the cases to run (default: all)")
    a = ap.parse_args()
    chosen = {int(i) for i in a.cases.split(",")} if a.cases else set(range(len(CASES)))
    for index, (name, (config, sets)) in enumerate(CASES.items()):
        if index not in chosen:
            continue
        t = {"off": [], "differences": [], "variational": []}
        mu = {}
        note = {}
        for _ in range(a.repeat):
            for method in t:
                extra = dict(sets)
                if method == "off":
                    extra["simulation.multipliers"] = False
                else:
                    extra["simulation.jacobian"] = method
                s = run(config, extra)
                t[method].append(s["wall_time_s"])
                if method != "off":
                    st = s["steady_state"]
                    mu[method] = [complex(m["re"], m["im"]) for m in st["multipliers"]]
                    note[method] = st["jacobian"]
        off = statistics.median(t["off"])
        cost = {m: statistics.median(t[m]) - off for m in ("differences", "variational")}
        print(name)
        if mu["differences"] and mu["variational"]:
            diff = max(abs(x - y) for x, y in zip(mu["differences"], mu["variational"]))
            print(f"  search alone {off:.3f} s; multipliers by differences {cost['differences']:.3f} s, "
                  f"variational {cost['variational']:.3f} s ({note['variational']}): ratio "
                  f"{cost['variational'] / cost['differences']:.3f}\n  largest |mu|: {abs(mu['differences'][0]):.6f} "
                  f"(differences), {abs(mu['variational'][0]):.6f} (variational); largest difference {diff:.2e}")
        else:
            print(f"  brute force found no steady state in 400 revolutions ({off:.1f} s): no multipliers")
        shoot = {}
        for method in ("differences", "variational"):
            times, last = [], None
            for _ in range(a.repeat):
                extra = dict(sets)
                extra.update({"simulation.steady_method": "shooting", "simulation.jacobian": method})
                last = run(config, extra)
                times.append(last["wall_time_s"])
            st = last["steady_state"]
            shoot[method] = statistics.median(times)
            print(f"  shooting, Jacobian by {method}: {shoot[method]:.3f} s, reached {st['reached']}, "
                  f"{st['newton_iterations']} Newton iterations, {st['map_evaluations']} map evaluations, "
                  f"used {st['jacobian'] or '-'}; largest |mu| "
                  f"{st['multipliers'][0]['abs'] if st['multipliers'] else float('nan'):.6f}")
        print(f"  shooting time ratio variational / differences: {shoot['variational'] / shoot['differences']:.3f}")


if __name__ == "__main__":
    main()
