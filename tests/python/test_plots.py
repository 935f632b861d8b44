"""The pictures say what they show (rotbeam.plots): no legend entry without data, no empty panel
without a word why, the impacts' impulses and the binned force where a pass is made of impacts,
the Jacobi integral's rise at impacts explained with numbers that close; the sweep's series each
with their own style and the legend off the data. Also: a Python without numpy gets a one-line
hint, the example case lists every documented key, and the docs' tables are whole. Run by ctest
with PYTHONPATH=<build>/python and ROTBEAM_CLI=<rotbeam binary>."""

import csv
import math
import os
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import StepPatch  # noqa: E402

import rotbeam  # noqa: E402
from rotbeam import plots  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")


def cli(*args):
    done = subprocess.run([CLI, *args], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The base case (550 rpm: impacts and sustained contact) and 3000 rpm (impacts only), each as
    the run wrote it ("…") and without force_bins.csv ("…-files": the binned force computed here)."""
    out = {}
    for name, sets in (("base", []), ("fast", ["--set", "hub.speed_rpm=3000"])):
        folder = tmp_path_factory.mktemp(name)
        cli("run", *sets, "-o", str(folder), "--quiet")
        out[name] = folder
        bare = tmp_path_factory.mktemp(name + "-files")
        for f in ("history.csv", "events.csv", "summary.json"):
            shutil.copy(folder / f, bare / f)
        out[name + "-files"] = bare
    return out


def loaded(folder):
    h, events, summary = plots.read_run(folder)
    return h, events, summary, plots.case_title(summary)


def has_data(artist):
    if isinstance(artist, Line2D):
        return np.isfinite(np.asarray(artist.get_ydata(), dtype=float)).any()
    if isinstance(artist, StepPatch):
        return len(artist.get_data().values) > 0 and np.isfinite(artist.get_data().values).any()
    if isinstance(artist, LineCollection):
        return len(artist.get_segments()) > 0
    return True


def labelled(fig):
    """{label: [artists]} of every labelled artist of the figure's axes."""
    out = {}
    for ax in fig.axes:
        for a in [*ax.get_lines(), *ax.patches, *ax.collections]:
            if not a.get_label().startswith("_"):
                out.setdefault(a.get_label(), []).append(a)
    return out


def legend_texts(fig):
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend()] + list(fig.legends)
    return [t.get_text() for legend in legends for t in legend.get_texts()]


def assert_every_legend_entry_has_data(fig):
    artists = labelled(fig)
    for text in legend_texts(fig):
        assert text in artists and any(has_data(a) for a in artists[text]), f"legend entry without data: {text}"


def assert_no_silent_empty_panel(fig):
    for ax in fig.axes:
        drawn = any(has_data(a) for a in [*ax.get_lines(), *ax.patches, *ax.collections])
        twin_drawn = any(other is not ax and other.bbox.bounds == ax.bbox.bounds and
                         any(has_data(a) for a in other.get_lines()) for other in fig.axes)
        assert drawn or twin_drawn or ax.texts, f"an empty panel without a word why: {ax.get_title()!r}"


def assert_units_on_axes(fig):
    for ax in fig.axes:
        for label in (ax.get_xlabel(), ax.get_ylabel()):
            if label and label not in ("impacts", "contact episodes", "max |y_t|/L", "restitution e") and \
                    not label.startswith(("hub.", "surface.")):
                assert re.search(r"\(.+\)", label), f"no unit: {label!r}"


def bottom_stairs(fig):
    (stairs,) = [p for ax in fig.axes for p in ax.patches if isinstance(p, StepPatch)]
    return stairs


# --- normal_force_vs_y.png ------------------------------------------------------------------------


def test_a_pass_of_impacts_shows_its_impulses_and_the_binned_force(runs):
    h, events, summary, title = loaded(runs["fast-files"])
    assert summary["contact_episodes"] == 0 and summary["impacts"] == 6  # the case this test is about
    fig = plots.force_figure(runs["fast-files"], h, events, summary, title)
    top = fig.axes[0]
    assert "peak 0 N" not in top.get_title() and "no sustained contact" in top.get_title()
    assert "sustained contact F_n" not in " ".join(legend_texts(fig))
    assert_every_legend_entry_has_data(fig)
    assert_no_silent_empty_panel(fig)
    assert_units_on_axes(fig)
    # The stems are the impacts' impulses in mN·s at their tip Y.
    (stems,) = [a for label, arts in labelled(fig).items() if label.startswith("impact impulses") for a in arts]
    imp = events["kind"] == "impact"
    assert np.allclose(stems.get_xdata(), events["y_tip_m"][imp] * 1e3)
    assert np.allclose(stems.get_ydata(), np.abs(events["impulse_n_s"][imp]) * 1e3)
    assert "mN·s" in top.get_ylabel()
    # The binned mean force carries the whole normal impulse: Σ mean · bin time = Σ|P|.
    stairs = bottom_stairs(fig)
    edges, mean = stairs.get_data().edges, stairs.get_data().values
    omega = summary["config"]["hub"]["speed_rpm"] * math.pi / 30
    momentum = np.sum(mean * np.diff(edges) * math.pi / 180 / omega)
    assert momentum == pytest.approx(summary["normal_impulse_n_s"], rel=1e-12)
    assert "events.csv" in fig.axes[1].get_title()
    plt.close(fig)


def test_a_pass_with_contact_shows_the_force_the_impulses_and_the_binned_force(runs):
    h, events, summary, title = loaded(runs["base-files"])
    fig = plots.force_figure(runs["base-files"], h, events, summary, title)
    assert f"peak F_n {summary['peak_normal_force_n']:.3g} N in sustained contact" in fig.axes[0].get_title()
    texts = legend_texts(fig)
    assert any(t.startswith("F_n in sustained contact") for t in texts)
    assert any(t.startswith("impact impulses") for t in texts)
    assert_every_legend_entry_has_data(fig)
    assert_no_silent_empty_panel(fig)
    assert_units_on_axes(fig)
    stairs = bottom_stairs(fig)
    edges, mean = stairs.get_data().edges, stairs.get_data().values
    omega = summary["config"]["hub"]["speed_rpm"] * math.pi / 30
    momentum = np.sum(mean * np.diff(edges) * math.pi / 180 / omega)
    # Impacts exactly, sustained contact by the trapezoidal rule on the history rows.
    assert momentum == pytest.approx(summary["normal_impulse_n_s"], rel=1e-3)
    plt.close(fig)


def test_the_runs_force_bins_are_drawn_when_it_wrote_them(runs, tmp_path):
    for f in ("history.csv", "events.csv", "summary.json"):
        shutil.copy(runs["fast-files"] / f, tmp_path / f)
    h, events, summary, title = loaded(tmp_path)
    with open(tmp_path / "force_bins.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(plots.FORCE_BIN_COLUMNS)
        w.writerow([-8.5, -8.0, 1.9e-3, 0.0, 68.0, 0.0, 1])
        w.writerow([-8.0, -7.5, 0.0, 0.0, 0.0, 0.0, 0])
        w.writerow([-7.5, -7.0, 1.0e-4, 0.0, 3.5, 0.0, 1])
    fig = plots.force_figure(tmp_path, h, events, summary, title)
    stairs = bottom_stairs(fig)
    assert list(stairs.get_data().values) == [68.0, 0.0, 3.5]
    assert list(stairs.get_data().edges) == [-8.5, -8.0, -7.5, -7.0]
    assert "force_bins.csv" in fig.axes[-1].get_title() and "68" in fig.axes[-1].get_title()
    plt.close(fig)


# --- tip_path.png and energy.png ------------------------------------------------------------------


def test_contact_samples_are_drawn_over_a_thin_surface_line(runs):
    h, events, summary, title = loaded(runs["base"])
    fig = plots.tip_path_figure(h, events, summary, title)
    panels = 0
    for ax in fig.axes:
        lines = {line.get_label(): line for line in ax.get_lines()}
        if "contact" in lines:
            panels += 1
            assert lines["contact"].get_zorder() > lines["surface"].get_zorder()
            assert lines["surface"].get_linewidth() < 1
    assert panels >= 2
    assert_every_legend_entry_has_data(fig)
    assert_no_silent_empty_panel(fig)
    plt.close(fig)


@pytest.mark.parametrize("case", ["base", "fast"])
def test_the_jacobi_integrals_rise_at_impacts_is_the_moving_surfaces_work(runs, case):
    h, events, summary, title = loaded(runs[case])
    ledger = plots.impact_energy(h, events, summary)
    imp = events["kind"] == "impact"
    omega = summary["config"]["hub"]["speed_rpm"] * math.pi / 30
    surface_work = np.sum(omega * events["y_tip_m"][imp] * events["impulse_n_s"][imp])
    # Δh at the impacts (from the history) = the impulses' work on the tip + ωY_tP, to round-off.
    assert ledger["dh_j"] == pytest.approx(ledger["loss_j"] + surface_work, rel=1e-9)
    assert ledger["loss_j"] == pytest.approx(summary["impact_loss_j"], rel=1e-12)
    assert ledger["hub_j"] == pytest.approx(summary["hub_impulsive_work_j"], rel=1e-12)
    # What the picture says: h rises though every impact loses energy, and E = T + U falls.
    assert ledger["dh_j"] > 0 > ledger["loss_j"]
    assert ledger["loss_j"] + ledger["hub_j"] < 0
    fig = plots.energy_figure(h, events, summary, title)
    note = " ".join(t.get_text() for t in fig.axes[0].texts)
    assert "moving surface" in note and f"{1e6 * ledger['dh_j']:+.0f} µJ" in note
    assert_units_on_axes(fig)
    plt.close(fig)


def test_every_picture_of_a_run_is_written(runs, tmp_path):
    for case in ("base", "fast"):
        written = plots.plot_run(runs[case], tmp_path / case)
        assert [p.name for p in written] == ["normal_force_vs_y.png", "tip_path.png", "modal_coordinates.png",
                                             "energy.png", "impacts.png"]
        assert all(p.stat().st_size > 20_000 for p in written)


# --- sweeps ---------------------------------------------------------------------------------------


def test_series_styles_are_distinct():
    for series in ([(s, m) for s in (550, 1000, 1500, 2000) for m in (0.1, 0.2, 0.4, 0.6)],
                   [(k,) for k in range(45)], [(s, m) for s in range(12) for m in (0, 1)]):
        styles = plots.series_styles(series)
        assert len({(s["color"], s["linestyle"], s["marker"]) for s in styles}) == len(series)
    assert [plots.value_text(v) for v in (550.0, 0.1, 1e-7, "thesis")] == ["550", "0.1", "1e-07", "thesis"]


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sweep")
    cli("sweep", "--vary", "hub.speed_rpm=550,1000,2000,3000", "--vary", "surface.friction=0.1,0.2,0.4,0.6",
        "--set", "output.interval_s=1e-4", "-o", str(folder))
    return folder


def test_a_sweeps_pictures_give_each_series_its_style_and_keep_the_legend_off_the_data(sweep):
    table, keys, ok = plots.read_sweep(sweep)
    assert keys == ["hub.speed_rpm", "surface.friction"] and ok.all()
    metrics = plots.sweep_metrics_figure(table, keys, ok)
    folders = list(table["folder"])
    force = plots.sweep_force_figure(sweep, table, keys, ok, folders)
    for fig in (metrics, force):
        fig.canvas.draw()
        assert len(fig.legends) == 1
        box = fig.legends[0].get_window_extent()
        for ax in fig.axes:
            assert not box.overlaps(ax.get_window_extent()), "the legend covers a panel"
        assert_every_legend_entry_has_data(fig)
        assert_no_silent_empty_panel(fig)
        texts = legend_texts(fig)
        assert texts and not any(re.search(r"\d\.0\b", t) for t in texts), texts  # 550, not 550.0
        handles = fig.legends[0].legend_handles if hasattr(fig.legends[0], "legend_handles") else \
            fig.legends[0].legendHandles
        styles = {(matplotlib.colors.to_hex(h.get_color()), h.get_linestyle(), h.get_marker()) for h in handles}
        assert len(styles) == len(handles)
    # All 16 have results: no note in the title; 3000 rpm (impacts only) is named, not drawn.
    assert "without results" not in metrics._suptitle.get_text() and "\n" not in metrics._suptitle.get_text()
    assert len(legend_texts(force)) == 12
    assert "4 of 16 cases with results have no sustained contact" in force.axes[0].get_title()
    assert "3000, 0.1" in force.axes[0].get_title()
    plt.close(metrics)
    plt.close(force)


def test_a_sweeps_title_says_which_cases_have_no_results():
    table = {"case": np.array([1.0, 2.0, 3.0, 4.0]), "folder": np.array(["case-0001", "case-0002", "case-0003",
                                                                           "case-0004"]),
             "status": np.array(["done", "error", "failed", "resumed"])}
    ok = np.isin(table["status"], ["done", "resumed", "failed"])
    note = plots._cases_note(table, ok)
    assert "1 of 4 cases has no results, not drawn: case-0002 (error)" in note
    assert "1 of 4 cases stopped on a diagnosed failure, drawn up to the stop: case-0003" in note
    assert plots._cases_note(table, np.ones(4, dtype=bool) & (table["status"] != "failed")) == \
        "\n1 of 4 cases has no results, not drawn: case-0003 (failed)"
    table["status"][:] = "done"
    assert plots._cases_note(table, np.ones(4, dtype=bool)) == ""


# --- a Python without numpy -----------------------------------------------------------------------


def pythons_without_numpy(tmp_path):
    """(python, environment) pairs where `import numpy` fails: the python3 first on PATH if it lacks
    numpy (as on a machine whose default Python is not Debian's), and always this Python with a
    numpy that cannot be imported ahead of the real one."""
    package = str(Path(rotbeam.__file__).parent.parent)
    out = []
    first = shutil.which("python3")
    if first and subprocess.run([first, "-c", "import numpy"], capture_output=True).returncode != 0:
        out.append((first, {"PYTHONPATH": package}))
    fake = tmp_path / "fake"
    (fake / "numpy").mkdir(parents=True)
    (fake / "numpy" / "__init__.py").write_text("raise ModuleNotFoundError(\"No module named 'numpy'\")\n")
    out.append((sys.executable, {"PYTHONPATH": f"{fake}:{package}"}))
    return out


def test_importing_rotbeam_without_numpy_says_what_to_install(tmp_path):
    for python, env in pythons_without_numpy(tmp_path):
        env = {**os.environ, **env}
        done = subprocess.run([python, "-c", "import rotbeam; rotbeam.run()"], capture_output=True, text=True,
                              env=env)
        assert done.returncode == 1
        last = done.stderr.strip().splitlines()[-1]
        assert last.startswith("ImportError: rotbeam needs numpy"), done.stderr
        assert "apt-get install python3-numpy" in last and "/usr/bin/python3" in last
        assert "_core" not in done.stderr  # not from deep inside a run
        # What `rotbeam plot` runs: one line, the command line's form.
        done = subprocess.run([python, "-m", "rotbeam.plots", str(tmp_path)], capture_output=True, text=True,
                              env=env)
        assert done.returncode == 1
        assert done.stderr.count("\n") == 1 and done.stderr.startswith("rotbeam: error: rotbeam needs numpy"), \
            done.stderr


# --- the example case and the docs ----------------------------------------------------------------


def documented_keys():
    text = (ROOT / "docs" / "configuration.md").read_text()
    keys = set()
    for line in text.splitlines():
        if line.startswith("| `"):
            first_cell = line.split(" | ")[0]
            keys |= set(re.findall(r"`([a-z0-9_]+\.[a-z0-9_]+)`", first_cell))
    return keys


def example_keys():
    """The keys thesis-base.toml sets, and those it shows commented out (`# key = …` in a section, which
    may be a commented-out `# [section]` too: the brush's, whose keys make a case a brush)."""
    path = ROOT / "examples" / "thesis-base.toml"
    keys = {f"{section}.{key}" for section, table in tomllib.loads(path.read_text()).items() for key in table}
    section = None
    for line in path.read_text().splitlines():
        if m := re.match(r"(?:#\s*)?\[(\w+)\]", line):
            section = m.group(1)
        elif m := re.match(r"#\s*(\w+)\s*=", line):
            keys.add(f"{section}.{m.group(1)}")
    return keys


def test_the_example_case_lists_every_documented_key():
    documented, listed = documented_keys(), example_keys()
    assert len(documented) > 30
    assert documented - listed == set(), "documented in configuration.md, missing from thesis-base.toml"
    assert listed - documented == set(), "in thesis-base.toml, not documented in configuration.md"


def test_the_example_case_is_the_default_case():
    # Its values are the defaults: the configuration it resolves to is that of no file at all.
    assert rotbeam.impact(str(ROOT / "examples" / "thesis-base.toml"))["config"] == rotbeam.impact()["config"]


def markdown_tables(text):
    """The tables of a Markdown text as lists of (line number, line): runs of lines that begin and end
    with '|' outside code fences."""
    tables, current, fence = [], [], False
    for number, line in enumerate(text.splitlines(), 1):
        if line.startswith("```"):
            fence = not fence
        if not fence and line.startswith("|") and line.rstrip().endswith("|"):
            current.append((number, line))
        elif current:
            tables.append(current)
            current = []
    if current:
        tables.append(current)
    return tables


@pytest.mark.parametrize("name", ["docs/deviations.md", "docs/configuration.md", "docs/cli.md", "docs/model.md",
                                  "docs/python.md", "docs/verification.md", "docs/reliability.md", "README.md",
                                  "docs/distributed.md"])
def test_every_table_of_the_docs_is_one_block_under_its_header(name):
    for table in markdown_tables((ROOT / name).read_text()):
        first = table[0][0]
        assert len(table) >= 2 and re.fullmatch(r"\|(\s*:?-+:?\s*\|)+", table[1][1].rstrip()), \
            f"{name}:{first}: rows without a header row and separator (a table cut by a blank line?)"
        cells = {len(re.findall(r"(?<!\\)\|", line)) for _, line in table}
        assert len(cells) == 1, f"{name}:{first}: rows with different numbers of cells {cells}"


def test_a_picture_named_through_a_link_replaces_the_linked_file_and_keeps_the_link(tmp_path):
    # save_figure renamed its temporary onto the link itself: the link became a regular file and
    # the file it named was left as it was. A node that is not a regular file is written into.
    (tmp_path / "real.png").write_text("old")
    (tmp_path / "link.png").symlink_to("real.png")
    fig = plt.figure()
    plots.save_figure(fig, tmp_path / "link.png")
    assert (tmp_path / "link.png").is_symlink()
    assert (tmp_path / "real.png").read_bytes().startswith(b"\x89PNG")
    fifo = tmp_path / "pipe.png"
    os.mkfifo(fifo)
    reader = subprocess.Popen(["cat", str(fifo)], stdout=subprocess.PIPE)
    plots.save_figure(fig, fifo)
    assert reader.communicate(timeout=30)[0].startswith(b"\x89PNG")
    assert fifo.is_fifo()
    plt.close(fig)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.png", "pipe.png", "real.png"]


def _texts(fig):
    """Every title and suptitle of a figure."""
    texts = [ax.get_title() for ax in fig.axes]
    if fig._suptitle is not None:
        texts.append(fig._suptitle.get_text())
    return " ".join(texts)


def test_every_picture_of_a_run_says_when_the_pass_left_the_models_validity(runs, tmp_path):
    # The base case bends past 0.1 L ("edge"): each of the five pictures says so in a title. At a
    # hundredth of its depth the filament stays within, and no picture says anything of it.
    figures = plots.run_figures(runs["base"])
    try:
        for name, fig in figures:
            assert "validity edge: max |y_t|/L = " in _texts(fig) or "tip deflection exceeds" in _texts(fig), name
    finally:
        for _, fig in figures:
            plt.close(fig)
    folder = tmp_path / "within"
    cli("run", "--set", "surface.depth_fraction=0.0002", "-o", str(folder), "--quiet")
    figures = plots.run_figures(folder)
    try:
        for name, fig in figures:
            assert "validity" not in _texts(fig) and "tip deflection exceeds" not in _texts(fig), name
    finally:
        for _, fig in figures:
            plt.close(fig)


def _data_points(ax):
    """Display coordinates of every data vertex drawn in ax: line points, markers, stems' ends, bars'
    and steps' corners (reference lines across the axes excluded)."""
    points = []
    for line in ax.get_lines():
        if line.get_transform() == ax.transData:
            points.append(ax.transData.transform(np.asarray(line.get_xydata(), float)))
    for coll in ax.collections:
        if isinstance(coll, LineCollection):
            for seg in coll.get_segments():
                points.append(coll.get_transform().transform(np.asarray(seg, float)))
        elif len(coll.get_offsets()):
            points.append(coll.get_offset_transform().transform(np.asarray(coll.get_offsets(), float)))
    for patch in ax.patches:
        points.append(patch.get_transform().transform(patch.get_path().vertices))
    points = np.concatenate(points) if points else np.empty((0, 2))
    return points[np.all(np.isfinite(points), axis=1)]


def test_no_legend_of_a_run_covers_its_data(runs):
    # The base case's bottom panel hid its 2.03 N bin under the legend; every legend of every picture
    # of both runs now lies where no data point is (checked on the vertices, independently of the
    # placement's own test of lines crossing the box).
    for case in ("base", "fast"):
        figures = plots.run_figures(runs[case])
        try:
            for name, fig in figures:
                renderer = fig.canvas.get_renderer()
                for ax in fig.axes:
                    legend = ax.get_legend()
                    if legend is None:
                        continue
                    box = legend.get_window_extent(renderer)
                    twins = [a for a in fig.axes if np.allclose(a.get_position().bounds, ax.get_position().bounds)]
                    for a in twins:
                        inside = [p for p in _data_points(a) if box.contains(*p)]
                        assert not inside, f"{case} {name}: the legend covers {len(inside)} data points"
        finally:
            for _, fig in figures:
                plt.close(fig)


def test_neighbouring_series_differ_in_line_style_and_a_failed_case_is_a_gap():
    # One varied key besides the first: series that coincide (equal frictions' results) stay visible.
    styles = plots.series_styles([(k,) for k in range(12)])
    assert all(a["linestyle"] != b["linestyle"] for a, b in zip(styles, styles[1:]))
    # A case without results breaks its series' line instead of being bridged.
    from rotbeam import sweep_plots
    table = {"case": np.arange(1, 4), "status": np.array(["done", "failed", "done"]),
             "hub.speed_rpm": np.array([1000.0, 2000.0, 3000.0]), "impacts": np.array([3.0, np.nan, 5.0])}
    ok = np.array([True, False, True])
    fig = sweep_plots.metrics_figure(table, ["hub.speed_rpm"], ok, [("impacts", 1, "impacts")] * 6, "t")
    try:
        line = fig.axes[0].get_lines()[0]
        y = np.asarray(line.get_ydata(), float)
        assert len(y) == 3 and math.isnan(y[1]), y
    finally:
        plt.close(fig)


def test_a_sweep_over_many_revolutions_draws_per_revolution_metrics(tmp_path):
    # Runs over revolutions are compared by their last complete revolution, not whole-run totals (runs
    # of different lengths) or an angle that grows without wrapping; a panel without values says why.
    from rotbeam import sweep_plots
    folder = tmp_path / "sweep"
    cli("sweep", "--vary", "hub.speed_rpm=550,1000", "--set", "simulation.revolutions=2",
        "--set", "beam.damping_ratio=0.03", "-o", str(folder), "--quiet")
    table, keys, ok = sweep_plots.read_sweep(folder)
    fig = sweep_plots.sweep_metrics_figure(table, keys, ok)
    try:
        labels = [ax.get_ylabel() for ax in fig.axes]
        assert "impacts per revolution" in labels and not any("last separation" in label for label in labels)
        assert "per revolution" in fig._suptitle.get_text()
        empty = [ax for ax in fig.axes if not any(np.isfinite(line.get_ydata()).any() for line in ax.get_lines())]
        assert empty and all(ax.texts for ax in empty)
    finally:
        plt.close(fig)
