"""The Python module against the command line: same numbers to the last digit, same errors,
and thread safety. Run by ctest with PYTHONPATH=<build>/python and ROTBEAM_CLI=<rotbeam binary>."""

import concurrent.futures
import csv
import json
import math
import os
import subprocess

import numpy as np
import pytest

import rotbeam
from process_support import interrupt_once_a_thread_starts

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")
OVERRIDES = {"hub.speed_rpm": 3000, "surface.friction": 0.3, "output.interval_s": 1e-4}


def cli(*args):
    done = subprocess.run([CLI, *args], capture_output=True, text=True)
    return done.returncode, done.stdout, done.stderr


def sets(overrides):
    out = []
    for key, value in overrides.items():
        out += ["--set", f"{key}={value!r}" if isinstance(value, float) else f"{key}={value}"]
    return out


def without_wall_time(summary):
    return {k: v for k, v in summary.items() if k != "wall_time_s"}


def test_run_equals_the_cli_to_the_last_digit(tmp_path):
    result = rotbeam.run(overrides=OVERRIDES)
    code, out, err = cli("run", *sets(OVERRIDES), "-o", str(tmp_path), "--json")
    assert code == 0, err
    assert without_wall_time(result.summary) == without_wall_time(json.loads(out))
    with open(tmp_path / "history.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == len(result.history["t_s"])
    for name, column in result.history.items():
        if name == "phase":
            assert list(column) == [r["phase"] for r in rows]
        else:
            # %.17g in the CSV round-trips a double exactly.
            assert np.array_equal(column, np.array([float(r[name]) for r in rows])), name
    with open(tmp_path / "events.csv", newline="") as f:
        events = list(csv.DictReader(f))
    assert [e["kind"] for e in result.events] == [e["kind"] for e in events]
    for mine, theirs in zip(result.events, events):
        assert mine["t_s"] == float(theirs["t_s"])
        if not math.isnan(mine["restitution"]):
            assert mine["restitution"] == float(theirs["restitution"])


def test_force_bins_equal_the_cli(tmp_path):
    # The force on the surface in hub-angle bins: the same table as force_bins.csv, to the last
    # digit, summing to the pass's normal impulse; for an impacts-only pass too.
    for overrides in ({"output.interval_s": 1e-4}, {"hub.speed_rpm": 3000, "output.bin_deg": 0.25}):
        result = rotbeam.run(overrides=overrides)
        folder = tmp_path / str(len(overrides))
        sets = [a for k, v in overrides.items() for a in ("--set", f"{k}={v}")]
        code, _, err = cli("run", *sets, "-o", str(folder), "--quiet")
        assert code == 0, err
        with open(folder / "force_bins.csv", newline="") as f:
            rows = list(csv.DictReader(f))
        assert rows and len(rows) == len(result.force_bins["theta_from_deg"])
        for name, column in result.force_bins.items():
            assert np.array_equal(column, np.array([float(r[name]) for r in rows])), name
        total = result.force_bins["normal_impulse_n_s"].sum()
        assert math.isclose(total, result.summary["normal_impulse_n_s"], rel_tol=1e-12)
        assert result.force_bins["impacts"].sum() == result.summary["impacts"]
        binned = result.summary["binned_force"]
        assert binned["peak_normal_force_n"] == result.force_bins["mean_normal_force_n"].max() > 0


def test_revolutions_and_the_steady_state_equal_the_cli(tmp_path):
    overrides = {"beam.modes": 3, "beam.damping_ratio": 0.05, "simulation.until_steady": True,
                 "simulation.steady_method": "shooting", "simulation.revolutions": 60, "output.interval_s": 1e-4}
    result = rotbeam.run(overrides=overrides)
    code, out, err = cli("run", "--set", "beam.modes=3", "--set", "beam.damping_ratio=0.05", "--set",
                         "simulation.until_steady=true", "--set", 'simulation.steady_method="shooting"', "--set",
                         "simulation.revolutions=60", "--set", "output.interval_s=1e-4", "-o", str(tmp_path), "--json")
    assert code == 0, err
    assert without_wall_time(result.summary) == without_wall_time(json.loads(out))
    steady = result.summary["steady_state"]
    assert steady["reached"] and steady["method"] == "shooting" and steady["multipliers"]
    with open(tmp_path / "revolutions.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == len(result.revolutions["revolution"]) == result.summary["revolutions"]
    for name, column in result.revolutions.items():
        if name == "complete":
            assert list(column) == [r[name] == "true" for r in rows]
        else:
            assert np.array_equal(column, np.array([float(r[name]) for r in rows])), name
    # One pass: no revolutions.
    assert all(len(v) == 0 for v in rotbeam.run(overrides={"output.interval_s": 1e-3}).revolutions.values())


def test_impact_and_modes_equal_the_cli():
    overrides = {"initial.modal_velocity": [2, 0, 0, 0, 0], "hub.speed_rpm": 3000}
    mine = rotbeam.impact(overrides=overrides)
    code, out, err = cli("impact", "--set", "initial.modal_velocity=[2,0,0,0,0]", "--set", "hub.speed_rpm=3000", "--json")
    assert code == 0, err
    assert mine == json.loads(out)
    assert round(mine["vx_before_m_s"], 4) == 5.0358  # thesis Table 5-3
    m = rotbeam.modes(speeds_rpm=[0, 1500, 3000])
    code, out, err = cli("modes", "--speeds-rpm", "0:3000:3", "--json")
    assert code == 0, err
    theirs = json.loads(out)
    assert m["speeds_rpm"].tolist() == theirs["speeds_rpm"]
    assert m["frequencies_hz"].tolist() == theirs["frequencies_hz"]
    assert rotbeam.modes()["speeds_rpm"].tolist() == [0, 550, 1000, 2000, 3000]


def test_config_as_dict_path_or_overrides_agree(tmp_path):
    case = tmp_path / "case.toml"
    case.write_text('[hub]\nspeed_rpm = 3000\n[surface]\nfriction = 0.3\n[output]\ninterval_s = 1e-4\n')
    a = rotbeam.run(str(case))
    b = rotbeam.run({"hub": {"speed_rpm": 3000}, "surface": {"friction": 0.3}, "output": {"interval_s": 1e-4}})
    c = rotbeam.run(overrides=OVERRIDES)
    assert without_wall_time(a.summary) == without_wall_time(b.summary) == without_wall_time(c.summary)
    assert np.array_equal(a.history["normal_force_n"], c.history["normal_force_n"])


@pytest.mark.parametrize(
    "config, overrides, message",
    [
        (None, {"surface.depth_fraction": -0.1}, "surface.depth_fraction = -0.1"),
        (None, {"hub.sped_rpm": 3}, "hub.speed_rpm"),
        (None, {"beam.modes": 2.5}, "beam.modes"),
        (None, {"initial.modal_velocity": [1, 2]}, "initial.modal_velocity"),
        ({"hub": 3}, None, "hub = 3"),
        ("/nonexistent/case.toml", None, "/nonexistent/case.toml"),
        (None, {"impact.restitution": float("nan")}, "impact.restitution"),
    ],
)
def test_bad_input_raises_with_the_cli_message(config, overrides, message):
    with pytest.raises(rotbeam.ConfigError) as info:
        rotbeam.run(config, overrides)
    assert message in str(info.value)
    assert isinstance(info.value, ValueError)


def test_a_numerical_failure_is_reported_not_raised():
    r = rotbeam.run(overrides={"simulation.scheme": "thesis", "simulation.corrector_max_iterations": 1,
                               "impact.plastic_below_m_s": 10.0})
    assert r.failure is not None and r.failure["kind"] == "corrector"
    assert len(r.history["t_s"]) > 0


def test_concurrent_runs_equal_sequential_runs():
    speeds = [550, 1000, 2000, 3000]
    cases = [{"hub.speed_rpm": s, "output.interval_s": 1e-4} for s in speeds]
    sequential = [rotbeam.run(overrides=c) for c in cases]
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        concurrent_results = list(pool.map(lambda c: rotbeam.run(overrides=c), cases))
    for a, b in zip(sequential, concurrent_results):
        assert without_wall_time(a.summary) == without_wall_time(b.summary)
        for name in a.history:
            assert np.array_equal(a.history[name], b.history[name]), name


def test_override_keys_are_never_pasted_into_assignments():
    # A key holding '=' or spaces is an unknown key, not a way to set another one (it ran at 3000 rpm).
    with pytest.raises(rotbeam.ConfigError) as info:
        rotbeam.impact(overrides={"hub.speed_rpm=3000 #": 550})
    assert "unknown key" in str(info.value)


def test_a_missing_file_is_also_a_file_not_found_error():
    with pytest.raises(FileNotFoundError) as info:
        rotbeam.run("/nonexistent/case.toml")
    assert info.value.filename == "/nonexistent/case.toml"
    assert isinstance(info.value, rotbeam.ConfigError)


def test_empty_speeds_are_an_error_not_the_defaults():
    with pytest.raises(rotbeam.ConfigError) as info:
        rotbeam.modes(speeds_rpm=[])
    assert "speeds_rpm" in str(info.value)


@pytest.mark.parametrize("speeds", ["550", b"550", ["550"], [550, None], [True]])
def test_speeds_that_are_not_numbers_are_an_error(speeds):
    with pytest.raises(rotbeam.ConfigError) as info:
        rotbeam.modes(speeds_rpm=speeds)
    assert "speeds_rpm" in str(info.value)


def test_one_speed_or_a_numpy_array_is_taken():
    assert list(rotbeam.modes(speeds_rpm=550)["speeds_rpm"]) == [550.0]
    assert list(rotbeam.modes(speeds_rpm=np.array([0.0, 550.0]))["speeds_rpm"]) == [0.0, 550.0]


# Ctrl-C during a long call: SIGINT, sent once the call is under way, must raise KeyboardInterrupt.
# Each call would run on for a quarter of an hour or more were the stop not heeded (beyond ctest's
# timeout), so none needs a bound on the time it took (bench/reproduce_time.py reports how quickly
# a stop ends a pass).
def test_ctrl_c_stops_a_run_within_a_step():
    # A 270° pass at 5 rpm in steps of at most 50 ns: hours.
    with pytest.raises(KeyboardInterrupt), interrupt_once_a_thread_starts():
        rotbeam.run(overrides={"hub.speed_rpm": 5, "simulation.end_angle_deg": 270, "output.interval_s": 1e30,
                               "simulation.max_step_s": 5e-8})


def test_ctrl_c_stops_the_search_for_the_first_impact():
    # A flexible start at 0.1 rpm with 1 ns steps: hours of search for the first impact.
    with pytest.raises(KeyboardInterrupt), interrupt_once_a_thread_starts():
        rotbeam.impact(overrides={"initial.start": "flexible", "initial.modal_velocity": [0.1, 0, 0, 0, 0],
                                  "hub.speed_rpm": 0.1, "simulation.free_step_s": 1e-9})


def test_ctrl_c_stops_a_long_modal_analysis():
    # The elastica's 80 modes at 100 000 speeds: about a quarter of an hour on two cores, the longest
    # modal analysis the ranges allow. More speeds than the command line allows
    # (100 000) are refused.
    with pytest.raises(KeyboardInterrupt), interrupt_once_a_thread_starts():
        rotbeam.modes(overrides={"beam.theory": "elastica", "beam.modes": 80}, speeds_rpm=np.linspace(0, 5000, 100000))
    with pytest.raises(rotbeam.ConfigError, match="100001 speeds, more than 100000"):
        rotbeam.modes(speeds_rpm=np.zeros(100001))


def test_plot_names_a_damaged_file_in_one_line(tmp_path):
    out = tmp_path / "run"
    code, _, err = cli("run", "-o", str(out))
    assert code == 0, err
    with open(out / "history.csv", "r+") as f:
        f.truncate(1000)
    code, _, err = cli("plot", str(out))
    assert code == 2
    assert err.count("\n") == 1 and "history.csv" in err and "truncated" in err, err


@pytest.fixture(scope="module")
def base_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("base") / "run"
    code, _, err = cli("run", "-o", str(out), "--quiet")
    assert code == 0, err
    return out


def damaged_copy(base_run, tmp_path, name, damage):
    """A copy of the base run with one file changed in place by damage(bytes) -> bytes of the same size
    (the check of sizes against summary.json cannot see it)."""
    import shutil

    folder = tmp_path / "damaged"
    shutil.copytree(base_run, folder)
    for png in folder.glob("*.png"):
        png.unlink()
    data = (folder / name).read_bytes()
    changed = damage(data)
    assert len(changed) == len(data) and changed != data
    (folder / name).write_bytes(changed)
    return folder


def replace_in_line(line_number, old, new):
    def damage(data):
        lines = data.split(b"\n")
        assert old in lines[line_number - 1], lines[line_number - 1]
        lines[line_number - 1] = lines[line_number - 1].replace(old, new, 1)
        return b"\n".join(lines)
    return damage


def first_line_starting(data, start):
    return next(i + 1 for i, line in enumerate(data.split(b"\n")) if line.startswith(start))


def first_free_line(data):
    return next(i + 1 for i, line in enumerate(data.split(b"\n")) if b",free," in line and i > 2)


@pytest.mark.parametrize("name,damage,said", [
    # A NUL byte (numpy's "ufunc 'multiply' did not contain a loop" named the folder, after a picture).
    ("history.csv", lambda d: d[:4000] + b"\0" + d[4001:], "history.csv: line {line}: a NUL byte"),
    # A word in the phase column that is no phase (the row was silently dropped from every picture).
    ("history.csv", lambda d: replace_in_line(first_free_line(d), b",free,", b",fr#e,")(d),
     "history.csv: line {line}, column phase: 'fr#e' is not one of free, contact, stick"),
    # A letter in a number (it was drawn as NaN).
    ("history.csv", lambda d: replace_in_line(first_line_starting(d, b"0."), b"0.", b"x.")(d),
     "history.csv: line {line}, column t_s: 'x."),
    # summary.json's mode count changed (two pictures were written before "missing or odd entry 'q6_m'").
    ("summary.json", lambda d: d.replace(b'"modes": 5', b'"modes": 7', 1),
     "history.csv: no column q6_m (summary.json: config.beam.modes = 7; the files are not of one run)"),
    ("events.csv", lambda d: replace_in_line(2, b",impact,", b",imp#ct,")(d),
     "events.csv: line 2, column kind: 'imp#ct' is not one of impact"),
])
def test_plot_and_animate_name_same_size_damage_and_draw_nothing(base_run, tmp_path, name, damage, said):
    # Damage that keeps the file's size is found by reading every value strictly: one line naming the
    # file, the line and the value, exit 2, and nothing drawn — no picture in the run folder, and the
    # -o folder not even made.
    folder = damaged_copy(base_run, tmp_path, name, damage)
    data = (folder / name).read_bytes()
    line = data.count(b"\n", 0, data.index(b"\0")) + 1 if b"\0" in data else None
    if line is None and "{line}" in said:
        line = next(i + 1 for i, row in enumerate(data.split(b"\n")) if b"fr#e" in row or row.startswith(b"x."))
    expected = said.format(line=line)
    for args, output in ((("plot", str(folder), "-o", str(tmp_path / "pictures")), tmp_path / "pictures"),
                         (("animate", str(folder)), None)):
        code, _, err = cli(*args)
        assert code == 2, err
        assert err.count("\n") == 1 and expected in err, err
        assert "damaged or incomplete" not in err and "ufunc" not in err, err
        assert not list(folder.glob("*.png")) and not list(folder.glob("animation.*")), list(folder.iterdir())
        if output is not None:
            assert not output.exists()
    from rotbeam import plots

    with pytest.raises(plots.DamagedFolder, match="history.csv|events.csv"):
        plots.read_run(folder)


def test_plot_makes_its_output_folder_only_for_a_folder_it_accepts(base_run, tmp_path):
    import shutil

    folder = tmp_path / "bad"
    shutil.copytree(base_run, folder)
    (folder / "summary.json").write_text("{")
    code, _, err = cli("plot", str(folder), "-o", str(tmp_path / "P"))
    assert code == 2 and "summary.json: not valid JSON" in err, err
    assert not (tmp_path / "P").exists()
    code, _, err = cli("plot", str(base_run), "-o", str(tmp_path / "P"))
    assert code == 0, err
    assert len(list((tmp_path / "P").glob("*.png"))) == 5


def test_numbers_in_python_errors_are_shown_as_given():
    # -1 was shown as -1.000000; 2**80 as the quoted string "1208925819614629174706176" said to be no
    # integer. Beyond 64 bits an integer is still a number: the key's own range is named.
    with pytest.raises(rotbeam.ConfigError, match=r"^speeds_rpm: -1 must be in \[0, 1000000\] rpm$"):
        rotbeam.modes(speeds_rpm=[-1])
    with pytest.raises(rotbeam.ConfigError, match=r"^speeds_rpm: -1e-05 must be in"):
        rotbeam.modes(speeds_rpm=[-1e-5])
    with pytest.raises(rotbeam.ConfigError, match=r"^beam.modes = 1208925819614629174706176: must be in 1\.\.40 \(1\.\.80 with beam.theory = \"elastica\"\)$"):
        rotbeam.impact(overrides={"beam.modes": 2**80})
    with pytest.raises(rotbeam.ConfigError, match=r"^beam.modes = -1208925819614629174706176: must be in 1\.\.40 \(1\.\.80 with beam.theory = \"elastica\"\)$"):
        rotbeam.impact(overrides={"beam.modes": -2**80})
    with pytest.raises(rotbeam.ConfigError, match=r"^hub.speed_rpm = 10{30}: must be in \[0\.001, 1e\+06\]$"):
        rotbeam.impact(overrides={"hub.speed_rpm": 10**30})


@pytest.mark.parametrize("config, overrides, message", [
    (None, {"hub.speed\udcff": 600}, "hub.speed\\udcff: not valid text (a lone surrogate)"),
    ({"hub": {"speed\udcff": 600}}, None, "hub.speed\\udcff: not valid text (a lone surrogate)"),
    (None, {"initial.start": "ri\udcffgid"}, "initial.start = 'ri\\udcffgid': not valid text"),
    (None, {"initial.modal_velocity": np.ma.masked_array([0.1, 0, 0, 0, 0], [1, 0, 0, 0, 0])},
     "initial.modal_velocity: a masked array, element 0 masked; give a value for every element"),
    (None, {"hub.speed_rpm": np.ma.masked}, "hub.speed_rpm: a masked value; give a value"),
    ("c\udcffase.toml", None, "c\\udcffase.toml: no such configuration file"),
])
def test_text_that_is_not_utf8_and_masked_arrays_are_named(config, overrides, message):
    # A lone surrogate (os.fsdecode of a byte that is not UTF-8) gave pybind11's list of signatures;
    # a masked element was shown as "None: a NoneType is not a configuration value".
    with pytest.raises(rotbeam.ConfigError) as e:
        rotbeam.impact(config, overrides)
    assert message in str(e.value)
    assert "\n" not in str(e.value)
