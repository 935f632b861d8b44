"""Continuation from the command line and from Python (docs/continuation.md): `rotbeam continue` writes
branch.csv and summary.json (last, with the sizes), rotbeam.continue_orbits() gives the same points,
`rotbeam plot` draws continuation.png with data in every panel, and bad input is refused in one line
naming the option or key with nothing written. Run by ctest with PYTHONPATH=<build>/python and
ROTBEAM_CLI=<rotbeam binary>."""

import json
import os
import subprocess

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402

import rotbeam  # noqa: E402
from rotbeam import continuation_plots  # noqa: E402
from rotbeam._csv import read_csv  # noqa: E402

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")
ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
CASING = os.path.join(ROOT, "examples", "casing-rub.toml")
RANGE = ["--parameter", "hub.speed_rpm", "--from", "1000", "--to", "1001", "--step", "0.5", "--max-step", "1"]


def run(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True)


def test_the_command_and_python_agree_and_the_picture_has_data(tmp_path):
    out = tmp_path / "c"
    done = run("continue", CASING, *RANGE, "-o", str(out), "--quiet")
    assert done.returncode == 0, done.stderr
    summary = json.loads((out / "summary.json").read_text())
    assert summary["kind"] == "continuation" and summary["complete"] and summary["period"] == 1
    for name, entry in summary["files"].items():
        assert (out / name).stat().st_size == entry["bytes"]
    branch = read_csv(out / "branch.csv", modes=2 * summary["modes"])
    assert len(branch["parameter"]) == summary["points"] >= 2
    assert branch["parameter"][0] == 1000 and branch["parameter"][-1] == 1001
    assert all(branch["stable"]) and (branch["max_abs_multiplier"] < 1).all()
    assert (branch["impacts"] == 4).all() and (branch["peak_normal_force_n"] > 0).all()
    # |μ1| is the largest; the state z has 2n components.
    mu = np.hypot(branch["mu1_re"], branch["mu1_im"])
    assert np.allclose(mu, branch["max_abs_multiplier"])
    assert f"z{2 * summary['modes']}" in branch

    r = rotbeam.continue_orbits(CASING, parameter="hub.speed_rpm", start=1000, stop=1001, step=0.5, max_step=1)
    assert "hub.speed_rpm" in repr(r)
    # The same points (the same arithmetic, threads only share out the Jacobian's columns).
    assert np.array_equal(r.branch["parameter"], branch["parameter"])
    assert np.array_equal(r.branch["z1"], branch["z1"])

    plotted = run("plot", str(out))
    assert plotted.returncode == 0, plotted.stderr
    assert (out / "continuation.png").stat().st_size > 10000
    fig = continuation_plots.continuation_figure(*continuation_plots.read_continuation(out))
    for ax in fig.axes:
        assert ax.lines, "an empty panel"
        assert ax.get_ylabel()


def test_bad_input_is_one_line_naming_it(tmp_path):
    cases = [
        (["--parameter", "hub.speed", "--from", "1", "--to", "2"], "hub.speed"),
        (["--parameter", "hub.speed_rpm", "--from", "1000", "--to", "1000"], "empty"),
        (["--parameter", "beam.modes", "--from", "3", "--to", "4"], "beam.modes"),
        (["--parameter", "surface.friction", "--from", "0.1", "--to", "-1"], "surface.friction"),
        (["--parameter", "hub.speed_rpm", "--from", "1000", "--to", "1001", "--step", "0"], "--step"),
    ]
    for args, named in cases:
        out = tmp_path / "bad"
        done = run("continue", CASING, *args, "-o", str(out))
        assert done.returncode == 2, (args, done.stderr)
        lines = done.stderr.strip().splitlines()
        assert len(lines) == 1 and named in lines[0], (args, done.stderr)
        assert not out.exists(), args
