"""Pictures of rotbeam outputs (matplotlib; reads only the files a run or sweep wrote).

    python3 -m rotbeam.plots DIR [-o OUT]      # or: rotbeam plot DIR

A run folder (history.csv, events.csv, summary.json; force_bins.csv where the run wrote one) gives
normal_force_vs_y.png (the thesis's figures: sustained contact's F_n, the impacts' impulses, and the
mean force over bins of hub angle), tip_path.png (the path with close-ups, thesis Figure 13),
modal_coordinates.png, energy.png (the Jacobi integral, why impacts move it, and the hub torque)
and impacts.png. A sweep folder (sweep.csv) gives sweep_metrics.png and
sweep_normal_force_vs_y.png, plus the pictures of each case with --cases. Each picture is also a
function returning its matplotlib figure (force_figure, tip_path_figure, energy_figure, …).
"""

import argparse
import errno
import json
import math
import os
import shutil
import sys
import tempfile
from pathlib import Path

if __name__ == "__main__":
    from rotbeam._interrupt import announce_start, stop_quietly_on_interrupt

    stop_quietly_on_interrupt()
    announce_start()

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as missing:
    from rotbeam._interrupt import missing_package

    raise missing_package(
        f"drawing rotbeam's pictures needs numpy and matplotlib for {sys.executable} (Debian: apt-get install "
        f"python3-numpy python3-matplotlib): {missing}") from None

DEG = "°"

from ._interrupt import error, file_error, run_main, wrote  # noqa: E402
from ._csv import (EVENT_COLUMNS, EVENT_KINDS, EVENT_OPTIONAL, FORCE_BIN_COLUMNS, PHASES,  # noqa: E402,F401
                   Columns, DamagedFolder, columns_of, read_csv)
from ._surface import casing_radius, draw_surface, surface_of, surface_words, surface_x  # noqa: E402
from .brush_plots import BRUSH_MAP_PANELS, DamagedBrush, brush_figures, read_brush  # noqa: E402
from .rub_map import is_rub_sweep, rub_map_figure  # noqa: E402


def remove_stale_temporaries(path):
    """Removes the temporaries `.NAME.PID.tmp[.EXT]` that a killed writer of `path` left beside it
    (its process is gone); those of a live writer, and every other file, are left alone."""
    path = Path(path)
    prefix = f".{path.stem if path.suffix in ('.gif', '.mp4') else path.name}."
    try:
        entries = list(path.parent.iterdir())
    except OSError:
        return
    for entry in entries:
        name = entry.name
        if not name.startswith(prefix):
            continue
        rest = name[len(prefix):].split(".")
        if len(rest) < 2 or not rest[0].isdigit() or rest[1] != "tmp" or len(rest) > 3:
            continue
        try:
            os.kill(int(rest[0]), 0)
        except ProcessLookupError:
            try:
                entry.unlink()
            except OSError:
                pass
        except OSError:
            pass


def output_target(path):
    """The file that writing to path replaces: the file a symbolic link names (the link stays), or
    path itself. None for a node that is not a regular file (a device, a pipe, /dev/stdout): that
    one is written into, never replaced."""
    path = Path(path)
    if path.exists() and not path.is_file():
        if path.is_dir():
            raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), str(path))
        return None
    return Path(os.path.realpath(path))


def put_in_place(tmp, path):
    """Puts the finished temporary tmp (made beside output_target(path)) at path."""
    target = output_target(path)
    if target is None:
        with open(tmp, "rb") as src, open(path, "wb") as dst:
            shutil.copyfileobj(src, dst)
        Path(tmp).unlink()
    else:
        os.replace(tmp, target)


def temporary_beside(path, stem=False, suffix=""):
    """A temporary name `.NAME.PID.tmp[SUFFIX]` (NAME: the name, or its stem) beside the file that
    writing to path replaces (see output_target; the temporary folder for a device)."""
    path = Path(path)
    target = output_target(path) or Path(tempfile.gettempdir()) / path.name
    return target.with_name(f".{target.stem if stem else target.name}.{os.getpid()}.tmp{suffix}")


def save_figure(fig, path, dpi=120):
    """Writes fig to path whole: into a temporary file beside it, renamed into place (an interrupted
    or failed save leaves no partial picture under the user's name)."""
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower() or "png"
    if fmt not in fig.canvas.get_supported_filetypes():
        raise ValueError(f"{path}: cannot write a picture as '.{fmt}' (use .png, .pdf or .svg)")
    remove_stale_temporaries(path)
    tmp = temporary_beside(path)
    try:
        fig.savefig(tmp, dpi=dpi, format=fmt)
        put_in_place(tmp, path)
    except OSError as e:  # the temporary's name means nothing to the user: theirs, and why
        raise OSError(e.errno, e.strerror, str(path)) from None
    finally:
        if tmp.exists():
            tmp.unlink()


def animate(folder, output=None, **options):
    """The animation of a run folder (rotbeam.animate.animate; its options): the paths written."""
    from .animate import animate as draw_animation
    return draw_animation(folder, output, **options)


def history_columns(n):
    """The columns of a history.csv of n modes, in their order."""
    return list(columns_of("history.csv", n))


def read_run_table(path, required, words=None, text=(), may_be_empty=(), why_required=""):
    """A CSV file a run wrote as {column: numpy array}, read strictly (rotbeam._csv.read_csv): the
    damage a size check cannot see (a NUL byte, a letter in a number, an unknown word) raises
    DamagedFolder naming the file, the line, the column and the value. `required`: the columns it
    must have; `words`: {column: the words allowed}; `text`: free-text columns; `may_be_empty`:
    numeric columns whose value may be missing (NaN); every other column holds a number on every row."""
    return read_csv(path, Columns(tuple(required), words or {}, tuple(text), optional=tuple(may_be_empty)),
                    why_required=why_required)


def modes_words(c):
    """'5 modes', with the beam theory and the rotation terms where they are not the thesis's."""
    words = f"{c['beam']['modes']} mode{'' if c['beam']['modes'] == 1 else 's'}"
    if c["beam"].get("theory", "foreshortening") != "foreshortening":
        words += f", {c['beam']['theory']}"
    model = c.get("model", {})
    off = [name for name in ("centrifugal", "Coriolis") if model.get(name.lower(), True) is False]
    if off:
        words += ", without the " + (" and ".join(off) if len(off) < 2 else "rotation") + " terms"
    return words


def case_title(summary):
    c = summary["config"]
    return (f"{c['hub']['speed_rpm']:g} rpm, {surface_words(c)}, "
            f"μ = {c['surface']['friction']:g}, {modes_words(c)}, {summary['scheme']} scheme")


class OutputFolderError(Exception):
    """The folder the pictures go to cannot be made (the message names it and why)."""


def _summary_entry(summary, path, *keys):
    """summary[keys[0]][keys[1]]…, or DamagedFolder naming summary.json and the entry."""
    value = summary
    for k in keys:
        if not isinstance(value, dict) or k not in value:
            raise DamagedFolder(f"{path}: no entry {'.'.join(keys)}")
        value = value[k]
    return value


def check_summary(summary, path):
    """Raises DamagedFolder, naming summary.json (`path`) and the entry, when an entry the pictures
    read is missing or not of its kind: every one is checked before anything is drawn."""
    modes = _summary_entry(summary, path, "config", "beam", "modes")
    if isinstance(modes, bool) or not isinstance(modes, int) or not 1 <= modes <= 40:
        raise DamagedFolder(f"{path}: config.beam.modes = {json.dumps(modes)}: not a mode count (1..40)")
    casing = isinstance(summary.get("config", {}).get("surface"), dict) and \
        summary["config"]["surface"].get("shape") == "casing"
    place = ("config", "surface", "clearance_m" if casing else "depth_fraction")
    for keys, positive in ((("config", "hub", "speed_rpm"), True), (("config", "beam", "length_m"), True),
                           (("config", "hub", "radius_m"), False), (place, False),
                           (("config", "surface", "friction"), False)):
        v = _summary_entry(summary, path, *keys)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or (positive and v <= 0):
            raise DamagedFolder(f"{path}: {'.'.join(keys)} = {json.dumps(v)[:40]}: not a "
                                f"{'positive ' if positive else ''}number")
    residual = _summary_entry(summary, path, "energy_audit_residual")
    if residual is not None and (isinstance(residual, bool) or not isinstance(residual, (int, float))):
        raise DamagedFolder(f"{path}: energy_audit_residual = {json.dumps(residual)[:40]}: not a number")
    scheme = _summary_entry(summary, path, "scheme")
    if not isinstance(scheme, str):
        raise DamagedFolder(f"{path}: scheme = {json.dumps(scheme)[:40]}: not a word")
    warnings = summary.get("warnings", [])
    if not isinstance(warnings, list) or not all(isinstance(w, str) for w in warnings):
        raise DamagedFolder(f"{path}: warnings: not a list of lines")


def check_run_files(folder):
    """The run's summary.json, once it is a run's summary and history.csv / events.csv are there at
    the sizes it recorded; raises DamagedFolder otherwise (a truncated or replaced file). The
    contents are read strictly by read_run."""
    folder = Path(folder)
    try:
        summary = json.loads((folder / "summary.json").read_text())
    except ValueError as e:
        raise DamagedFolder(f"{folder / 'summary.json'}: not valid JSON ({e})") from None
    files = summary.get("files") if isinstance(summary, dict) else None
    if not isinstance(summary, dict) or not isinstance(summary.get("config"), dict) or \
            not isinstance(files, dict) or not all(isinstance(v, dict) for v in files.values()):
        raise DamagedFolder(f"{folder / 'summary.json'}: not a rotbeam run summary (its config or files are missing)")
    check_summary(summary, folder / "summary.json")
    for name in ("history.csv", "events.csv"):
        path = folder / name
        if not path.exists():
            raise DamagedFolder(f"{path}: missing")
        recorded = files.get(name, {}).get("bytes")
        if recorded is not None and path.stat().st_size != recorded:
            raise DamagedFolder(f"{path}: {path.stat().st_size} bytes where summary.json records {recorded}: "
                                "truncated or replaced")
    return summary


def warning_line(summary):
    """The run's warnings as a line for a title (empty without warnings)."""
    warnings = summary.get("warnings", [])
    if not warnings:
        return ""
    return "\nwarning: " + "; ".join(warnings) if len(warnings) == 1 else \
        f"\n{len(warnings)} warnings: " + "; ".join(w.split(":")[0] for w in warnings)


def _impacts(events):
    return [i for i, k in enumerate(events["kind"]) if k == "impact"]


def impact_energy(h, events, summary):
    """What the impacts drawn did to the Jacobi integral: {impacts, dh_j (Σ of h's jumps at them, from
    the history rows before and after each), loss_j (Σ P(V⁻ + V⁺)/2, the impulses' work on the tip;
    NaN for Coulomb impacts, whose tangential impulse events.csv does not hold), hub_j (Σ of the
    hub's work during them)}, or None without impacts. h = E − ωH_z, so at an impact
    Δh = loss − ω(R × P)_z = loss + ωY_tP for a normal impulse P along X."""
    imp = _impacts(events)
    if not imp:
        return None
    t = h["t_s"]
    dh = 0.0
    for i in imp:
        rows = np.flatnonzero(t == events["t_s"][i])
        if len(rows) < 2:
            dh = math.nan
            break
        dh += h["jacobi_j"][rows[-1]] - h["jacobi_j"][rows[0]]
    p = events["impulse_n_s"][imp]
    loss = float(np.sum(p * (events["vx_before_m_s"][imp] + events["vx_after_m_s"][imp]) / 2))
    if summary["config"].get("impact", {}).get("friction", "none") != "none":
        loss = math.nan
    return {"impacts": len(imp), "dh_j": dh, "loss_j": loss, "hub_j": float(np.nansum(events["hub_work_j"][imp]))}


def relative_angle(theta_deg):
    """Hub angle in (−180°, 180°] from the surface's deepest point (θ itself for one pass)."""
    theta = np.asarray(theta_deg, dtype=float)
    return np.where(np.abs(theta) <= 180.0, theta, 180.0 - np.mod(180.0 - theta, 360.0))


def impact_impulses(events):
    """(θ (°), tip Y (m), |P| (N·s)) of the impacts in events.csv: the momentum each gave the surface."""
    imp = _impacts(events)
    return (np.asarray(events["theta_deg"][imp], dtype=float), np.asarray(events["y_tip_m"][imp], dtype=float),
            np.abs(np.asarray(events["impulse_n_s"][imp], dtype=float)))


def force_bins(folder, h, events, summary, bin_deg=0.5):
    """The normal force in bins of hub angle: (columns, source). From the run's force_bins.csv where it
    has one; otherwise computed here from the files (each impact's |P| from events.csv, ∫F_n dt of
    sustained contact by the trapezoidal rule on history.csv's rows), with the same bins: width
    `bin_deg` from −180° over the relative hub angle, from the first bin that received momentum to
    the last, mean force = the bin's momentum / the time the hub takes to turn through it."""
    path = Path(folder) / "force_bins.csv"
    if path.exists():
        return read_csv(path), "force_bins.csv"
    bin_deg = float((summary.get("binned_force") or {}).get("bin_deg") or bin_deg)
    omega = summary["config"]["hub"]["speed_rpm"] * math.pi / 30.0
    count = int(math.ceil(360.0 / bin_deg - 1e-9))

    def index(angle):
        return np.minimum((np.mod(np.asarray(angle) + 180.0, 360.0) / bin_deg).astype(int), count - 1)

    normal = np.zeros(count)
    impacts = np.zeros(count, dtype=int)
    touched = np.zeros(count, dtype=bool)
    theta, _, impulse = impact_impulses(events)
    ok = np.isfinite(impulse)
    k = index(theta[ok])
    np.add.at(normal, k, impulse[ok])
    np.add.at(impacts, k, 1)
    touched[k] = True
    pressed = np.isin(h["phase"], ["contact", "stick"])
    seg = pressed[:-1] & pressed[1:] & (np.diff(h["t_s"]) > 0)
    if seg.any():
        dt = np.diff(h["t_s"])[seg]
        f = 0.5 * (h["normal_force_n"][:-1][seg] + h["normal_force_n"][1:][seg])
        mid = 0.5 * (h["theta_deg"][:-1][seg] + h["theta_deg"][1:][seg])
        k = index(mid)
        np.add.at(normal, k, f * dt)
        touched[k] = True
    if not touched.any():
        return {c: np.array([]) for c in FORCE_BIN_COLUMNS}, "events.csv and history.csv"
    first, last = np.flatnonzero(touched)[[0, -1]]
    sl = slice(first, last + 1)
    lo = -180.0 + np.arange(first, last + 1) * bin_deg
    duration = bin_deg * math.pi / 180.0 / omega
    return ({"theta_from_deg": lo, "theta_to_deg": np.minimum(180.0, lo + bin_deg),
             "normal_impulse_n_s": normal[sl], "tangential_impulse_n_s": np.full(last + 1 - first, np.nan),
             "mean_normal_force_n": normal[sl] / duration, "mean_tangential_force_n": np.full(last + 1 - first, np.nan),
             "impacts": impacts[sl]}, "events.csv and history.csv")


def sustained(h):
    """The rows in sustained contact (sliding or stuck)."""
    return np.isin(h["phase"], ["contact", "stick"])


def plot_normal_force(h, events, summary, ax, label=None, **style):
    """Sustained-contact F_n against the tip's Y (mm); draws nothing (and no legend entry) for a pass
    without sustained contact. Returns whether it drew."""
    contact = sustained(h)
    if not contact.any():
        return False
    y = np.where(contact, h["y_tip_m"] * 1e3, np.nan)
    f = np.where(contact, h["normal_force_n"], np.nan)
    line, = ax.plot(y, f, label=label, **style)
    # A row in contact between two that are not (a pass stopped at its first contact step) is no line:
    # a dot, so that nothing drawn is invisible.
    alone = contact & ~np.r_[False, contact[:-1]] & ~np.r_[contact[1:], False]
    if alone.any():
        ax.plot(y[alone], f[alone], "o", ms=3, color=line.get_color())
    return True


def _stems(ax, x, height, color, label, **style):
    ax.vlines(x, 0, height, color=color, lw=1, alpha=0.8)
    ax.plot(x, height, "o", color=color, ms=3.5, label=label, **style)


def force_figure(folder, h, events, summary, title):
    """normal_force_vs_y.png: the force the surface takes along it — sustained contact's F_n, the
    impacts' impulses (an impact has no force, it has momentum) and the mean force over bins of hub
    angle that puts both on one scale."""
    fig, (ax, axb) = plt.subplots(2, 1, figsize=(9, 7), gridspec_kw={"height_ratios": [3, 1.7]})
    s = summary
    _, y_i, p_i = impact_impulses(events)
    has_contact = sustained(h).any()
    headroom = 1.35 if has_contact else 1.7  # room for the legend (and the note) above the data
    axp = None
    if has_contact:
        plot_normal_force(h, events, summary, ax, color="C0", lw=1.2, label="F_n in sustained contact (left axis)")
        ax.set_ylabel("normal force F_n (N)")
        ax.set_ylim(0, headroom * np.nanmax(np.where(sustained(h), h["normal_force_n"], np.nan)))
    if len(p_i):
        axp = ax.twinx() if has_contact else ax
        where = ", right axis" if has_contact else ""
        _stems(axp, y_i * 1e3, p_i * 1e3, "C3",
               f"impact impulses |P| ({len(p_i)}, Σ {1e3 * np.nansum(p_i):.3g} mN·s{where})")
        axp.set_ylabel("impact impulse |P| (mN·s)", color="C3" if has_contact else "k")
        axp.set_ylim(0, headroom * np.nanmax(p_i) * 1e3)
        if has_contact:
            axp.tick_params(axis="y", colors="C3")
    if not has_contact and len(p_i):
        ax.text(0.02, 0.96, f"No sustained contact in this pass: the tip only struck\nthe surface "
                f"({len(p_i)} impacts). An impact gives momentum, not a force:\nits impulse is drawn here, the "
                "mean force over hub angle below.", transform=ax.transAxes, va="top", fontsize=8,
                bbox=dict(boxstyle="round", fc="white", ec="0.7"))
    elif not has_contact:
        ax.text(0.5, 0.5, "the tip did not reach the surface: no contact, no impacts", transform=ax.transAxes,
                ha="center", va="center", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
    ax.set_xlabel("tip position Y (mm)")
    ax.grid(alpha=0.3)
    lines, labels = ax.get_legend_handles_labels()
    if axp is not None and axp is not ax:
        more = axp.get_legend_handles_labels()
        lines, labels = lines + more[0], labels + more[1]
    if lines:
        ax.legend(lines, labels, fontsize=8, loc="upper right" if not has_contact else "upper center",
                  ncol=1 if not has_contact else 2)
    if has_contact:
        peak = f"peak F_n {s['peak_normal_force_n']:.3g} N in sustained contact"
    else:
        peak = "no sustained contact, so no instantaneous peak force"
    ax.set_title(f"{title}\n{s['impacts']} impacts, {s['contact_episodes']} contact episodes, "
                 f"normal impulse {1e3 * s['normal_impulse_n_s']:.4g} mN·s; {peak}", fontsize=9)

    # The mean force over bins of hub angle: momentum per time, impacts and sustained contact alike.
    bins, source = force_bins(folder, h, events, summary)
    lo, hi = np.asarray(bins["theta_from_deg"], float), np.asarray(bins["theta_to_deg"], float)
    if len(lo):
        width = float(np.median(hi - lo))
        mean = np.asarray(bins["mean_normal_force_n"], float)
        axb.stairs(mean, np.append(lo, hi[-1]), color="C2", lw=1.2, fill=True, alpha=0.35,
                   label=f"mean normal force over {width:g}° bins (momentum / time)")
        with_imp = np.asarray(bins["impacts"], float) > 0
        if with_imp.any():
            axb.plot(0.5 * (lo + hi)[with_imp], mean[with_imp], "v", color="C3", ms=3.5,
                     label="bins holding impacts")
        if has_contact:
            th = relative_angle(h["theta_deg"])
            f = np.where(sustained(h), h["normal_force_n"], np.nan)
            f[1:][np.diff(th) < 0] = np.nan
            axb.plot(th, f, color="C0", lw=0.8, label="F_n in sustained contact")
        k = int(np.nanargmax(mean))
        peak_deg = 0.5 * (lo[k] + hi[k])
        axb.set_xlim(lo[0] - 2 * width, hi[-1] + 2 * width)
        axb.legend(fontsize=7, loc="upper right")
        axb.set_title(f"Mean normal force over {width:g}{DEG} bins of hub angle: peak {mean[k]:.3g} N at "
                      f"θ = {peak_deg:.4g}{DEG}\n(each bin's impulses and ∫F_n dt divided by the time the hub takes "
                      f"to turn {width:g}{DEG}; from {source})", fontsize=8)
    else:
        axb.text(0.5, 0.5, "no momentum reached the surface: nothing to bin", transform=axb.transAxes,
                 ha="center", va="center", fontsize=9)
        axb.set_xticks([])
        axb.set_yticks([])
    axb.set_xlabel(f"hub angle θ ({DEG})")
    axb.set_ylabel("force (N)")
    axb.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def read_run(folder):
    """(history, events, summary) of a run folder: columns by name, and summary.json, all checked
    before anything is drawn (check_run_files, then every value of history.csv, events.csv and
    force_bins.csv read strictly). Raises DamagedFolder naming the file and what is wrong."""
    folder = Path(folder)
    summary = check_run_files(folder)
    n = summary["config"]["beam"]["modes"]
    history = read_csv(folder / "history.csv", modes=n,
                       why_required=f" (summary.json: config.beam.modes = {n}; the files are not of one run)")
    events = read_csv(folder / "events.csv")
    if (folder / "force_bins.csv").exists():
        read_csv(folder / "force_bins.csv")
    return history, events, summary


def tip_path_figure(h, events, summary, title):
    """tip_path.png: −X against Y (thesis Figure 13) with close-ups, and the gap against θ."""
    imp = _impacts(events)
    surface = surface_of(summary)
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    phase_colors = {"free": "C0", "contact": "C1", "stick": "C2"}
    X, Y = h["x_tip_m"] * 1e3, h["y_tip_m"] * 1e3

    def path(ax):
        for ph, color in phase_colors.items():
            sel = h["phase"] == ph
            if sel.any():  # above the surface line: contact samples lie on it
                ax.plot(Y[sel], -X[sel], ".", ms=1.5 if ph == "free" else 2.5, color=color, label=ph, zorder=3)
        draw_surface(ax, surface, Y, color="k", lw=0.5, label="surface", zorder=2)
        if imp:
            y_imp = events["y_tip_m"][imp]
            x_imp = np.interp(events["t_s"][imp], h["t_s"], h["x_tip_m"])
            ax.plot(y_imp * 1e3, -surface_x(surface, y_imp, x_imp) * 1e3, "v", color="C3", ms=4, label="impacts",
                    zorder=4)
        ax.set_xlabel("tip position Y (mm)")
        ax.set_ylabel("−X (mm)")
        ax.grid(alpha=0.3)

    def empty(ax, why):
        ax.text(0.5, 0.5, why, transform=ax.transAxes, ha="center", va="center", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])

    path(axes[0, 0])
    axes[0, 0].set_title("whole pass", fontsize=9)
    axes[0, 0].legend(fontsize=7, markerscale=2)
    near = h["gap_m"] > -2e-3
    casing = surface["shape"] == "casing"
    if casing:  # a casing all round: its radius and the tip's, unrolled against the polar angle
        axes[0, 0].set_aspect("equal", adjustable="datalim")
        ax = axes[0, 1]
        phi = np.degrees(np.arctan2(h["y_tip_m"], h["x_tip_m"]))
        rho = np.hypot(h["x_tip_m"], h["y_tip_m"])
        grid = np.linspace(-180.0, 180.0, 1441)
        ax.plot(grid, (casing_radius(surface, np.radians(grid)) - surface["nominal_radius_m"]) * 1e3, color="k",
                lw=0.8, label="casing")
        for ph, color in phase_colors.items():
            sel = h["phase"] == ph
            if sel.any():
                ax.plot(phi[sel], (rho[sel] - surface["nominal_radius_m"]) * 1e3, ".", ms=1.5, color=color, label=ph)
        ax.set_xlabel(f"polar angle of the tip φ ({DEG})")
        ax.set_ylabel("radius − (r_h + L) (mm)")
        ax.set_title("unrolled: the tip's radius and the casing's", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, markerscale=2)
    else:
        axes[0, 1].set_title("close-up: where the tip meets the surface", fontsize=9)
    if casing:
        pass
    elif near.any():
        path(axes[0, 1])
        axes[0, 1].set_xlim(Y[near].min() - 1, Y[near].max() + 1)
        x_near = surface_x(surface, h["y_tip_m"][near], h["x_tip_m"][near]) * 1e3
        if not np.isfinite(x_near).any():  # the tip beside a small workpiece: its own X
            x_near = h["x_tip_m"][near] * 1e3
        axes[0, 1].set_ylim(-np.nanmax(x_near) - 0.05, -np.nanmin(x_near) + 2.0)
    else:
        empty(axes[0, 1], "the tip never came within 2 mm of the surface")
    axes[1, 0].set_title("close-up: the first impact and the bounce back", fontsize=9)
    if imp:
        y0 = events["y_tip_m"][imp[0]] * 1e3
        x_tip0 = np.interp(events["t_s"][imp[:1]], h["t_s"], h["x_tip_m"])
        x0 = float(surface_x(surface, [y0 * 1e-3], x_tip0)[0]) * 1e3
        if not math.isfinite(x0):
            x0 = float(x_tip0[0]) * 1e3
        path(axes[1, 0])
        axes[1, 0].set_xlim(y0 - 0.5, y0 + 1.5)
        axes[1, 0].set_ylim(-x0 - 0.01, -x0 + 0.3)
    else:
        empty(axes[1, 0], "no impact in this pass")
    axes[1, 1].plot(h["theta_deg"], h["gap_m"] * 1e3, lw=0.8)
    axes[1, 1].axhline(0, color="k", lw=0.8)
    axes[1, 1].set_xlabel(f"hub angle θ ({DEG})")
    axes[1, 1].set_ylabel("gap C (mm)")
    low = np.nanmin(h["gap_m"]) * 1e3
    axes[1, 1].set_ylim((1.1 * low, -0.1 * low) if casing else (min(-5, low), 0.5))
    axes[1, 1].grid(alpha=0.3)
    axes[1, 1].set_title("gap against the hub angle", fontsize=9)
    fig.suptitle(f"Tip path — {title}" + warning_line(summary), fontsize=10,
                 color="C3" if summary.get("warnings") else "k")
    fig.tight_layout()
    return fig


def modal_figure(h, events, summary, title):
    """modal_coordinates.png: q and q̇ against θ."""
    n = summary["config"]["beam"]["modes"]
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    for i in range(1, n + 1):
        a1.plot(h["theta_deg"], h[f"q{i}_m"] * 1e3, lw=0.8, label=f"q{i}")
        a2.plot(h["theta_deg"], h[f"qd{i}_m_s"], lw=0.8, label=f"q̇{i}")
    a1.set_ylabel("q (mm)")
    a2.set_ylabel("q̇ (m/s)")
    a2.set_xlabel(f"hub angle θ ({DEG})")
    for a in (a1, a2):
        a.grid(alpha=0.3)
        a.legend(fontsize=7, ncol=min(n, 6))
    a1.set_title(f"Modal coordinates — {title}", fontsize=10)
    fig.tight_layout()
    return fig


def energy_note(ledger):
    """Why the Jacobi integral jumps up at impacts with e < 1, with this run's numbers (impact_energy)."""
    def uj(joules):
        return f"{1e6 * joules:+.0f} µJ" if abs(joules) >= 1e-4 else f"{1e6 * joules:+.3g} µJ"

    why = ("h rises at impacts even with e < 1: the surface, fixed in the inertial frame, moves in the hub's frame,"
           "\nand its impulse P works on the tip: Δh = impact loss (≤ 0) + ωY_tP (> 0 where Y_t < 0, before the "
           "deepest point).")
    if math.isfinite(ledger["loss_j"]) and math.isfinite(ledger["dh_j"]):
        why += (f"\nHere: loss {uj(ledger['loss_j'])} + moving surface {uj(ledger['dh_j'] - ledger['loss_j'])} "
                f"= Δh {uj(ledger['dh_j'])} over the {ledger['impacts']} impacts; E = T + U: "
                f"{uj(ledger['loss_j'] + ledger['hub_j'])} (loss + the hub's impulsive work).")
    elif math.isfinite(ledger["dh_j"]):
        why += f"\nHere the {ledger['impacts']} impacts change h by {uj(ledger['dh_j'])}."
    return why


def energy_figure(h, events, summary, title):
    """energy.png: the Jacobi integral (with why impacts raise it) and the hub torque against θ."""
    imp = _impacts(events)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    a1.plot(h["theta_deg"], (h["jacobi_j"] - h["jacobi_j"][0]) * 1e6, lw=1)
    for i in imp:
        a1.axvline(events["theta_deg"][i], color="C3", lw=0.4, alpha=0.5)
    a1.set_ylabel("h − h(0) (µJ)")
    a1.set_title(f"Jacobi integral h = T2 − T0 + U, the energy in the hub's rotating frame (red: impacts)\n"
                 f"energy-audit residual {summary['energy_audit_residual']:.2e} — {title}", fontsize=9)
    ledger = impact_energy(h, events, summary)
    if ledger is not None:
        a1.text(0.01, 0.97, energy_note(ledger), transform=a1.transAxes, va="top", fontsize=7,
                bbox=dict(boxstyle="round", fc="white", ec="0.7", alpha=0.9))
        top = np.nanmax(h["jacobi_j"] - h["jacobi_j"][0]) * 1e6
        bottom = np.nanmin(h["jacobi_j"] - h["jacobi_j"][0]) * 1e6
        span = max(top - bottom, 1e-9)
        a1.set_ylim(bottom - 0.05 * span, top + 0.45 * span)  # room for the note
    a2.plot(h["theta_deg"], h["hub_torque_n_m"] * 1e3, lw=0.8, color="C2")
    a2.set_ylabel("hub torque τ (mN·m)")
    a2.set_xlabel(f"hub angle θ ({DEG})")
    for a in (a1, a2):
        a.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def impacts_figure(h, events, summary, title):
    """impacts.png: V_X before and after, and e, at each impact."""
    imp = _impacts(events)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    if imp:
        th = events["theta_deg"][imp]
        a1.plot(th, events["vx_before_m_s"][imp], "o", ms=4, label="V_X before")
        a1.plot(th, events["vx_after_m_s"][imp], "s", ms=4, label="V_X after")
        a2.plot(th, events["restitution"][imp], "o", ms=4, color="C2")
        a1.legend(fontsize=8)
    else:
        a1.text(0.5, 0.5, "no impact in this pass", transform=a1.transAxes, ha="center", va="center")
    a1.axhline(0, color="k", lw=0.6)
    a1.set_ylabel("normal tip velocity (m/s)")
    a2.set_ylabel("restitution e")
    a2.set_ylim(-0.05, 1.05)
    a2.set_xlabel(f"hub angle θ ({DEG})")
    a1.set_title(f"{len(imp)} impacts ({summary.get('plastic_impacts', 0)} plastic) — {title}", fontsize=9)
    for a in (a1, a2):
        a.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def run_figures(folder, run=None):
    """[(name, figure)] of a run folder's pictures, all drawn before any is written (run: read_run's
    answer, when read already). Closes the ones drawn when one fails."""
    folder = Path(folder)
    h, events, summary = run if run is not None else read_run(folder)
    title = case_title(summary)
    figures = []
    try:
        for name, draw in (("normal_force_vs_y", lambda: force_figure(folder, h, events, summary, title)),
                           ("tip_path", lambda: tip_path_figure(h, events, summary, title)),
                           ("modal_coordinates", lambda: modal_figure(h, events, summary, title)),
                           ("energy", lambda: energy_figure(h, events, summary, title)),
                           ("impacts", lambda: impacts_figure(h, events, summary, title))):
            figures.append((name, draw()))
    except BaseException:
        for _, fig in figures:
            plt.close(fig)
        raise
    return figures


def save_figures(figures, out):
    """Writes run_figures' pictures into the folder out (made here) and closes them: the paths."""
    out = Path(out)
    written = []
    try:
        try:
            out.mkdir(parents=True, exist_ok=True)
        except OSError as e:
            raise OutputFolderError(f"-o {out}: cannot create the output folder ({e.strerror or e})") from None
        for name, fig in figures:
            written.append(out / f"{name}.png")
            save_figure(fig, written[-1])
    finally:
        for _, fig in figures:
            plt.close(fig)
    return written


def plot_run(folder, out):
    """The pictures of a run folder into out: the files are read and checked and every picture is
    drawn before the folder out is made and anything is written (damaged files leave nothing)."""
    return save_figures(run_figures(folder), out)


def value_text(v):
    """A sweep value as it was meant: 550 and 0.1, not 550.0 (numbers with %g; others as written)."""
    if isinstance(v, (float, np.floating)):
        return f"{v:g}"
    return str(v)


LINESTYLES = ["-", "--", ":", "-."]
MARKERS = ["o", "s", "^", "D", "v", "P", "X", "*"]


def series_styles(series):
    """A distinct (colour, linestyle, marker) for every series, each a tuple of values: with two or more
    values per series and at most 10 × 4 combinations, the colour follows the first value and the
    line style and marker the rest; otherwise series i gets colour i mod 10 and line style and marker
    from i // 10 (distinct for any number of series)."""
    firsts = list(dict.fromkeys(t[0] for t in series))
    rests = list(dict.fromkeys(t[1:] for t in series))
    styles = []
    for i, t in enumerate(series):
        if len(t) > 1 and len(firsts) <= 10 and len(rests) <= len(LINESTYLES):
            c, k = firsts.index(t[0]), rests.index(t[1:])
        else:
            c, k = i % 10, i // 10
        styles.append({"color": f"C{c}", "linestyle": LINESTYLES[k % len(LINESTYLES)],
                       "marker": MARKERS[k % len(MARKERS)]})
    return styles


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


def _legend_beside(fig, handles, labels, **options):
    """A legend right of the panels, never over the data; returns the share of the width left to them."""
    legend = fig.legend(handles, labels, loc="center right", **options)
    fig.canvas.draw()
    return 1.0 - legend.get_window_extent().width / fig.bbox.width - 0.01


def read_sweep(folder):
    """(table, keys, ok) of a sweep folder: sweep.csv's columns, the varied keys (the columns between
    `folder` and `status`, docs/cli.md) and which cases have results (done, resumed, or failed: stopped
    on a diagnosed failure, their files kept). A case with results whose files are missing or damaged
    raises DamagedFolder."""
    folder = Path(folder)
    table = read_csv(folder / "sweep.csv")
    columns = list(table)
    keys = columns[columns.index("folder") + 1:columns.index("status")]
    ok = np.isin(table["status"], ["done", "resumed", "failed"])
    for f, good in zip(table["folder"], ok):
        if good:  # a case with results must have its files: a missing or damaged one is named
            if not (folder / f / "summary.json").exists():
                raise DamagedFolder(f"{folder / f / 'summary.json'}: missing (sweep.csv lists results for {f})")
            check_run_files(folder / f)
    return table, keys, ok


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
    for ax, (metric, scale, label) in zip(axes.flat, panels):
        for g, style in zip(groups, styles):
            sel = ok.copy()
            for k, v in zip(rest, g):
                sel &= table[k] == v
            order = np.argsort(x[sel].astype(float)) if x.dtype.kind == "f" else np.arange(sel.sum())
            label_g = ", ".join(f"{k} = {value_text(v)}" for k, v in zip(rest, g)) or None
            ax.plot(x[sel][order], table[metric][sel][order] * scale, ms=4, label=label_g, **style)
        ax.set_xlabel(first)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        if not ok.any():
            ax.text(0.5, 0.5, "no case has results", transform=ax.transAxes, ha="center", va="center")
    fig.suptitle(title, fontsize=10)
    right = _legend_beside(fig, *axes[0, 0].get_legend_handles_labels(), fontsize=8) if rest and ok.any() else 1.0
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
    return metrics_figure(table, keys, ok, panels,
                          f"Sweep of {len(table['case'])} cases over {', '.join(keys)}{_cases_note(table, ok)}")


def sweep_force_figure(folder, table, keys, ok, folders, runs=None):
    """sweep_normal_force_vs_y.png: every case's sustained-contact F_n against the tip's Y; the cases
    made of impacts alone are named, not drawn. runs: {case folder: read_run's answer} read already."""
    folder = Path(folder)
    fig, ax = plt.subplots(figsize=(11, 5.5))
    where = {f: i for i, f in enumerate(table["folder"])}
    values = [tuple(table[k][where[f]] for k in keys) for f in folders]
    impacts_only = []
    for f, v, style in zip(folders, values, series_styles(values)):
        h, _, summary = runs[f] if runs and f in runs else read_run(folder / f)
        label = ", ".join(value_text(u) for u in v)
        if not plot_normal_force(h, None, summary, ax, label=label, lw=1.1, **dict(style, marker=None)):
            impacts_only.append(label)
    ax.set_xlabel("tip position Y (mm)")
    ax.set_ylabel("normal force F_n (N)")
    ax.grid(alpha=0.3)
    title = "Sustained-contact normal force along the surface, every case"
    if impacts_only:
        shown = "; ".join(impacts_only[:6]) + ("; …" if len(impacts_only) > 6 else "")
        title += (f"\n{_of(len(impacts_only), len(folders), 'cases with results')} no sustained contact "
                  f"(impacts only: see their normal_force_vs_y.png), not drawn: {shown}")
    right = 1.0
    if len(impacts_only) < len(folders):
        right = _legend_beside(fig, *ax.get_legend_handles_labels(), fontsize=7, title=", ".join(keys),
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
        named = ", ".join(f"{table['folder'][i]} ({table['status'][i]}"
                          f"{': ' + table['message'][i].split(':')[0] if table['message'][i] else ''})"
                          for i in missing[:4])
        note = (f"\n{len(missing)} of {n} brushes not drawn (a filament failed, so the sums would leave it out; "
                f"or no results): {named}{', …' if len(missing) > 4 else ''}")
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
    named = ", ".join(f"{table['folder'][i]} ({table['status'][i]}"
                      f"{': ' + table['message'][i].split(':')[0] if table['message'][i] else ''})" for i in left[:4])
    return f"\n{len(left)} of {len(table['case'])} cases not drawn: {named}{', …' if len(left) > 4 else ''}"


def plot_sweep(folder, out, cases=False):
    """The pictures of a sweep folder into out; every case with results is read and checked first
    (read_run), so a damaged one is named before the folder out is made and anything is written."""
    folder, out = Path(folder), Path(out)
    if "force_ratio" in read_csv(folder / "sweep.csv"):  # a sweep over brushes (docs/brush.md)
        table = read_csv(folder / "sweep.csv")
        columns = list(table)
        keys = columns[columns.index("folder") + 1:columns.index("status")]
        # A brush with a failed filament has sums without it: only whole brushes are drawn.
        ok = np.isin(table["status"], ["done", "resumed"])
        return plot_brush_sweep(folder, out, table, keys, ok, cases)
    table, keys, ok = read_sweep(folder)
    folders = [f for f, good in zip(table["folder"], ok) if good and (folder / f / "history.csv").exists()]
    drawn = folders if folders and len(folders) <= 24 else []
    runs = {f: read_run(folder / f) for f in drawn}
    if cases:
        for f in folders:
            if f not in runs:
                read_run(folder / f)
    figures = [("sweep_metrics", sweep_metrics_figure(table, keys, ok))]
    try:
        if drawn:
            figures.append(("sweep_normal_force_vs_y", sweep_force_figure(folder, table, keys, ok, drawn, runs)))
        if is_rub_sweep(folder, table, keys, ok):
            figures.append(("rub_map", rub_map_figure(folder, table, keys, ok, _rub_note(table))))
    except BaseException:
        for _, fig in figures:
            plt.close(fig)
        raise
    written = save_figures(figures, out)
    if cases:
        for f in folders:
            written += save_figures(run_figures(folder / f, runs.get(f)), out / f)
    return written


def plot_campbell(csv_path, png_path, orders=(1, 2, 3, 5, 10, 20)):
    """Campbell diagram from `rotbeam modes --csv`: frequencies against speed with engine orders."""
    table = read_csv(csv_path)
    speeds = table["speed_rpm"]
    modes = sorted((k for k in table if k.endswith("_hz")), key=lambda k: int(k[1:-3]))
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for k in modes:
        ax.plot(speeds, table[k], lw=2, label=f"mode {k[1:-3]}")
    top = max(np.nanmax(table[k]) for k in modes) * 1.3
    fine = np.linspace(0, speeds.max(), 200)
    for order in orders:
        ax.plot(fine, order * fine / 60.0, "k--", lw=0.7, alpha=0.6)
        x_end = min(fine[-1], top * 60.0 / order)
        ax.annotate(f"{order}×", (x_end, order * x_end / 60.0), fontsize=8, ha="right", va="bottom")
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


def main(argv=None):
    parser = argparse.ArgumentParser(prog="rotbeam plot", description="Pictures of a rotbeam run or sweep folder")
    parser.add_argument("folder", help="a run folder (summary.json) or a sweep folder (sweep.csv); with "
                        "--campbell, the CSV of `rotbeam modes --csv`")
    parser.add_argument("-o", "--output", help="where to write the PNGs (default: the folder itself)")
    parser.add_argument("--cases", action="store_true", help="for a sweep, also the pictures of every case")
    parser.add_argument("--campbell", metavar="PNG", help="draw a Campbell diagram of the CSV into PNG")
    parser.add_argument("--reproduce", action="store_true", help="draw the figures and report of `rotbeam reproduce`")
    args = parser.parse_args(argv)
    folder = Path(args.folder)
    out = Path(args.output) if args.output else folder
    if args.output and out.exists() and not out.is_dir():
        print(f"rotbeam: error: -o {out}: exists and is not a folder", file=sys.stderr)
        return 2
    try:
        if args.reproduce:
            from .reproduce import write_report
            written = [write_report(folder)]
        elif args.campbell:
            written = plot_campbell(args.folder, args.campbell)
        elif (folder / "sweep.csv").exists():
            written = plot_sweep(folder, out, args.cases)
        elif (folder / "summary.json").exists() and is_brush_folder(folder):
            written = save_figures(brush_figures(folder), out)
        elif (folder / "summary.json").exists():
            written = plot_run(folder, out)
        elif not folder.exists():
            print(f"rotbeam: error: {folder}: no such folder", file=sys.stderr)
            return 2
        else:
            print(f"rotbeam: error: {folder}: neither a run folder (summary.json) nor a sweep folder (sweep.csv)",
                  file=sys.stderr)
            return 2
    except (DamagedFolder, DamagedBrush, OutputFolderError) as e:
        return error(e)
    except OSError as e:  # before ValueError: some OSErrors are not, but say what file and why
        return file_error(e)
    except ValueError as e:
        if str(e).startswith(str(args.campbell or "\0")) or "cannot write a picture" in str(e):
            print(f"rotbeam: error: {e}", file=sys.stderr)
        else:  # json.JSONDecodeError is a ValueError
            print(f"rotbeam: error: {folder}: damaged or incomplete run files ({e})"[:400], file=sys.stderr)
        return 2
    except (KeyError, IndexError, TypeError, AttributeError) as e:
        print(f"rotbeam: error: {folder}: damaged or incomplete run files (missing or odd entry {e})"[:400],
              file=sys.stderr)
        return 2
    return wrote(written)


if __name__ == "__main__":
    run_main(main)
