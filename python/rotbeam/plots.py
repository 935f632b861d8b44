"""Pictures of rotbeam outputs (matplotlib; reads only the files a run or sweep wrote).

    python3 -m rotbeam.plots DIR [-o OUT]      # or: rotbeam plot DIR

A run folder (history.csv, events.csv, summary.json; force_bins.csv where the run wrote one) gives
normal_force_vs_y.png (the thesis's figures: sustained contact's F_n, the impacts' impulses, and the
mean force over bins of hub angle), tip_path.png (the path with close-ups, thesis Figure 13),
modal_coordinates.png, energy.png (the Jacobi integral, why impacts move it, and the hub torque)
and impacts.png. A sweep folder (sweep.csv) gives sweep_metrics.png and
sweep_normal_force_vs_y.png, plus the pictures of each case with --cases. Each picture is also a
function returning its matplotlib figure (force_figure, tip_path_figure, energy_figure, …).

This module is the command line, and the one place that names every picture: they are drawn by
rotbeam.run_plots (a run), rotbeam.sweep_plots (a sweep), rotbeam.rub_map (Campbell diagrams, the
rub map), rotbeam.brush_plots (a brush), on what rotbeam._figures (writing pictures, titles,
styles), rotbeam._runs (a run's files, read and checked), rotbeam._csv (the CSV reader) and
rotbeam._surface (the surface's outline) share. Their names are importable from here as well.
"""

import argparse
import sys
from pathlib import Path

if __name__ == "__main__":
    from rotbeam._interrupt import announce_start, stop_quietly_on_interrupt

    stop_quietly_on_interrupt()
    announce_start()

# rotbeam._figures first: where numpy or matplotlib is missing it says so in one line.
from ._figures import (DEG, LINESTYLES, MARKERS, OutputFolderError, case_title, modes_words,  # noqa: E402
                       output_target, put_in_place, remove_stale_temporaries, save_figure, save_figures,
                       series_styles, temporary_beside, value_text, warning_line)
from ._interrupt import error, file_error, run_main, wrote  # noqa: E402
from ._csv import (EVENT_COLUMNS, EVENT_KINDS, EVENT_OPTIONAL, FORCE_BIN_COLUMNS, PHASES,  # noqa: E402
                   DamagedFolder, read_csv)
from ._runs import (check_run_files, check_summary, force_bins, history_columns, impact_energy,  # noqa: E402
                    impact_impulses, read_run, read_run_table, relative_angle, sustained)
from ._surface import casing_radius, draw_surface, surface_of, surface_words, surface_x  # noqa: E402
from .brush_plots import BRUSH_MAP_PANELS, DamagedBrush, brush_figures, read_brush  # noqa: E402
from .wear_plots import DamagedWear, is_wear_folder, wear_figures  # noqa: E402
from .continuation_plots import DamagedContinuation, continuation_figures, is_continuation_folder  # noqa: E402
from .rub_map import is_rub_sweep, plot_campbell, rub_map_figure  # noqa: E402
from .run_plots import (energy_figure, energy_note, force_figure, impacts_figure, modal_figure,  # noqa: E402
                        plot_normal_force, plot_run, run_figures, tip_path_figure)
from .sweep_plots import (_cases_note, is_brush_folder, metrics_figure, plot_brush_sweep, plot_sweep,  # noqa: E402,F401
                          read_sweep, sweep_force_figure, sweep_metrics_figure)

# The names of every picture module, importable from here as they always were.
__all__ = ["DEG", "LINESTYLES", "MARKERS", "OutputFolderError", "case_title", "modes_words", "output_target",
           "put_in_place", "remove_stale_temporaries", "save_figure", "save_figures", "series_styles",
           "temporary_beside", "value_text", "warning_line", "run_main", "EVENT_COLUMNS", "EVENT_KINDS",
           "EVENT_OPTIONAL", "FORCE_BIN_COLUMNS", "PHASES", "DamagedFolder", "read_csv", "check_run_files",
           "check_summary", "force_bins", "history_columns", "impact_energy", "impact_impulses", "read_run",
           "read_run_table", "relative_angle", "sustained", "casing_radius", "draw_surface", "surface_of",
           "surface_words", "surface_x", "BRUSH_MAP_PANELS", "DamagedBrush", "brush_figures", "read_brush",
           "is_rub_sweep", "plot_campbell", "rub_map_figure", "energy_figure", "energy_note", "force_figure",
           "impacts_figure", "modal_figure", "plot_normal_force", "plot_run", "run_figures", "tip_path_figure",
           "is_brush_folder", "metrics_figure", "plot_brush_sweep", "plot_sweep", "read_sweep",
           "sweep_force_figure", "sweep_metrics_figure", "animate", "main"]


def animate(folder, output=None, **options):
    """The animation of a run folder (rotbeam.animate.animate; its options): the paths written."""
    from .animate import animate as draw_animation
    return draw_animation(folder, output, **options)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="rotbeam plot", description="Pictures of a rotbeam run or sweep folder")
    parser.add_argument("folder", help="a run folder (summary.json) or a sweep folder (sweep.csv); with "
                        "--campbell, the CSV of `rotbeam modes --csv`")
    parser.add_argument("-o", "--output", help="where to write the PNGs (default: the folder itself)")
    parser.add_argument("--cases", action="store_true", help="for a sweep, also the pictures of every case")
    parser.add_argument("--campbell", metavar="PNG", help="draw a Campbell diagram of the CSV into PNG")
    parser.add_argument("--reproduce", action="store_true", help="draw the figures and report of `rotbeam reproduce`")
    parser.add_argument("--brute-force", metavar="SWEEP", help="for a continuation, a sweep folder over the same key "
                        "whose steady states are drawn over the branch")
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
        elif (folder / "summary.json").exists() and is_wear_folder(folder):
            written = save_figures(wear_figures(folder), out)
        elif (folder / "summary.json").exists() and is_continuation_folder(folder):
            written = save_figures(continuation_figures(folder, args.brute_force), out)
        elif (folder / "summary.json").exists():
            written = plot_run(folder, out)
        elif not folder.exists():
            print(f"rotbeam: error: {folder}: no such folder", file=sys.stderr)
            return 2
        else:
            print(f"rotbeam: error: {folder}: neither a run folder (summary.json) nor a sweep folder (sweep.csv)",
                  file=sys.stderr)
            return 2
    except (DamagedFolder, DamagedBrush, DamagedWear, DamagedContinuation, OutputFolderError) as e:
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
