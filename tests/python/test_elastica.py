"""The elastica from Python and the shell (docs/model.md "The elastica"): `rotbeam.static` and
`rotbeam static --json` give the same equilibrium, which at rest matches the linear cantilever at a
small load and departs from the thesis model's at a large one; `rotbeam theories` runs a case under
both theories; a run's pictures draw the elastica's own shape. Run by ctest with
PYTHONPATH=<build>/python and ROTBEAM_CLI=<rotbeam binary>."""

import json
import math
import os
import subprocess

import numpy as np
import pytest

import rotbeam

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")
EI = 2.2e11 * math.pi * 5.08e-4 ** 4 / 64
L = 0.0635
AT_REST = {"model.centrifugal": False, "model.coriolis": False}


def cli(*args, code=0):
    done = subprocess.run([CLI, *args], capture_output=True, text=True)
    assert done.returncode == code, done.stderr
    return done


def test_static_from_python_equals_the_command_line():
    load = 2 * EI / L ** 2  # PL²/EI = 2
    got = rotbeam.static(load, overrides={"beam.theory": "elastica", "beam.modes": 12, **AT_REST})
    shell = json.loads(cli("static", "--set", "beam.theory=elastica", "--set", "beam.modes=12", "--set",
                           "model.centrifugal=false", "--set", "model.coriolis=false", "--tip-load-n", repr(load),
                           "--json").stdout)
    assert shell["tip_x_m"] == got["tip_x_m"] and shell["tip_y_m"] == got["tip_y_m"]
    assert np.array_equal(np.asarray(shell["q"]), got["q"])
    # Bisshopp–Drucker at PL²/EI = 2: tip at (0.83936, 0.49346) L from the clamp (1e-5 L with 12 modes).
    assert abs((got["tip_x_m"] - L) / L - 0.8393583) < 1e-5
    assert abs(got["tip_y_m"] / L - 0.4934575) < 1e-5
    fore = rotbeam.static(load, overrides={"beam.modes": 12, **AT_REST})
    assert fore["tip_y_m"] / L - 0.4934575 > 0.03, "the quadratic foreshortening overshoots at large load"


def test_a_small_load_deflects_both_theories_as_the_linear_cantilever():
    load = 1e-3 * EI / L ** 2
    for theory in ("foreshortening", "elastica"):
        got = rotbeam.static(load, overrides={"beam.theory": theory, "beam.modes": 20, **AT_REST})
        assert got["tip_y_m"] == pytest.approx(load * L ** 3 / (3 * EI), rel=2e-5), theory


def test_static_warns_where_the_thesis_model_leaves_its_geometry():
    # PL²/EI = 5: the thesis model's tip lies 1.06 L from its clamp (docs/model.md); the elastica's
    # answer carries no warning. At PL²/EI = 0.5 (|y_t|/L = 0.16) the thesis model is only past
    # the deflection warning ratio (0.1).
    load = 5 * EI / L ** 2
    fore = rotbeam.static(load, overrides={"beam.modes": 12, **AT_REST})
    assert len(fore["warnings"]) == 1 and "farther than a filament of length L can reach" in fore["warnings"][0]
    assert rotbeam.static(load, overrides={"beam.theory": "elastica", "beam.modes": 12, **AT_REST})["warnings"] == []
    mild = rotbeam.static(0.5 * EI / L ** 2, overrides=AT_REST)
    assert len(mild["warnings"]) == 1 and "deflection_warning_ratio" in mild["warnings"][0]
    shell = json.loads(cli("static", "--set", "model.centrifugal=false", "--tip-load-n", repr(load), "--json").stdout)
    assert shell["warnings"] == rotbeam.static(load, overrides={"model.centrifugal": False})["warnings"] != []


def test_static_follows_the_branch_to_huge_loads_and_says_when_the_modes_cannot_follow():
    # The elastica's tip turns toward the load as it grows (PL²/EI = 10 … 1e12), never past L; the
    # load is followed from the filament's own scale (a single jump to 1e12 N once landed on another
    # equilibrium). Beyond PL²/EI = n² the bend at the clamp is finer than the modes resolve: said.
    tips = []
    for k in (10, 100, 1e3, 1e6, 1e12):
        got = rotbeam.static(k * EI / L ** 2, overrides={"beam.theory": "elastica", "beam.modes": 20, **AT_REST})
        tips.append(got["tip_y_m"] / L)
        assert (len(got["warnings"]) == 1 and "give more modes" in got["warnings"][0]) == (k > 400), k
    assert all(0.8 < a <= b + 1e-6 and b <= 1.0 for a, b in zip(tips, tips[1:])), tips


def test_static_refuses_what_it_cannot_compute():
    with pytest.raises(rotbeam.ConfigError, match="tip_load_n"):
        rotbeam.static(float("nan"))
    with pytest.raises(rotbeam.ConfigError, match="tip_load_n"):
        rotbeam.static("1")
    done = cli("static", "--tip-load-n", "inf", code=2)
    assert "--tip-load-n" in done.stderr and done.stderr.count("\n") == 1
    done = cli("static", "--set", "beam.modes=60", "--tip-load-n", "0.1", code=2)
    assert "beam.modes" in done.stderr and "elastica" in done.stderr


def test_theories_runs_the_case_under_both_and_reports_the_difference():
    j = json.loads(cli("theories", "--set", "hub.speed_rpm=1000", "--set", "surface.depth_fraction=0.01",
                       "--json").stdout)
    for theory in ("foreshortening", "elastica"):
        assert j[theory]["failure"] is None
        assert j[theory]["impacts"] > 0
        assert 0 < j[theory]["max_tip_deflection_ratio"] < 0.5
    d = j["difference"]
    assert d["last_separation_deg"] == pytest.approx(j["elastica"]["last_separation_deg"]
                                                     - j["foreshortening"]["last_separation_deg"])
    text = cli("theories", "--set", "hub.speed_rpm=1000", "--set", "surface.depth_fraction=0.01").stdout
    assert "foreshortening" in text and "elastica" in text and "max|y_t|/L" in text
    # A run that stops on a failure: both rows printed, exit 1, in text and in JSON.
    for extra in ([], ["--json"]):
        done = cli("theories", "--set", "simulation.max_impacts=3", *extra, code=1)
        assert "foreshortening" in done.stdout and "elastica" in done.stdout
    # More modes than the thesis model takes: the refusal says theories runs it too.
    done = cli("theories", "--set", "beam.theory=elastica", "--set", "beam.modes=41", code=2)
    assert "beam.modes = 41" in done.stderr and 'runs the case under beam.theory = "foreshortening" too' in done.stderr


def test_an_elastica_run_draws_its_own_shape(tmp_path):
    r = rotbeam.run(overrides={"beam.theory": "elastica"})
    assert r.summary["config"]["beam"]["theory"] == "elastica"
    assert r.summary["impacts"] > 0
    q = np.array([[r.history[f"q{i}_m"][-1] for i in range(1, 6)]])
    xi = np.linspace(0, 1, 11)
    shape = rotbeam._core.filament_shape(None, [("beam.theory", '"elastica"')], q, xi)
    # An inextensible filament: each point within ξL of the clamp, the tip where the run says.
    reach = np.hypot(shape[0, :, 0] - 0.0635, shape[0, :, 1])
    assert np.all(reach <= xi * L * (1 + 1e-12))
    assert (reach[-1] / L) > 0.99
    # The tip of the shape is the run's (global frame → hub frame by the last row's angle).
    th = math.radians(r.history["theta_deg"][-1])
    x, y = r.history["x_tip_m"][-1], r.history["y_tip_m"][-1]
    assert shape[0, -1, 0] == pytest.approx(x * math.cos(th) + y * math.sin(th), abs=1e-12)
    assert shape[0, -1, 1] == pytest.approx(-x * math.sin(th) + y * math.cos(th), abs=1e-12)
