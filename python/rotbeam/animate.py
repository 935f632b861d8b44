"""An animation of a run: the filament bending as it strikes, bounces back and rubs.

    python3 -m rotbeam.animate DIR [-o FILE]      # or: rotbeam animate DIR

Reads a run folder (summary.json, history.csv, events.csv) and draws, frame by frame, the
filament's centreline (from the recorded modal coordinates q through the beam model,
BeamModel::shape) with the hub and the surface to scale, an inset that follows the tip, and a strip
of the normal force against the hub angle with a cursor. Frames are history rows, placed densely
where things happen (around impacts and in sustained contact) and sparsely in free flight: time
runs in hub angle, in slow motion around contact. Written as GIF (Pillow) and, where ffmpeg is
installed, MP4.
"""

if __name__ == "__main__":
    from rotbeam._interrupt import announce_start, stop_quietly_on_interrupt

    stop_quietly_on_interrupt()
    announce_start()

import argparse  # noqa: E402
import errno  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import shutil  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

# rotbeam._figures first: where matplotlib is missing it says so in one line.
from ._figures import case_title, put_in_place, remove_stale_temporaries, temporary_beside  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import _interrupt  # noqa: E402

try:
    from PIL import Image
except ImportError as missing:  # one line naming what to install, not a traceback
    raise _interrupt.missing_package(
        f"an animation needs Pillow for {sys.executable} (Debian: apt-get install python3-pil): {missing}") from None

from ._csv import DamagedFolder, read_csv  # noqa: E402
from ._interrupt import error, file_error, wrote  # noqa: E402
from ._runs import coordinate_count, read_run  # noqa: E402
from ._surface import draw_surface, outline, reach_m, surface_of, surface_x  # noqa: E402

#: Slow motion: a degree of hub angle within `EVENT_HALF_WIDTH_DEG` of an impact, contact start or
#: separation gets `EVENT_WEIGHT` times the frames of a degree of free flight; one in sustained
#: contact `CONTACT_WEIGHT` times.
EVENT_WEIGHT = 40.0
CONTACT_WEIGHT = 8.0
EVENT_HALF_WIDTH_DEG = 0.4
EVENT_KINDS = ("impact", "contact_start", "contact_end")
#: A GIF holds its frames in memory until it is written (about 0.5 MB each at the default size).
MAX_FRAMES = 2000


def _shape_overrides(summary):
    """The keys of the run's resolved configuration that make its filament, as `--set` pairs: the beam
    and hub sections, the rotation switches, and the contact law, which some beam keys belong to
    (beam.poisson is the compliant law's: without contact.model = "hertz" it is refused)."""
    from . import _arguments
    c = summary["config"]
    sections = {"beam": c["beam"], "hub": c["hub"]}
    if isinstance(c.get("model"), dict):
        sections["model"] = c["model"]
    if isinstance(c.get("contact"), dict) and "model" in c["contact"]:
        sections["contact"] = {"model": c["contact"]["model"]}
    return _arguments(sections, None)[1]


def with_rigid_approach(history, summary, step_deg=0.05):
    """The history with the rigid approach filled in, for histories written before runs recorded
    it: such a rigid start has the state at θ0 and next at the first impact (the undeformed
    filament turns rigidly in between, q = 0, thesis §4.6 Step 1). Rows every `step_deg` of that
    turn are added, exact (q = 0, t = (θ − θ0)/ω), so that an animation shows the filament
    approaching the surface. Histories that record the turn are returned as they are."""
    c = summary["config"]
    theta = history["theta_deg"]
    n = coordinate_count(c)
    if c.get("initial", {}).get("start") != "rigid" or len(theta) < 2 or theta[1] - theta[0] <= 2 * step_deg:
        return history
    if any(history[f"q{i + 1}_m"][k] != 0.0 for i in range(n) for k in (0, 1)):
        return history
    fill = np.arange(theta[0] + step_deg, theta[1] - 0.5 * step_deg, step_deg)
    omega_deg = 6.0 * c["hub"]["speed_rpm"]  # deg/s
    reach = c["hub"]["radius_m"] + c["beam"]["length_m"]
    added = {key: np.full(len(fill), np.nan) for key in history}
    added["theta_deg"] = fill
    added["t_s"] = history["t_s"][0] + (fill - theta[0]) / omega_deg
    added["phase"] = np.array(["free"] * len(fill))
    added["x_tip_m"] = reach * np.cos(np.radians(fill))
    added["y_tip_m"] = reach * np.sin(np.radians(fill))
    for key in ("normal_force_n", "friction_force_n", "lambda_n"):
        if key in added:
            added[key] = np.zeros(len(fill))
    for i in range(n):
        added[f"q{i + 1}_m"] = np.zeros(len(fill))
        added[f"qd{i + 1}_m_s"] = np.zeros(len(fill))
    return {key: np.concatenate([history[key][:1], added[key], history[key][1:]]) for key in history}


def revolution_span(history, summary):
    """(θ_from, θ_to) [deg] of the last complete revolution in the history of a run over many
    revolutions; the whole recorded span for one pass."""
    theta = history["theta_deg"]
    if summary.get("revolutions", 0) and len(theta):
        return max(theta[0], theta[-1] - 360.0), theta[-1]
    return theta[0], theta[-1]


def default_window(history, events, summary):
    """The contact region (impacts and contact) of the recorded span with a margin of a third of its
    width (at least 3°) each side; the whole span when the tip never touched."""
    lo, hi = revolution_span(history, summary)
    theta = history["theta_deg"]
    touched = [float(t) for t, k in zip(events.get("theta_deg", []), events.get("kind", [])) if k in EVENT_KINDS]
    touched += list(theta[(history["phase"] != "free") & (theta >= lo)])
    touched = [t for t in touched if lo <= t <= hi]
    if not touched:
        return lo, hi
    a, b = min(touched), max(touched)
    margin = max(3.0, (b - a) / 3.0)
    return max(lo, a - margin), min(hi, b + margin)


def frame_rows(history, events, window, frames):
    """Indices of the history rows shown as frames: `frames` targets spread evenly over the
    cumulative weight of hub angle (slow motion near events and in contact), each taken as the
    nearest recorded row (so every frame shows a computed state, never an interpolation)."""
    theta = history["theta_deg"]
    inside = np.flatnonzero((theta >= window[0]) & (theta <= window[1]))
    if len(inside) == 0:
        raise ValueError(f"no history rows between {window[0]:g}° and {window[1]:g}°")
    th = theta[inside]
    weight = np.ones_like(th)
    weight[history["phase"][inside] != "free"] = CONTACT_WEIGHT
    for t, k in zip(events.get("theta_deg", []), events.get("kind", [])):
        if k in EVENT_KINDS:
            weight = np.where(np.abs(th - float(t)) <= EVENT_HALF_WIDTH_DEG, np.maximum(weight, EVENT_WEIGHT), weight)
    cumulative = np.concatenate([[0.0], np.cumsum(np.diff(th) * 0.5 * (weight[1:] + weight[:-1]))])
    targets = np.linspace(0.0, cumulative[-1], max(int(frames), 2))
    nearest = np.clip(np.searchsorted(cumulative, targets), 0, len(th) - 1)
    before = np.clip(nearest - 1, 0, len(th) - 1)
    pick = np.where(np.abs(cumulative[before] - targets) < np.abs(cumulative[nearest] - targets), before, nearest)
    return inside[np.unique(pick)]


def filament_frames(folder, rows=None, points=41, magnify=1.0, history=None, summary=None):
    """The filament drawn at history rows `rows` (default: all): {"x", "y"} global positions [m],
    arrays rows × points along the filament (ξ = 0 … 1), rotated by the hub angle of each row.
    With magnify = k the deflection from the straight filament is drawn k times."""
    from . import _core
    folder = Path(folder)
    if summary is None:
        summary = json.loads((folder / "summary.json").read_text())
    n = coordinate_count(summary["config"])
    if history is None:
        history = read_csv(folder / "history.csv", modes=n)
    rows = np.arange(len(history["t_s"])) if rows is None else np.asarray(rows)
    q = np.column_stack([history[f"q{i + 1}_m"][rows] for i in range(n)])
    xi = np.linspace(0.0, 1.0, points)
    hub = np.asarray(_core.filament_shape(None, _shape_overrides(summary), q, xi))  # rows × points × 2
    if magnify != 1.0:
        c = summary["config"]
        straight_x = c["hub"]["radius_m"] + xi * c["beam"]["length_m"]
        hub = hub.copy()
        hub[:, :, 0] = straight_x + magnify * (hub[:, :, 0] - straight_x)
        hub[:, :, 1] *= magnify
    th = np.radians(history["theta_deg"][rows])[:, None]
    x = hub[:, :, 0] * np.cos(th) - hub[:, :, 1] * np.sin(th)
    y = hub[:, :, 0] * np.sin(th) + hub[:, :, 1] * np.cos(th)
    return {"x": x, "y": y}


def _refuse_brush(folder):
    """A brush's folder holds sums over its filaments, no filament's history: said as such (it named
    a summary entry the brush does not write)."""
    try:
        kind = json.loads((folder / "summary.json").read_text()).get("kind")
    except (OSError, ValueError, AttributeError):
        return  # read_run says what is wrong with it
    if kind == "brush":
        raise ValueError(f"{folder}: holds a brush (rotbeam brush), not a run: animate draws one filament's run; "
                         f"draw the brush with `rotbeam plot {folder}`, or animate one of its filaments with "
                         "`rotbeam run` (without the [brush] keys)")


def _tty_progress(done, total):
    if sys.stderr.isatty():
        print(f"\r  frame {done + 1} of {total}", end="", file=sys.stderr, flush=True)


def animate(folder, output=None, frames=None, frames_per_degree=None, window=None, zoom_mm=None, magnify=1.0,
            fps=20, dpi=80, progress=None, note=None):
    """Draws the animation of the run in `folder` and returns the paths written.

    output: a .gif or .mp4 file (default: folder/animation.gif, and folder/animation.mp4 where ffmpeg
    is installed). frames (default 240) or frames_per_degree: how many frames over the window.
    window: (θ_from, θ_to) [deg] (default: the contact region with a margin; for a run over many
    revolutions, in its last revolution). zoom_mm: half-width of the inset around the tip [mm]
    (default: three depths of the surface, at least 2.5 mm). magnify: draws the deflection k times
    (1: to scale; said in the title otherwise). progress(i, n): called per frame written; note(text):
    told when the history holds fewer distinct states than frames asked for (each frame is a
    recorded state, never an interpolation)."""
    folder = Path(folder)
    _refuse_brush(folder)
    history, events, summary = read_run(folder)  # every file checked before anything is drawn
    if not len(history.get("t_s", [])):
        raise DamagedFolder(f"{folder / 'history.csv'}: no rows to animate")
    history = with_rigid_approach(history, summary)
    if magnify <= 0 or not math.isfinite(magnify):
        raise ValueError(f"magnify = {magnify:g}: must be a positive number")
    lo, hi = window if window is not None else default_window(history, events, summary)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise ValueError(f"window {lo:g}:{hi:g}: must be finite hub angles")
    if not hi > lo:
        raise ValueError(f"window {lo:g}:{hi:g}: the end angle must exceed the start")
    # A window is drawn over the angles the history recorded: beyond them there is nothing to show,
    # and -1e308:1e308 overflowed in matplotlib's transforms (a traceback).
    recorded = history["theta_deg"]
    first, last = float(np.min(recorded)), float(np.max(recorded))
    if hi < first or lo > last:
        raise ValueError(f"window {lo:g}:{hi:g}: no history rows in it (the run recorded {first:.6g}° … {last:.6g}°)")
    lo, hi = max(lo, first), min(hi, last)
    if frames_per_degree is not None:
        if not frames_per_degree > 0:
            raise ValueError(f"frames per degree = {frames_per_degree:g}: must be positive")
        frames = math.ceil(frames_per_degree * (hi - lo))
        if not 2 <= frames <= MAX_FRAMES:
            raise ValueError(f"frames per degree = {frames_per_degree:g} over the {hi - lo:.4g}° window gives "
                             f"{frames} frames: must give 2 … {MAX_FRAMES}")
    frames = 240 if frames is None else int(frames)
    if not 2 <= frames <= MAX_FRAMES:
        raise ValueError(f"frames = {frames}: must be in 2 … {MAX_FRAMES}")
    rows = frame_rows(history, events, (lo, hi), frames)
    if len(rows) < 0.9 * frames and note is not None:
        note(f"{len(rows)} frames of the {frames} asked for: the history holds no more distinct states in "
             f"{lo:.4g}° … {hi:.4g}° where the frames are wanted (a smaller output.interval_s records more)")
    shape = filament_frames(folder, rows, magnify=magnify, history=history, summary=summary)
    c = summary["config"]
    surface = surface_of(summary)
    # How far the tip reaches into the surface: the zoom's scale.
    zoom = (zoom_mm if zoom_mm is not None else max(2.5, 3e3 * reach_m(c))) * 1e-3
    if not zoom > 0:
        raise ValueError(f"zoom = {zoom_mm:g} mm: must be positive")

    # Display plane: Y to the right, −X up (the thesis's figures): the hub turns above the surface.
    px, py = shape["y"] * 1e3, -shape["x"] * 1e3
    t, theta = history["t_s"][rows], history["theta_deg"][rows]
    phase, fn = history["phase"][rows], history["normal_force_n"][rows]
    impacts = [(float(et), float(eth), float(ey)) for et, eth, k, ey in
               zip(events.get("t_s", []), events.get("theta_deg", []), events.get("kind", []),
                   events.get("y_tip_m", [])) if k == "impact"]
    impacts = [i for i in impacts if lo <= i[1] <= hi]

    fig = plt.figure(figsize=(9, 6.6), dpi=dpi)
    grid = fig.add_gridspec(2, 2, height_ratios=[3, 1], width_ratios=[4, 3], hspace=0.32, wspace=0.12,
                            left=0.09, right=0.97, top=0.9, bottom=0.08)
    ax = fig.add_subplot(grid[0, 0])
    side = grid[0, 1].subgridspec(2, 1, height_ratios=[5, 2], hspace=0.45)
    inset = fig.add_subplot(side[0])
    text_ax = fig.add_subplot(side[1])
    text_ax.axis("off")
    strip = fig.add_subplot(grid[1, :])
    title = case_title(summary) + "\n"
    title += "to scale" if magnify == 1.0 else f"deflection drawn ×{magnify:g} (not to scale)"
    fig.suptitle(title, fontsize=10)

    # The whole filament, the hub and the surface, to scale (static axes).
    r_hub = c["hub"]["radius_m"] * 1e3
    ax.add_patch(plt.Circle((0, 0), r_hub, color="0.85", zorder=0))
    ax.plot([0], [0], "+", color="0.4")
    span_x = np.concatenate([px.ravel(), [-r_hub, r_hub]])
    span_y = np.concatenate([py.ravel(), [-r_hub, r_hub]])
    xmin, xmax = span_x.min(), span_x.max()
    casing = surface["shape"] == "casing"
    ymin = span_y.min() if casing else min(span_y.min(), -surface_x(surface, [0.0])[0] * 1e3)
    ymax = span_y.max()
    pad = 0.06 * max(xmax - xmin, ymax - ymin)
    ax.set_xlim(xmin - pad, xmax + pad)
    ax.set_ylim(ymin - 2 * pad, ymax + pad)
    ax.set_aspect("equal")
    if casing:  # the casing all round the hub (the view shows the part the filament sweeps)
        draw_surface(ax, surface, None, color="0.3", lw=1)
    else:
        surface_y, surface_h = outline(surface, [xmin - pad, xmax + pad])
        ax.fill_between(surface_y, surface_h, ymin - 3 * pad, color="0.55", alpha=0.5, lw=0)
        ax.plot(surface_y, surface_h, color="0.3", lw=1)
    ax.set_xlabel("Y (mm)")
    ax.set_ylabel("−X (mm)")

    # The tip's neighbourhood in coordinates relative to the tip (static axes, moving surface).
    zmm = zoom * 1e3
    inset.set_xlim(-zmm, zmm)
    inset.set_ylim(-zmm, zmm)
    inset.set_aspect("equal")
    inset.tick_params(labelsize=7)
    inset.set_title("around the tip (mm from it)", fontsize=9)
    inset.set_xlabel("ΔY (mm)", fontsize=8)
    inset.set_ylabel("−ΔX (mm)", fontsize=8)

    # F_n against hub angle, impacts as lines, a cursor.
    window_rows = (history["theta_deg"] >= lo) & (history["theta_deg"] <= hi)
    sustained = bool(np.any(history["normal_force_n"][window_rows] > 0))
    strip.plot(history["theta_deg"][window_rows], history["normal_force_n"][window_rows], color="C1", lw=1,
               label="F_n (sustained contact)" if sustained else None)
    for k, (_, eth, _) in enumerate(impacts):
        strip.axvline(eth, color="C3", lw=0.6, alpha=0.6, label=f"impacts ({len(impacts)})" if k == 0 else None)
    strip.set_xlim(lo, hi)
    strip.set_xlabel("hub angle θ (°, counted on over revolutions)" if summary.get("revolutions", 0)
                     else "hub angle θ (°)")
    strip.set_ylabel("F_n (N)")
    if not sustained:
        strip.text(0.5, 0.5, "no sustained contact in this window: impacts only" if impacts else
                   "the tip does not touch the surface in this window", transform=strip.transAxes,
                   ha="center", va="center", fontsize=8, color="0.4")
    if sustained or impacts:
        strip.legend(loc="upper right", fontsize=7)

    # The moving parts, drawn over a saved background (blitting).
    line, = ax.plot([], [], color="C0", lw=2, animated=True)
    tip_dot, = ax.plot([], [], "o", color="C3", ms=4, animated=True)
    marks, = ax.plot([], [], "x", color="C3", ms=6, mew=1.5, animated=True)
    in_surface, = inset.plot([], [], color="0.3", lw=1, animated=True)
    in_line, = inset.plot([], [], color="C0", lw=2, animated=True)
    in_dot, = inset.plot([], [], "o", color="C3", ms=4, animated=True)
    in_marks, = inset.plot([], [], "x", color="C3", ms=6, mew=1.5, animated=True)
    info = text_ax.text(0.0, 1.0, "", transform=text_ax.transAxes, va="top", family="monospace", fontsize=9,
                        animated=True)
    cursor = strip.axvline(lo, color="k", lw=1, animated=True)
    moving = [(ax, line), (ax, tip_dot), (ax, marks), (inset, in_surface), (inset, in_line), (inset, in_dot),
              (inset, in_marks), (text_ax, info), (strip, cursor)]
    impact_points = np.array([(ey * 1e3, -surface_x(surface, [ey], [np.interp(et, history["t_s"], history["x_tip_m"])])[0]
                               * 1e3) for et, _, ey in impacts]).reshape(-1, 2)
    impact_t = np.array([i[0] for i in impacts])
    inset_surface_y = np.linspace(-zmm, zmm, 50)

    many = bool(summary.get("revolutions", 0))
    theta0 = -90.0  # the hub angle at t = 0 (docs/model.md §2): revolution k spans θ0 + 360°(k − 1) … θ0 + 360°k

    def draw(k):
        tx, ty = px[k, -1], py[k, -1]
        line.set_data(px[k], py[k])
        tip_dot.set_data([tx], [ty])
        in_line.set_data(px[k] - tx, py[k] - ty)
        in_dot.set_data([0.0], [0.0])
        in_surface.set_data(inset_surface_y, -surface_x(surface, (inset_surface_y + tx) * 1e-3,
                                                        np.full_like(inset_surface_y, -ty * 1e-3)) * 1e3 - ty)
        done = impact_t <= t[k]
        marks.set_data(impact_points[done, 0], impact_points[done, 1])
        in_marks.set_data(impact_points[done, 0] - tx, impact_points[done, 1] - ty)
        hit_now = k > 0 and np.any((impact_t > t[k - 1]) & done)
        state = "IMPACT" if hit_now else str(phase[k])
        turn = f" (revolution {int((theta[k] - theta0) // 360.0) + 1})" if many else ""
        info.set_text(f"t   = {t[k] * 1e3:10.4f} ms\nθ   = {theta[k]:10.4f}°{turn}\nphase  {state}\n"
                      f"F_n = {fn[k]:10.4g} N\nimpacts so far {int(done.sum())}")
        cursor.set_xdata([theta[k], theta[k]])

    targets = [Path(output)] if output else [folder / "animation.gif"]
    if not output and shutil.which("ffmpeg"):
        targets.append(folder / "animation.mp4")
    for target in targets:
        if target.suffix.lower() not in (".gif", ".mp4"):
            raise ValueError(f"{target}: the animation is written as .gif or .mp4")
        if target.suffix.lower() == ".mp4" and not shutil.which("ffmpeg"):
            raise ValueError(f"{target}: MP4 needs ffmpeg (Debian: apt-get install ffmpeg); write a .gif")
    report = progress if progress is not None else _tty_progress
    sinks = []
    try:
        fig.canvas.draw()
        background = fig.canvas.copy_from_bbox(fig.bbox)
        width, height = fig.canvas.get_width_height()
        sinks = [_GifSink(t_, fps) if t_.suffix.lower() == ".gif" else _Mp4Sink(t_, fps, width, height)
                 for t_ in targets]
        for k in range(len(rows)):
            fig.canvas.restore_region(background)
            draw(k)
            for owner, artist in moving:
                owner.draw_artist(artist)
            rgba = np.asarray(fig.canvas.buffer_rgba())
            for sink in sinks:
                sink.add(rgba)
            report(k, len(rows))
        for sink in sinks:
            sink.finish()
    finally:
        for sink in sinks:
            sink.discard()
        plt.close(fig)
        if report is _tty_progress and sys.stderr.isatty():
            print("\r" + " " * 40 + "\r", end="", file=sys.stderr, flush=True)
    return targets


class _GifSink:
    """Frames quantised to a palette as they come (bounded memory: a byte per pixel), written by
    Pillow at the end into a temporary name beside the target, then renamed."""

    def __init__(self, target, fps):
        self.target = Path(target)
        remove_stale_temporaries(self.target)
        self.tmp = temporary_beside(self.target, stem=True, suffix=".gif")
        self.duration_ms = 1000.0 / fps
        self.frames = []

    def add(self, rgba):
        # One palette for every frame, from the first (the figure's few colours are all in it):
        # 30 times faster than a palette per frame, and no flicker between frames.
        image = Image.fromarray(rgba[:, :, :3])
        if not self.frames:
            self.frames.append(image.quantize(colors=64, method=Image.Quantize.MEDIANCUT))
        else:
            self.frames.append(image.quantize(palette=self.frames[0], dither=Image.Dither.NONE))

    def finish(self):
        try:
            self.frames[0].save(self.tmp, save_all=True, append_images=self.frames[1:], duration=self.duration_ms,
                                loop=0, optimize=False)
            put_in_place(self.tmp, self.target)
        except OSError as e:  # a full disk, a folder that cannot be written: the user's file and why
            raise OSError(e.errno, e.strerror or str(e), str(self.target)) from None

    def discard(self):
        self.frames = []
        if self.tmp.exists():
            self.tmp.unlink()


class _Mp4Sink:
    """Frames piped to ffmpeg as raw RGBA (H.264, yuv420p), into a temporary name, then renamed."""

    def __init__(self, target, fps, width, height):
        self.target = Path(target)
        remove_stale_temporaries(self.target)
        self.tmp = temporary_beside(self.target, stem=True, suffix=".mp4")
        self.proc = subprocess.Popen(
            ["ffmpeg", "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgba", "-s", f"{width}x{height}",
             "-r", f"{fps:g}", "-i", "-", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264",
             "-pix_fmt", "yuv420p", str(self.tmp)],
            stdin=subprocess.PIPE, stderr=subprocess.PIPE)

    def add(self, rgba):
        try:
            self.proc.stdin.write(np.ascontiguousarray(rgba).tobytes())
        except BrokenPipeError:  # ffmpeg stopped (a full disk, a folder it cannot write): why, from it
            self._end()
            raise OSError(errno.EIO, f"ffmpeg failed: {self._last_word()}", str(self.target)) from None

    def _end(self):
        """Closes ffmpeg's input and waits for it, keeping its messages: its exit code."""
        try:
            self.proc.stdin.close()
        except BrokenPipeError:
            pass
        self.err = self.proc.stderr.read().decode(errors="replace").strip()
        return self.proc.wait()

    def _last_word(self):
        return self.err.splitlines()[-1] if self.err else "no message"

    def finish(self):
        if self._end() != 0:
            raise OSError(errno.EIO, f"ffmpeg failed: {self._last_word()}", str(self.target))
        try:
            put_in_place(self.tmp, self.target)
        except OSError as e:
            raise OSError(e.errno, e.strerror or str(e), str(self.target)) from None

    def discard(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        if self.tmp.exists():
            self.tmp.unlink()


def _window(text):
    try:
        a, b = (float(v) for v in text.split(":"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected FROM:TO in degrees, e.g. -12:40") from None
    return a, b


def main(argv=None):
    parser = argparse.ArgumentParser(prog="rotbeam animate",
                                     description="An animation of a run: the filament through contact (GIF, MP4)")
    parser.add_argument("folder", help="a run folder (summary.json, history.csv, events.csv)")
    parser.add_argument("-o", "--output", help="a .gif or .mp4 file (default: FOLDER/animation.gif, and "
                        "animation.mp4 where ffmpeg is installed)")
    count = parser.add_mutually_exclusive_group()
    count.add_argument("--frames", type=int, help="number of frames (default 240)")
    count.add_argument("--frames-per-degree", type=float, help="frames per degree of hub angle")
    parser.add_argument("--window", type=_window, metavar="FROM:TO",
                        help="hub angles to show [deg] (default: the contact region with a margin)")
    parser.add_argument("--zoom", type=float, metavar="MM", help="half-width of the tip inset [mm]")
    parser.add_argument("--magnify", type=float, default=1.0, help="draw the deflection this many times (default 1)")
    parser.add_argument("--fps", type=float, default=20.0, help="frames per second of the file (default 20)")
    parser.add_argument("--quiet", action="store_true", help="no frame counter and no `wrote` lines (notes and "
                        "errors are still said)")
    args = parser.parse_args(argv)
    folder = Path(args.folder)
    if not folder.exists():
        print(f"rotbeam: error: {folder}: no such folder", file=sys.stderr)
        return 2
    if not (folder / "summary.json").exists():
        print(f"rotbeam: error: {folder}: not a run folder (no summary.json)", file=sys.stderr)
        return 2
    if args.output and Path(args.output).is_dir():
        print(f"rotbeam: error: -o {args.output}: is a folder; give a .gif or .mp4 file", file=sys.stderr)
        return 2
    if not args.fps > 0:
        print(f"rotbeam: error: --fps {args.fps:g}: must be positive", file=sys.stderr)
        return 2
    try:
        written = animate(folder, args.output, frames=args.frames, frames_per_degree=args.frames_per_degree,
                          window=args.window, zoom_mm=args.zoom, magnify=args.magnify, fps=args.fps,
                          note=lambda text: print(f"rotbeam: note: {text}", file=sys.stderr),
                          progress=(lambda done, total: None) if args.quiet else None)
    except DamagedFolder as e:
        return error(e)
    except OSError as e:
        return file_error(e)
    except (ValueError, KeyError, IndexError) as e:
        print(f"rotbeam: error: {e}"[:400], file=sys.stderr)
        return 2
    return 0 if args.quiet else wrote(written)


if __name__ == "__main__":
    from rotbeam._interrupt import run_main

    run_main(main)
