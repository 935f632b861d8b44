"""A small sweep from Python: normal force against the tip's Y position (the thesis's Figures 6 and
8) for four hub speeds and three friction coefficients at 2 % depth, plotted with matplotlib.

    PYTHONPATH=build/python python3 examples/python/sweep.py [OUTPUT_DIR]
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

speeds = [550, 1000, 2000, 3000]
frictions = [0.1, 0.4, 0.7]
cases = [(s, mu) for s in speeds for mu in frictions]
with ThreadPoolExecutor() as pool:  # the C++ core releases the GIL
    results = list(pool.map(lambda c: rotbeam.run(overrides={"hub.speed_rpm": c[0], "surface.friction": c[1],
                                                             "output.interval_s": 2e-6}), cases))

fig, axes = plt.subplots(1, len(frictions), figsize=(13, 5.4), sharey=True)
for ax, mu in zip(axes, frictions):
    impacts_only = []
    for (speed, m), r in zip(cases, results):
        if m != mu:
            continue
        h = r.history
        contact = np.isin(h["phase"], ["contact", "stick"])  # sustained contact, sliding or stuck
        if not contact.any():  # no force to draw: said in the title, not a legend entry without data
            impacts_only.append(f"{speed} rpm ({r.summary['impacts']} impacts)")
            continue
        ax.plot(h["y_tip_m"][contact] * 1e3, h["normal_force_n"][contact], ".", ms=2,
                label=f"{speed} rpm: {r.summary['impacts']} impacts, {r.summary['contact_episodes']} "
                      f"episode{'' if r.summary['contact_episodes'] == 1 else 's'}")
    only = f"\nimpacts only, no sustained contact: {', '.join(impacts_only)}" if impacts_only else ""
    ax.set_title(f"μ = {mu}, depth 2 %{only}", fontsize=10)
    ax.set_xlabel("tip position Y (mm)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), markerscale=4)  # below: over no point
axes[0].set_ylabel("normal force F_n (N)")
fig.suptitle("Sustained-contact normal force along the surface (adaptive scheme, 5 modes)")
fig.tight_layout()
fig.savefig(out / "sweep_normal_force.png", dpi=120)

print("speed_rpm friction impacts contact_episodes last_separation_deg peak_normal_force_n normal_impulse_n_s")
for (speed, mu), r in zip(cases, results):
    s = r.summary
    print(f"{speed:9d} {mu:8.1f} {s['impacts']:7d} {s['contact_episodes']:16d} {s['last_separation_deg']:19.4f} "
          f"{s['peak_normal_force_n']:19.4f} {s['normal_impulse_n_s']:18.4e}")
print(f"wrote {out / 'sweep_normal_force.png'}")
