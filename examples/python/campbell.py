"""Campbell diagram from Python: the in-plane natural frequencies of the spinning filament against
hub speed, with the engine-order lines f = k·rpm/60.

    PYTHONPATH=build/python python3 examples/python/campbell.py [OUTPUT_DIR]
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rotbeam

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
out.mkdir(parents=True, exist_ok=True)

speeds = np.linspace(0, 5000, 51)
m = rotbeam.modes(overrides={"beam.modes": 6}, speeds_rpm=speeds)
f = m["frequencies_hz"]

fig, ax = plt.subplots(figsize=(8, 5.5))
for k in range(f.shape[1]):
    ax.plot(m["speeds_rpm"], f[:, k], lw=2, label=f"mode {k + 1}")
for order in (1, 2, 5, 10, 20):
    ax.plot(speeds, order * speeds / 60.0, "k--", lw=0.7, alpha=0.6)
    # Beside the axes, where each line leaves them: over no curve.
    ax.annotate(f"{order}×", (speeds[-1], order * speeds[-1] / 60.0), xytext=(4, 0), textcoords="offset points",
                fontsize=8, va="center", ha="left", annotation_clip=False)
ax.set_yscale("log")
ax.set_ylim(10, 2e4)
ax.set_xlabel("hub speed (rpm)")
ax.set_ylabel("natural frequency (Hz)")
ax.set_title("Campbell diagram: filament L = 63.5 mm, D = 0.508 mm, hub r_h = 63.5 mm", fontsize=10)
ax.grid(alpha=0.3, which="both")
ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=6)  # below the axes: over no line
fig.tight_layout()
fig.savefig(out / "campbell.png", dpi=120)
print(f"f1 rises from {f[0, 0]:.2f} Hz at rest to {f[-1, 0]:.2f} Hz at {speeds[-1]:.0f} rpm; wrote {out / 'campbell.png'}")
