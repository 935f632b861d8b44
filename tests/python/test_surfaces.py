"""The pictures of the surfaces beyond the plane (docs/surfaces.md): a cylinder's and a casing's run
draw their surface where the tip meets it, and a sweep over speed with a lobed casing draws the rub
map over the Campbell diagram, with its engine-order crossings where the sampled frequencies cross
k·Ω. Run by ctest with PYTHONPATH=<build>/python and ROTBEAM_CLI=<rotbeam binary>."""

import json
import os
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from rotbeam import plots, rub_map  # noqa: E402

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")
CASING = ["--set", "surface.shape=casing", "--set", "surface.clearance_m=1e-4", "--set", "surface.lobes=2",
          "--set", "surface.lobe_amplitude_m=3e-4", "--set", "surface.friction=0.02", "--set",
          "beam.damping_ratio=0.02"]


def cli(*args):
    done = subprocess.run([CLI, *args], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done


@pytest.fixture(scope="module")
def folders(tmp_path_factory):
    out = {}
    cylinder = tmp_path_factory.mktemp("cylinder")
    cli("run", "--set", "surface.shape=cylinder", "--set", "surface.radius_m=0.02", "--set", "surface.speed_rpm=-500",
        "-o", str(cylinder), "--quiet")
    out["cylinder"] = cylinder
    casing = tmp_path_factory.mktemp("casing")
    cli("run", *CASING, "--set", "simulation.revolutions=2", "--set", "hub.speed_rpm=2000", "-o", str(casing), "--quiet")
    out["casing"] = casing
    sweep = tmp_path_factory.mktemp("rub")
    cli("sweep", *CASING, "--set", "simulation.revolutions=2", "--vary", "hub.speed_rpm=2500:4500:5", "-o", str(sweep),
        "--quiet")
    out["sweep"] = sweep
    return out


@pytest.mark.parametrize("sets", [
    ["--set", "surface.shape=cylinder", "--set", "surface.radius_m=0.002", "--set", "surface.friction=0.1"],
    ["--set", "surface.shape=casing", "--set", "surface.clearance_m=1e-5", "--set", "surface.lobes=999",
     "--set", "surface.lobe_amplitude_m=3e-5", "--set", "surface.friction=0.02"]])
def test_a_small_workpiece_or_many_lobes_are_drawn(tmp_path, sets):
    # The tip beside a workpiece narrower than its path (no surface point at its Y) and a first impact
    # near φ = ±90° on a casing of 999 lobes: both stopped `plot` with NaN axis limits before.
    cli("run", *sets, "-o", str(tmp_path / "run"), "--quiet")
    cli("plot", str(tmp_path / "run"), "-o", str(tmp_path / "pictures"))
    assert (tmp_path / "pictures" / "tip_path.png").stat().st_size > 10000


@pytest.mark.parametrize("shape", ["cylinder", "casing"])
def test_contact_rows_lie_on_the_drawn_surface(folders, shape):
    # The surface's curve passes through the tip wherever the tip is in sustained contact (to 1 µm):
    # the drawing follows the same law as the gap, on the side of the tip.
    h, events, summary = plots.read_run(folders[shape])
    surface = plots.surface_of(summary)
    assert surface["shape"] == shape
    contact = h["phase"] != "free"
    assert contact.any()
    x = plots.surface_x(surface, h["y_tip_m"][contact], h["x_tip_m"][contact])
    assert np.max(np.abs(x - h["x_tip_m"][contact])) < 1e-6
    fig = plots.tip_path_figure(h, events, summary, plots.case_title(summary))
    assert shape in plots.case_title(summary)
    fig.canvas.draw()
    plt.close(fig)


def test_the_rub_map_marks_where_engine_orders_cross_the_modes(folders):
    table, keys, ok = plots.read_sweep(folders["sweep"])
    assert rub_map.is_rub_sweep(folders["sweep"], table, keys, ok)
    speeds = table["hub.speed_rpm"].astype(float)
    f1 = table["f1_hz"].astype(float)
    # The crossing of 2× with mode 1 lies between the sampled speeds where 2Ω/60 − f1 changes sign.
    below = speeds[2 * speeds / 60 < f1].max()
    above = speeds[2 * speeds / 60 > f1].min()
    (x,) = rub_map.crossings(speeds, f1, 2)
    assert below < x < above
    fig = rub_map.rub_map_figure(folders["sweep"], table, keys, ok)
    campbell = fig.axes[0]
    assert any(line.get_marker() == "o" and np.isclose(line.get_xdata()[0], x) for line in campbell.lines)
    for ax in fig.axes[1:6]:  # the response panels: one line of data, every crossing dotted
        assert any(len(line.get_xdata()) == len(speeds) and line.get_linestyle() == "-" for line in ax.lines)
        assert ax.get_xlabel() and ax.get_ylabel()
    plt.close(fig)
    cli("plot", str(folders["sweep"]), "-o", str(folders["sweep"] / "pictures"))
    assert (folders["sweep"] / "pictures" / "rub_map.png").stat().st_size > 10000


def test_the_last_revolution_and_the_frequencies_are_in_the_summary(folders):
    s = json.loads((folders["casing"] / "summary.json").read_text())
    assert s["last_revolution"]["revolution"] == 2
    assert len(s["natural_frequencies_hz"]) == 5 and s["natural_frequencies_hz"][0] > 90
    assert s["surface"]["shape"] == "casing" and s["surface"]["lobes"] == 2
    # The ledger of the last revolution closes with the surface's work (0 for a casing at rest).
    r = s["last_revolution"]
    assert r["surface_work_j"] == 0.0
    assert abs(r["ledger_residual_j"]) < 1e-8 * abs(r["hub_work_j"])


def test_a_casings_force_is_drawn_along_the_hub_angle_with_both_lobes_apart(folders):
    # A casing meets the tip at the same Y on both sides of a lobe: its force is drawn against the hub
    # angle from the deepest point, in (−180°, 180°], and an episode across ±180° is not joined across
    # the axis. The sweep's picture does the same for a sweep of casings.
    from rotbeam._runs import read_run, sustained_force

    h, events, summary = read_run(folders["casing"])
    fig = plots.force_figure(folders["casing"], h, events, summary, "casing")
    ax = fig.axes[0]
    assert "hub angle" in ax.get_xlabel()
    x, f = sustained_force(h, True)
    drawn = x[np.isfinite(x)]
    assert drawn.size and drawn.min() > -180.0 - 1e-9 and drawn.max() <= 180.0 + 1e-9
    steps = np.abs(np.diff(x))
    assert not (steps[np.isfinite(steps)] > 180.0).any()  # no line drawn across the axis
    # Both lobes: contact near 0° and near ±180° (a 2-lobe casing's deepest points).
    assert (np.abs(drawn) < 45).any() and (np.abs(drawn) > 135).any()
    plt.close(fig)
    from rotbeam import sweep_plots

    table, keys, ok = sweep_plots.read_sweep(folders["sweep"])
    drawn_folders = [f for f, good in zip(table["folder"], ok) if good]
    assert drawn_folders
    fig = sweep_plots.sweep_force_figure(folders["sweep"], table, keys, ok, drawn_folders)
    assert "hub angle" in fig.axes[0].get_xlabel()
    plt.close(fig)
