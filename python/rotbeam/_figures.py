"""What every picture of rotbeam shares: matplotlib (Agg; a missing one said in one line), pictures
written whole (a temporary file beside the target, renamed into place), the titles' words, the
series' styles and a legend beside the panels.

The picture modules sit on this one and never on each other's command line: run_plots (a run),
sweep_plots (a sweep), rub_map (Campbell diagrams and the rub map), brush_plots (a brush),
animate, reproduce; plots is the command line and names them all.
"""

import errno
import os
import shutil
import sys
import tempfile
from pathlib import Path

from . import _interrupt

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as missing:
    raise _interrupt.missing_package(
        f"drawing rotbeam's pictures needs numpy and matplotlib for {sys.executable} (Debian: apt-get install "
        f"python3-numpy python3-matplotlib): {missing}") from None

from ._surface import surface_words  # noqa: E402

DEG = "°"


class OutputFolderError(Exception):
    """The folder the pictures go to cannot be made (the message names it and why)."""


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


def save_figures(figures, out):
    """Writes [(name, figure)] as out/NAME.png into the folder out (made here) and closes them: the paths."""
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


# Legend locations in the order they are tried (matplotlib's codes): the corners first.
_LEGEND_LOCATIONS = (1, 2, 4, 3, 9, 8, 7, 6, 10)


def data_under(bbox, axes, renderer):
    """Whether anything drawn as data in `axes` (lines, markers, stems, bars, steps, scatter) lies in
    the display-space box `bbox`; reference lines spanning an axis (axhline, axvline) do not count."""
    from matplotlib.collections import LineCollection
    from matplotlib.path import Path as MPath

    pad = bbox.expanded(1.0, 1.0)
    for ax in axes:
        for line in ax.get_lines():
            if line.get_transform() != ax.transData or not line.get_visible():
                continue
            xy = np.asarray(line.get_xydata(), float)
            xy = xy[np.all(np.isfinite(xy), axis=1)]
            if len(xy) == 0:
                continue
            disp = ax.transData.transform(xy)
            if any(pad.contains(x, y) for x, y in disp):
                return True
            if line.get_linestyle() not in ("None", "", " ") and len(disp) > 1 and \
                    MPath(disp).intersects_bbox(pad, filled=False):
                return True
        for coll in ax.collections:
            if not coll.get_visible():
                continue
            if isinstance(coll, LineCollection):
                for seg in coll.get_segments():
                    seg = np.asarray(seg, float)
                    if len(seg) > 1 and MPath(coll.get_transform().transform(seg)).intersects_bbox(pad, filled=False):
                        return True
                continue
            offsets = np.asarray(coll.get_offsets(), float)
            if offsets.size:
                disp = coll.get_offset_transform().transform(offsets)
                if any(pad.contains(x, y) for x, y in disp if np.isfinite(x) and np.isfinite(y)):
                    return True
        for patch in ax.patches:
            if not patch.get_visible():
                continue
            path = patch.get_transform().transform_path(patch.get_path())
            if len(path.vertices) and path.intersects_bbox(pad, filled=bool(patch.get_fill())):
                return True
    return False


def _axes_sharing(ax):
    """ax and its twins (axes at the same place in the figure)."""
    return [a for a in ax.figure.axes if a is ax or np.allclose(a.get_position().bounds, ax.get_position().bounds)]


def keep_legends_off_data(fig):
    """Moves every legend of `fig` to the first location where it covers no data (a corner first),
    or, where every location inside covers some, outside its axes on the right (and lays the figure
    out again)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    moved_out = False
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is None:
            continue
        axes = _axes_sharing(ax)
        if legend._bbox_to_anchor is not None:
            continue  # placed outside on purpose
        for loc in (legend._loc,) + _LEGEND_LOCATIONS:
            legend._set_loc(loc)
            if not data_under(legend.get_window_extent(renderer), axes, renderer):
                break
        else:
            legend._set_loc(2)
            legend.set_bbox_to_anchor((1.01, 1.0), transform=ax.transAxes)
            moved_out = True
    if moved_out and not fig.get_constrained_layout():
        fig.tight_layout()


def draw_all(drawings):
    """[(name, figure)] of [(name, function drawing it)], every one drawn before any is written, with
    every legend kept off the data (keep_legends_off_data); the ones drawn are closed when one fails."""
    figures = []
    try:
        for name, draw in drawings:
            fig = draw()
            keep_legends_off_data(fig)
            figures.append((name, fig))
    except BaseException:
        for _, fig in figures:
            plt.close(fig)
        raise
    return figures


def modes_words(c):
    """'5 modes', with the beam theory and the rotation terms where they are not the thesis's."""
    words = f"{c['beam']['modes']} mode{'' if c['beam']['modes'] == 1 else 's'}"
    if c["beam"].get("theory", "foreshortening") != "foreshortening":
        words += f", {c['beam']['theory']}"
    if c["beam"].get("axial", "inextensible") == "extensible":
        words += ", extensible"
    model = c.get("model", {})
    off = [name for name in ("centrifugal", "Coriolis") if model.get(name.lower(), True) is False]
    if off:
        words += ", without the " + (" and ".join(off) if len(off) < 2 else "rotation") + " terms"
    return words


def case_title(summary):
    c = summary["config"]
    return (f"{c['hub']['speed_rpm']:g} rpm, {surface_words(c)}, "
            f"μ = {c['surface']['friction']:g}, {modes_words(c)}, {summary['scheme']} scheme")


def warning_line(summary):
    """The run's warnings as a line for a title (empty without warnings)."""
    warnings = summary.get("warnings", [])
    if not warnings:
        return ""
    return "\nwarning: " + "; ".join(warnings) if len(warnings) == 1 else \
        f"\n{len(warnings)} warnings: " + "; ".join(w.split(":")[0] for w in warnings)


def validity_note(summary):
    """A title's line on the model's validity when the pass left it (summary.json `validity` "edge" or
    "outside"; docs/model.md "Validity of a pass"), empty within it."""
    validity = summary.get("validity", "within")
    if validity == "within":
        return ""
    ratio = summary.get("max_tip_deflection_ratio")
    limit = summary.get("config", {}).get("simulation", {}).get("deflection_warning_ratio", 0.1)
    how = f"max |y_t|/L = {ratio:.3g} > {limit:g}" if isinstance(ratio, (int, float)) else "see the warnings"
    what = ("outside the model: not physical" if validity == "outside"
            else "the quadratic foreshortening at the edge of its validity")
    return f"\nvalidity {validity}: {how}, {what} (docs/model.md §10)"


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
    line style and marker the rest; otherwise series i gets colour i mod 10, the marker of i // 10 and
    a line style that changes from one series to the next, so that series that coincide stay visible
    (distinct up to 80 series)."""
    firsts = list(dict.fromkeys(t[0] for t in series))
    rests = list(dict.fromkeys(t[1:] for t in series))
    styles = []
    for i, t in enumerate(series):
        if len(t) > 1 and len(firsts) <= 10 and len(rests) <= len(LINESTYLES):
            c, k = firsts.index(t[0]), rests.index(t[1:])
        else:
            c, block = i % 10, i // 10
            styles.append({"color": f"C{c}", "linestyle": LINESTYLES[(i + block) % len(LINESTYLES)],
                           "marker": MARKERS[block % len(MARKERS)]})
            continue
        styles.append({"color": f"C{c}", "linestyle": LINESTYLES[k % len(LINESTYLES)],
                       "marker": MARKERS[k % len(MARKERS)]})
    return styles


def legend_beside(fig, handles, labels, **options):
    """A legend right of the panels, never over the data; returns the share of the width left to them."""
    legend = fig.legend(handles, labels, loc="center right", **options)
    fig.canvas.draw()
    return 1.0 - legend.get_window_extent().width / fig.bbox.width - 0.01
