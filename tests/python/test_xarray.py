"""xarray and netCDF results (issue 20): Result.to_xarray, rotbeam.sweep's Dataset (its grid, units,
failed cases as NaN with their status, the pandas view), rotbeam.open_sweep, and `rotbeam sweep
--format netcdf` (sweep.nc read back by xarray.open_dataset)."""

import json
import math
import re
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import rotbeam

xr = pytest.importorskip("xarray")
pytest.importorskip("netCDF4")

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")
QUICK = {"beam.modes": 3, "output.interval_s": 1e-3, "output.near_surface_interval_s": 1e-4}


def cli(*args, **kwargs):
    return subprocess.run([CLI, *args], capture_output=True, text=True, **kwargs)


def test_a_pass_as_a_dataset_over_t_with_units_and_its_events():
    r = rotbeam.run(overrides={"output.interval_s": 1e-4})
    ds = r.to_xarray()
    assert list(ds["normal_force_n"].dims) == ["t"]
    t = r.history["t_s"]
    kept = np.append(t[1:] != t[:-1], True)  # of an impact's two rows at one t, the one after it
    np.testing.assert_array_equal(ds["t"].values, t[kept])
    np.testing.assert_array_equal(ds["normal_force_n"].values, r.history["normal_force_n"][kept])
    assert list(ds["phase"].values) == list(r.history["phase"][kept])
    units = {name: ds[name].attrs.get("units") for name in ds.variables}
    assert units["t"] == "s" and units["normal_force_n"] == "N" and units["vx_m_s"] == "m s-1"
    assert units["q1_m"] == "m" and units["hub_torque_n_m"] == "N m" and units["jacobi_j"] == "J"
    assert units["theta_deg"] == "degree" and units["event_impulse_n_s"] == "N s"
    assert units["bin_mean_normal_force_n"] == "N" and units["bin_impacts"] == "1"
    assert "units" not in ds["phase"].attrs
    # The events are a table over `event`, a variable per column of events.csv.
    assert ds.sizes["event"] == len(r.events)
    assert list(ds["event_kind"].values) == [e["kind"] for e in r.events]
    assert ds["event_kind"].values.tolist().count("impact") == r.summary["impacts"]
    # The summary, the resolved configuration and the version in the attributes.
    assert json.loads(ds.attrs["configuration"]) == r.summary["config"]
    assert json.loads(ds.attrs["summary"])["impacts"] == r.summary["impacts"]
    assert ds.attrs["rotbeam_version"] == rotbeam.__version__


def test_a_pass_dataset_survives_netcdf(tmp_path):
    ds = rotbeam.run(overrides={"output.interval_s": 1e-4, "simulation.revolutions": 2}).to_xarray()
    assert ds.sizes["revolution"] == 2 and ds["revolution_mean_hub_power_w"].attrs["units"] == "W"
    ds.to_netcdf(tmp_path / "pass.nc")
    back = xr.open_dataset(tmp_path / "pass.nc").load()
    xr.testing.assert_identical(back, ds)


def test_a_sweep_is_a_dataset_over_its_keys_with_failed_cases_missing():
    # A cap of 30 impacts stops the cases with more on a diagnosed failure: NaN in every metric,
    # status `failed` and the failure's message, never zeros.
    vary = {"hub.speed_rpm": [550, 1000, 3000], "surface.friction": "0.1:0.7:3"}
    ds = rotbeam.sweep(vary, overrides={**QUICK, "surface.depth_fraction": 0.03, "simulation.max_impacts": 30},
                       progress=False)
    assert list(ds.dims) == ["hub.speed_rpm", "surface.friction"]
    assert ds["hub.speed_rpm"].dtype == np.int64 and ds["hub.speed_rpm"].attrs["units"] == "rpm"
    assert ds["surface.friction"].values.tolist() == [0.1, 0.4, 0.7] and ds["surface.friction"].attrs["units"] == "1"
    assert ds["case"].values.ravel().tolist() == list(range(1, 10))
    for column, units, _ in rotbeam._core.sweep_metrics(False):
        assert ds[column].attrs["units"] == units and ds[column].dtype == np.float64
    status = ds["status"].values.ravel().tolist()
    assert "failed" in status and "done" in status, status
    for i, st in enumerate(status):
        case = ds.isel({"hub.speed_rpm": i // 3, "surface.friction": i % 3})
        if st == "failed":
            assert math.isnan(float(case["impacts"])) and math.isnan(float(case["normal_impulse_n_s"]))
            # the failure's kind, then where it stopped (t and θ), then its message
            assert re.match(r"impacts at t = \S+ s, θ = \S+ deg: ", str(case["message"].values)), case["message"].values
        else:
            # A done case's metrics are those of rotbeam.run for it, to the last bit.
            s = rotbeam.run(overrides={**QUICK, "surface.depth_fraction": 0.03, "simulation.max_impacts": 30,
                                       "hub.speed_rpm": int(case["hub.speed_rpm"]),
                                       "surface.friction": float(case["surface.friction"])}).summary
            assert float(case["impacts"]) == s["impacts"]
            assert float(case["normal_impulse_n_s"]) == s["normal_impulse_n_s"]
            assert float(case["binned_peak_normal_force_n"]) == s["binned_force"]["peak_normal_force_n"]
            # Empty within the model's validity; beyond it, the validity and the warning that says how far.
            if s["validity"] == "within":
                assert str(case["message"].values) == ""
            else:
                assert str(case["message"].values).startswith(f"validity {s['validity']}: "), case["message"].values
    # The configuration the cases share, and what varies.
    config = json.loads(ds.attrs["configuration"])
    assert config["beam"]["modes"] == 3 and "speed_rpm" not in config["hub"]
    assert json.loads(ds.attrs["varying_keys"]) == ["hub.speed_rpm", "surface.friction"]
    assert ds.attrs["rotbeam_version"] == rotbeam.__version__ and ds.attrs["kind"] == "filament"
    # The pandas view: a row per case, indexed by the swept keys, in case order.
    df = ds.to_dataframe()
    assert list(df.index.names) == ["hub.speed_rpm", "surface.friction"] and len(df) == 9
    assert df["case"].tolist() == list(range(1, 10))


def test_sweep_reports_progress_and_refuses_bad_input_in_one_line():
    seen = []
    ds = rotbeam.sweep({"hub.speed_rpm": [2000, 3000]}, overrides=QUICK, progress=lambda n, total: seen.append((n, total)))
    assert seen[-1] == (2, 2) and ds.sizes["hub.speed_rpm"] == 2
    with pytest.raises(rotbeam.ConfigError, match=r"^vary hub.sped_rpm: unknown key \(did you mean hub.speed_rpm\?\)$"):
        rotbeam.sweep({"hub.sped_rpm": [550]})
    with pytest.raises(rotbeam.ConfigError, match=r"^case-0002 \(surface.friction=-0.4\): surface.friction = -0.4: "):
        rotbeam.sweep({"surface.friction": [0.1, -0.4]})
    with pytest.raises(rotbeam.ConfigError, match=r"^vary hub.speed_rpm: no values"):
        rotbeam.sweep({"hub.speed_rpm": []})
    with pytest.raises(rotbeam.ConfigError, match=r"^--vary hub.speed_rpm=1:2: a range is A:B:N$"):
        rotbeam.sweep({"hub.speed_rpm": "1:2"})
    with pytest.raises(rotbeam.ConfigError, match=r"^vary: give a dict"):
        rotbeam.sweep({})
    with pytest.raises(TypeError, match="jobs"):
        rotbeam.sweep({"hub.speed_rpm": [550]}, jobs="2")


def test_cli_netcdf_output_is_the_sweeps_dataset(tmp_path):
    out = tmp_path / "grid"
    done = cli("sweep", "--vary", "hub.speed_rpm=550,3000", "--vary", "surface.friction=0.1,0.4", "--set", "beam.modes=3",
               "--set", "output.interval_s=1e-3", "--set", "simulation.max_impacts=6", "--format", "netcdf",
               "-o", str(out), "--quiet")
    assert done.returncode == 0, done.stderr
    assert f"wrote {out / 'sweep.csv'}, {out / 'sweep.nc'}" in done.stdout
    assert not [p for p in out.iterdir() if ".tmp." in p.name]
    nc = xr.open_dataset(out / "sweep.nc").load()
    assert nc["impacts"].attrs["units"] == "1" and nc["contact_time_s"].attrs["units"] == "s"
    assert json.loads(nc.attrs["configuration"])["beam"]["modes"] == 3
    assert nc.attrs["rotbeam_version"] == rotbeam.__version__
    assert (nc["status"] == "failed").any() and np.isnan(nc["impacts"].where(nc["status"] == "failed")).all()
    xr.testing.assert_identical(nc, rotbeam.open_sweep(out))
    py = rotbeam.sweep({"hub.speed_rpm": [550, 3000], "surface.friction": [0.1, 0.4]},
                       overrides={"beam.modes": 3, "output.interval_s": 1e-3, "simulation.max_impacts": 6})
    xr.testing.assert_identical(nc.drop_vars("wall_time_s"), py.drop_vars("wall_time_s"))
    # A resumed sweep (every case already done) gives the same file.
    again = cli("sweep", "--vary", "hub.speed_rpm=550,3000", "--vary", "surface.friction=0.1,0.4", "--set", "beam.modes=3",
                "--set", "output.interval_s=1e-3", "--set", "simulation.max_impacts=6", "--format", "netcdf",
                "-o", str(out), "--quiet")
    assert again.returncode == 0 and "4 already done" in again.stdout, again.stdout + again.stderr
    xr.testing.assert_identical(xr.open_dataset(out / "sweep.nc").load(), nc)


def test_cli_format_is_checked_before_anything_runs(tmp_path):
    out = tmp_path / "grid"
    bad = cli("sweep", "--vary", "hub.speed_rpm=550", "--format", "hdf", "-o", str(out))
    assert bad.returncode == 2
    assert bad.stderr == "rotbeam: error: --format hdf: must be csv (sweep.csv) or netcdf (sweep.nc beside sweep.csv)\n"
    assert not out.exists()
    # A Python that cannot write netCDF (here: whose xarray cannot be imported) stops the sweep
    # before any case runs, saying what to install.
    fake = tmp_path / "fake"
    (fake / "xarray").mkdir(parents=True)
    (fake / "xarray" / "__init__.py").write_text("raise ModuleNotFoundError(\"No module named 'xarray'\")\n")
    package = str(Path(rotbeam.__file__).parent.parent)
    lacking = cli("sweep", "--vary", "hub.speed_rpm=550", "--format", "netcdf", "-o", str(out),
                  env={**os.environ, "ROTBEAM_PYTHONPATH": f"{fake}:{package}"})
    assert lacking.returncode == 2, lacking.stderr
    # One line: the refusal names the option, what is missing and what to do (it was two lines).
    lines = lacking.stderr.splitlines()
    assert len(lines) == 1, lacking.stderr
    assert lines[0].startswith("rotbeam: error: --format netcdf: writing sweep.nc needs xarray and netCDF4"), lines
    assert "apt-get install python3-xarray python3-netcdf4" in lines[0]
    assert lines[0].endswith("; use --format csv"), lines
    assert not out.exists()


def test_open_sweep_names_a_damaged_index(tmp_path):
    out = tmp_path / "grid"
    assert cli("sweep", "--vary", "hub.speed_rpm=2000,3000", "--set", "beam.modes=3", "--set", "output.interval_s=1e-3",
               "-o", str(out), "--quiet").returncode == 0
    text = (out / "sweep.csv").read_text()
    (out / "sweep.csv").write_text(text.replace("case,folder", "case,dossier"))
    with pytest.raises(ValueError, match="sweep.csv: its columns are not those of the sweep"):
        rotbeam.open_sweep(out)
    done = subprocess.run([sys.executable, "-m", "rotbeam.netcdf", str(out)],
                          capture_output=True, text=True)
    assert done.returncode == 2 and done.stderr.startswith("rotbeam: error: ") and done.stderr.count("\n") == 1
    assert not (out / "sweep.nc").exists()
