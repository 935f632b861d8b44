"""Pictures of rotbeam outputs (matplotlib; reads only the files a run or sweep wrote).

    python3 -m rotbeam.plots DIR [-o OUT]      # or: rotbeam plot DIR

A run folder (history.csv, events.csv, summary.json) gives normal_force_vs_y.png (the thesis's
figures), tip_path.png (the path with close-ups, thesis Figure 13), modal_coordinates.png,
energy.png (the energy audit and the hub torque) and impacts.png. A sweep folder (sweep.csv) gives
sweep_metrics.png and sweep_normal_force_vs_y.png, plus the pictures of each case with
--cases.
"""

import argparse
import csv
import json
import math
import os
import sys
from pathlib import Path

if __name__ == "__main__":
    from rotbeam._interrupt import stop_quietly_on_interrupt

    stop_quietly_on_interrupt()

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as missing:
    _HINT = (f"rotbeam.plots needs numpy and matplotlib for {sys.executable} (Debian: apt-get install "
             f"python3-numpy python3-matplotlib): {missing}")
    if __name__ == "__main__":
        print(f"rotbeam: error: {_HINT}", file=sys.stderr)
        sys.exit(1)
    raise ImportError(_HINT) from None

DEG = "°"


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


def save_figure(fig, path, dpi=120):
    """Writes fig to path whole: into a temporary file beside it, renamed into place (an interrupted
    or failed save leaves no partial picture under the user's name)."""
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower() or "png"
    if fmt not in fig.canvas.get_supported_filetypes():
        raise ValueError(f"{path}: cannot write a picture as '.{fmt}' (use .png, .pdf or .svg)")
    remove_stale_temporaries(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        fig.savefig(tmp, dpi=dpi, format=fmt)
        os.replace(tmp, path)
    except OSError as e:  # the temporary's name means nothing to the user: theirs, and why
        raise OSError(e.errno, e.strerror, str(path)) from None
    finally:
        if tmp.exists():
            tmp.unlink()


def animate(folder, output=None, **options):
    """The animation of a run folder (rotbeam.animate.animate; its options): the paths written."""
    from .animate import animate as draw_animation
    return draw_animation(folder, output, **options)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    columns = {}
    for key in rows[0].keys() if rows else []:
        values = [r[key] for r in rows]
        try:
            columns[key] = np.array([float(v) if v != "" else math.nan for v in values])
        except ValueError:
            columns[key] = np.array(values)
    return columns


def case_title(summary):
    c = summary["config"]
    return (f"{c['hub']['speed_rpm']:g} rpm, depth {100 * c['surface']['depth_fraction']:g} %, "
            f"μ = {c['surface']['friction']:g}, {c['beam']['modes']} modes, {summary['scheme']} scheme")


class DamagedFolder(Exception):
    """A run folder whose files are not those its summary.json describes."""


def check_run_files(folder):
    """Raises DamagedFolder when summary.json does not parse or history.csv / events.csv are missing
    or not the size summary.json recorded (a truncated or replaced file)."""
    folder = Path(folder)
    try:
        summary = json.loads((folder / "summary.json").read_text())
    except ValueError as e:
        raise DamagedFolder(f"{folder / 'summary.json'}: not valid JSON ({e})") from None
    files = summary.get("files") if isinstance(summary, dict) else None
    if not isinstance(summary, dict) or not isinstance(summary.get("config"), dict) or \
            not isinstance(files, dict) or not all(isinstance(v, dict) for v in files.values()):
        raise DamagedFolder(f"{folder / 'summary.json'}: not a rotbeam run summary (its config or files are missing)")
    for name in ("history.csv", "events.csv"):
        path = folder / name
        if not path.exists():
            raise DamagedFolder(f"{path}: missing")
        recorded = files.get(name, {}).get("bytes")
        if recorded is not None and path.stat().st_size != recorded:
            raise DamagedFolder(f"{path}: {path.stat().st_size} bytes where summary.json records {recorded}: "
                                "truncated or replaced")


def surface_of(summary):
    """The surface as the run described it (summary.json `surface`). Folders written before the
    surface described itself hold the thesis's plane, rebuilt here from their configuration."""
    if "surface" in summary:
        return summary["surface"]
    c = summary["config"]
    return {"shape": "plane",
            "distance_m": c["hub"]["radius_m"] + c["beam"]["length_m"] * (1 - c["surface"]["depth_fraction"])}


def surface_x(surface, y):
    """X (m) of the surface at the global Y values `y` (m), for drawing it in the (Y, −X) plane."""
    y = np.asarray(y, dtype=float)
    if surface["shape"] == "plane":
        return np.full_like(y, surface["distance_m"])
    raise ValueError(f"cannot draw a surface of shape {surface['shape']!r}")


def draw_surface(ax, surface, y_mm, **style):
    """The surface as a curve −X against Y (mm) over the Y values `y_mm`."""
    y = np.linspace(np.nanmin(y_mm), np.nanmax(y_mm), 200)
    ax.plot(y, -surface_x(surface, y * 1e-3) * 1e3, **style)


def warning_line(summary):
    """The run's warnings as a line for a title (empty without warnings)."""
    warnings = summary.get("warnings", [])
    if not warnings:
        return ""
    return "\nwarning: " + "; ".join(warnings) if len(warnings) == 1 else \
        f"\n{len(warnings)} warnings: " + "; ".join(w.split(":")[0] for w in warnings)


def _impacts(events):
    return [i for i, k in enumerate(events["kind"]) if k == "impact"]


def plot_normal_force(h, events, summary, ax, label=None, **style):
    contact = h["phase"] == "contact"
    y = np.where(contact, h["y_tip_m"] * 1e3, np.nan)
    f = np.where(contact, h["normal_force_n"], np.nan)
    ax.plot(y, f, label=label, **style)
    return ax


def plot_run(folder, out):
    folder, out = Path(folder), Path(out)
    out.mkdir(parents=True, exist_ok=True)
    h = read_csv(folder / "history.csv")
    events = read_csv(folder / "events.csv")
    summary = json.loads((folder / "summary.json").read_text())
    title = case_title(summary)
    written = []
    imp = _impacts(events)

    # 1. Normal force against the tip's Y (the thesis's Figures 4–12).
    fig, ax = plt.subplots(figsize=(8, 4.5))
    plot_normal_force(h, events, summary, ax, color="C0", lw=1.2, label="sustained contact F_n")
    if imp:
        ax.plot(events["y_tip_m"][imp] * 1e3, np.zeros(len(imp)), "v", color="C3", ms=5,
                label=f"impacts ({len(imp)})")
    ax.set_xlabel("tip position Y (mm)")
    ax.set_ylabel("normal force F_n (N)")
    s = summary
    ax.set_title(f"{title}\n{s['impacts']} impacts, {s['contact_episodes']} contact episodes, "
                 f"peak {s['peak_normal_force_n']:.3g} N, impulse {1e3 * s['normal_impulse_n_s']:.4g} mN·s", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    written.append(out / "normal_force_vs_y.png")
    save_figure(fig, written[-1])
    plt.close(fig)

    # 2. Tip path with close-ups (thesis Figure 13: −X against Y).
    surface = surface_of(summary)
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    phase_colors = {"free": "C0", "contact": "C1", "stick": "C2"}
    X, Y = h["x_tip_m"] * 1e3, h["y_tip_m"] * 1e3
    def path(ax):
        for ph, color in phase_colors.items():
            sel = h["phase"] == ph
            if sel.any():
                ax.plot(Y[sel], -X[sel], ".", ms=1.5, color=color, label=ph)
        draw_surface(ax, surface, Y, color="k", lw=1, label="surface")
        if imp:
            y_imp = events["y_tip_m"][imp]
            ax.plot(y_imp * 1e3, -surface_x(surface, y_imp) * 1e3, "v", color="C3", ms=4, label="impacts")
        ax.set_xlabel("tip position Y (mm)")
        ax.set_ylabel("−X (mm)")
        ax.grid(alpha=0.3)
    path(axes[0, 0])
    axes[0, 0].set_title("whole pass", fontsize=9)
    axes[0, 0].legend(fontsize=7, markerscale=2)
    near = h["gap_m"] > -2e-3
    if near.any():
        path(axes[0, 1])
        axes[0, 1].set_xlim(Y[near].min() - 1, Y[near].max() + 1)
        x_near = surface_x(surface, h["y_tip_m"][near]) * 1e3
        axes[0, 1].set_ylim(-x_near.max() - 0.05, -x_near.min() + 2.0)
        axes[0, 1].set_title("close-up: the contact region", fontsize=9)
    if imp:
        y0 = events["y_tip_m"][imp[0]] * 1e3
        x0 = float(surface_x(surface, [y0 * 1e-3])[0]) * 1e3
        path(axes[1, 0])
        axes[1, 0].set_xlim(y0 - 0.5, y0 + 1.5)
        axes[1, 0].set_ylim(-x0 - 0.01, -x0 + 0.3)
        axes[1, 0].set_title("close-up: the first impact and the bounce back", fontsize=9)
    axes[1, 1].plot(h["theta_deg"], h["gap_m"] * 1e3, lw=0.8)
    axes[1, 1].axhline(0, color="k", lw=0.8)
    axes[1, 1].set_xlabel(f"hub angle θ ({DEG})")
    axes[1, 1].set_ylabel("gap C (mm)")
    axes[1, 1].set_ylim(min(-5, np.nanmin(h["gap_m"]) * 1e3), 0.5)
    axes[1, 1].grid(alpha=0.3)
    axes[1, 1].set_title("gap against the hub angle", fontsize=9)
    fig.suptitle(f"Tip path — {title}" + warning_line(summary), fontsize=10,
                 color="C3" if summary.get("warnings") else "k")
    fig.tight_layout()
    written.append(out / "tip_path.png")
    save_figure(fig, written[-1])
    plt.close(fig)

    # 3. Modal coordinates.
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
    written.append(out / "modal_coordinates.png")
    save_figure(fig, written[-1])
    plt.close(fig)

    # 4. Energy audit and hub torque.
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    a1.plot(h["theta_deg"], (h["jacobi_j"] - h["jacobi_j"][0]) * 1e6, lw=1)
    for i in imp:
        a1.axvline(events["theta_deg"][i], color="C3", lw=0.4, alpha=0.5)
    a1.set_ylabel("h − h(0) (µJ)")
    a1.set_title(f"Jacobi integral (changes only by contact work and impacts; red: impacts)\n"
                 f"energy-audit residual {summary['energy_audit_residual']:.2e} — {title}", fontsize=9)
    a2.plot(h["theta_deg"], h["hub_torque_n_m"] * 1e3, lw=0.8, color="C2")
    a2.set_ylabel("hub torque τ (mN·m)")
    a2.set_xlabel(f"hub angle θ ({DEG})")
    for a in (a1, a2):
        a.grid(alpha=0.3)
    fig.tight_layout()
    written.append(out / "energy.png")
    save_figure(fig, written[-1])
    plt.close(fig)

    # 5. Impacts.
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    if imp:
        th = events["theta_deg"][imp]
        a1.plot(th, events["vx_before_m_s"][imp], "o", ms=4, label="V_X before")
        a1.plot(th, events["vx_after_m_s"][imp], "s", ms=4, label="V_X after")
        a2.plot(th, events["restitution"][imp], "o", ms=4, color="C2")
    a1.axhline(0, color="k", lw=0.6)
    a1.set_ylabel("normal tip velocity (m/s)")
    a1.legend(fontsize=8)
    a2.set_ylabel("restitution e")
    a2.set_ylim(-0.05, 1.05)
    a2.set_xlabel(f"hub angle θ ({DEG})")
    a1.set_title(f"{len(imp)} impacts ({summary.get('plastic_impacts', 0)} plastic) — {title}", fontsize=9)
    for a in (a1, a2):
        a.grid(alpha=0.3)
    fig.tight_layout()
    written.append(out / "impacts.png")
    save_figure(fig, written[-1])
    plt.close(fig)
    return written


def plot_sweep(folder, out, cases=False):
    folder, out = Path(folder), Path(out)
    out.mkdir(parents=True, exist_ok=True)
    table = read_csv(folder / "sweep.csv")
    keys = [k for k in table if k not in ("case", "folder", "status", "message") and k not in METRICS]
    written = []
    ok = np.isin(table["status"], ["done", "resumed", "failed"])
    for f, good in zip(table["folder"], ok):
        if good:  # a case with results must have its files: a missing or damaged one is named
            if not (folder / f / "summary.json").exists():
                raise DamagedFolder(f"{folder / f / 'summary.json'}: missing (sweep.csv lists results for {f})")
            check_run_files(folder / f)
    first = keys[0]
    second = keys[1] if len(keys) > 1 else None
    x = table[first]
    fig, axes = plt.subplots(2, 3, figsize=(14, 7.5))
    for ax, (metric, label) in zip(axes.flat, [
        ("impacts", "impacts"), ("contact_episodes", "contact episodes"), ("last_separation_deg", f"last separation ({DEG})"),
        ("peak_normal_force_n", "peak F_n (N)"), ("normal_impulse_n_s", "normal impulse (N·s)"),
        ("max_tip_deflection_ratio", "max |y_t|/L")]):
        groups = sorted(set(table[second][ok])) if second else [None]
        for g in groups:
            sel = ok & ((table[second] == g) if second else True)
            order = np.argsort(x[sel].astype(float)) if x.dtype.kind == "f" else np.arange(sel.sum())
            ax.plot(x[sel][order], table[metric][sel][order], "o-", ms=4, label=f"{second} = {g}" if second else None)
        ax.set_xlabel(first)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    if second:
        axes[0, 0].legend(fontsize=7)
    fig.suptitle(f"Sweep of {len(table['case'])} cases over {', '.join(keys)} "
                 f"({int((~ok).sum())} without results)", fontsize=10)
    fig.tight_layout()
    written.append(out / "sweep_metrics.png")
    save_figure(fig, written[-1])
    plt.close(fig)

    folders = [f for f, good in zip(table["folder"], ok) if good and (folder / f / "history.csv").exists()]
    if folders and len(folders) <= 24:
        fig, ax = plt.subplots(figsize=(9, 5))
        for i, f in enumerate(folders):
            h = read_csv(folder / f / "history.csv")
            summary = json.loads((folder / f / "summary.json").read_text())
            label = ", ".join(f"{k}={table[k][list(table['folder']).index(f)]}" for k in keys)
            plot_normal_force(h, None, summary, ax, label=label, lw=1, color=f"C{i % 10}")
        ax.set_xlabel("tip position Y (mm)")
        ax.set_ylabel("normal force F_n (N)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        ax.set_title("Sustained-contact normal force along the surface, every case", fontsize=10)
        fig.tight_layout()
        written.append(out / "sweep_normal_force_vs_y.png")
        save_figure(fig, written[-1])
        plt.close(fig)
    if cases:
        for f in folders:
            written += plot_run(folder / f, out / f)
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


METRICS = ["impacts", "contact_episodes", "first_impact_deg", "last_separation_deg", "contact_time_s",
           "peak_normal_force_n", "mean_normal_force_n", "normal_impulse_n_s", "friction_work_j",
           "max_tip_deflection_ratio", "energy_audit_residual", "steps", "rhs_evaluations", "wall_time_s"]


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
    if args.output and not args.campbell:
        try:
            out.mkdir(parents=True, exist_ok=True)
        except OSError as e:
            print(f"rotbeam: error: -o {out}: cannot create the output folder ({e.strerror or e})", file=sys.stderr)
            return 2
    try:
        if args.reproduce:
            from .reproduce import write_report
            written = [write_report(folder)]
        elif args.campbell:
            written = plot_campbell(args.folder, args.campbell)
        elif (folder / "sweep.csv").exists():
            written = plot_sweep(folder, out, args.cases)
        elif (folder / "summary.json").exists():
            check_run_files(folder)
            written = plot_run(folder, out)
        else:
            print(f"rotbeam: error: {folder}: neither a run folder (summary.json) nor a sweep folder (sweep.csv)",
                  file=sys.stderr)
            return 2
    except DamagedFolder as e:
        print(f"rotbeam: error: {e}", file=sys.stderr)
        return 2
    except OSError as e:  # before ValueError: some OSErrors are not, but say what file and why
        where = f"{e.filename}: " if e.filename else ""
        print(f"rotbeam: error: {where}{e.strerror or e}", file=sys.stderr)
        return 1
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
    for w in written:
        print(f"wrote {w}")
    return 0


def run_main(main_function):
    """sys.exit(main_function()), with standard output that cannot be written (a full disk, a
    closed pipe) reported in one line, exit 1, as by `rotbeam` itself."""
    try:
        code = main_function()
        sys.stdout.flush()
    except OSError as e:
        if e.errno is None:
            raise
        print(f"rotbeam: error: standard output: the results could not be written ({e.strerror})", file=sys.stderr)
        code = 1
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # nothing left to flush at exit
    sys.exit(code)


if __name__ == "__main__":
    run_main(main)
