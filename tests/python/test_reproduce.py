"""`rotbeam reproduce`: the thesis's Table 5-3 and Figures 4-13 with report.md — what it writes
(summaries and the history rows the figures draw; every row with --keep-history, announced), its
progress line (on a terminal only), and the rules of its pictures: no legend entry without data,
no empty panel without a word why, units on every axis."""

import json
import os
import pty
import re
import shutil
import signal
import subprocess
import threading
from pathlib import Path

import numpy as np
import pytest
from process_support import catches, wait_until

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")
MODELS = ("thesis", "physical")


def run(*args, **kwargs):
    return subprocess.run([CLI, *args], capture_output=True, text=True, **kwargs)


def run_with_terminal_stderr(args, interrupt_when=None):
    """Runs rotbeam with stderr on a pseudo-terminal (stdout on a pipe): (returncode, stdout, stderr).
    With interrupt_when, SIGINT is sent once interrupt_when(process) holds (polled)."""
    master, slave = pty.openpty()
    proc = subprocess.Popen([CLI, *args], stdout=subprocess.PIPE, stderr=slave, text=True)
    os.close(slave)
    chunks = []

    def drain():
        while True:
            try:
                data = os.read(master, 4096)
            except OSError:  # EIO: the child closed the terminal
                return
            if not data:
                return
            chunks.append(data)

    reader = threading.Thread(target=drain)
    reader.start()
    if interrupt_when is not None:
        under_way = wait_until(lambda: interrupt_when(proc) or proc.poll() is not None)
        proc.send_signal(signal.SIGINT if under_way and proc.poll() is None else signal.SIGKILL)
    out = proc.stdout.read()
    proc.wait(timeout=600)
    reader.join(timeout=60)
    os.close(master)
    return proc.returncode, out, b"".join(chunks).decode(errors="replace")


def folder_bytes(path):
    return sum(p.stat().st_size for p in Path(path).rglob("*") if p.is_file())


@pytest.fixture(scope="module")
def reproduction(tmp_path_factory):
    """One default reproduction, stderr on a terminal."""
    out = tmp_path_factory.mktemp("reproduce") / "rep"
    code, stdout, stderr = run_with_terminal_stderr(["reproduce", "-o", str(out)])
    return {"dir": out, "code": code, "stdout": stdout, "stderr": stderr,
            "report": (out / "report.md").read_text() if (out / "report.md").exists() else ""}


@pytest.fixture(scope="module")
def drawn(reproduction):
    """The reproduction's figures drawn again in this process, kept as matplotlib objects."""
    import matplotlib

    matplotlib.use("Agg")
    from rotbeam import reproduce

    figures = {}
    saved = reproduce.save_figure
    reproduce.plt.close("all")
    original_close = reproduce.plt.close
    try:
        reproduce.save_figure = lambda fig, path, dpi=100: figures.__setitem__(Path(path).stem, fig)
        reproduce.plt.close = lambda fig=None: None  # keep them for inspection
        reproduce.write_report(reproduction["dir"])
    finally:
        reproduce.save_figure = saved
        reproduce.plt.close = original_close
    yield figures
    for fig in figures.values():
        original_close(fig)


def section(report, number):
    start = report.index(f"## Figure {number}:")
    end = report.find("\n## ", start + 1)
    return report[start:end]


def test_reproduce_writes_every_figure_and_table(reproduction):
    assert reproduction["code"] == 0, reproduction["stderr"][-2000:]
    report = reproduction["report"]
    assert "## Table 5-3" in report and report.count("| yes |") == 8  # every Table 5-3 row matches
    for number in range(4, 14):
        png = reproduction["dir"] / "figures" / f"figure_{number:02d}.png"
        assert png.exists() and png.stat().st_size > 20_000, number
        assert f"## Figure {number}:" in report and f"(figures/figure_{number:02d}.png)" in report
    assert report.count("**The thesis states:**") == 10
    assert "## Summary: which of the thesis's trends hold" in report


def test_progress_is_one_redrawn_line_on_a_terminal(reproduction):
    err = reproduction["stderr"]
    # Redrawn with carriage returns, never a new line, and cleared at the end.
    assert "\n" not in err.replace("\r\n", "\n").strip("\r\n "), err[-500:]
    runs = re.findall(r"reproduce: run (\d+)/(\d+) ", err)
    assert runs and runs[-1][0] == runs[-1][1] == "62"
    assert "reproduce: figure 10/10" in err
    assert err.split("\r")[-1].strip() == ""  # cleared at the end
    assert "wrote " in reproduction["stdout"] and "the runs' files take" in reproduction["stdout"]


def test_quiet_on_a_terminal_with_quiet(tmp_path):
    # With --quiet, no progress line on a terminal: only the interruption's one line. (Off a
    # terminal it is quiet too: see test_keep_history_keeps_every_row_and_announces_its_size.)
    # Interrupted once it is under way: its interrupt handler installed and a run's files written.
    out = tmp_path / "q"
    code, _, err = run_with_terminal_stderr(
        ["reproduce", "--quiet", "-o", str(out)],
        interrupt_when=lambda proc: catches(proc.pid, signal.SIGINT) and any(p.is_file() for p in out.glob("*/*/*")))
    assert code == 130, err
    assert "reproduce:" not in err
    assert err.strip() == "rotbeam: error: reproduction interrupted; run it again"


def test_studies_keep_summaries_and_the_rows_the_figures_draw(reproduction):
    out = reproduction["dir"]
    size = folder_bytes(out / "thesis") + folder_bytes(out / "physical")
    assert size < 40e6, f"{size / 1e6:.0f} MB"  # every row of every run is ~300 MB
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["history"]["kept"] == "thinned"
    whole = manifest["history"]["whole_path_case"]
    from rotbeam.reproduce import read_table

    for model in MODELS:
        for case in (p.name for p in (out / model).iterdir()):
            folder = out / model / case
            for name in ("summary.json", "events.csv", "history.csv"):
                assert (folder / name).exists(), folder / name
            h = read_table(folder / "history.csv", ("t_s", "theta_deg", "phase"))
            pressed = h["phase"] != "free"
            if case == whole:
                # Figure 13's path: the whole pass, from the first impact on a row at least every 1e-5 s
                # or every step where steps are longer (at most simulation.max_step_s = 2e-5 s; before
                # the first impact the rigid start's rows are as the pass took them).
                assert h["theta_deg"][-1] == pytest.approx(90)
                ev = read_table(folder / "events.csv")
                t = h["t_s"][h["t_s"] >= ev["t_s"][ev["kind"] == "impact"][0]]
                gaps = t[1:] - t[:-1]
                assert gaps.max() <= 2e-5 * (1 + 1e-9) and 0.9e-5 < float(np.median(gaps)) < 1.3e-5
                continue
            # Elsewhere: every free row is the first, the last, or next to a contact row.
            near = pressed.copy()
            near[1:] |= pressed[:-1]
            near[:-1] |= pressed[1:]
            near[0] = near[-1] = True
            assert near.all(), f"{folder}: {int((~near).sum())} free rows the figures do not draw"
            s = json.loads((folder / "summary.json").read_text())
            assert s["files"]["history.csv"]["bytes"] == (folder / "history.csv").stat().st_size


def test_keep_history_keeps_every_row_and_announces_its_size(reproduction, tmp_path):
    out = tmp_path / "full"
    try:
        done = run("reproduce", "--keep-history", "-o", str(out), timeout=600)
        assert done.returncode == 0, done.stderr[-2000:]
        note = re.fullmatch(r"rotbeam: note: --keep-history: the 62 histories will take about (\d+) MB in .*\n",
                            done.stderr)
        assert note, done.stderr  # announced, and no progress off a terminal
        size = folder_bytes(out / "thesis") + folder_bytes(out / "physical")
        assert size > 200e6 and abs(size / 1e6 - int(note.group(1))) < 0.1 * size / 1e6
        # The thinned histories change no number of the report.
        strip = lambda text: text.split("\n", 6)[6]  # noqa: E731 (the header says how histories were kept)
        assert strip((out / "report.md").read_text()) == strip(reproduction["report"])
    finally:
        shutil.rmtree(out, ignore_errors=True)


def test_every_panel_has_data_or_says_why_and_every_axis_has_units(drawn):
    assert sorted(drawn) == [f"figure_{n:02d}" for n in range(4, 14)]
    for name, fig in drawn.items():
        for ax in fig.axes:
            where = f"{name}: {ax.get_title()!r}"
            for axis, label in (("x", ax.get_xlabel()), ("y", ax.get_ylabel())):
                shared = getattr(ax, f"get_shared_{axis}_axes")().get_siblings(ax)
                labels = [label] + [getattr(a, f"get_{axis}label")() for a in shared]
                assert any(re.search(r"\(.+\)$", l) for l in labels), f"{where}: no unit on the {axis} axis"
            data = [l for l in ax.get_lines() if len(l.get_xdata()) and
                    any(x == x for x in map(float, l.get_ydata()))]
            data += list(ax.patches)
            said = [t.get_text() for t in ax.texts if len(t.get_text()) > 20]
            assert data or said, f"{where}: an empty panel with no word why"
            legend = ax.get_legend()
            if legend is None:
                continue
            drawn_labels = {h.get_label() for h in ax.get_lines() + list(ax.patches)
                            if (not hasattr(h, "get_xdata") or any(y == y for y in map(float, h.get_ydata())))}
            for text in legend.get_texts():
                assert text.get_text() in drawn_labels, f"{where}: legend entry {text.get_text()!r} without data"


def test_a_pass_of_impacts_shows_its_impulses_and_says_so(reproduction, drawn):
    report = reproduction["report"]
    fig10 = section(report, 10)
    # Figure 10 has no sustained contact at all: the report says the panel is empty and why.
    for model in MODELS:
        assert f"* {model}: top panel (a) empty: μ = 0.1, 0.3, 0.5, 0.7 (the same pass): no sustained contact, " \
               "the pass is 6 impacts, 2.84 mN·s" in fig10
    assert "so μ cannot act" in fig10
    # The figure itself says it, on the panel; the impulses and the binned force are drawn.
    top = [ax for ax in drawn["figure_10"].axes if "sustained contact" in ax.get_title()]
    assert len(top) == 2 and all(any("no sustained contact" in t.get_text() for t in ax.texts) for ax in top)
    impulses = [ax for ax in drawn["figure_10"].axes if ax.get_title().startswith("each impact's impulse")]
    assert len(impulses) == 2 and all(len(ax.get_lines()[0].get_xdata()) == 6 for ax in impulses)
    # Figures 6 and 7 name the case they cannot draw (3000 rpm; 2000 rpm in the thesis model).
    assert "thesis: not in the top panel (a): 3000 rpm: no sustained contact, the pass is 6 impacts" in section(report, 6)
    assert "thesis: not in the top panel (a): 2000 rpm: no sustained contact, the pass is 18 impacts" in section(report, 7)


def test_trends_use_the_binned_peak_without_sustained_contact(reproduction):
    fig6 = section(reproduction["report"], 6)
    row = next(l for l in fig6.splitlines() if l.startswith("| 3000 rpm | thesis |"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert cells[4] == "– (no sustained contact)" and cells[6] == "binned" and float(cells[5]) > 1
    assert "3000 rpm: 67.7 N (binned)" in fig6 and "3000 rpm: 0 N" not in fig6
    assert "the peak of the mean normal force over 0.5° bins" in fig6


def test_contact_lengths_are_defined_and_named(reproduction):
    report = reproduction["report"]
    assert "* **touch span in Y (mm)**: the span of the tip's Y over which it touches the surface, from the first " \
           "impact to the last separation" in report
    assert "* **sustained-contact length in Y (mm)**" in report
    assert "contact length in Y (mm)" not in report.replace("sustained-contact length in Y (mm)", "")
    row = next(l for l in section(report, 10).splitlines() if l.startswith("| μ = 0.1 | physical |"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert cells[3] == "0" and float(cells[7]) == pytest.approx(22.2, abs=0.1) and float(cells[8]) == 0


def test_figure_12_is_readable_and_explains_its_unit(reproduction, drawn):
    fig = drawn["figure_12"]
    assert len(fig.axes) == 10  # a panel per disturbed mode and model, as the thesis's 12(a)-(e)
    limits = {ax.get_ylim() for ax in fig.axes}
    assert len(limits) == 1  # one scale, stated in the title
    assert "every panel on the same scales" in fig._suptitle.get_text()
    labels = [t.get_text() for ax in fig.axes for t in ax.get_legend().get_texts()]
    for k in range(1, 6):
        assert any(l.startswith(f"$\\dot{{q}}_{{{k}}}$(0) = 0.1 m/s") for l in labels), labels
    assert any("as 0.1 $\\mathrm{s}^{-1}$" in t.get_text() and "0.1 m/s" in t.get_text() for t in fig.texts)
    assert "the thesis gives the disturbance as 0.1 s⁻¹" in section(reproduction["report"], 12)


def test_figure_13_has_the_thesis_panels(reproduction, drawn):
    titles = [ax.get_title() for ax in drawn["figure_13"].axes]
    for panel in ("(a) the whole pass", "(b1) disturbance 1", "(b2) disturbance 2", "(c) the contact region",
                  "(d) the bounce back"):
        assert sum(panel in t for t in titles) == 2, (panel, titles)
    fig13 = section(reproduction["report"], 13)
    assert fig13.count("2 disturbances after the last separation") == 2
    assert fig13.count("bounce back after the first impact: yes") == 2


def test_bad_input_is_one_line(tmp_path):
    for args, text in ((["--jobs", "-1"], "--jobs -1: must be >= 0"),
                       (["--bogus"], "--bogus"),
                       (["-o", "/proc/rotbeam-cannot-be-here"], "-o /proc/rotbeam-cannot-be-here")):
        done = run("reproduce", *args)
        assert done.returncode == 2 and done.stderr.count("\n") == 1 and text in done.stderr, done.stderr
    done = subprocess.run(["/usr/bin/python3", "-m", "rotbeam.reproduce", str(tmp_path)], capture_output=True, text=True)
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and "no manifest.json" in done.stderr, done.stderr


def test_without_binned_force_the_figures_bin_the_impulses_themselves(reproduction, tmp_path):
    # A reproduction whose runs have no force_bins.csv and no binned_force (as before they had them):
    # the binned force is computed from events.csv and the contact rows of history.csv.
    copy = tmp_path / "old"
    shutil.copytree(reproduction["dir"], copy, ignore=shutil.ignore_patterns("*.png"))
    for summary in copy.glob("*/*/summary.json"):
        s = json.loads(summary.read_text())
        s.pop("binned_force", None)
        s["files"].pop("force_bins.csv", None)
        summary.write_text(json.dumps(s))
        (summary.parent / "force_bins.csv").unlink(missing_ok=True)
    done = subprocess.run(["/usr/bin/python3", "-m", "rotbeam.reproduce", str(copy)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    fig6 = section((copy / "report.md").read_text(), 6)
    assert "3000 rpm: 67.7 N (binned)" in fig6  # six impacts: the same bins as force_bins.csv
    from rotbeam.reproduce import Runs

    run = Runs(copy)("thesis", "3000rpm_d2_mu0.4_rigid")
    assert run["bins_source"] == "events.csv and history.csv"
    assert run["metrics"]["binned_source"] == "events.csv and history.csv"
    assert (copy / "figures" / "figure_06.png").stat().st_size > 20_000
