"""Pictures of a continuation folder (`rotbeam continue`, docs/continuation.md): continuation.png, the
bifurcation diagram — the peak normal force and the mean hub power of one period, and the largest
multiplier, against the continued key — stable orbits solid, unstable dashed, the special points
marked, the Campbell diagram's engine-order crossings where the key is the hub speed, and a
brute-force sweep's steady states over it when one is given."""

import json
from pathlib import Path

# rotbeam._figures first: where matplotlib is missing it says so in one line.
from ._figures import draw_all

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ._csv import read_csv, read_study_summary  # noqa: E402


class DamagedContinuation(Exception):
    """A continuation folder whose files are not those its summary.json describes."""


MARKS = {"fold": ("^", "C3", "fold"), "branch_point": ("o", "C4", "branch point"),
         "period_doubling": ("s", "C1", "period doubling"), "neimark_sacker": ("D", "C2", "Neimark–Sacker"),
         "grazing": ("x", "0.35", "grazing (impacts change)")}


def is_continuation_folder(folder):
    """True when folder's summary.json is a continuation's (`rotbeam continue`)."""
    try:
        return json.loads((Path(folder) / "summary.json").read_text()).get("kind") == "continuation"
    except (ValueError, AttributeError, OSError):
        return False


def read_continuation(folder):
    """(summary, branch) of a continuation folder, checked against the sizes summary.json records."""
    folder = Path(folder)
    summary = read_study_summary(folder, "continuation", DamagedContinuation)
    branch = read_csv(folder / "branch.csv", modes=2 * int(summary.get("modes", 0)), error=DamagedContinuation)
    return summary, branch


def _unit(key):
    return {"hub.speed_rpm": "rpm", "surface.friction": "-", "surface.clearance_m": "m",
            "surface.lobe_amplitude_m": "m", "surface.depth_fraction": "-"}.get(key, "as in the configuration")


def _segments(ax, x, y, branch, stable, colors):
    """Each branch as a line, solid between stable points and dashed elsewhere."""
    for b in np.unique(branch):
        idx = np.flatnonzero(branch == b)
        color = colors[int(b) % len(colors)]
        for i, j in zip(idx[:-1], idx[1:]):
            style = "-" if stable[i] and stable[j] else "--"
            ax.plot(x[[i, j]], y[[i, j]], style, color=color, lw=1.4)


def _brute_force(path, key):
    """(speeds, peak force, steady) of a brute-force sweep over `key`, or None."""
    sweep = Path(path) / "sweep.csv" if Path(path).is_dir() else Path(path)
    table = read_csv(sweep, error=DamagedContinuation)
    if key not in table:
        raise DamagedContinuation(f"{sweep}: has no column {key} (the continued key)")
    steady = np.asarray(table.get("steady_after_revolutions", np.zeros(len(table[key]))), float) > 0
    force = table.get("last_revolution_peak_normal_force_n", table.get("peak_normal_force_n"))
    if force is None:
        raise DamagedContinuation(f"{sweep}: has no peak normal force column to draw")
    force = np.asarray(force, float)
    return np.asarray(table[key], float), force, steady


def continuation_figure(summary, branch, brute_force=None):
    key = summary["parameter"]
    x = np.asarray(branch["parameter"], float)
    fig, (a_force, a_power, a_mu) = plt.subplots(3, 1, figsize=(11, 10), sharex=True)
    colors = ["C0", "C1", "C2", "C4", "C5", "C6", "C7", "C8", "C9"]
    if x.size == 0:
        for ax in (a_force, a_power, a_mu):
            ax.text(0.5, 0.5, "no point was found: " + (summary["branches"][0]["end"] if summary["branches"] else ""),
                    transform=ax.transAxes, ha="center", va="center", fontsize=9, wrap=True)
    else:
        b = np.asarray(branch["branch"], int)
        stable = np.asarray(branch["stable"], bool)
        _segments(a_force, x, np.asarray(branch["peak_normal_force_n"], float), b, stable, colors)
        _segments(a_power, x, np.asarray(branch["mean_hub_power_w"], float), b, stable, colors)
        _segments(a_mu, x, np.asarray(branch["max_abs_multiplier"], float), b, stable, colors)
        a_mu.axhline(1.0, color="k", lw=0.8, ls=":")
        a_mu.set_yscale("log")
        a_force.plot([], [], "-", color="k", label="stable orbit")
        a_force.plot([], [], "--", color="k", label="unstable orbit")
        seen = set()
        rows = {"peak_normal_force_n": a_force, "mean_hub_power_w": a_power, "max_abs_multiplier": a_mu}
        for sp in summary["special_points"]:
            marker, color, label = MARKS.get(sp["kind"], ("*", "k", sp["kind"]))
            i, j = sp["between_rows"]
            if not (0 <= i < x.size and 0 <= j < x.size):
                continue
            for column, ax in rows.items():
                y = np.asarray(branch[column], float)
                t = 0.5 if x[j] == x[i] else np.clip((sp["parameter"] - x[i]) / (x[j] - x[i]), 0, 1)
                ax.plot(sp["parameter"], y[i] + t * (y[j] - y[i]), marker, color=color, ms=7, mfc="none", mew=1.5,
                        label=label if (ax is a_force and label not in seen) else None)
            seen.add(label)
        if brute_force is not None:
            bx, bf, bsteady = brute_force
            if bsteady.any():
                a_force.plot(bx[bsteady], bf[bsteady], "o", color="0.5", ms=3, label="brute force: steady")
            if (~bsteady).any():
                a_force.plot(bx[~bsteady], bf[~bsteady], "o", color="0.5", ms=3, mfc="none",
                             label="brute force: not steady (last revolution)")
        for ax in (a_force, a_power, a_mu):
            ax.grid(alpha=0.3)
        crossings = summary.get("engine_order_crossings", [])
        lo, hi = min(summary["from"], summary["to"]), max(summary["from"], summary["to"])
        for c in crossings:
            if lo <= c["speed_rpm"] <= hi:
                for ax in (a_force, a_power, a_mu):
                    ax.axvline(c["speed_rpm"], color="0.75", lw=0.7, ls=":", zorder=0)
                a_force.annotate(f"{c['order']}×, mode {c['mode']}", (c["speed_rpm"], 1.0),
                                 xycoords=("data", "axes fraction"), rotation=90, fontsize=6, va="top", ha="right",
                                 color="0.45")
        a_force.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
        if any(lo <= c["speed_rpm"] <= hi for c in crossings):
            a_mu.plot([], [], ":", color="0.6", label="engine-order crossing (Campbell)")
            a_mu.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    a_force.set_ylabel("peak normal force over a period (N)")
    a_power.set_ylabel("mean hub power (W)")
    a_mu.set_ylabel("largest |multiplier| (-)")
    a_mu.set_xlabel(f"{key} ({_unit(key)})")
    c = summary["config"]
    stalled = sum("stalled" in b["end"] for b in summary["branches"])
    branches = (f"{len(summary['branches'])} branch" + ("es" if len(summary["branches"]) != 1 else "") +
                (f", {stalled} stalled where the map is not smooth (summary.json says where)" if stalled else ""))
    incomplete = "" if summary.get("complete", True) else "; interrupted: the orbits found so far"
    fig.suptitle(f"Continuation in {key} from {summary['from']:g} to {summary['to']:g}: {summary['points']} orbits, "
                 f"{summary['stable_points']} stable; {c['beam']['modes']} modes\n{branches}; "
                 f"{summary['map_evaluations']} map evaluations, {summary['wall_time_s']:.0f} s{incomplete}", fontsize=9)
    fig.tight_layout()
    return fig


def continuation_figures(folder, brute_force=None):
    """[(name, figure)] of a continuation folder, its files read and checked first; brute_force: a
    sweep folder (or its sweep.csv) over the same key whose steady states are drawn over it."""
    summary, branch = read_continuation(folder)
    bf = _brute_force(brute_force, summary["parameter"]) if brute_force else None
    return draw_all((("continuation", lambda: continuation_figure(summary, branch, bf)),))
