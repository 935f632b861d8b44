"""A brush from Python and its pictures (docs/brush.md): rotbeam.brush's tables against rotbeam.run's
own revolutions (an independent route), the files `rotbeam brush` writes read the same, the three
pictures with data in every panel and the zone shaded, a damaged folder named in one line with
nothing drawn, and the brush map of a sweep over brushes. Run by ctest with
PYTHONPATH=<build>/python and ROTBEAM_CLI=<rotbeam binary>."""

import json
import os
import subprocess
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import rotbeam  # noqa: E402
from rotbeam import brush_plots  # noqa: E402

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")
DAMPED = {"beam.damping_ratio": 0.05}


def test_identical_filaments_sum_to_n_times_one_run():
    # One filament's steady revolution from rotbeam.run (its revolutions table), against a brush of 3.
    one = rotbeam.run(overrides={**DAMPED, "simulation.until_steady": True, "simulation.multipliers": False})
    rev = one.revolutions
    period = rev["t_end_s"][-1] - rev["t_start_s"][-1]
    b = rotbeam.brush(overrides={**DAMPED, "brush.filaments": 3}, jobs=1)
    assert b.failure is None
    assert b.summary["mean_normal_force_n"] == pytest.approx(3 * rev["normal_impulse_n_s"][-1] / period, rel=1e-9)
    assert b.summary["mean_hub_power_w"] == pytest.approx(3 * rev["mean_hub_power_w"][-1], rel=1e-9)
    # Tables as numpy arrays, one entry per bin and per filament; numbers, booleans and words typed.
    assert b.workpiece["normal_force_n"].dtype == float and len(b.workpiece["theta_from_deg"]) == 720
    assert b.filaments["filament"].tolist() == [1, 2, 3]
    assert b.filaments["reaches"].dtype == bool and b.filaments["status"].tolist() == ["steady"] * 3
    assert np.sum(b.workpiece["normal_impulse_n_s"]) == pytest.approx(3 * rev["normal_impulse_n_s"][-1], rel=1e-9)
    assert "3 filaments" in repr(b)


def test_bad_input_is_a_config_error():
    with pytest.raises(rotbeam.ConfigError, match=r"no \[brush\] section"):
        rotbeam.brush()
    with pytest.raises(rotbeam.ConfigError, match=r"^brush.length_scatter = 0.5: must be in"):
        rotbeam.brush(overrides={"brush.length_scatter": 0.5})
    with pytest.raises(TypeError, match="jobs"):
        rotbeam.brush(overrides={"brush.filaments": 2}, jobs=1.5)
    with pytest.raises(rotbeam.ConfigError, match="rotbeam brush"):
        rotbeam.run(overrides={"brush.filaments": 2})


@pytest.fixture(scope="module")
def brush_folder(tmp_path_factory):
    out = tmp_path_factory.mktemp("brush") / "b"
    done = subprocess.run([CLI, "brush", "--quiet", "-o", str(out), "--set", "brush.filaments=3",
                           "--set", "brush.length_scatter=0.005", "--set", "beam.damping_ratio=0.05"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return out


def test_files_read_as_the_python_result(brush_folder):
    summary, workpiece, profile, filaments = brush_plots.read_brush(brush_folder)
    again = rotbeam.brush(overrides={"brush.filaments": 3, "brush.length_scatter": 0.005, **DAMPED})
    assert summary["mean_normal_force_n"] == again.summary["mean_normal_force_n"]
    assert np.array_equal(workpiece["normal_force_n"], again.workpiece["normal_force_n"])
    assert np.array_equal(filaments["length_m"], again.filaments["length_m"])
    assert len(profile["theta_from_deg"]) == 720


def test_pictures_have_data_in_every_panel(brush_folder, tmp_path):
    figures = brush_plots.brush_figures(brush_folder)
    assert [name for name, _ in figures] == ["brush_force", "brush_profile", "brush_filaments", "brush_spectrum"]
    for name, fig in figures:
        for ax in fig.axes:
            # Units on every axis (a panel sharing its x axis with the one below has it there).
            assert ax.get_ylabel(), name
            assert ax.get_xlabel() or any(o.get_xlabel() for o in ax.get_shared_x_axes().get_siblings(ax)), name
            assert ax.lines or ax.collections or ax.patches, name
            legend = ax.get_legend()
            if legend:
                assert all(text.get_text() for text in legend.get_texts()), name
        plt.close(fig)
    # The profile zooms on the contact zone.
    _, profile, _ = [f for _, f in brush_plots.brush_figures(brush_folder)][:3]
    lo, hi = profile.axes[0].get_xlim()
    assert hi - lo < 120
    plt.close("all")
    done = subprocess.run([CLI, "plot", str(brush_folder), "-o", str(tmp_path / "pics")], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in (tmp_path / "pics").iterdir()) == [
        "brush_filaments.png", "brush_force.png", "brush_profile.png", "brush_spectrum.png"]


def test_a_damaged_brush_is_named_and_nothing_is_drawn(brush_folder, tmp_path):
    damaged = tmp_path / "damaged"
    damaged.mkdir()
    for f in brush_folder.iterdir():
        if f.suffix in (".csv", ".json"):
            (damaged / f.name).write_bytes(f.read_bytes())
    with open(damaged / "workpiece.csv", "a") as f:
        f.write("1,2\n")
    done = subprocess.run([CLI, "plot", str(damaged), "-o", str(tmp_path / "none")], capture_output=True, text=True)
    assert done.returncode == 2
    assert "workpiece.csv" in done.stderr and len(done.stderr.strip().splitlines()) == 1, done.stderr
    assert not (tmp_path / "none").exists()


def test_brush_map_of_a_sweep(tmp_path):
    out = tmp_path / "map"
    done = subprocess.run([CLI, "sweep", "--quiet", "-o", str(out), "--set", "brush.filaments=2",
                           "--set", "beam.damping_ratio=0.05", "--vary", "surface.depth_fraction=0.01,0.02",
                           "--vary", "hub.speed_rpm=550,1100"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    header = (out / "sweep.csv").read_text().splitlines()[0]
    assert ",force_ratio," in header
    done = subprocess.run([CLI, "plot", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert (out / "brush_map.png").exists()
    summary = json.loads((out / "case-0001" / "summary.json").read_text())
    assert summary["kind"] == "brush"


def test_a_population_from_python_matches_its_representatives():
    # brush.method = "population": the representatives stand for every filament that reaches (their
    # weights sum to that count), each filament's interpolated means sum to the brush's, and the
    # summary carries the estimate the population made of its own error.
    fast = {"beam.modes": 3, "beam.damping_ratio": 0.1, "surface.depth_fraction": 0.03, "brush.filaments": 40,
            "brush.length_scatter": 0.05, "brush.method": "population", "brush.population_max_runs": 20}
    b = rotbeam.brush(overrides=fast, jobs=2)
    assert b.failure is None
    s = b.summary
    assert s["method"] == "population" and s["population"]["representatives"] == s["distinct_filaments"] <= 20
    r = b.representatives
    reaching = r["status"] != "clear"
    assert np.sum(r["weight"][reaching]) == pytest.approx(s["reaching_filaments"], rel=1e-12)
    assert np.sum(r["nearest"]) == s["filaments"]
    assert np.sum(b.filaments["mean_normal_force_n"]) == pytest.approx(s["mean_normal_force_n"], rel=1e-9)
    assert 0 < s["population"]["estimated_error"]["mean_normal_force"] < 1
    assert "representatives" in repr(b)


def test_a_brush_as_an_xarray_dataset():
    # BrushResult.to_xarray: every table on its dimension with units, the same numbers as the tables.
    xr = pytest.importorskip("xarray")
    b = rotbeam.brush(overrides={"beam.modes": 3, "beam.damping_ratio": 0.1, "brush.filaments": 6,
                                 "brush.length_scatter": 0.01, "brush.phase_jitter_deg": 2}, jobs=2)
    ds = b.to_xarray()
    assert isinstance(ds, xr.Dataset)
    assert ds.sizes["theta"] == 720 and ds.sizes["filament"] == 6 and ds.sizes["order"] == 361
    assert ds["workpiece_normal_force_n"].attrs["units"] == "N"
    assert ds["filament_length_m"].attrs["units"] == "m"
    assert ds["spectrum_frequency_hz"].attrs["units"] == "Hz"
    np.testing.assert_array_equal(ds["filament_mean_normal_force_n"].values, b.filaments["mean_normal_force_n"])
    assert float(ds["theta"][0]) == pytest.approx(-179.75)
    assert float(ds["spectrum_normal_force_n"].sel(order=0)) == pytest.approx(b.summary["mean_normal_force_n"], rel=1e-12)
    assert json.loads(ds.attrs["summary"])["filaments"] == 6
