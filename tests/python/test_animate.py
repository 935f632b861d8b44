"""rotbeam animate / rotbeam.plots.animate: the drawn filament is the computed one, frames are
placed densely around events, the files are whole GIFs (and MP4s where ffmpeg is installed), and
bad requests are one line. Run by ctest with PYTHONPATH=<build>/python and ROTBEAM_CLI=<rotbeam>."""

import json
import os
import shutil
import subprocess

import numpy as np
import pytest
from PIL import Image

import rotbeam.animate as anim
import rotbeam.plots
from rotbeam.plots import read_csv

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")

# Cases: the base case (impacts, then sustained rubbing), 3000 rpm (impacts only, the bounce back)
# and a flexible start (free flight before the first impact, no rigid jump).
CASES = {
    "base": [],
    "3000rpm": ["--set", "hub.speed_rpm=3000"],
    "flexible": ["--set", "beam.modes=4", "--set", "initial.modal_velocity=[0.2,0,0,0]"],
}


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    out = {}
    for name, args in CASES.items():
        folder = tmp_path_factory.mktemp(name)
        done = subprocess.run([CLI, "run", *args, "-o", str(folder)], capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        out[name] = folder
    return out


@pytest.mark.parametrize("name", list(CASES))
def test_the_drawn_tip_is_the_recorded_tip(runs, name):
    # The filament drawn at each frame (q through BeamModel::shape, rotated by θ) ends where the run
    # recorded the tip, x_tip_m and y_tip_m, to 1e-9 m; its root is on the hub at radius r_h.
    folder = runs[name]
    summary = json.loads((folder / "summary.json").read_text())
    history = read_csv(folder / "history.csv")
    events = read_csv(folder / "events.csv")
    window = anim.default_window(history, events, summary)
    rows = anim.frame_rows(history, events, window, 240)
    shape = anim.filament_frames(folder, rows, history=history, summary=summary)
    assert np.max(np.abs(shape["x"][:, -1] - history["x_tip_m"][rows])) < 1e-9
    assert np.max(np.abs(shape["y"][:, -1] - history["y_tip_m"][rows])) < 1e-9
    root = np.hypot(shape["x"][:, 0], shape["y"][:, 0])
    assert np.allclose(root, summary["config"]["hub"]["radius_m"], rtol=0, atol=1e-15)
    # Magnified k times: the tip's distance from the straight filament is k times as large.
    big = anim.filament_frames(folder, rows, magnify=3.0, history=history, summary=summary)
    theta = np.radians(history["theta_deg"][rows])
    across = -shape["x"][:, -1] * np.sin(theta) + shape["y"][:, -1] * np.cos(theta)
    across_big = -big["x"][:, -1] * np.sin(theta) + big["y"][:, -1] * np.cos(theta)
    assert np.allclose(across_big, 3.0 * across, rtol=0, atol=1e-12)


def test_the_rigid_approach_is_drawn_exactly(runs):
    # A rigid start's history records the rigid turn (q = 0) from θ0 to the first impact; a history
    # written before it did (θ0, then the first impact) gets the turn filled in. Either way the
    # drawn tips lie on the circle of radius r_h + L at their angle, in order.
    folder = runs["base"]
    summary = json.loads((folder / "summary.json").read_text())
    history = read_csv(folder / "history.csv")
    first_impact = summary["first_impact_deg"]
    recorded = np.flatnonzero(history["theta_deg"] < first_impact - 1e-9)
    assert len(recorded) > 500  # −90° … −8.1° every 0.1°, and finer near the surface
    assert len(anim.with_rigid_approach(history, summary)["t_s"]) == len(history["t_s"])
    older = {key: np.concatenate([values[:1], values[recorded[-1] + 1:]]) for key, values in history.items()}
    filled = anim.with_rigid_approach(older, summary)
    added = len(filled["t_s"]) - len(older["t_s"])
    assert added > 1000  # −90° … −8.1° every 0.05°
    for h, rows in ((history, recorded[1:]), (filled, np.arange(1, 1 + added))):
        assert np.all(np.diff(h["theta_deg"][: rows[-1] + 2]) > 0)  # θ0, the turn, the first impact
        assert np.all(np.diff(h["t_s"][: rows[-1] + 2]) > 0)
        shape = anim.filament_frames(folder, rows, history=h, summary=summary)
        reach = summary["config"]["hub"]["radius_m"] + summary["config"]["beam"]["length_m"]
        theta = np.radians(h["theta_deg"][rows])
        assert np.max(np.abs(shape["x"][:, -1] - reach * np.cos(theta))) < 1e-12
        assert np.max(np.abs(shape["y"][:, -1] - reach * np.sin(theta))) < 1e-12
    # Flexible starts are left as recorded.
    flexible = runs["flexible"]
    fs = json.loads((flexible / "summary.json").read_text())
    fh = read_csv(flexible / "history.csv")
    assert len(anim.with_rigid_approach(fh, fs)["t_s"]) == len(fh["t_s"])


def test_frames_are_dense_around_impacts(runs):
    # Slow motion: within 0.4° of an impact a frame every few hundredths of a degree, in free flight
    # far from any event many times sparser.
    folder = runs["base"]
    summary = json.loads((folder / "summary.json").read_text())
    history = anim.with_rigid_approach(read_csv(folder / "history.csv"), summary)
    events = read_csv(folder / "events.csv")
    window = anim.default_window(history, events, summary)
    rows = anim.frame_rows(history, events, window, 240)
    theta = history["theta_deg"][rows]
    impacts = np.array([t for t, k in zip(events["theta_deg"], events["kind"]) if k == "impact"])
    near = np.min(np.abs(theta[:, None] - impacts[None, :]), axis=1) <= anim.EVENT_HALF_WIDTH_DEG
    far = (np.min(np.abs(theta[:, None] - impacts[None, :]), axis=1) > 2.0) & (history["phase"][rows] == "free")
    spacing_near = np.median(np.diff(theta)[near[1:]])
    spacing_far = np.median(np.diff(theta)[far[1:]])
    assert spacing_far > 10 * spacing_near, (spacing_near, spacing_far)
    assert window[0] < impacts.min() < impacts.max() < window[1]


def test_cli_writes_a_whole_gif_with_the_frames_asked_for(runs, tmp_path):
    out = tmp_path / "base.gif"
    done = subprocess.run([CLI, "animate", str(runs["base"]), "-o", str(out), "--frames", "60"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == f"wrote {out}"
    with Image.open(out) as im:
        assert im.n_frames == 60
        assert im.size[0] > 500 and im.size[1] > 400
    assert sorted(p.name for p in tmp_path.iterdir()) == ["base.gif"]  # no temporary left


def test_python_entry_point_and_default_names(runs, tmp_path):
    folder = tmp_path / "copy"
    shutil.copytree(runs["3000rpm"], folder)
    notes = []
    written = rotbeam.plots.animate(folder, frames=300, note=notes.append)
    expected = [folder / "animation.gif"] + ([folder / "animation.mp4"] if shutil.which("ffmpeg") else [])
    assert written == expected
    for path in written:
        assert path.stat().st_size > 10000
    # 3000 rpm sampled every 10 µs holds fewer distinct states than 300 frames: said, not padded.
    assert notes and "frames of the 300 asked for" in notes[0]
    with Image.open(folder / "animation.gif") as im:
        assert 20 < im.n_frames < 300


@pytest.mark.skipif(not shutil.which("ffmpeg"), reason="ffmpeg is not installed (MP4 is written only where it is)")
def test_mp4_has_every_frame(runs, tmp_path):
    out = tmp_path / "base.mp4"
    done = subprocess.run([CLI, "animate", str(runs["base"]), "-o", str(out), "--frames", "40"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-show_entries", "stream=nb_read_frames",
                            "-of", "csv=p=0", str(out)], capture_output=True, text=True)
    assert probe.stdout.strip() == "40"


@pytest.mark.parametrize("args, message", [
    (["--window", "5:1"], "--window: FROM must be below TO, got 5:1"),
    (["--window", "100:120"], "window 100:120: no history rows in it (the run recorded"),
    # checked before Python: a traceback from matplotlib, and argparse's usage block with exit 1
    (["--window=-1e308:1e308"], "--window: must be FROM:TO, two hub angles in degrees"),
    (["--window", "5"], "--window: must be FROM:TO, two hub angles in degrees"),
    # the option given is named, not a --frames never given
    (["--frames-per-degree", "1000"], "frames per degree = 1000 over the"),
    (["-o", "x.png"], "x.png: must end in .gif, .mp4"),
    (["--magnify", "0"], "--magnify"),
    (["--frames", "3", "--frames-per-degree", "2"], "excludes"),
])
def test_bad_requests_are_one_line(runs, tmp_path, args, message):
    args = [str(tmp_path / a) if a == "x.png" else a for a in args]
    done = subprocess.run([CLI, "animate", str(runs["base"]), *args], capture_output=True, text=True)
    assert done.returncode == 2, done.stderr
    assert done.stderr.count("\n") == 1 and message in done.stderr, done.stderr
    assert not list(tmp_path.iterdir())
