"""Wear from the command line and from Python (docs/wear.md): `rotbeam wear` writes its three files
with summary.json last and sizes that match, its history is the steps' chain (each length the last
less its loss), rotbeam.wear() gives the same numbers, `rotbeam plot` draws wear.png with data in every
panel, bad options are refused in one line naming them with nothing written, and a run's
wear_profile.csv sums to its summary's worn volume. Run by ctest with PYTHONPATH=<build>/python and
ROTBEAM_CLI=<rotbeam binary>."""

import json
import os
import subprocess

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import rotbeam  # noqa: E402
from rotbeam import wear_plots  # noqa: E402
from rotbeam._csv import read_csv  # noqa: E402

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")
SETS = ["--set", "beam.damping_ratio=0.05"]


def run(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True)


def test_the_command_and_python_agree_and_the_picture_has_data(tmp_path):
    out = tmp_path / "w"
    done = run("wear", *SETS, "--hours", "2", "--steps", "2", "-o", str(out), "--quiet")
    assert done.returncode == 0, done.stderr
    summary = json.loads((out / "summary.json").read_text())
    assert summary["kind"] == "wear" and summary["completed_steps"] == 2 and not summary["stopped_early"]
    for name, entry in summary["files"].items():
        assert (out / name).stat().st_size == entry["bytes"]
    history = read_csv(out / "wear_history.csv")
    assert len(history["step"]) == 3 and all(history["steady"])
    # Each length is the previous one less the previous step's loss (length_rate_mm_h × 1 h).
    lengths, rates = history["length_m"], history["length_rate_mm_h"] * 1e-3
    assert lengths[1:] == pytest.approx(lengths[:-1] - rates[:-1] * 1.0, rel=1e-12)
    assert summary["length_lost_m"] == pytest.approx(lengths[0] - lengths[-1], rel=1e-12)
    depth = read_csv(out / "wear_depth.csv")
    assert np.sum(depth["surface_volume_m3"]) == pytest.approx(summary["volume_removed_m3"], rel=1e-9)

    w = rotbeam.wear(overrides={"beam.damping_ratio": 0.05}, hours=2, steps=2)
    assert w.summary["length_lost_m"] == pytest.approx(summary["length_lost_m"], rel=1e-12)
    assert w.history["removal_rate_mm3_h"] == pytest.approx(history["removal_rate_mm3_h"], rel=1e-12)

    drawn = run("plot", str(out))
    assert drawn.returncode == 0, drawn.stderr
    assert (out / "wear.png").stat().st_size > 20000
    fig = wear_plots.wear_figure(*wear_plots.read_wear(out))
    for ax in fig.axes:
        assert ax.lines or ax.texts, ax.get_title()
        assert ax.get_ylabel()
    matplotlib.pyplot.close(fig)


def test_bad_options_are_refused_by_name_and_write_nothing(tmp_path):
    for args, word in ((["--hours", "0"], "--hours"), (["--steps", "0"], "--steps"),
                       (["--set", "wear.surface_hardness_pa=0"], "wear.surface_hardness_pa"),
                       (["--set", "brush.filaments=3"], "brush")):
        out = tmp_path / word.strip("-").replace(".", "_")
        done = run("wear", *args, "-o", str(out))
        assert done.returncode == 2, done.stderr
        assert word in done.stderr and len(done.stderr.strip().splitlines()) == 1, done.stderr
        assert not (out / "summary.json").exists()
    with pytest.raises(rotbeam.ConfigError, match="--hours"):
        rotbeam.wear(hours=-1)


def test_a_runs_wear_profile_sums_to_its_worn_volume(tmp_path):
    out = tmp_path / "r"
    done = run("run", "-o", str(out), "--quiet")
    assert done.returncode == 0, done.stderr
    summary = json.loads((out / "summary.json").read_text())
    profile = read_csv(out / "wear_profile.csv")
    wear = summary["wear"]
    assert np.sum(profile["surface_volume_m3"]) == pytest.approx(wear["surface_volume_m3"], rel=1e-12)
    assert np.sum(profile["sliding_load_n_m"]) == pytest.approx(summary["sliding_load_n_m"], rel=1e-12)
    width = wear["track_width_m"]
    area = width * (profile["position_to_m"] - profile["position_from_m"])
    assert np.sum(profile["removed_depth_m"] * area) == pytest.approx(wear["surface_volume_m3"], rel=1e-12)
    assert summary["files"]["wear_profile.csv"]["bytes"] == (out / "wear_profile.csv").stat().st_size
    # The same table from Python, for a run and for a brush.
    r = rotbeam.run()
    assert r.wear_profile["sliding_load_n_m"] == pytest.approx(profile["sliding_load_n_m"], rel=1e-12)
    b = rotbeam.brush(overrides={"beam.damping_ratio": 0.05, "brush.filaments": 2}, jobs=1)
    assert np.sum(b.wear_profile["sliding_load_n_m"]) == pytest.approx(b.summary["wear"]["sliding_load_n_m"], rel=1e-12)
