"""The pictures of a sweep folder (sweep.csv, docs/cli.md): sweep_metrics.png (six metrics against
the first varied key, a line per value of the others), sweep_normal_force_vs_y.png (every case's
sustained-contact force along the surface), rub_map.png for a sweep over speed with a casing
(rotbeam.rub_map), brush_map.png for a sweep over brushes (rotbeam.brush_plots), and with
cases=True the pictures of every case.
"""

import json
from dataclasses import replace
from pathlib import Path

# rotbeam._figures first: where matplotlib is missing it says so in one line.
from ._figures import DEG, draw_all, legend_beside, save_figures, series_styles, value_text

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import _core  # noqa: E402
from ._csv import FILES, DamagedFolder, read_csv  # noqa: E402
from ._runs import along_angle, along_label, check_run_files, read_run  # noqa: E402
from .brush_plots import BRUSH_MAP_PANELS, brush_figures, read_brush  # noqa: E402
from .rub_map import is_rub_sweep, rub_map_figure  # noqa: E402
from .run_plots import plot_normal_force, run_figures  # noqa: E402


def _of(count, total, noun="cases"):
    """'1 of 4 cases has' / '2 of 4 cases have'."""
    return f"{count} of {total} {noun} {'has' if count == 1 else 'have'}"


def _cases_note(table, ok):
    """The title's plain words on the cases without results and those stopped on a failure."""
    n = len(table["case"])
    notes = []
    missing = [i for i in range(n) if not ok[i]]
    if missing:
        named = ", ".join(f"{table['folder'][i]} ({table['status'][i]})" for i in missing[:4])
        notes.append(f"{_of(len(missing), n)} no results, not drawn: {named}{', …' if len(missing) > 4 else ''}")
    failed = [i for i in range(n) if ok[i] and table["status"][i] == "failed"]
    if failed:
        named = ", ".join(table["folder"][i] for i in failed[:4])
        notes.append(f"{len(failed)} of {n} cases stopped on a diagnosed failure, drawn up to the stop: "
                     f"{named}{', …' if len(failed) > 4 else ''}")
    return "".join("\n" + line for line in notes)


def sweep_keys(table):
    """The varied keys of sweep.csv's columns: those between `folder` and `status` (docs/cli.md)."""
    columns = list(table)
    return columns[columns.index("folder") + 1:columns.index("status")]


def read_sweep_csv(folder):
    """A sweep folder's sweep.csv (rotbeam._csv.read_csv): the metrics the library writes
    (_core.sweep_metrics, of filaments and of brushes) read as numbers, empty where a case has no
    result; the varied keys as numbers where every value is one, text otherwise."""
    metrics = tuple(m[0] for brush in (False, True) for m in _core.sweep_metrics(brush))
    return read_csv(Path(folder) / "sweep.csv", replace(FILES["sweep.csv"], optional=metrics))


def read_sweep(folder, table=None):
    """(table, keys, ok) of a sweep folder: sweep.csv's columns (`table`, when read already), the
    varied keys and which cases have results (done, resumed, or failed: stopped on a diagnosed
    failure, their files kept). A case with results whose files are missing or damaged raises
    DamagedFolder."""
    folder = Path(folder)
    table = read_sweep_csv(folder) if table is None else table
    ok = np.isin(table["status"], ["done", "resumed", "failed"])
    for f, good in zip(table["folder"], ok):
        if good:  # a case with results must have its files: a missing or damaged one is named
            if not (folder / f / "summary.json").exists():
                raise DamagedFolder(f"{folder / f / 'summary.json'}: missing (sweep.csv lists results for {f})")
            check_run_files(folder / f)
    return table, sweep_keys(table), ok


def _named(table, rows):
    """The cases `rows` for a title: 'case-0003 (failed: its message's first part), …' (four at most)."""
    return ", ".join(f"{table['folder'][i]} ({table['status'][i]}"
                     f"{': ' + table['message'][i].split(':')[0] if table['message'][i] else ''})"
                     for i in rows[:4]) + (", …" if len(rows) > 4 else "")


def metrics_figure(table, keys, ok, panels, title):
    """Six of sweep.csv's columns against the first varied key, a line per value of the others.
    panels: (column, scale, axis label) for each of the six."""
    first, rest = keys[0], keys[1:]
    x = table[first]
    groups = list(dict.fromkeys(tuple(table[k][i] for k in rest) for i in range(len(x)) if ok[i]))
    try:
        groups.sort()
    except TypeError:
        pass
    styles = series_styles(groups) if rest else [{"color": "C0", "linestyle": "-", "marker": "o"}] * len(groups)
    fig, axes = plt.subplots(2, 3, figsize=(14, 7.5))
    for ax, (metric, scale, label, *why_empty) in zip(axes.flat, panels):
        # A case without results is a gap in its line (NaN), never a segment drawn across it.
        y = np.where(ok, np.asarray(table[metric], float), np.nan)
        if ok.any() and not np.isfinite(y).any():
            ax.text(0.5, 0.5, why_empty[0] if why_empty else "no case has a value here", transform=ax.transAxes,
                    ha="center", va="center", fontsize=9, wrap=True)
            ax.set_yticks([])
            if x.dtype.kind in "fiu" and len(x) > 1 and np.ptp(x.astype(float)) > 0:
                ax.set_xlim(float(np.min(x)), float(np.max(x)))
        for g, style in zip(groups, styles):
            sel = np.ones(len(x), bool)
            for k, v in zip(rest, g):
                sel &= table[k] == v
            order = np.argsort(x[sel].astype(float)) if x.dtype.kind == "f" else np.arange(sel.sum())
            label_g = ", ".join(f"{k} = {value_text(v)}" for k, v in zip(rest, g)) or None
            ax.plot(x[sel][order], y[sel][order] * scale, ms=4, label=label_g, **style)
        ax.set_xlabel(first)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        if not ok.any():
            ax.text(0.5, 0.5, "no case has results", transform=ax.transAxes, ha="center", va="center")
    fig.suptitle(title, fontsize=10)
    right = legend_beside(fig, *axes[0, 0].get_legend_handles_labels(), fontsize=8) if rest and ok.any() else 1.0
    fig.tight_layout(rect=(0, 0, right, 1))
    return fig


def sweep_metrics_figure(table, keys, ok):
    """sweep_metrics.png: six metrics against the first varied key, a line per value of the others."""
    # Sweeps written before sweep.csv had the binned peak show the sustained-contact peak.
    peak = (("binned_peak_normal_force_n", 1, "peak F_n over hub-angle bins (N)\nimpacts included")
            if "binned_peak_normal_force_n" in table else ("peak_normal_force_n", 1, "peak F_n in sustained contact (N)"))
    panels = [("impacts", 1, "impacts"), ("contact_episodes", 1, "contact episodes"),
              ("last_separation_deg", 1, f"last separation ({DEG})"), peak,
              ("normal_impulse_n_s", 1e3, "normal impulse (mN·s)"), ("max_tip_deflection_ratio", 1, "max |y_t|/L")]
    over = ""
    last = table.get("last_revolution_impacts")
    if last is not None and ok.any() and np.isfinite(np.asarray(last, float)[ok]).any():
        # Runs over many revolutions (of lengths that may differ, and angles that grow without
        # wrapping): the last complete revolution's metrics, comparable from case to case.
        panels = [("last_revolution_impacts", 1, "impacts per revolution"),
                  ("last_revolution_friction_work_j", 1e3, "friction work per revolution (mJ)"),
                  ("steady_after_revolutions", 1, "revolutions to the steady state\n(0: not reached)",
                   "no case searched for its steady state\n(simulation.until_steady = false)"),
                  ("last_revolution_peak_normal_force_n", 1, "peak F_n in a revolution (N)"),
                  ("last_revolution_normal_impulse_n_s", 1e3, "normal impulse per revolution (mN·s)"),
                  ("last_revolution_max_tip_deflection_ratio", 1, "max |y_t|/L in a revolution")]
        over = "; per revolution: each case's last complete one"
    return metrics_figure(table, keys, ok, panels,
                          f"Sweep of {len(table['case'])} cases over {', '.join(keys)}{over}{_cases_note(table, ok)}")


def sweep_force_figure(folder, table, keys, ok, folders, runs=None):
    """sweep_normal_force_vs_y.png: every case's sustained-contact F_n against the tip's Y; the cases
    made of impacts alone are named, not drawn. runs: {case folder: read_run's answer} read already."""
    folder = Path(folder)
    fig, ax = plt.subplots(figsize=(11, 5.5))
    where = {f: i for i, f in enumerate(table["folder"])}
    values = [tuple(table[k][where[f]] for k in keys) for f in folders]
    impacts_only = []
    read = {f: runs[f] if runs and f in runs else read_run(folder / f) for f in folders}
    # On casings the position along the surface is the hub angle (their two sides share a Y); a sweep
    # that mixes shapes keeps Y for all, its casings' lobes folded (said in the title).
    by_angle = [along_angle(read[f][2]) for f in folders]
    angle = bool(by_angle) and all(by_angle)
    for f, v, style in zip(folders, values, series_styles(values)):
        h, _, summary = read[f]
        label = ", ".join(value_text(u) for u in v)
        if not plot_normal_force(h, None, summary, ax, label=label, by_angle=angle, lw=1.1, **dict(style, marker=None)):
            impacts_only.append(label)
    ax.set_xlabel(along_label(angle))
    ax.set_ylabel("normal force F_n (N)")
    ax.grid(alpha=0.3)
    title = "Sustained-contact normal force along the surface, every case"
    if any(by_angle) and not angle:
        title += " (the casings' cases against Y: both sides of a lobe share a Y)"
    if impacts_only:
        shown = "; ".join(impacts_only[:6]) + ("; …" if len(impacts_only) > 6 else "")
        title += (f"\n{_of(len(impacts_only), len(folders), 'cases with results')} no sustained contact "
                  f"(impacts only: see their normal_force_vs_y.png), not drawn: {shown}")
    right = 1.0
    if len(impacts_only) < len(folders):
        right = legend_beside(fig, *ax.get_legend_handles_labels(), fontsize=7, title=", ".join(keys),
                               title_fontsize=7)
    else:
        ax.text(0.5, 0.5, "no case has sustained contact: every one is made of impacts only",
                transform=ax.transAxes, ha="center", va="center")
    ax.set_title(title + _cases_note(table, ok), fontsize=9)
    fig.tight_layout(rect=(0, 0, right, 1))
    return fig


def is_brush_folder(folder):
    """True when folder's summary.json is a brush's (`rotbeam brush`)."""
    try:
        return json.loads((Path(folder) / "summary.json").read_text()).get("kind") == "brush"
    except (ValueError, AttributeError, OSError):
        return False


def plot_brush_sweep(folder, out, table, keys, ok, cases):
    """brush_map.png of a sweep over brushes (and each case's brush pictures with --cases), every
    case with results read and checked first."""
    folders = [f for f, good in zip(table["folder"], ok) if good]
    checked = {f: brush_figures(folder / f) for f in folders} if cases else {}
    for f in folders:
        if not cases:
            read_brush(folder / f)
    n = len(table["case"])
    missing = [i for i in range(n) if not ok[i]]
    note = ""
    if missing:
        note = (f"\n{len(missing)} of {n} brushes not drawn (a filament failed, so the sums would leave it out; "
                f"or no results): {_named(table, missing)}")
    title = f"Brush map: {n} brushes over {', '.join(keys)}{note}"
    figures = [("brush_map", metrics_figure(table, keys, ok, BRUSH_MAP_PANELS, title))]
    written = save_figures(figures, out)
    for f, figs in checked.items():
        written += save_figures(figs, out / f)
    return written


def _rub_note(table):
    """The rub map's title line on the cases it leaves out: those without a steady revolution to show
    (stopped on a failure, or without results), named with their status."""
    left = [i for i, s in enumerate(table["status"]) if s not in ("done", "resumed")]
    if not left:
        return ""
    return f"\n{len(left)} of {len(table['case'])} cases not drawn: {_named(table, left)}"


def plot_sweep(folder, out, cases=False):
    """The pictures of a sweep folder into out; every case with results is read and checked first
    (read_run), so a damaged one is named before the folder out is made and anything is written."""
    folder, out = Path(folder), Path(out)
    table = read_sweep_csv(folder)
    if "force_ratio" in table:  # a sweep over brushes (docs/brush.md)
        # A brush with a failed filament has sums without it: only whole brushes are drawn.
        ok = np.isin(table["status"], ["done", "resumed"])
        return plot_brush_sweep(folder, out, table, sweep_keys(table), ok, cases)
    table, keys, ok = read_sweep(folder, table)
    folders = [f for f, good in zip(table["folder"], ok) if good and (folder / f / "history.csv").exists()]
    drawn = folders if folders and len(folders) <= 24 else []
    runs = {f: read_run(folder / f) for f in drawn}
    if cases:
        for f in folders:
            if f not in runs:
                read_run(folder / f)
    drawings = [("sweep_metrics", lambda: sweep_metrics_figure(table, keys, ok))]
    if drawn:
        drawings.append(("sweep_normal_force_vs_y", lambda: sweep_force_figure(folder, table, keys, ok, drawn, runs)))
    if is_rub_sweep(folder, table, keys, ok):
        drawings.append(("rub_map", lambda: rub_map_figure(folder, table, keys, ok, _rub_note(table))))
    figures = draw_all(drawings)
    written = save_figures(figures, out)
    if cases:
        for f in folders:
            written += save_figures(run_figures(folder / f, runs.get(f)), out / f)
    return written
