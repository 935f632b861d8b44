"""Pictures of a wear folder (`rotbeam wear`, docs/wear.md): wear.png, four panels over operating time
(the filament's length, the mean normal force and hub torque, the surface's removal rate and the
frictional heat) and the surface's removed depth along it after the whole run."""

import json
from pathlib import Path

# rotbeam._figures first: where matplotlib is missing it says so in one line.
from ._figures import draw_all

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ._csv import read_csv, read_study_summary  # noqa: E402
from ._surface import surface_words  # noqa: E402


class DamagedWear(Exception):
    """A wear folder whose files are not those its summary.json describes."""


def is_wear_folder(folder):
    """True when folder's summary.json is a wear run's (`rotbeam wear`)."""
    try:
        return json.loads((Path(folder) / "summary.json").read_text()).get("kind") == "wear"
    except (ValueError, AttributeError, OSError):
        return False


def read_wear(folder):
    """(summary, history, depth) of a wear folder, checked against the sizes summary.json records."""
    folder = Path(folder)
    summary = read_study_summary(folder, "wear", DamagedWear)
    return (summary, read_csv(folder / "wear_history.csv", error=DamagedWear),
            read_csv(folder / "wear_depth.csv", error=DamagedWear))


def _empty(ax, text):
    ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", va="center", fontsize=9)


def wear_figure(summary, history, depth):
    """wear.png: length, force and torque, removal and heat against operating time; the removed depth."""
    fig, axes = plt.subplots(2, 2, figsize=(12, 8))
    (a_len, a_force), (a_rate, a_depth) = axes
    t = np.asarray(history["time_h"], float)
    if t.size == 0:
        for ax in (a_len, a_force, a_rate):
            _empty(ax, "no slow step was run")
    else:
        a_len.plot(t, history["length_m"] * 1e3, "o-", ms=3, color="C0")
        a_len.set_ylabel("filament length L (mm)")
        a_force.plot(t, history["mean_normal_force_n"], "o-", ms=3, color="C0", label="mean normal force (N)")
        a_force.set_ylabel("mean normal force (N)", color="C0")
        a_torque = a_force.twinx()
        a_torque.plot(t, history["mean_hub_torque_n_m"] * 1e3, "s--", ms=3, color="C2", label="hub torque (mN·m)")
        a_torque.set_ylabel("mean hub torque (mN·m)", color="C2")
        a_rate.plot(t, history["removal_rate_mm3_h"], "o-", ms=3, color="C1")
        a_rate.set_ylabel("surface removal rate (mm³/h)", color="C1")
        a_heat = a_rate.twinx()
        a_heat.plot(t, history["heat_w"], "s--", ms=3, color="C3")
        a_heat.set_ylabel("frictional heat (W)", color="C3")
        for ax in (a_len, a_force, a_rate):
            ax.set_xlabel("operating time (h)")
            ax.grid(alpha=0.3)
    unit = summary.get("coordinate_unit", "m")
    if len(depth["position_from_m"]) == 0:
        _empty(a_depth, "no contact: the surface did not wear")
    else:
        if unit == "deg":
            x = 0.5 * (depth["coordinate_from"] + depth["coordinate_to"])
            a_depth.set_xlabel(f"{summary.get('coordinate', 'angle')} (°)")
        else:
            x = 0.5 * (depth["position_from_m"] + depth["position_to_m"]) * 1e3
            a_depth.set_xlabel(f"{summary.get('coordinate', 'position')} (mm)")
        a_depth.step(x, depth["removed_depth_m"] * 1e6, where="mid", color="C1")
        ran = history["time_h"][-1] if t.size else 0.0
        a_depth.set_ylabel(f"removed depth after {ran:.4g} h (µm)")
        a_depth.grid(alpha=0.3)
    a_len.set_title("the filament shortens by its tip's wear", fontsize=9)
    a_force.set_title("the force and torque it then gives", fontsize=9)
    a_rate.set_title("the surface's removal rate and the heat made", fontsize=9)
    a_depth.set_title(f"the surface's worn track (width {summary['track_width_m'] * 1e3:.3g} mm)", fontsize=9)
    c = summary["config"]
    note = f"\n{summary['note']}" if summary.get("note") else ""
    fig.suptitle(f"Wear over {summary['hours']:g} h: {c['hub']['speed_rpm']:g} rpm, {surface_words(c)}, "
                 f"μ = {c['surface']['friction']:g}; L lost {summary['length_lost_m'] * 1e6:.4g} µm, "
                 f"{summary['volume_removed_m3'] * 1e9:.4g} mm³ removed, {summary['heat_j']:.4g} J of heat" + note,
                 fontsize=10)
    fig.tight_layout()
    return fig


def wear_figures(folder):
    """[(name, figure)] of a wear folder, its files read and checked first."""
    summary, history, depth = read_wear(folder)
    return draw_all((("wear", lambda: wear_figure(summary, history, depth)),))
