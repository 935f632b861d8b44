"""Pictures of a brush folder (`rotbeam brush`, docs/brush.md) and of a sweep over brushes.

A brush folder (summary.json with "kind": "brush", workpiece.csv, profile.csv, filaments.csv) gives
brush_force.png (the force on the workpiece and the hub's torque against hub angle over one
revolution), brush_profile.png (the mean filament's force across the contact zone) and
brush_filaments.png (each filament's mean force against its length and its phase). A sweep over
brushes gives brush_map.png: the brush's mean forces, power, peak force, contact zone and force
ratio against the first varied key, a line per value of the others (force against depth, a line
per speed: the brush-stiffness curves brush makers measure).
"""

from pathlib import Path

# rotbeam._figures first: where matplotlib is missing it says so in one line.
from ._figures import DEG, draw_all

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ._csv import read_csv, read_study_summary  # noqa: E402
from ._surface import surface_words  # noqa: E402


class DamagedBrush(Exception):
    """A brush folder whose files are not those its summary.json describes."""


def read_brush(folder):
    """(summary, workpiece, profile, filaments) of a brush folder, checked: summary.json is a brush's
    and every file it lists has the size it records."""
    folder = Path(folder)
    summary = read_study_summary(folder, "brush", DamagedBrush)
    tables = [read_csv(folder / name, error=DamagedBrush)
              for name in ("workpiece.csv", "profile.csv", "filaments.csv")]
    return (summary, *tables)


def read_listed(folder, summary, name):
    """A table of a brush folder that older folders lack (representatives.csv, spectrum.csv), or None
    where the summary does not list it."""
    if name not in summary.get("files", {}):
        return None
    return read_csv(Path(folder) / name, error=DamagedBrush)


def spectrum_figure(summary, spectrum):
    """brush_spectrum.png: the amplitudes of the workpiece's normal force and of the hub torque by
    harmonic of the revolution, with the multiples of brush.filaments (the filaments around the
    hub) marked: identical, equally spaced filaments put their force there."""
    around = summary["config"]["brush"]["filaments"]
    order = np.asarray(spectrum["order"])
    shown = order <= max(8 * around, 40)
    fig, axes = plt.subplots(2, 1, figsize=(11, 7.5), sharex=True)
    for ax, column, label in ((axes[0], "normal_force_n", "normal force amplitude (N)"),
                              (axes[1], "hub_torque_n_m", "hub torque amplitude (N m)")):
        amplitude = np.asarray(spectrum[column])
        ax.vlines(order[shown][1:], 0, amplitude[shown][1:], color="C0", lw=1.2, label="harmonic of the revolution")
        top = np.max(amplitude[shown][1:]) if np.any(shown[1:]) else 0.0
        for k in range(1, int(order[shown].max() // around) + 1):
            ax.axvline(k * around, color="C3", lw=0.6, ls=":",
                       label=f"multiple of brush.filaments = {around}" if k == 1 else None)
        ax.set_ylabel(label)
        ax.set_ylim(0, 1.1 * top if top > 0 else 1)
        ax.grid(alpha=0.3)
        ax.set_title(f"mean (order 0): {amplitude[0]:.4g}", fontsize=9, loc="right")
        if around > order.max():
            ax.set_title(f"brush.filaments = {around} is beyond the bins' highest order ({order.max()}): "
                         "a finer output.bin_deg resolves it", fontsize=8, loc="left")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", ncol=2, fontsize=8, bbox_to_anchor=(0.5, 0.925))
    revolution_hz = spectrum["frequency_hz"][1] if len(order) > 1 else 0.0
    axes[1].set_xlabel(f"harmonic of the revolution (1) — × {revolution_hz:.4g} Hz")
    fig.suptitle(_title(summary) + "\nthe workpiece's force and the hub torque by harmonic of the revolution",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.9))
    return fig


def _title(summary):
    c = summary["config"]
    b = c["brush"]
    run = "representatives run" if summary.get("method") == "population" else "distinct"
    return (f"Brush of {summary['filaments']} filaments ({b['filaments']} around × {b['rows']} rows, "
            f"{summary['distinct_filaments']} {run}), {c['hub']['speed_rpm']:g} rpm, {surface_words(c)}, "
            f"μ = {c['surface']['friction']:g}")


def _centres(table):
    return 0.5 * (table["theta_from_deg"] + table["theta_to_deg"])


def force_figure(summary, workpiece):
    """brush_force.png: the workpiece's normal and tangential force and the hub torque per bin."""
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(11, 7), sharex=True)
    x = _centres(workpiece)
    ax.step(x, workpiece["normal_force_n"], where="mid", lw=1, label="normal")
    ax.step(x, workpiece["tangential_force_n"], where="mid", lw=1, label="tangential (along +Y)")
    ax.axhline(summary["mean_normal_force_n"], color="C0", ls="--", lw=0.8,
               label=f"mean normal {summary['mean_normal_force_n']:.4g} N")
    ax.set_ylabel(f"force on the workpiece (N)\nmomentum per {summary['bin_deg']:g}{DEG} bin / its duration")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    ax2.step(x, workpiece["hub_torque_n_m"] * 1e3, where="mid", lw=1, color="C2")
    ax2.axhline(summary["mean_hub_torque_n_m"] * 1e3, color="C2", ls="--", lw=0.8,
                label=f"mean {summary['mean_hub_torque_n_m'] * 1e3:.4g} mN·m, power {summary['mean_hub_power_w']:.4g} W")
    ax2.set_ylabel("hub torque on the filaments (mN·m)")
    ax2.set_xlabel(f"hub angle of the reference filament from the surface's deepest point ({DEG})")
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8, loc="upper right")
    ax2.set_xlim(-180, 180)
    fig.suptitle(_title(summary) + "\nover one revolution at the filaments' steady state", fontsize=10)
    fig.tight_layout()
    return fig


def profile_figure(summary, profile):
    """brush_profile.png: the mean filament's force against its own angle across the contact zone."""
    fig, ax = plt.subplots(figsize=(9, 5))
    if len(profile["theta_from_deg"]) == 0:
        ax.text(0.5, 0.5, "no filament touched the surface", transform=ax.transAxes, ha="center", va="center")
    else:
        x = _centres(profile)
        ax.step(x, profile["normal_force_n"], where="mid", lw=1.2, label="normal")
        ax.step(x, profile["tangential_force_n"], where="mid", lw=1.2, label="tangential (along +Y)")
        zone = summary["contact_zone"]
        ax.axvspan(zone["from_deg"], zone["to_deg"], color="0.9", zorder=0,
                   label=f"contact zone {zone['angle_deg']:.3g}{DEG}, {zone['width_m'] * 1e3:.3g} mm along the surface")
        ax.legend(fontsize=8)
        touched = np.flatnonzero((profile["normal_impulse_n_s"] != 0) | (profile["tangential_impulse_n_s"] != 0))
        if touched.size:  # the zone and a margin of half its width (at least 5°) either side
            lo, hi = profile["theta_from_deg"][touched[0]], profile["theta_to_deg"][touched[-1]]
            margin = max(5.0, 0.5 * (hi - lo))
            ax.set_xlim(max(-180.0, lo - margin), min(180.0, hi + margin))
        else:
            ax.text(0.5, 0.5, "no filament touched the surface", transform=ax.transAxes, ha="center", va="center")
    ax.set_xlabel(f"filament angle from the surface's deepest point ({DEG})")
    ax.set_ylabel(f"mean force per filament (N)\nmomentum per {summary['bin_deg']:g}{DEG} bin / its duration")
    ax.grid(alpha=0.3)
    ax.set_title(_title(summary) + "\nthe force profile across the contact zone: every filament at its own angle, "
                 "divided by their number", fontsize=9)
    fig.tight_layout()
    return fig


def filaments_figure(summary, filaments, representatives=None):
    """brush_filaments.png: each filament's mean normal force and its largest deflection |y_t|/L
    against its length (and diameter where they scatter): what makes filaments differ. Their phase
    cannot (every filament meets the same surface), so it is not drawn. For a population the
    filaments' values are interpolated, and the representatives that were run are drawn over them."""
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 5))
    status = filaments["status"]
    groups = [("steady", "C0", "o"), ("not_steady", "C1", "s"), ("clear", "0.6", "x"), ("failed", "C3", "^"),
              ("error", "C3", "v"), ("interrupted", "C4", "D")]
    diameters = np.asarray(filaments["diameter_m"], float)
    by_diameter = np.ptp(diameters) > 1e-9 * np.max(diameters) if diameters.size else False
    for name, color, marker in groups:
        sel = status == name
        if not sel.any():
            continue
        label = f"{name.replace('_', ' ')} ({sel.sum()})"
        size = 3 + 6 * (diameters[sel] - diameters.min()) / np.ptp(diameters) if by_diameter else np.full(sel.sum(), 4.0)
        for a, column in ((ax, "mean_normal_force_n"), (ax2, "max_tip_deflection_ratio")):
            a.scatter(filaments["length_m"][sel] * 1e3, filaments[column][sel], s=size ** 2, marker=marker,
                      color=color, label=label, linewidths=1)
    if summary.get("method") == "population" and representatives is not None:
        ran = representatives["status"] != "clear"
        for a, column in ((ax, "mean_normal_force_n"), (ax2, "max_tip_deflection_ratio")):
            a.scatter(representatives["length_m"][ran] * 1e3, representatives[column][ran], s=40, marker="+",
                      color="k", label=f"representative run ({ran.sum()})", linewidths=1.2, zorder=3)
    limit = summary.get("config", {}).get("simulation", {}).get("deflection_warning_ratio", 0.1)
    ax2.axhline(limit, color="C3", lw=0.8, ls="--", label=f"warning ratio {limit:g} (docs/model.md §10)")
    ax.set_ylabel("mean normal force over a revolution (N)")
    ax2.set_ylabel("largest tip deflection |y_t|/L over its orbit (1)")
    for a in (ax, ax2):
        a.set_xlabel("filament length (mm)" + (" — marker size: diameter" if by_diameter else ""))
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    what = ("each filament interpolated from the representatives run (brush.method = \"population\")"
            if summary.get("method") == "population" else "each filament at its steady state")
    fig.suptitle(_title(summary) + f"\n{what} (clear: too short to reach the surface);\n"
                 "filaments differ by length and diameter, not by their phase", fontsize=10)
    fig.tight_layout()
    return fig


def brush_figures(folder):
    """[(name, figure)] of a brush folder, every file read and checked before any is drawn."""
    summary, workpiece, profile, filaments = read_brush(folder)
    representatives = read_listed(folder, summary, "representatives.csv")
    spectrum = read_listed(folder, summary, "spectrum.csv")
    figures = [("brush_force", lambda: force_figure(summary, workpiece)),
               ("brush_profile", lambda: profile_figure(summary, profile)),
               ("brush_filaments", lambda: filaments_figure(summary, filaments, representatives))]
    if spectrum is not None:
        figures.append(("brush_spectrum", lambda: spectrum_figure(summary, spectrum)))
    return draw_all(tuple(figures))


# brush_map.png of a sweep over brushes (rotbeam.sweep_plots.metrics_figure draws it as the sweep's
# metrics): six of sweep.csv's brush columns, (column, scale, axis label).
BRUSH_MAP_PANELS = [
    ("mean_normal_force_n", 1, "mean normal force (N)"),
    ("mean_tangential_force_n", 1, "mean tangential force (N)"),
    ("mean_hub_power_w", 1, "mean hub power (W)"),
    ("peak_normal_force_n", 1, "peak binned normal force (N)"),
    ("contact_zone_width_m", 1e3, "contact zone along the surface (mm)"),
    ("force_ratio", 1, "mean normal force per filament\n/ (3EI·pL/L³)"),
]
