"""Campbell diagrams: of `rotbeam modes --csv` (plot_campbell), and the rub map of a sweep over hub
speed with a casing (docs/surfaces.md): the last complete revolution's response of every case (peak
tip deflection, peak contact force, impulse, friction work, impacts) against speed, under the
Campbell diagram whose engine-order crossings k·Ω = ω_j(Ω) mark where a casing of k lobes excites a
mode. The rub map is read from sweep.csv alone: the natural frequencies are its f1_hz … f3_hz
columns, each case's own."""

import json
from pathlib import Path

# rotbeam._figures first: where matplotlib is missing it says so in one line.
from ._figures import save_figure, value_text

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ._csv import Columns, read_csv  # noqa: E402
from ._surface import casing_words  # noqa: E402

SPEED = "hub.speed_rpm"

# (column, scale, axis label) of the response panels.
RESPONSE_PANELS = [
    ("last_revolution_max_tip_deflection_ratio", 1.0, "peak |y_t|/L"),
    ("last_revolution_peak_normal_force_n", 1.0, "peak force in sustained\ncontact (N; 0: none)"),
    ("last_revolution_normal_impulse_n_s", 1e3, "normal impulse per revolution (mN·s)"),
    ("last_revolution_friction_work_j", -1e3, "friction dissipation per revolution (mJ)"),
    ("last_revolution_impacts", 1.0, "impacts per revolution"),
]


def _surface_in(folder, case):
    """The surface (summary.json `surface`) of a case's folder, {} for a run without one, None when
    its summary.json cannot be read."""
    try:
        return json.loads((Path(folder) / case / "summary.json").read_text()).get("surface", {})
    except (OSError, ValueError):
        return None


def casing_of(folder, table, ok):
    """The surface (summary.json `surface`) of the first case with results when it is a casing, else None."""
    first = next((f for f, good in zip(table["folder"], ok) if good), None)
    surface = _surface_in(folder, first) if first is not None else None
    return surface if surface and surface.get("shape") == "casing" else None


def is_rub_sweep(folder, table, keys, ok):
    """True for a sweep over hub.speed_rpm whose cases rub a casing and that has the rub columns."""
    return (SPEED in keys and "last_revolution_peak_normal_force_n" in table and "f1_hz" in table
            and casing_of(folder, table, ok) is not None)


MAX_MULTIPLES = 6  # the engine orders drawn: k, 2k, …, 6k for a casing of k lobes


def engine_orders(lobes):
    """The orders k·m (m = 1 … MAX_MULTIPLES) of a casing with k lobes: the harmonics its lobes put on
    a filament turning past them (a cosine law's own is k; contact makes the multiples); none for a
    concentric casing (nothing turns in the hub frame)."""
    return [lobes * m for m in range(1, MAX_MULTIPLES + 1)] if lobes > 0 else []


def crossings(speeds_rpm, frequencies_hz, order):
    """Speeds [rpm] where order·Ω/60 = f(Ω), linearly interpolated between the sampled speeds."""
    s = np.asarray(speeds_rpm, dtype=float)
    d = np.asarray(frequencies_hz, dtype=float) - order * s / 60.0
    out = []
    for i in range(len(s) - 1):
        if np.isfinite(d[i]) and np.isfinite(d[i + 1]) and d[i] * d[i + 1] <= 0 and d[i] != d[i + 1]:
            out.append(s[i] + (s[i + 1] - s[i]) * d[i] / (d[i] - d[i + 1]))
    return out


# The modes' colours (their curves, crossings and dotted lines), apart from the series' C0, C1, ….
MODE_COLORS = ["k", "0.45", "0.7"]


def casings(folder, table, ok):
    """The distinct casings (summary.json `surface`) of the cases with results, in sweep order."""
    out = []
    for f, good in zip(table["folder"], ok):
        s = _surface_in(folder, f) if good else None
        if s and s.get("shape") == "casing" and s not in out:
            out.append(s)
    return out


def engine_order_lines(ax, speeds, orders, top):
    """The engine orders f = k·rpm/60 dashed over `speeds` (rpm), each named k× at its end, below `top` (Hz)."""
    for order in orders:
        ax.plot(speeds, order * speeds / 60.0, "k--", lw=0.7, alpha=0.6)
        x_end = min(speeds[-1], top * 60.0 / order)
        ax.annotate(f"{order}×", (x_end, order * x_end / 60.0), fontsize=8, ha="right", va="bottom")


def plot_campbell(csv_path, png_path, orders=(1, 2, 3, 5, 10, 20)):
    """Campbell diagram from `rotbeam modes --csv`: frequencies against speed with engine orders."""
    table = read_csv(csv_path, Columns(("speed_rpm",)))
    speeds = table["speed_rpm"]
    modes = sorted((k for k in table if k.endswith("_hz")), key=lambda k: int(k[1:-3]))
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for k in modes:
        ax.plot(speeds, table[k], lw=2, label=f"mode {k[1:-3]}")
    top = max(np.nanmax(table[k]) for k in modes) * 1.3
    engine_order_lines(ax, np.linspace(0, speeds.max(), 200), orders, top)
    ax.set_yscale("log")
    ax.set_ylim(max(1.0, 0.5 * np.nanmin(table[modes[0]])), top)
    ax.set_xlabel("hub speed (rpm)")
    ax.set_ylabel("natural frequency (Hz)")
    ax.set_title("Campbell diagram: in-plane modes of the spinning filament\n(dashed: engine orders f = k·rpm/60)",
                 fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    save_figure(fig, png_path)
    plt.close(fig)
    return [Path(png_path)]


def rub_map_figure(folder, table, keys, ok, note=""):
    """rub_map.png: the Campbell diagram with its engine-order crossings, and the response panels,
    against hub speed; a line per value of the other varied keys. When the casing itself varies
    (its lobes, say), the orders of every casing are drawn and the title says so."""
    found = casings(folder, table, ok) or [casing_of(folder, table, ok)]
    lobe_counts = sorted({int(s.get("lobes", 0)) for s in found})
    lobes = lobe_counts[0] if len(lobe_counts) == 1 else 0
    law = found[0].get("lobe_law", "cosine") if lobes else "concentric"
    drawn = ok & np.isin(table["status"], ["done", "resumed"])
    rest = [k for k in keys if k != SPEED]
    speed = table[SPEED].astype(float)
    groups = list(dict.fromkeys(tuple(table[k][i] for k in rest) for i in range(len(speed)) if drawn[i]))
    fig = plt.figure(figsize=(13, 11))
    grid = fig.add_gridspec(4, 2, height_ratios=[1.4, 1, 1, 1])
    campbell = fig.add_subplot(grid[0, :])
    panels = [fig.add_subplot(grid[1 + i // 2, i % 2], sharex=campbell) for i in range(5)]
    legend_ax = fig.add_subplot(grid[3, 1])
    legend_ax.axis("off")

    # The Campbell diagram from the cases' own frequencies (every case: they do not depend on the run).
    order = np.argsort(speed)
    s_sorted = speed[order]
    orders = sorted({o for k in lobe_counts for o in engine_orders(k)})
    # Up to the highest order's frequency at the top speed (or the first mode's, without orders): the
    # modes above it are not excited over these speeds and are left out, so the crossings stay legible.
    reach = max(orders) * float(np.nanmax(s_sorted)) / 60.0 if orders else 0.0
    modes = []
    top = 0.0
    for c in ("f1_hz", "f2_hz", "f3_hz"):
        if c not in table:
            continue
        f = table[c].astype(float)[order]
        if not np.isfinite(f).any() or (modes and np.nanmin(f) > reach):
            continue
        modes.append(c)
        campbell.plot(s_sorted, f, color=MODE_COLORS[len(modes) - 1], lw=2, label=f"mode {len(modes)}")
        top = max(top, float(np.nanmax(f)))
    top = max(top, min(reach, 1.5 * top)) * 1.1 if top > 0 else 1.0
    crossing_speeds = []
    engine_order_lines(campbell, s_sorted, orders, 0.88 * top)
    for o in orders:
        for j, c in enumerate(modes):
            for x in crossings(s_sorted, table[c].astype(float)[order], o):
                if not o * x / 60.0 < top:
                    continue
                crossing_speeds.append((x, j, o))
                campbell.plot([x], [o * x / 60.0], "o", color=MODE_COLORS[j], ms=6, mfc="none", mew=1.5)
    campbell.set_ylim(0, top)
    campbell.set_ylabel("frequency (Hz)")
    campbell.set_xlabel(f"{SPEED} (rpm)")
    campbell.grid(alpha=0.3)
    why = ("engine orders dashed, crossings circled" if len(lobe_counts) > 1 and orders
           else f"engine orders k·Ω of a casing of {lobes} lobes ({law}) dashed, crossings circled" if orders
           else "a concentric casing excites no engine order")
    campbell.set_title(f"Campbell diagram: in-plane modes at each case's speed; {why}", fontsize=9, pad=4)
    campbell.legend(fontsize=8, loc="upper left")

    styles = ([{"color": f"C{i % 10}", "marker": "o", "linestyle": "-"} for i in range(len(groups))]
              if rest else [{"color": "C0", "marker": "o", "linestyle": "-"}])
    revolutions = drawn & np.isfinite(table["last_revolution_peak_normal_force_n"].astype(float))
    # Filled markers: the case reached its periodic steady state; hollow: its last revolution is one of
    # a motion that did not settle (or the run did not look for a steady state).
    after = table["steady_after_revolutions"].astype(float) if "steady_after_revolutions" in table \
        else np.zeros(len(speed))
    steady = np.nan_to_num(after) > 0
    for ax, (column, scale, label) in zip(panels, RESPONSE_PANELS):
        for g, style in zip(groups, styles):
            sel = revolutions.copy()
            for k, v in zip(rest, g):
                sel &= table[k] == v
            o = np.argsort(speed[sel])
            name = ", ".join(f"{k} = {value_text(v)}" for k, v in zip(rest, g)) or None
            xs, ys, st = speed[sel][o], table[column][sel][o].astype(float) * scale, steady[sel][o]
            ax.plot(xs, ys, lw=1, label=name, **dict(style, marker=None))
            ax.plot(xs[~st], ys[~st], ls="none", marker=style["marker"], ms=4, mfc="white", color=style["color"])
            ax.plot(xs[st], ys[st], ls="none", marker=style["marker"], ms=4, color=style["color"])
        for x, j, _ in crossing_speeds:
            ax.axvline(x, color=MODE_COLORS[j], lw=0.8, ls=":", alpha=0.8)
        ax.set_ylabel(label)
        ax.set_xlabel(f"{SPEED} (rpm)")
        ax.grid(alpha=0.3)
        if not revolutions.any():
            ax.text(0.5, 0.5, "no case ran over whole revolutions\n(set simulation.revolutions or until_steady)",
                    transform=ax.transAxes, ha="center", va="center", fontsize=8)
    handles, labels = panels[0].get_legend_handles_labels()
    if rest and handles:
        legend_ax.legend(handles, labels, loc="center", fontsize=8, title=", ".join(rest), title_fontsize=8)
    elif crossing_speeds:
        legend_ax.text(0.0, 0.5, "dotted: the engine-order crossings\n(colour: the mode crossed)\n" +
                       "\n".join(f"{o}× mode {j + 1} at {x:.0f} rpm" for x, j, o in crossing_speeds[:8]) +
                       ("\n…" if len(crossing_speeds) > 8 else ""),
                       transform=legend_ax.transAxes, va="center", fontsize=8)
    n = len(table["case"])
    settled = int((steady & revolutions).sum())
    note = (f"\nfilled markers: the {settled} of {int(revolutions.sum())} cases that reached their periodic steady "
            "state; hollow: the last revolution of a motion that did not settle" + note)
    which = (f"casing: {casing_words(found[0])}" if len(found) == 1
             else f"{len(found)} casings, the orders of each drawn: " + "; ".join(casing_words(s) for s in found[:4])
             + ("; …" if len(found) > 4 else ""))
    fig.suptitle(f"Rub map: {int(drawn.sum())} of {n} cases drawn, the last complete revolution of each ({which})"
                 f"{note}", fontsize=10)
    fig.tight_layout()
    return fig
