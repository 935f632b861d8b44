"""rotbeam from Python: a flexible filament on a spinning hub whose tip strikes and rubs a surface.

    import rotbeam
    r = rotbeam.run()                                   # the thesis's base case, adaptive scheme
    r = rotbeam.run("case.toml", {"hub.speed_rpm": 3000})
    r = rotbeam.run({"hub": {"speed_rpm": 3000}, "surface": {"friction": 0.1}})
    r.summary["last_separation_deg"], r.history["normal_force_n"], r.events[0]["kind"]
    rotbeam.impact(overrides={"initial.modal_velocity": [2, 0, 0, 0, 0]})["vx_before_m_s"]
    rotbeam.modes(speeds_rpm=[0, 1000, 3000])["frequencies_hz"]

`config` is a TOML file's path, a dict shaped like the TOML file ({"section": {"key": value}}), or
None for the defaults; `overrides` maps dotted keys ("section.key") to values, applied after it,
exactly like the command line's --set. Keys, defaults and units: docs/configuration.md. Bad input
raises rotbeam.ConfigError (a ValueError) with the command line's one-line message. The C++ work
runs with the GIL released, so threads can run cases concurrently.
"""

import errno
import math
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

from ._core import ConfigError, config_keys
from . import _core

__all__ = ["run", "impact", "modes", "brush", "Result", "BrushResult", "ConfigError", "ConfigFileNotFoundError",
           "config_keys"]


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


def _table_arrays(text, ints=("revolution", "impacts", "contact_episodes"), bools=("complete",), words=()):
    """A CSV table's text (revolutions.csv, force_bins.csv, the brush's tables) as {column: numpy
    array}: the columns named in `ints` as integers, in `bools` as booleans (true/false), in `words`
    as strings, the others as floats ("nan" included); empty arrays for a table without rows."""
    import numpy as np
    lines = text.decode().splitlines()
    names = lines[0].split(",")
    rows = [line.split(",") for line in lines[1:]]
    out = {}
    for k, name in enumerate(names):
        values = [r[k] for r in rows]
        if name in ints:
            out[name] = np.array([int(v) for v in values], dtype=np.int64)
        elif name in bools:
            out[name] = np.array([v == "true" for v in values], dtype=bool)
        elif name in words:
            out[name] = np.array(values, dtype=str)
        else:
            out[name] = np.array([float(v) for v in values], dtype=float)
    return out


class Result:
    """A whole pass or a run over many revolutions: `summary` (the keys of summary.json), `history`
    (numpy arrays by the column names of history.csv), `events` (dicts with the columns of
    events.csv), `revolutions` (numpy arrays by the column names of revolutions.csv, one entry per
    revolution; empty for one pass) and `force_bins` (numpy arrays by the column names of
    force_bins.csv: the force on the surface in hub-angle bins, impacts included). History and
    events hold the last `output.history_revolutions` revolutions, as the files do; `revolutions`
    holds every one."""

    def __init__(self, summary, history, events, revolutions=None, force_bins=None):
        self.summary = summary
        self.history = history
        self.events = events
        self.revolutions = revolutions if revolutions is not None else {}
        self.force_bins = force_bins if force_bins is not None else {}

    @property
    def failure(self):
        """None, or {kind, t_s, theta_deg, message} when the pass stopped on a diagnosed failure."""
        return self.summary.get("failure")

    def __repr__(self):
        s = self.summary
        return (f"<rotbeam.Result {s['scheme']}: {s['impacts']} impacts, {s['contact_episodes']} contact episodes, "
                f"last separation {s['last_separation_deg']} deg, {len(self.history['t_s'])} history rows"
                f"{', failure: ' + s['failure']['kind'] if s.get('failure') else ''}>")


def run(config=None, overrides=None):
    """A whole pass (`rotbeam run`). Returns a Result; a diagnosed numerical failure is reported in
    Result.failure with everything computed up to it. Ctrl-C stops the pass within a step and
    raises KeyboardInterrupt."""
    path, sets = _arguments(config, overrides)
    summary, history, events, revolutions, force_bins = _core.run(path, sets)
    return Result(summary, history, events, _table_arrays(revolutions), _table_arrays(force_bins))


class BrushResult:
    """A brush at its steady state (`rotbeam brush`, docs/brush.md): `summary` (the keys of its
    summary.json), `workpiece` (numpy arrays by the columns of workpiece.csv: the force, torque and
    power on the workpiece in hub-angle bins over one revolution), `profile` (the same columns for the
    mean filament against its own angle across the contact zone, profile.csv) and `filaments` (numpy
    arrays by the columns of filaments.csv, one entry per filament). The tables are dicts of
    equal-length arrays: pandas.DataFrame(r.workpiece) makes a data frame of one."""

    def __init__(self, summary, workpiece, profile, filaments):
        self.summary = summary
        self.workpiece = workpiece
        self.profile = profile
        self.filaments = filaments

    @property
    def failure(self):
        """None, or {kind, filament, t_s, theta_deg, message} of the first filament that failed."""
        return self.summary.get("failure")

    def __repr__(self):
        s = self.summary
        return (f"<rotbeam.BrushResult {s['filaments']} filaments ({s['distinct_filaments']} distinct): mean force "
                f"{s['mean_normal_force_n']:.6g} N normal, {s['mean_tangential_force_n']:.6g} N tangential, "
                f"mean power {s['mean_hub_power_w']:.6g} W"
                f"{', failure: ' + s['failure']['kind'] if s.get('failure') else ''}>")


def brush(config=None, overrides=None, jobs=0):
    """A brush (`rotbeam brush`): every distinct filament run to its periodic steady state on `jobs`
    threads (0: all cores), and the sum on the workpiece. The configuration needs the [brush] keys,
    e.g. overrides={"brush.filaments": 24, "beam.damping_ratio": 0.05}. Returns a BrushResult; a
    filament's numerical failure is reported in BrushResult.failure (the sums hold the others).
    Ctrl-C stops the filaments under way and raises KeyboardInterrupt."""
    if isinstance(jobs, bool) or not isinstance(jobs, int):
        raise TypeError(f"jobs must be a whole number of threads (0: all cores), not {jobs!r}")
    path, sets = _arguments(config, overrides)
    summary, workpiece, profile, filaments = _core.brush(path, sets, jobs)
    bins = {"ints": ("impacts",), "bools": ()}
    return BrushResult(summary, _table_arrays(workpiece, **bins), _table_arrays(profile, **bins),
                       _table_arrays(filaments, ints=("filament", "row", "position", "distinct", "period_revolutions",
                                                      "revolutions_run"), bools=("reaches",), words=("status",)))


def impact(config=None, overrides=None):
    """The first impact (`rotbeam impact --json`) as a dict, or None if the tip never reaches the
    surface before the end angle."""
    path, sets = _arguments(config, overrides)
    return _core.impact(path, sets)


def _speeds(speeds_rpm):
    """The speeds as a list of floats: one number or an iterable of numbers (not a string)."""
    if isinstance(speeds_rpm, (str, bytes)):
        raise ConfigError(f"speeds_rpm = {speeds_rpm!r}: give numbers (e.g. [550, 3000]), not a string")
    if isinstance(speeds_rpm, (int, float)) or (hasattr(speeds_rpm, "ndim") and speeds_rpm.ndim == 0):
        return [float(speeds_rpm)]
    out = []
    for s in speeds_rpm:
        if isinstance(s, (str, bytes, bool)):
            raise ConfigError(f"speeds_rpm: {s!r} is not a speed in rpm")
        try:
            out.append(float(s))
        except (TypeError, ValueError):
            raise ConfigError(f"speeds_rpm: {s!r} is not a speed in rpm") from None
    return out


def modes(config=None, overrides=None, speeds_rpm=None):
    """Natural frequencies versus hub speed (`rotbeam modes --json`):
    {"speeds_rpm": array (S,), "frequencies_hz": array (S, n)}. Default speeds: 0, the Table 5-2
    speeds and the case's own."""
    path, sets = _arguments(config, overrides)
    speeds, freq = _core.modes(path, sets, None if speeds_rpm is None else _speeds(speeds_rpm))
    return {"speeds_rpm": speeds, "frequencies_hz": freq}
