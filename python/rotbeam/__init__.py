"""rotbeam from Python: a flexible filament on a spinning hub whose tip strikes and rubs a surface.

    import rotbeam
    r = rotbeam.run()                                   # the thesis's base case, adaptive scheme
    r = rotbeam.run("case.toml", {"hub.speed_rpm": 3000})
    r = rotbeam.run({"hub": {"speed_rpm": 3000}, "surface": {"friction": 0.1}})
    r.summary["last_separation_deg"], r.history["normal_force_n"], r.events[0]["kind"]
    rotbeam.impact(overrides={"initial.modal_velocity": [2, 0, 0, 0, 0]})["vx_before_m_s"]
    rotbeam.modes(speeds_rpm=[0, 1000, 3000])["frequencies_hz"]
    r.to_xarray()                                       # the pass as an xarray Dataset over t, units in attributes
    ds = rotbeam.sweep({"hub.speed_rpm": [550, 3000], "surface.friction": "0.1:0.7:4"})   # a Dataset over the keys
    ds = rotbeam.sweep({...}, client=dask.distributed.Client(...))                      # the same, on a Dask cluster
    rotbeam.open_sweep("out/grid")                      # a `rotbeam sweep` folder's Dataset (sweep.csv)

`config` is a TOML file's path, a dict shaped like the TOML file ({"section": {"key": value}}), or
None for the defaults; `overrides` maps dotted keys ("section.key") to values, applied after it,
exactly like the command line's --set. Keys, defaults and units: docs/configuration.md. Bad input
raises rotbeam.ConfigError (a ValueError) with the command line's one-line message. The C++ work
runs with the GIL released, so threads can run cases concurrently. docs/python.md says more;
help(rotbeam.run), help(rotbeam.sweep) each function.
"""

from __future__ import annotations

import errno
import math
import numbers
import os
import sys

if sys.argv[:1] == ["-m"]:  # `python3 -m rotbeam.plots` (what `rotbeam plot` runs) while it imports
    from ._interrupt import stop_quietly_on_interrupt
    stop_quietly_on_interrupt()  # a Ctrl-C during the imports below ends quietly, as the module would

try:  # every result holds numpy arrays: without numpy, say so here in one line, not deep inside a run
    import numpy  # noqa: F401
except ImportError:
    if sys.argv[:1] == ["-m"]:
        from . import _interrupt
        if _interrupt.interrupted:  # a Ctrl-C broke numpy's import: the interruption, not a missing numpy
            sys.exit(130)
    _hint = (f"rotbeam needs numpy, which {sys.executable} lacks: apt-get install python3-numpy "
             "python3-matplotlib and use /usr/bin/python3 (Debian), or pip install numpy matplotlib")
    if sys.argv[:1] == ["-m"]:  # `python3 -m rotbeam.plots` (what `rotbeam plot` runs): the CLI's one line
        print(f"rotbeam: error: {_hint}", file=sys.stderr)
        sys.exit(1)
    raise ImportError(_hint, name=__name__) from None

from typing import TYPE_CHECKING, Any, Callable, Mapping, Optional, Sequence, Union

from ._core import ConfigError, config_keys, keys
from . import _core

if TYPE_CHECKING:  # only for the annotations: xarray is imported when a Dataset is made
    import xarray

__version__: str = _core.__version__
"""rotbeam's version (project(VERSION) in CMakeLists.txt, the one place it is set)."""

__all__ = ["run", "impact", "modes", "static", "brush", "wear", "continue_orbits", "ContinuationResult", "sweep", "open_sweep", "Result", "BrushResult",
           "WearResult", "ConfigError", "ConfigFileNotFoundError", "config_keys", "keys", "__version__"]

# What `config` may be: a TOML file's path, a dict shaped like the file, or None for the defaults.
ConfigLike = Union[str, "os.PathLike[str]", Mapping[str, Mapping[str, Any]], None]
# What `overrides` may be: {"section.key": value}, applied after `config` as --set is.
Overrides = Optional[Mapping[str, Any]]


_EMPTY_PATH = '""'  # how a message shows the empty path


class ConfigFileNotFoundError(ConfigError, FileNotFoundError):
    """A configuration file that does not exist: a ConfigError with the command line's message, and a
    FileNotFoundError (errno ENOENT, filename) for code that expects one."""

    def __init__(self, path):
        ConfigError.__init__(self, f"{_text_shown(path) or _EMPTY_PATH}: no such configuration file")
        self.errno = errno.ENOENT
        self.strerror = "no such configuration file"
        self.filename = path

    def __str__(self):
        return f"{_text_shown(self.filename) or _EMPTY_PATH}: no such configuration file"


# The most threads (jobs) and Dask retries: the library counts them in a C int.
_MOST = 2**31 - 1


def _number_shown(v):
    """A number for a message: as given, but a whole number of more than 40 digits (10**400) as
    1.00000e+400, since its digits would fill the line and a float cannot hold it."""
    if isinstance(v, numbers.Integral) and not isinstance(v, (bool, numpy.bool_)):
        digits = str(abs(int(v)))
        if len(digits) > 40:
            return f"{'-' if v < 0 else ''}{digits[0]}.{digits[1:6]}e+{len(digits) - 1}"
        return str(int(v))
    return repr(v.item() if isinstance(v, numpy.generic) else v)


def _is_number(v):
    """Whether v is a real number, Python's or numpy's (numpy.float32, numpy.int64, …), not a boolean."""
    return isinstance(v, numbers.Real) and not isinstance(v, (bool, numpy.bool_))


def _whole(value, name, what, note=""):
    """value as an int when it is a whole number (Python's or numpy's) in 0.._MOST: TypeError naming
    `name` when it is not a whole number of `what`, ConfigError (a ValueError) `name = value: must
    be in 0..2147483647` when it is one out of range (`note` follows both: " (0: all cores)")."""
    if isinstance(value, (bool, numpy.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be a whole number of {what}{note}, not {value!r}")
    if not 0 <= int(value) <= _MOST:
        raise ConfigError(f"{name} = {_number_shown(value)}: must be in 0..{_MOST}{note}")
    return int(value)


def _jobs(jobs):
    """jobs as an int: a whole number of threads, 0 for all cores (TypeError, ConfigError otherwise)."""
    return _whole(jobs, "jobs", "threads", " (0: all cores)")


def _text_shown(s):
    """s for a message: a lone surrogate as \\udcXX."""
    return s.encode("utf-8", "backslashreplace").decode()


def _text(s, where):
    """s when it can be given to the library (UTF-8): a lone surrogate, as os.fsdecode makes of a
    byte that is not UTF-8, is one line naming it, not pybind11's list of signatures."""
    try:
        s.encode("utf-8")
    except UnicodeEncodeError:
        raise ConfigError(f"{_text_shown(where)}: not valid text (a lone surrogate)") from None
    return s


def _toml_value(value, where):
    """A TOML literal for a Python value (exact for floats: repr round-trips)."""
    if value is numpy.ma.masked or (isinstance(value, numpy.ma.MaskedArray) and value.ndim == 0 and value.mask):
        raise ConfigError(f"{_text_shown(where)}: a masked value; give a value")
    if isinstance(value, numpy.ma.MaskedArray) and numpy.ma.is_masked(value):
        masked = [int(i) for i in numpy.flatnonzero(numpy.ma.getmaskarray(value))]
        raise ConfigError(f"{_text_shown(where)}: a masked array, element{'s' if len(masked) > 1 else ''} "
                          f"{', '.join(map(str, masked[:5]))}{' …' if len(masked) > 5 else ''} masked; "
                          "give a value for every element")
    if isinstance(value, bool):
        return "true" if value else "false"
    if hasattr(value, "item") and not isinstance(value, (list, tuple)) and getattr(value, "ndim", 0) == 0:
        value = value.item()  # numpy scalar
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        _text(value, f"{where} = {value!r}")
        escaped = "".join(c if c not in '\\"' and ord(c) >= 0x20 and ord(c) != 0x7F else
                          {"\\": "\\\\", '"': '\\"'}.get(c, f"\\u{ord(c):04X}") for c in value)
        return '"' + escaped + '"'
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v, where) for v in value) + "]"
    raise ConfigError(f"{where} = {value!r}: a {type(value).__name__} is not a configuration value")


def _dangling(path):
    """Whether the link at path names nothing (a loop of links is not that: the library names it)."""
    try:
        os.stat(path)
    except FileNotFoundError:
        return True
    except OSError:
        return False
    return False


def _arguments(config, overrides):
    """(path or None, [(dotted key, TOML value), …]): the keys are passed whole, never pasted into
    `key=value` text, so a key holding '=' or spaces is an unknown key, not another assignment."""
    path = None
    sets = []
    if config is None:
        pass
    elif isinstance(config, (str, os.PathLike)):
        path = os.fspath(config)
        if not os.path.lexists(path) or (os.path.islink(path) and _dangling(path)):
            raise ConfigFileNotFoundError(path)
    elif isinstance(config, dict):
        for section, table in config.items():
            if not isinstance(table, dict):
                raise ConfigError(f"{section} = {table!r}: expected a table of keys, e.g. {{'{section}': {{'key': value}}}}")
            for key, value in table.items():
                if isinstance(key, str):
                    _text(f"{section}.{key}", f"{section}.{key}")
                sets.append((f"{section}.{key}", _toml_value(value, f"{section}.{key}")))
    else:
        raise TypeError(f"config must be a path, a dict or None, not {type(config).__name__}")
    if overrides:
        if not isinstance(overrides, dict):
            raise TypeError(f"overrides must be a dict of dotted keys, not {type(overrides).__name__}")
        for key, value in overrides.items():
            if not isinstance(key, str):
                raise TypeError(f"override keys are dotted strings like 'hub.speed_rpm', not {key!r}")
            sets.append((_text(key, key), _toml_value(value, key)))
    return path, sets


def _table_arrays(text, name):
    """A table the library returned, the text of its file `name` (revolutions.csv, force_bins.csv, the
    brush's tables), as {column: numpy array} by rotbeam._csv.read_csv: whole numbers as integers,
    true/false as booleans, words as strings, the others as floats; empty arrays for a table
    without rows."""
    from ._csv import read_csv
    return read_csv(name, data=text)


class Result:
    """A whole pass or a run over many revolutions: `summary` (the keys of summary.json), `history`
    (numpy arrays by the column names of history.csv), `events` (dicts with the columns of
    events.csv), `revolutions` (numpy arrays by the column names of revolutions.csv, one entry per
    revolution; empty for one pass), `force_bins` (numpy arrays by the column names of
    force_bins.csv: the force on the surface in hub-angle bins, impacts included) and `wear_profile`
    (wear_profile.csv's columns: the contact's load–distance, worn volume, removed depth and heat
    along the surface, docs/wear.md; summary["wear"] has the totals). History and
    events hold the last `output.history_revolutions` revolutions, as the files do; `revolutions`
    holds every one."""

    summary: dict[str, Any]
    history: dict[str, "numpy.ndarray"]
    events: list[dict[str, Any]]
    revolutions: dict[str, "numpy.ndarray"]
    force_bins: dict[str, "numpy.ndarray"]
    wear_profile: dict[str, "numpy.ndarray"]

    def __init__(self, summary: dict[str, Any], history: dict[str, "numpy.ndarray"], events: list[dict[str, Any]],
                 revolutions: dict[str, "numpy.ndarray"] | None = None,
                 force_bins: dict[str, "numpy.ndarray"] | None = None,
                 wear_profile: dict[str, "numpy.ndarray"] | None = None):
        self.summary = summary
        self.history = history
        self.events = events
        self.revolutions = revolutions if revolutions is not None else {}
        self.force_bins = force_bins if force_bins is not None else {}
        self.wear_profile = wear_profile if wear_profile is not None else {}

    @property
    def failure(self) -> dict[str, Any] | None:
        """None, or {kind, t_s, theta_deg, message} when the pass stopped on a diagnosed failure."""
        return self.summary.get("failure")

    def to_xarray(self, every_row: bool = False) -> "xarray.Dataset":
        """The pass as an xarray Dataset (needs xarray): the history over the dimension `t` (the
        coordinate, in s), each other column of history.csv a variable with its `units` attribute
        ("N", "m s-1", "degree"; "1" for pure numbers); the events as a table over `event`
        (`event_t_s`, `event_kind`, …, the columns of events.csv); the revolutions over `revolution`
        (`revolution_<column>`, runs over many revolutions) and the force bins over `bin`
        (`bin_<column>`). Attributes: `summary` and `configuration` (the resolved configuration) as
        JSON text, `failure` (JSON: null or the failure), `rotbeam_version`. `ds.to_netcdf(path)`
        writes it (with netCDF4); `ds["normal_force_n"].to_pandas()` is a pandas Series over t.

        `t` is unique and increasing, so `ds.sel(t=0.0123, method="nearest")` and
        `ds.interp(t=times)` work: of an impact's two rows at one time (the states before and after
        it) the Dataset keeps the one after, the state the pass goes on from; the impact is in the
        events. every_row=True keeps every row of history.csv instead, over the dimension `row`
        with `t` a coordinate along it (not an index)."""
        from ._xarray import result_dataset
        return result_dataset(self, __version__, every_row)

    def __repr__(self):
        s = self.summary
        return (f"<rotbeam.Result {s['scheme']}: {s['impacts']} impacts, {s['contact_episodes']} contact episodes, "
                f"last separation {s['last_separation_deg']} deg, {len(self.history['t_s'])} history rows"
                f"{', failure: ' + s['failure']['kind'] if s.get('failure') else ''}>")


def run(config: ConfigLike = None, overrides: Overrides = None) -> Result:
    """A whole pass of the filament (`rotbeam run`): free flight, impacts, sustained contact with
    Coulomb friction, separations, from θ0 = −90° to simulation.end_angle_deg (or over
    simulation.revolutions revolutions).

    config: a TOML file's path, a dict shaped like the file ({"hub": {"speed_rpm": 3000}}), or None
        for the defaults (the thesis's base case: 550 rpm, 2 % depth, μ = 0.4, 5 modes).
    overrides: {"section.key": value} applied after config, as the command line's --set.

    Returns a Result: .summary (the keys of summary.json: impacts, contact_episodes,
    last_separation_deg, peak_normal_force_n, …), .history (numpy arrays by the columns of
    history.csv), .events (dicts, the rows of events.csv), .revolutions, .force_bins, .failure, and
    .to_xarray() (an xarray Dataset over t with units). A diagnosed numerical failure (Painlevé's
    paradox, a step-size underflow, …) is not an exception: Result.failure describes it and the
    history holds everything up to it. Bad input raises ConfigError with the command line's
    one-line message. Ctrl-C stops the pass within a step and raises KeyboardInterrupt. The work
    runs with the GIL released.

    >>> r = rotbeam.run(overrides={"hub.speed_rpm": 3000})
    >>> r.summary["impacts"], r.history["normal_force_n"].max()
    """
    path, sets = _arguments(config, overrides)
    summary, history, events, revolutions, force_bins, wear = _core.run(path, sets)
    return Result(summary, history, events, _table_arrays(revolutions, "revolutions.csv"),
                  _table_arrays(force_bins, "force_bins.csv"), _table_arrays(wear, "wear_profile.csv"))


class BrushResult:
    """A brush at its steady state (`rotbeam brush`, docs/brush.md): `summary` (the keys of its
    summary.json), `workpiece` (numpy arrays by the columns of workpiece.csv: the force, torque and
    power on the workpiece in hub-angle bins over one revolution), `profile` (the same columns for the
    mean filament against its own angle across the contact zone, profile.csv) and `filaments` (numpy
    arrays by the columns of filaments.csv, one entry per filament), `wear_profile` (wear_profile.csv:
    the wear all the filaments leave along the surface per revolution, docs/wear.md) and
    `representatives` (representatives.csv: the filaments run, the distinct ones or a population's
    representatives, with what each stands for) and `spectrum` (spectrum.csv: the workpiece's force
    and torque by harmonic of the revolution). The tables are dicts of equal-length arrays:
    pandas.DataFrame(r.workpiece) makes a data frame of one."""

    summary: dict[str, Any]
    workpiece: dict[str, "numpy.ndarray"]
    profile: dict[str, "numpy.ndarray"]
    filaments: dict[str, "numpy.ndarray"]
    wear_profile: dict[str, "numpy.ndarray"]
    representatives: dict[str, "numpy.ndarray"]
    spectrum: dict[str, "numpy.ndarray"]

    def __init__(self, summary: dict[str, Any], workpiece: dict[str, "numpy.ndarray"], profile: dict[str, "numpy.ndarray"],
                 filaments: dict[str, "numpy.ndarray"], wear_profile: dict[str, "numpy.ndarray"] | None = None,
                 representatives: dict[str, "numpy.ndarray"] | None = None,
                 spectrum: dict[str, "numpy.ndarray"] | None = None):
        self.summary = summary
        self.workpiece = workpiece
        self.profile = profile
        self.filaments = filaments
        self.wear_profile = wear_profile if wear_profile is not None else {}
        self.representatives = representatives if representatives is not None else {}
        self.spectrum = spectrum if spectrum is not None else {}

    @property
    def failure(self) -> dict[str, Any] | None:
        """None, or {kind, filament, t_s, theta_deg, message} of the first filament that failed."""
        return self.summary.get("failure")

    def to_xarray(self) -> "xarray.Dataset":
        """The brush as an xarray Dataset (needs xarray): the workpiece over `theta` (the bins'
        centres, degrees; `workpiece_normal_force_n`, …), the mean filament's profile over `angle`
        (`profile_<column>`), the filaments over `filament` (`filament_length_m`,
        `filament_mean_normal_force_n`, …), the filaments run over `representative`, the spectrum
        over `order` and the wear profile over `wear_bin`, each variable with its `units`.
        Attributes: `summary` and `configuration` as JSON text, `failure`, `rotbeam_version`.
        `ds.to_netcdf(path)` writes it (with netCDF4)."""
        from ._xarray import brush_dataset
        return brush_dataset(self, __version__)

    def __repr__(self):
        s = self.summary
        run = "representatives" if s.get("method") == "population" else "distinct"
        return (f"<rotbeam.BrushResult {s['filaments']} filaments ({s['distinct_filaments']} {run}): mean force "
                f"{s['mean_normal_force_n']:.6g} N normal, {s['mean_tangential_force_n']:.6g} N tangential, "
                f"mean power {s['mean_hub_power_w']:.6g} W"
                f"{', failure: ' + s['failure']['kind'] if s.get('failure') else ''}>")


def brush(config: ConfigLike = None, overrides: Overrides = None, jobs: int = 0) -> BrushResult:
    """A brush (`rotbeam brush`, docs/brush.md): every distinct filament run to its periodic steady
    state on `jobs` threads (0: all cores), or with overrides={"brush.method": "population"} a few
    representatives whose interpolation gives the sums, and the sum on the workpiece. The configuration needs the
    [brush] keys, e.g. overrides={"brush.filaments": 24, "beam.damping_ratio": 0.05}; config and
    overrides as for run(). Returns a BrushResult (.summary, .workpiece, .profile, .filaments as
    numpy arrays); a filament's numerical failure is reported in BrushResult.failure (the sums hold
    the others). Ctrl-C stops the filaments under way and raises KeyboardInterrupt."""
    jobs = _jobs(jobs)
    path, sets = _arguments(config, overrides)
    summary, workpiece, profile, filaments, wear, representatives, spectrum = _core.brush(path, sets, jobs)
    return BrushResult(summary, _table_arrays(workpiece, "workpiece.csv"), _table_arrays(profile, "profile.csv"),
                       _table_arrays(filaments, "filaments.csv"), _table_arrays(wear, "wear_profile.csv"),
                       _table_arrays(representatives, "representatives.csv"), _table_arrays(spectrum, "spectrum.csv"))


class WearResult:
    """Wear over hours of operation (`rotbeam wear`, docs/wear.md): `summary` (the keys of its
    summary.json: length_lost_m, volume_removed_m3, heat_j, max_removed_depth_m, …), `history`
    (numpy arrays by the columns of wear_history.csv: one row per slow-time step, its filament length,
    mean force, torque, power, removal rate, heat) and `depth` (wear_depth.csv: the surface's removed
    depth along it over the whole run)."""

    def __init__(self, summary, history, depth):
        self.summary = summary
        self.history = history
        self.depth = depth

    def __repr__(self):
        s = self.summary
        return (f"WearResult({s['completed_steps']} of {s['steps']} steps over {s['hours']:g} h, "
                f"length lost {s['length_lost_m'] * 1e6:.4g} µm, {s['volume_removed_m3'] * 1e9:.4g} mm³ removed)")


def wear(config: ConfigLike = None, overrides: Overrides = None, hours: float = 10.0, steps: int = 10) -> WearResult:
    """A filament's wear and frictional heat over `hours` of operation in `steps` slow-time steps
    (`rotbeam wear`, docs/wear.md): at each step its periodic steady state, its Archard wear and heat
    per revolution, and the filament shortened by its tip's wear over the step. config and overrides as
    for run() (the [wear] keys set the coefficients). Returns a WearResult; a numerical failure ends the
    run with the steps before it (summary["failure"]). Ctrl-C raises KeyboardInterrupt."""
    path, sets = _arguments(config, overrides)
    summary, history, depth = _core.wear(path, sets, float(hours), int(steps))
    return WearResult(summary, _table_arrays(history, "wear_history.csv"), _table_arrays(depth, "wear_depth.csv"))


class ContinuationResult:
    """Periodic orbits followed in one key (`rotbeam continue`, docs/continuation.md): `summary` (the
    keys of its summary.json: branches, special_points, engine_order_crossings, map_evaluations, …)
    and `branch` (numpy arrays by the columns of branch.csv: one row per orbit, its parameter,
    stability, multipliers mu{i}_re/mu{i}_im, section state z{i} and the metrics of one period)."""

    def __init__(self, summary, branch):
        self.summary = summary
        self.branch = branch

    @property
    def special_points(self):
        """The special points (folds, period doublings, Neimark–Sacker, grazing) as dicts."""
        return self.summary["special_points"]

    def __repr__(self):
        s = self.summary
        kinds = ", ".join(sorted({p["kind"] for p in s["special_points"]})) or "no special point"
        return (f"ContinuationResult({s['parameter']} {s['from']:g} → {s['to']:g}: {s['points']} orbits, "
                f"{s['stable_points']} stable, {len(s['branches'])} branches; {kinds})")


def continue_orbits(config: ConfigLike = None, overrides: Overrides = None, *, parameter: str, start: float,
                    stop: float, period: int = 0, tolerance: float = 0.0, step: float = 0.02, max_step: float = 0.1,
                    max_points: int = 400, doubling: bool = True, threads: int = 0) -> ContinuationResult:
    """The filament's periodic orbit followed in the configuration key `parameter` from `start` to
    `stop` (`rotbeam continue`, docs/continuation.md): pseudo-arclength continuation of the section
    map's fixed points, with their multipliers at every point; folds, branch points, period doublings
    (the doubled branch followed when `doubling`), Neimark–Sacker pairs and grazing located. period:
    revolutions per orbit (0: the steady state's at `start`); tolerance: a point's relative residual
    (0: simulation.steady_tolerance); step, max_step: along the branch in the range's fraction;
    threads: for the Jacobian's evaluations (0: all cores). config and overrides as for run().
    Ctrl-C raises KeyboardInterrupt."""
    if not isinstance(parameter, str):
        raise ConfigError(f"parameter = {parameter!r}: give a configuration key such as 'hub.speed_rpm'")
    for name, value in (("start", start), ("stop", stop), ("tolerance", tolerance), ("step", step),
                        ("max_step", max_step)):
        if not _is_number(value):
            raise ConfigError(f"{name} = {value!r}: give a number")
    path, sets = _arguments(config, overrides)
    summary, branch = _core.continue_orbits(path, sets, parameter, float(start), float(stop), int(period),
                                            float(tolerance), float(step), float(max_step), int(max_points),
                                            bool(doubling), int(threads))
    from ._csv import read_csv
    return ContinuationResult(summary, read_csv("branch.csv", data=branch, modes=2 * int(summary["modes"])))


def impact(config: ConfigLike = None, overrides: Overrides = None) -> dict[str, Any] | None:
    """The first impact of a pass (`rotbeam impact --json`, thesis Table 5-3) as a dict (t_s,
    theta_deg, vx_before_m_s, vx_after_m_s, impulse_n_s, …, config), or None if the tip never
    reaches the surface before the end angle. config and overrides as for run()."""
    path, sets = _arguments(config, overrides)
    return _core.impact(path, sets)


def static(tip_load_n: float, config: ConfigLike = None, overrides: Overrides = None) -> dict[str, Any]:
    """The static equilibrium of the filament in the hub frame under a dead load tip_load_n [N] at its
    tip, normal to the undeformed filament (`rotbeam static --json`), for the configuration's
    beam.theory, at rest or spinning: a dict with tip_x_m and tip_y_m (the tip in the hub frame, x
    from the hub centre along the undeformed filament), q (modal coordinates, m), residual_n,
    iterations, load_steps. config and overrides as for run()."""
    if not _is_number(tip_load_n):
        raise ConfigError(f"tip_load_n = {tip_load_n!r}: give a number of newtons")
    try:
        load = float(tip_load_n)
    except OverflowError:  # a whole number beyond the largest float (10**400)
        raise ConfigError(f"tip_load_n = {_number_shown(tip_load_n)}: must be a finite number of newtons") from None
    path, sets = _arguments(config, overrides)
    return _core.static(path, sets, load)


def _speeds(speeds_rpm: Any) -> list[float]:
    """The speeds as a list of floats: one number or an iterable of numbers (not a string)."""
    if isinstance(speeds_rpm, (str, bytes)):
        raise ConfigError(f"speeds_rpm = {speeds_rpm!r}: give numbers (e.g. [550, 3000]), not a string")
    if isinstance(speeds_rpm, (int, float)) or (hasattr(speeds_rpm, "ndim") and speeds_rpm.ndim == 0):
        speeds_rpm = [speeds_rpm]
    out = []
    for s in speeds_rpm:
        if isinstance(s, (str, bytes, bool)):
            raise ConfigError(f"speeds_rpm: {s!r} is not a speed in rpm")
        try:
            out.append(float(s))
        except OverflowError:  # a whole number beyond the largest float (10**400): the library's range message
            raise ConfigError(f"speeds_rpm: {_number_shown(s)} must be in [0, 1000000] rpm") from None
        except (TypeError, ValueError):
            raise ConfigError(f"speeds_rpm: {s!r} is not a speed in rpm") from None
    return out


def modes(config: ConfigLike = None, overrides: Overrides = None,
          speeds_rpm: float | Sequence[float] | None = None) -> dict[str, "numpy.ndarray"]:
    """Natural frequencies of the spinning filament versus hub speed, linearised about the straight
    beam (`rotbeam modes --json`): {"speeds_rpm": array (S,), "frequencies_hz": array (S, n)}.
    speeds_rpm: one speed or a list (None: 0, the Table 5-2 speeds and the case's own)."""
    path, sets = _arguments(config, overrides)
    speeds, freq = _core.modes(path, sets, None if speeds_rpm is None else _speeds(speeds_rpm))
    return {"speeds_rpm": speeds, "frequencies_hz": freq}


def sweep(vary: Mapping[str, Any], config: ConfigLike = None, overrides: Overrides = None, *, jobs: int = 0,
          client: Any = None, retries: int = 2,
          progress: bool | Callable[[int, int], Any] | None = None) -> "xarray.Dataset":
    """A Cartesian grid of cases (`rotbeam sweep`), run in memory, as an xarray Dataset over the
    swept keys (needs xarray).

    vary: {"section.key": values}, one dimension per key in this order (the last varies fastest,
        as `rotbeam sweep`'s cases): values a list of Python values ([550, 1000]), or a string in
        --vary syntax ("550,1000", "0.1:0.7:4": 4 values from 0.1 to 0.7).
    config, overrides: the base case, as for run(); every case is validated before any runs
        (ConfigError naming the case and its values).
    jobs: threads on this machine (0: all cores), when client is None.
    client: a dask.distributed.Client: the cases run on its cluster, bundled so that a task runs
        about 0.5 s (at least 0.1 s; sized from a first task of 8 cases), each task retried
        `retries` times when it raises; a worker that dies has its tasks rescheduled, and finished
        cases are kept.
    progress: a callable progress(finished, total), True for a line on stderr, False for nothing;
        None (default): the line when stderr is a terminal.

    Returns a Dataset with a variable per metric of sweep.csv (impacts, contact_episodes,
    last_separation_deg, peak_normal_force_n, normal_impulse_n_s, …; float64 with a `units`
    attribute, NaN where a case has no result), `status` (done; failed: a diagnosed numerical
    failure; error; interrupted), `message` and `case` (the case number, as the CLI's folders);
    attributes: rotbeam_version, configuration (the resolved configuration the cases share, JSON),
    varying_keys, kind. Threads, Dask, and `rotbeam sweep --shard` plus `rotbeam merge`
    (rotbeam.open_sweep, sweep.nc) give identical Datasets but for wall_time_s (the machine's).
    ds.to_dataframe() is the pandas view (a row per case, indexed by the swept keys);
    ds.to_netcdf("sweep.nc") writes it. Ctrl-C stops the cases under way and raises
    KeyboardInterrupt (on Dask: the tasks are cancelled).

    >>> ds = rotbeam.sweep({"hub.speed_rpm": [550, 1000, 2000, 3000], "surface.friction": [0.1, 0.4]},
    ...                    overrides={"beam.modes": 3})
    >>> ds["impacts"].sel({"hub.speed_rpm": 3000})
    """
    from . import _sweep
    jobs = _jobs(jobs)  # checked with a client too, where the cluster's threads run the cases
    retries = _whole(retries, "retries", "retries of a Dask task")
    if client is not None and not all(callable(getattr(client, m, None)) for m in ("submit", "nthreads", "cancel")):
        raise TypeError(f"client must be a dask.distributed.Client (e.g. Client({client!r}) for an address), "
                        f"not {client!r}" if isinstance(client, str) else
                        f"client must be a dask.distributed.Client, not {client!r}")
    if not (progress is None or isinstance(progress, (bool, numpy.bool_)) or callable(progress)):
        raise TypeError(f"progress must be a callable progress(finished, total), True, False or None, not {progress!r}")
    if isinstance(progress, numpy.bool_):
        progress = bool(progress)
    return _sweep.sweep(vary, config, overrides, jobs=jobs, client=client, retries=retries, progress=progress,
                        arguments=_arguments, toml_value=_toml_value)


def open_sweep(folder: Union[str, "os.PathLike[str]"]) -> "xarray.Dataset":
    """The Dataset of a `rotbeam sweep` (or `rotbeam merge`) folder, from its sweep.json and
    sweep.csv: the same Dataset as sweep() of that grid and as the folder's sweep.nc (a shard's
    folder: the other shards' cases `missing`). Raises FileNotFoundError for a folder without
    them, ValueError for damaged ones."""
    from . import _sweep
    return _sweep.open_sweep(folder)
