"""The one reader of the CSV files rotbeam writes (history.csv, events.csv, force_bins.csv,
revolutions.csv, sweep.csv, a brush's workpiece.csv, profile.csv and filaments.csv, the table of
`rotbeam modes --csv`), from a file or from the text the library returns.

    table = read_csv("out/run/history.csv", modes=5)     # {column: numpy array}, by the header's names

A file is read whole and checked before any value is used: a NUL byte, text that is not UTF-8 or
not CSV, a missing or doubled column, a row whose length is not the header's, a word that is not
one of its column's words and a number that is not one raise DamagedFolder (or the `error` the
caller names) with the file's path, the line, the column and the value. What each file holds is
the table FILES below (by file name), made from the library's table of the columns its writers
write: the columns each file must have, the columns of words, of free text, of whole numbers and
of true/false, and the numbers that may be missing; every other column holds a number on every row.
columns_of(name) says which columns a file must have.

numpy and the library only: `import rotbeam` reads the library's tables through this module
without matplotlib.
"""

import csv
import io
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import _core


class DamagedFolder(Exception):
    """A run folder whose files are not those its summary.json describes (or a file rotbeam wrote
    that is damaged: the message names it and what is wrong)."""


@dataclass(frozen=True)
class Columns:
    """What a CSV file holds. `required`: the columns it must have, in the order written (a name
    holding `{i}` stands for one column per mode, i = 1 … modes); `words`: {column: the words
    allowed}; `text`: free-text columns; `ints`: whole numbers; `bools`: true/false; `optional`:
    numbers that may be missing (NaN); `infer`: every column not named here holds numbers where
    each of its values is one (Python's float, empty: NaN) and text otherwise (a sweep's keys, a
    file rotbeam does not name); without it every such column holds a number on every row."""

    required: tuple = ()
    words: dict = field(default_factory=dict)
    text: tuple = ()
    ints: tuple = ()
    bools: tuple = ()
    optional: tuple = ()
    infer: bool = False


# What a run and a brush write, from the library's one table of their columns
# (include/rotbeam/output_columns.hpp, rotbeam._core.output_columns): numbers in their shortest
# round-trip form (std::to_chars: 0.1, -3.2e-05, 1e+20, inf, nan), words, text, whole numbers and
# true/false as each column says.
def _library_files():
    files = {}
    for f in _core.output_columns():
        cols = f["columns"]
        named = lambda kind: tuple(c["name"] for c in cols if c["kind"] == kind)  # noqa: E731
        files[f["name"]] = Columns(tuple(c["name"] for c in cols),
                                   words={c["name"]: tuple(c["words"]) for c in cols if c["kind"] == "word"},
                                   text=named("text"), ints=named("integer"), bools=named("boolean"),
                                   optional=named("optional_number"))
    return files


FILES = {
    **_library_files(),
    # case, folder, the varied keys (any values: inferred), status, the metrics (empty for a case
    # without results), message (docs/cli.md).
    "sweep.csv": Columns(("case", "folder", "status", "message"), text=("folder", "status", "message"), ints=("case",),
                         infer=True),
}


# The names the pictures use, from the same table.
PHASES = FILES["history.csv"].words["phase"]
EVENT_KINDS = FILES["events.csv"].words["kind"]
EVENT_COLUMNS = FILES["events.csv"].required
EVENT_OPTIONAL = FILES["events.csv"].optional
FORCE_BIN_COLUMNS = FILES["force_bins.csv"].required
BRUSH_BIN_COLUMNS = FILES["workpiece.csv"].required
FILAMENT_STATUS = FILES["filaments.csv"].words["status"]


def columns_of(name, modes=None):
    """The columns the file `name` must have (FILES), a per-mode name once for each mode 1 … modes
    (none without `modes`); () for a file FILES does not name."""
    return _expand(FILES[name].required, modes) if name in FILES else ()


def _expand(names, modes):
    out = []
    for c in names:
        out += [c.format(i=i) for i in range(1, (modes or 0) + 1)] if "{i}" in c else [c]
    return tuple(out)


_NUMBER = r"[-+]?(?:[0-9]+(?:\.[0-9]+)?(?:[eE][-+]?[0-9]+)?|inf|nan)"
_NUMBER_RE = re.compile(_NUMBER)
_COLUMN_RE = {False: re.compile(f"{_NUMBER}(?:\n{_NUMBER})*"), True: re.compile(f"(?:{_NUMBER})?(?:\n(?:{_NUMBER})?)*")}
_INT_RE = re.compile("[-+]?[0-9]+")
_INTS_RE = re.compile("[-+]?[0-9]+(?:\n[-+]?[0-9]+)*")
_BOOLS = ("true", "false")


def read_csv(path, spec=None, *, data=None, modes=None, only=None, error=DamagedFolder, why_required="",
             check_header=None):
    """A CSV table as {column: numpy array}, in the header's order: numbers as float arrays (a
    missing one NaN), words and text as str arrays, whole numbers as int64, true/false as bool.

    path: the file; with `data` (the table's text, str or bytes) only its name, for the messages.
    spec: a Columns; None: FILES' entry for the file's name (Columns(infer=True) for a file it
        does not name). modes: the per-mode columns are required for this many modes.
    only: read just these columns (the others are checked for their count of values only).
    error: the exception raised, with "<file>: what is wrong" (DamagedFolder by default).
    why_required: added to the message of a missing required column.
    check_header(header): called with the header's names before any value is read (to raise the
        caller's own error for a file of other columns)."""
    if data is None:
        data = Path(path).read_bytes()
    elif isinstance(data, str):
        data = data.encode()
    if spec is None:
        spec = FILES.get(Path(path).name, Columns(infer=True))
    if b"\0" in data:
        line = data.count(b"\n", 0, data.index(b"\0")) + 1
        raise error(f"{path}: line {line}: a NUL byte")
    try:
        content = data.decode("utf-8")
    except UnicodeDecodeError as e:
        line = data.count(b"\n", 0, e.start) + 1
        raise error(f"{path}: line {line}: not UTF-8 text") from None
    reader = csv.reader(io.StringIO(content, newline=""))
    try:
        header = next(reader, None)
        if not header:
            raise error(f"{path}: empty (no header line)")
        if check_header is not None:
            check_header(header)
        missing = [c for c in _expand(spec.required, modes) if c not in header]
        if missing:
            raise error(f"{path}: no column {missing[0]}{why_required}")
        doubled = [c for c in header if header.count(c) > 1]
        if doubled:
            raise error(f"{path}: the column {doubled[0]} twice")
        rows, lines = [], []
        for row in reader:
            if len(row) != len(header):
                raise error(f"{path}: line {reader.line_num}: {len(row)} values where the header has {len(header)}")
            rows.append(row)
            lines.append(reader.line_num)
    except csv.Error as e:
        raise error(f"{path}: line {reader.line_num}: not CSV ({e})") from None
    return {column: _values(spec, column, [r[i] for r in rows], lines, f"{path}", error)
            for i, column in enumerate(header) if only is None or column in only}


def _values(spec, column, values, lines, where, error):
    """One column's values as an array of the kind `spec` gives it, or `error` naming the first
    value that is not of that kind."""
    def bad(fits, what):
        line, v = next((line, v) for line, v in zip(lines, values) if not fits(v))
        raise error(f"{where}: line {line}, column {column}: {v!r} is not {what}")

    if column in spec.text:
        return np.array(values, dtype=str)
    if column in spec.words:
        words = spec.words[column]
        if not set(values) <= set(words):
            bad(lambda v: v in words, f"one of {', '.join(words)}")
        return np.array(values, dtype=str)
    if column in spec.bools:
        if not set(values) <= set(_BOOLS):
            bad(lambda v: v in _BOOLS, "true or false")
        return np.array([v == "true" for v in values], dtype=bool)
    if column in spec.ints:
        if values and not _INTS_RE.fullmatch("\n".join(values)):
            bad(_INT_RE.fullmatch, "a whole number")
        return np.array([int(v) for v in values], dtype=np.int64)
    if spec.infer and column not in spec.optional and column not in spec.required:
        try:
            return np.array([float(v) if v != "" else math.nan for v in values], dtype=float)
        except ValueError:
            return np.array(values, dtype=str)
    empty_ok = column in spec.optional
    if values and not _COLUMN_RE[empty_ok].fullmatch("\n".join(values)):
        bad(lambda v: _NUMBER_RE.fullmatch(v) or (empty_ok and v == ""), "a number")
    return np.array([float(v) if v else math.nan for v in values], dtype=float)


def read_study_summary(folder, kind, error):
    """The summary.json of a study's folder (`"kind": kind`, "brush" or "wear"), checked: it is that
    kind's, and every file it lists has the size it records. Raises `error` naming the file."""
    import json
    folder = Path(folder)
    try:
        summary = json.loads((folder / "summary.json").read_text())
    except json.JSONDecodeError as e:
        raise error(f"{folder / 'summary.json'}: not valid JSON ({e})") from None
    if not isinstance(summary, dict) or summary.get("kind") != kind or not isinstance(summary.get("files"), dict):
        raise error(f"{folder / 'summary.json'}: not a rotbeam {kind} summary")
    for name, entry in summary["files"].items():
        path = folder / name
        if not path.exists():
            raise error(f"{path}: missing (summary.json lists it)")
        if path.stat().st_size != entry.get("bytes"):
            raise error(f"{path}: {path.stat().st_size} bytes where summary.json records {entry.get('bytes')}: "
                        "the folder holds files of different runs, or a damaged one")
    return summary

