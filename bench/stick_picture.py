#!/usr/bin/python3
"""Draws docs/images/stick_phase.png: a stick–slip sequence and a tangential impact of the rigid law
under the adaptive scheme (docs/contact.md, "Stick and Painlevé's paradox").

Runs `rotbeam run` on the base filament with damping (ζ = 0.03) with a fine history and draws
(left) the tip's slip speed V_t and (right) the normal force, |F_t| and the cone μF_n, with the stick
intervals shaded: above, the second revolution's contact at 1000 rpm, μ = 0.4, 2 % depth; below, the
episode a tangential impact opens in the fourth revolution at 1200 rpm, μ = 0.7, 1 % depth.

    bench/stick_picture.py [--rotbeam build/rotbeam] [--image docs/images/stick_phase.png]
"""
import argparse
import csv
import pathlib
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REPO = pathlib.Path(__file__).resolve().parent.parent
TOP = dict(rpm=1000, mu=0.4, depth=0.02, revolutions=2)
BOTTOM = dict(rpm=1200, mu=0.7, depth=0.01, revolutions=4)


def read(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def window(rows, events, kind_from, pad_deg):
    """The rows from `pad_deg` before the first event of kind_from to pad_deg after its episode."""
    start = next(e for e in events if kind_from(e))
    t0 = float(start["theta_deg"])
    end = next((float(e["theta_deg"]) for e in events
                if float(e["theta_deg"]) > t0 and e["kind"] in ("contact_end", "lift_off")), t0 + 1.0)
    lo, hi = t0 - pad_deg, end + pad_deg
    return [r for r in rows if lo <= float(r["theta_deg"]) <= hi], start, lo, hi


def run(rotbeam, case, folder):
    """The case's last revolution: its history and events."""
    sets = ["beam.damping_ratio=0.03", f"hub.speed_rpm={case['rpm']}", f"surface.friction={case['mu']}",
            f"surface.depth_fraction={case['depth']}", f"simulation.revolutions={case['revolutions']}",
            "output.history_revolutions=1", "output.interval_s=2e-7"]
    cmd = [rotbeam, "run", "-o", folder, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=False, capture_output=True)
    return read(pathlib.Path(folder) / "history.csv"), read(pathlib.Path(folder) / "events.csv")


def draw(ax_v, ax_f, rows, events, lo, hi, title, mu):
    th = [float(r["theta_deg"]) for r in rows]
    ax_v.plot(th, [float(r["vy_m_s"]) for r in rows], color="C0", lw=1.0, label="V_t (tip slip along the plane)")
    ax_f.plot(th, [float(r["normal_force_n"]) for r in rows], color="C1", lw=1.0, label="F_n")
    ax_f.plot(th, [abs(float(r["friction_force_n"])) for r in rows], color="C2", lw=1.0, label="|F_t|")
    ax_f.plot(th, [mu * float(r["normal_force_n"]) for r in rows], color="C3", lw=0.8, ls="--", label="μF_n")
    # Stick intervals, shaded on both panels.
    start = None
    for e in events:
        x = float(e["theta_deg"])
        if not lo <= x <= hi:
            continue
        if e["kind"] == "stick_start":
            start = x
        elif e["kind"] == "stick_end" or (e["kind"] in ("contact_end", "lift_off") and start is not None):
            for ax in (ax_v, ax_f):
                ax.axvspan(start, x, color="0.85", lw=0)
            start = None
        if e["kind"] == "impact" and e["detail"].startswith("tangential"):
            for ax in (ax_v, ax_f):
                ax.axvline(x, color="C4", lw=1.2, ls=":")
    ax_v.set_title(title, fontsize=9)
    ax_v.set_ylabel("V_t [m/s]")
    ax_f.set_ylabel("force [N]")
    for ax in (ax_v, ax_f):
        ax.set_xlabel("hub angle θ [deg]")
        ax.set_xlim(lo, hi)
        ax.grid(alpha=0.3)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rotbeam", default=str(REPO / "build" / "rotbeam"))
    ap.add_argument("--image", default=str(REPO / "docs" / "images" / "stick_phase.png"))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as a, tempfile.TemporaryDirectory() as b:
        top, bottom = run(args.rotbeam, TOP, a), run(args.rotbeam, BOTTOM, b)
    fig, axes = plt.subplots(2, 2, figsize=(11, 7), constrained_layout=True)
    rows, events = top
    w1, _, lo1, hi1 = window(rows, events, lambda e: e["kind"] == "stick_start", 0.3)
    draw(axes[0][0], axes[0][1], w1, events, lo1, hi1,
         f"{TOP['rpm']} rpm, μ = {TOP['mu']}: stick–slip, sticks shaded (V_t = 0, |F_t| < μF_n)", TOP["mu"])
    rows, events = bottom
    tangential = [e for e in events if e["kind"] == "impact" and e["detail"].startswith("tangential")]
    if tangential:
        w2, _, lo2, hi2 = window(rows, events, lambda e: e is tangential[0], 0.3)
        draw(axes[1][0], axes[1][1], w2, events, lo2, hi2,
             f"{BOTTOM['rpm']} rpm, μ = {BOTTOM['mu']}: a tangential impact (dotted) at a Painlevé point, then sticks",
             BOTTOM["mu"])
    else:
        for ax in axes[1]:
            ax.text(0.5, 0.5, "no tangential impact in this revolution", ha="center", va="center",
                    transform=ax.transAxes)
            ax.set_axis_off()
    for ax in (axes[0][0], axes[0][1]):
        ax.legend(loc="upper right", fontsize=8)
    fig.suptitle("Rigid law, adaptive scheme: base filament, ζ = 0.03", fontsize=10)
    fig.savefig(args.image, dpi=110)
    print("wrote", args.image)
    return 0


if __name__ == "__main__":
    sys.exit(main())
