"""xarray Datasets of rotbeam's results (issue 20): a pass (Result.to_xarray) and a sweep (rotbeam.sweep,
rotbeam.open_sweep, sweep.nc). One builder makes a sweep's Dataset from the rows of its cases, whichever
way they were computed (threads, shards and `rotbeam merge`, Dask), so the Datasets are identical.

xarray (and pandas) are imported here, not by `import rotbeam`: the rest of the package works without them.
"""

from __future__ import annotations

import json
import math
import tomllib
from typing import Any, Mapping, Sequence

import numpy as np

from ._csv import Columns, read_csv

try:
    import xarray as xr
except ImportError as missing:  # one line naming what to install, not a traceback from deep inside
    raise ImportError("rotbeam's xarray results need xarray (Debian: apt-get install python3-xarray; "
                      f"sweep.nc also python3-netcdf4): {missing}", name="xarray") from None

# Units (UDUNITS text) of a name by its suffix, longest first: the files' column names and the
# configuration's keys end in their unit (normal_impulse_n_s, hub.speed_rpm).
_SUFFIX_UNITS = (("_kg_m3", "kg m-3"), ("_n_m", "N m"), ("_n_s", "N s"), ("_m_s", "m s-1"), ("_deg", "degree"),
                 ("_rpm", "rpm"), ("_hz", "Hz"), ("_pa", "Pa"), ("_j", "J"), ("_w", "W"), ("_n", "N"), ("_m", "m"),
                 ("_s", "s"))

# Configuration keys that are pure numbers (docs/configuration.md): their coordinate's units are "1".
_DIMENSIONLESS_KEYS = {"beam.modes", "beam.damping_ratio", "surface.depth_fraction", "surface.friction",
                       "impact.restitution", "impact.restitution_cap", "simulation.revolutions",
                       "simulation.steady_tolerance", "simulation.rtol", "simulation.max_impacts",
                       "simulation.deflection_warning_ratio", "simulation.corrector_max_iterations",
                       "output.history_revolutions", "brush.filaments", "brush.rows", "brush.length_scatter",
                       "brush.diameter_scatter", "brush.seed", "brush.population_tolerance",
                       "brush.population_max_runs"}

# What a resumed case's message carries in sweep.csv that the result does not depend on.
_RESUMED_NOTE = " (computed by an earlier run)"

# The statuses `rotbeam sweep` writes in sweep.csv (sweep_status_name); `missing` is the Dataset's own.
SWEEP_STATUSES = ("done", "resumed", "failed", "error", "interrupted")

# The message of a case a shard's Dataset does not hold.
_OTHER_SHARD = "another shard's case"


def units_of(name: str) -> str | None:
    """The units of a column or key by the suffix of its last part (normal_impulse_n_s: "N s"), or None."""
    last = name.rsplit(".", 1)[-1]
    for suffix, units in _SUFFIX_UNITS:
        if last.endswith(suffix):
            return units
    return None


def _column(name: str, values: Any, dim: str, prefix: str = "") -> tuple[str, xr.Variable]:
    """(variable name, Variable) of one table column: numbers with units ("1" when the name has
    none), strings as Python str objects (as netCDF gives them back), booleans as they are."""
    a = np.asarray(values)
    attrs = {}
    if a.dtype.kind in "fiu":
        attrs["units"] = units_of(name) or "1"
    elif a.dtype.kind in "US":
        a = a.astype(object)
    return prefix + name, xr.Variable((dim,), a, attrs)


def _result_attrs(title: str, summary: Mapping[str, Any], version: str) -> dict[str, str]:
    """A result's Dataset attributes: its title, the version, the resolved configuration, the summary
    and the failure as JSON text."""
    return {"title": title, "rotbeam_version": version,
            "configuration": json.dumps(summary.get("config", {}), sort_keys=True),
            "summary": json.dumps(summary, sort_keys=True), "failure": json.dumps(summary.get("failure"))}


def result_dataset(result: Any, version: str, every_row: bool = False) -> xr.Dataset:
    """A pass's Dataset: the history over `t` (seconds; every other column of history.csv a variable
    with its units), the events over `event` (variables `event_<column>`), the revolutions over
    `revolution` (runs over many revolutions) and the force bins over `bin` (`bin_<column>`);
    attributes: the summary and the resolved configuration as JSON, the version.

    An impact gives two rows at one time, the states before and after it: `t` keeps the one after
    (the state the pass goes on from), so that it is a unique, increasing index that `sel` (with
    `method="nearest"`) and `interp` can use; the impact itself is in the events (`event_vx_before_m_s`,
    …). every_row=True keeps every row of history.csv, over the dimension `row` with `t` a coordinate
    along it (not an index: the pairs share their t)."""
    h = result.history
    variables = {}
    t = np.asarray(h["t_s"], dtype=float)
    if every_row:
        dim, keep = "row", slice(None)
        long_name = "time from the start of the pass (an impact's states before and after it share one)"
    else:
        dim = "t"
        keep = np.append(t[1:] != t[:-1], True) if len(t) else slice(None)  # the last row of each time
        long_name = "time from the start of the pass (at an impact, the state after it)"
    coords = {"t": xr.Variable((dim,), t[keep], {"units": "s", "long_name": long_name})}
    for name, values in h.items():
        if name != "t_s":
            key, var = _column(name, np.asarray(values)[keep], dim)
            variables[key] = var
    events = result.events
    if events:
        for name in events[0]:
            key, var = _column(name, [e[name] for e in events], "event", "event_")
            variables[key] = var
    for name, values in result.revolutions.items():
        if name == "revolution":
            coords["revolution"] = xr.Variable(("revolution",), np.asarray(values), {"units": "1"})
        else:
            key, var = _column(name, values, "revolution", "revolution_")
            variables[key] = var
    for name, values in result.force_bins.items():
        key, var = _column(name, values, "bin", "bin_")
        variables[key] = var
    return xr.Dataset(variables, coords=coords, attrs=_result_attrs("rotbeam pass", result.summary, version))


def brush_dataset(result: Any, version: str) -> xr.Dataset:
    """A brush's Dataset: the workpiece over `theta` (the bins' centres in degrees; every column of
    workpiece.csv a variable `workpiece_<column>`), the mean filament's profile over `angle`
    (`profile_<column>`), the filaments over `filament` (`filament_<column>`, one entry each), the
    filaments run over `representative` (`representative_<column>`), the spectrum over `order`
    (`spectrum_<column>`) and the wear profile over `wear_bin` (`wear_<column>`); attributes: the
    summary and the resolved configuration as JSON, the version."""
    variables = {}
    coords = {}

    def centres(table):
        return 0.5 * (np.asarray(table["theta_from_deg"], float) + np.asarray(table["theta_to_deg"], float))

    for table, dim, prefix in ((result.workpiece, "theta", "workpiece_"), (result.profile, "angle", "profile_")):
        if table:
            coords[dim] = xr.Variable((dim,), centres(table), {"units": "degree", "long_name": "the bin's centre"})
            for name, values in table.items():
                key, var = _column(name, values, dim, prefix)
                variables[key] = var
    for table, dim, prefix, index in ((result.filaments, "filament", "filament_", "filament"),
                                      (result.representatives, "representative", "representative_", "representative"),
                                      (result.spectrum, "order", "spectrum_", "order"),
                                      (result.wear_profile, "wear_bin", "wear_", None)):
        if not table:
            continue
        for name, values in table.items():
            if name == index:
                coords[dim] = xr.Variable((dim,), np.asarray(values), {"units": "1"})
                continue
            key, var = _column(name, values, dim, prefix)
            variables[key] = var
    return xr.Dataset(variables, coords=coords, attrs=_result_attrs("rotbeam brush", result.summary, version))


def _literal_value(text: str) -> Any:
    """A TOML literal's value (a bare word, which --set takes as a string, is itself)."""
    try:
        return tomllib.loads("v = " + text)["v"]
    except tomllib.TOMLDecodeError:
        return text


def axis_coordinate(key: str, literals: Sequence[str]) -> xr.Variable:
    """A swept key's coordinate: integers, floats, booleans or strings when every value is one;
    otherwise (arrays, mixed kinds) the values' TOML text. Numbers carry their units."""
    values = [_literal_value(t) for t in literals]
    attrs = {"long_name": f"configuration key {key}"}
    if all(isinstance(v, bool) for v in values):
        data = np.array(values, dtype=bool)
    elif all(isinstance(v, int) and not isinstance(v, bool) for v in values):
        data = np.array(values, dtype=np.int64)
    elif all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        data = np.array([float(v) for v in values], dtype=float)
    elif all(isinstance(v, str) for v in values):
        data = np.array(values, dtype=object)
    else:
        data = np.array(list(literals), dtype=object)
    if data.dtype.kind in "fi":
        units = units_of(key) or ("1" if key in _DIMENSIONLESS_KEYS else None)
        if units:
            attrs["units"] = units
    return xr.Variable((key,), data, attrs)


def sweep_dataset(description: Mapping[str, Any], metrics: Sequence[tuple[str, str, str]],
                  rows: Mapping[int, tuple[str, Sequence[float], str]]) -> xr.Dataset:
    """A sweep's Dataset over its swept keys (one dimension per key, in the grid's order) from
    sweep.json's description, the metric table (column, units, description) and the rows of its
    cases by 0-based index: (status, metric values, message). Variables: every metric (float64 with
    its units; NaN where a case has no result: `failed`, `error`, `interrupted` or not in the
    rows), `status` (done, failed, error, interrupted; `missing` for a case the rows lack;
    a resumed case is `done`), `message` and `case` (the case number, 1-based, as case-NNNN).
    Attributes: the version, the configuration the cases share (JSON), the keys that vary, the kind."""
    axes = description["axes"]
    dims = [a["key"] for a in axes]
    shape = tuple(len(a["values"]) for a in axes)
    n = math.prod(shape)
    status = np.full(n, "missing", dtype=object)
    message = np.full(n, "", dtype=object)
    values = np.full((len(metrics), n), np.nan)
    for i, (st, vals, msg) in rows.items():
        st = "done" if st == "resumed" else st
        status[i] = st
        message[i] = msg[:-len(_RESUMED_NOTE)] if msg.endswith(_RESUMED_NOTE) else msg
        if st == "done":
            values[:, i] = vals
    shard = description.get("shard", {"index": 0, "count": 1})
    for i in range(n):
        if status[i] == "missing" and shard["count"] > 1:
            message[i] = _OTHER_SHARD
    variables = {"case": xr.Variable(dims, np.arange(1, n + 1, dtype=np.int64).reshape(shape),
                                     {"long_name": "case number (the folder case-NNNN)"}),
                 "status": xr.Variable(dims, status.reshape(shape),
                                       {"long_name": "done, failed (a diagnosed numerical failure), error, "
                                                     "interrupted or missing"}),
                 "message": xr.Variable(dims, message.reshape(shape), {"long_name": "why a case has no result"})}
    for k, (column, units, text) in enumerate(metrics):
        variables[column] = xr.Variable(dims, values[k].reshape(shape), {"units": units, "long_name": text})
    coords = {a["key"]: axis_coordinate(a["key"], a["values"]) for a in axes}
    attrs = {"title": "rotbeam sweep", "rotbeam_version": description["version"],
             "kind": "brush" if description["brush"] else "filament",
             "configuration": json.dumps(description["config"], sort_keys=True),
             "varying_keys": json.dumps(description["varying_keys"]),
             "cases": int(description["cases"])}
    if shard["count"] > 1:
        attrs["shard"] = f"{shard['index']}/{shard['count']}"
    return xr.Dataset(variables, coords=coords, attrs=attrs)


class DamagedSweep(ValueError):
    """A sweep folder whose sweep.json or sweep.csv is not what rotbeam wrote."""


def read_index(description: Mapping[str, Any], metrics: Sequence[tuple[str, str, str]], text: str,
               where: str) -> dict[int, tuple[str, list[float], str]]:
    """The rows of sweep.csv's text by 0-based case index: (status, metric values, message), after
    checking its columns against the description and the metric table, and each status against
    those rotbeam writes (DamagedSweep naming `where`, the line and the value)."""
    keys = [a["key"] for a in description["axes"]]
    names = [m[0] for m in metrics]
    expected = ["case", "folder", *keys, "status", *names, "message"]

    def check_header(header):
        if header != expected:
            raise DamagedSweep(f"{where}: its columns are not those of the sweep its sweep.json describes")

    spec = Columns(tuple(expected), text=("folder", *keys, "message"), words={"status": SWEEP_STATUSES}, ints=("case",),
                   optional=tuple(names))
    table = read_csv(where, spec, data=text, error=DamagedSweep, check_header=check_header)
    n = int(description["cases"])
    values = np.column_stack([table[m] for m in names]).tolist() if names else [[] for _ in table["case"]]
    rows = {}
    for line, (case, status, vals, message) in enumerate(zip(table["case"].tolist(), table["status"], values,
                                                             table["message"]), start=2):
        if not 1 <= case <= n:
            raise DamagedSweep(f"{where}: line {line}: case {case} is not in the grid of {n} cases")
        rows[case - 1] = (str(status), vals, str(message))
    return rows


def read_description(path: str) -> dict[str, Any]:
    """sweep.json, checked for what the Dataset reads (DamagedSweep otherwise)."""
    try:
        with open(path, encoding="utf-8") as f:
            d = json.load(f)
        if d["format"] != "rotbeam sweep":
            raise KeyError("format")
        for a in d["axes"]:
            str(a["key"]), list(a["values"])
        d["version"], d["config"], d["varying_keys"], d["brush"], int(d["cases"])
    except (ValueError, KeyError, TypeError) as e:
        raise DamagedSweep(f"{path}: not a sweep description rotbeam wrote ({e})") from None
    return d
