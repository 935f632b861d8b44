"""A filament in operation: the periodic steady state's mean hub torque and power against the hub
speed, for a damped filament (ζ = 0.03 on every mode) at 2 % depth and μ = 0.4, with matplotlib.

Each speed runs revolution after revolution until the section state repeats (the steady state,
simulation.until_steady) or the cap; the means are over the orbit's last revolution (over its
whole period when the orbit repeats every m > 1 revolutions). Speeds where no steady state was
found within the cap are drawn hollow, with the mean of the last complete revolution; speeds
whose run stopped on a numerical failure (a Painlevé configuration at high speed, say) are named
under the plot and left out of the curves.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/steady_torque.py [OUTPUT_DIR] [SPEEDS_RPM ...]
"""

import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rotbeam

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
out.mkdir(parents=True, exist_ok=True)
speeds = [float(s) for s in sys.argv[2:]] or [250, 300, 350, 400, 450, 500, 550, 600, 650, 700, 750, 800, 850]
settings = {"beam.damping_ratio": 0.03, "simulation.until_steady": True, "simulation.revolutions": 200,
            "output.interval_s": 1e-4}


def steady(speed):
    r = rotbeam.run(overrides={**settings, "hub.speed_rpm": speed})
    st = r.summary["steady_state"]
    if r.failure:
        return {"speed_rpm": speed, "failure": r.failure["kind"],
                "where": f"revolution {len(r.revolutions['revolution'])}", "reached": False}
    complete = r.revolutions["complete"]
    rev = {k: v[complete] for k, v in r.revolutions.items()}
    m = st["period_revolutions"] if st["reached"] else 1
    last = slice(len(rev["revolution"]) - m, None)  # the orbit's period (or the last complete revolution)
    dt = rev["t_end_s"][last] - rev["t_start_s"][last]
    work = rev["hub_work_j"][last].sum()
    omega = speed * np.pi / 30.0
    return {"speed_rpm": speed, "failure": None, "reached": st["reached"], "period": m, "after": st["after_revolutions"],
            "torque_n_m": work / (omega * dt.sum()), "power_w": work / dt.sum(),
            "impacts": int(rev["impacts"][last].sum()) / m, "largest_multiplier":
                max((mu["abs"] for mu in st["multipliers"]), default=float("nan")), "note": st["note"]}


with ThreadPoolExecutor() as pool:  # the C++ core releases the GIL
    results = list(pool.map(steady, speeds))
rows = [r for r in results if r["failure"] is None]
failed = [r for r in results if r["failure"] is not None]

fig, (ax_t, ax_p) = plt.subplots(1, 2, figsize=(11, 5.0))
for ax, key, scale, label in ((ax_t, "torque_n_m", 1e3, "mean hub torque (mN m)"),
                              (ax_p, "power_w", 1e3, "mean hub power (mW)")):
    x = np.array([r["speed_rpm"] for r in rows])
    y = np.array([r[key] for r in rows]) * scale
    ok = np.array([r["reached"] for r in rows])
    ax.plot(x, y, "-", color="0.7", zorder=1)
    if ok.any():
        ax.plot(x[ok], y[ok], "o", color="C0", label="steady state (orbit's period)", zorder=2)
    if (~ok).any():
        ax.plot(x[~ok], y[~ok], "o", mfc="none", color="C3",
                label=f"no steady state in {settings['simulation.revolutions']} revolutions (last revolution)",
                zorder=2)
    for r, yy in zip(rows, y):
        if r["reached"] and r["period"] > 1:
            ax.annotate(f"period {r['period']}", (r["speed_rpm"], yy), textcoords="offset points", xytext=(4, 4),
                        fontsize=7)
    ax.set_xlabel("hub speed (rpm)")
    ax.set_ylabel(label)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14))  # below the axes: over no point
if failed:
    fig.text(0.01, 0.01, "no value (the run stopped on a numerical failure): " +
             ", ".join(f"{r['speed_rpm']:.0f} rpm ({r['failure']}, {r['where']})" for r in failed), fontsize=7)
fig.suptitle("Steady state of a damped filament (ζ = 0.03, 5 modes, depth 2 %, μ = 0.4): the hub's mean "
             "torque and power per revolution", fontsize=10)
fig.tight_layout(rect=(0, 0.04 if failed else 0, 1, 1))
fig.savefig(out / "steady_torque_power.png", dpi=120)

print("speed_rpm reached period after_revolutions impacts_per_rev torque_mN_m power_mW largest_|mu|")
for r in rows:
    print(f"{r['speed_rpm']:9.0f} {str(r['reached']):>7} {r['period']:6d} {r['after']:17d} {r['impacts']:15.1f} "
          f"{r['torque_n_m'] * 1e3:11.4f} {r['power_w'] * 1e3:8.3f} {r['largest_multiplier']:12.3f}")
for r in failed:
    print(f"{r['speed_rpm']:9.0f} stopped: {r['failure']} in {r['where']}")
print(f"wrote {out / 'steady_torque_power.png'}")
