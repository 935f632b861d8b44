"""rotbeam.sweep: a grid of cases run in memory on this machine's threads or on a Dask cluster, as an
xarray Dataset (issue 20). The grid, its validation and every case's run are the C++ library's
(the same as `rotbeam sweep`'s), so the Datasets equal those of the command line's sweep.nc.
"""

from __future__ import annotations

import collections
import math
import os
import statistics
import sys
import time
from typing import Any, Callable, Mapping, Sequence

from . import _core

# A Dask task's target duration: cases are bundled so that one task runs about this long, judged
# from the median time of the cases finished so far. Each task must run at least 0.1 s (the
# scheduler's overhead is a few milliseconds per task); the target leaves room for cases that cost
# up to five times the median.
TASK_SECONDS = 0.5
# The cases of the first task, whose times size the next ones.
PROBE_CASES = 4


def axes_of(vary: Mapping[str, Any], toml_value: Callable[[Any, str], str]) -> list[tuple[str, list[str]]]:
    """[(key, [TOML literals])] of `vary`: each value a list (tuple, range, numpy array) of Python
    values, or a string in `--vary` syntax ("550,1000" or "0.1:0.7:4"), or one number or boolean."""
    if not isinstance(vary, Mapping) or not vary:
        raise _core.ConfigError("vary: give a dict of keys and their values, e.g. {\"hub.speed_rpm\": [550, 3000]}")
    axes = []
    for key, values in vary.items():
        if not isinstance(key, str):
            raise TypeError(f"vary keys are dotted strings like 'hub.speed_rpm', not {key!r}")
        if isinstance(values, str):
            parsed_key, literals = _core.parse_sweep_axis(f"{key}={values}")
            axes.append((parsed_key, list(literals)))
            continue
        if isinstance(values, (bool, int, float)) or (hasattr(values, "ndim") and values.ndim == 0):
            values = [values]
        try:
            items = list(values)
        except TypeError:
            raise _core.ConfigError(f"vary {key}: {values!r} is not a list of values") from None
        axes.append((key, [toml_value(v, f"vary {key}") for v in items]))
    return axes


class _Progress:
    """Progress of a sweep: `progress(finished, total)` when a callable, a redrawn line on stderr
    when True (None: when stderr is a terminal), nothing when False."""

    def __init__(self, progress: bool | Callable[[int, int], Any] | None, total: int):
        self.total = total
        self.start = time.monotonic()
        self.callback = progress if callable(progress) else None
        self.line = progress is True or (progress is None and sys.stderr.isatty())
        self.shown = False

    def __call__(self, finished: int) -> None:
        if self.callback is not None:
            self.callback(finished, self.total)
        elif self.line:
            elapsed = time.monotonic() - self.start
            eta = elapsed / finished * (self.total - finished) if finished else float("nan")
            eta_text = f", ETA {eta:.0f} s" if finished else ""
            print(f"\rrotbeam.sweep: {finished}/{self.total} cases, {elapsed:.0f} s elapsed{eta_text}   ",
                  end="", file=sys.stderr, flush=True)
            self.shown = True

    def close(self) -> None:
        if self.shown:
            print("\r" + " " * 70 + "\r", end="", file=sys.stderr, flush=True)


def run_bundle(text: str | None, name: str, overrides: Sequence[tuple[str, str]], axes: Sequence[tuple[str, list[str]]],
               indices: Sequence[int]) -> tuple[str, list[tuple[str, list[float], str, float]], float]:
    """A Dask task: the cases `indices` of the grid, one after the other (the workers' threads run
    tasks side by side): (the worker's rotbeam version, the rows with each case's seconds, the
    seconds the task took)."""
    start = time.perf_counter()
    rows = _core.sweep_run(None, text, name, list(overrides), list(axes), list(indices), 1, None)
    return _core.__version__, rows, time.perf_counter() - start


def run_on_dask(client: Any, path: str | None, overrides: Sequence[tuple[str, str]], axes: Sequence[tuple[str, list[str]]],
                total: int, retries: int, progress: _Progress, task_seconds: float,
                log: list | None = None) -> dict[int, tuple]:
    """The rows of every case, run on the Dask cluster of `client`, in bundles of consecutive cases
    sized to run task_seconds each from the median time of the cases finished so far: the first
    task (PROBE_CASES cases) is waited for up to 2 task_seconds (cases that take longer are not
    bundled), then at most two tasks per worker thread are under way, each new one sized by what
    has been measured; the last bundle takes the rest when fewer than two bundles' cases are left,
    so that no task is a small remainder. Each task is retried `retries` times when it raises; a
    task on a worker that dies is rescheduled by the scheduler (up to its
    distributed.scheduler.allowed-failures). Rows are taken as each task finishes, so a worker lost
    later costs only its tasks under way. Ctrl-C cancels the tasks and raises KeyboardInterrupt.
    `log` gets (cases, seconds) of each task, in the order they finished."""
    from distributed import as_completed, wait
    text, name = None, ""
    if path is not None:  # the file's text travels: its path may not exist on the workers
        with open(path, encoding="utf-8") as f:
            text, name = f.read(), path
    rows: dict[int, tuple] = {}
    futures = []
    cases_of = {}  # a task's key: its cases
    times: list[float] = []  # every finished case's seconds
    queue = collections.deque(range(total))
    limit = 2 * max(1, sum(client.nthreads().values()))

    def submit(indices):
        f = client.submit(run_bundle, text, name, list(overrides), list(axes), indices, retries=retries, pure=False)
        cases_of[f.key] = indices
        futures.append(f)
        return f

    def take(future):
        version, got, seconds = future.result()
        if version != _core.__version__:
            raise RuntimeError(f"a Dask worker runs rotbeam {version}, this process {_core.__version__}: install the "
                               "same version everywhere (results of two versions are not one study)")
        for i, row in zip(cases_of[future.key], got):
            rows[i] = tuple(row[:3])
        times.extend(row[3] for row in got)
        if log is not None:
            log.append((cases_of[future.key], seconds))
        progress(len(rows))

    def next_bundle():
        size = 1 if not times else max(1, math.ceil(task_seconds / max(statistics.median(times), 1e-6)))
        n = len(queue) if len(queue) < 2 * size else size
        return [queue.popleft() for _ in range(n)]

    try:
        first = submit([queue.popleft() for _ in range(min(PROBE_CASES, total))])
        try:
            wait([first], timeout=2 * task_seconds)
        except TimeoutError:  # distributed's wait raises where concurrent.futures' returns
            pass
        if first.done():
            take(first)
            first.release()
            running = as_completed([])
        else:
            running = as_completed([first])
        while queue and running.count() < limit:
            running.add(submit(next_bundle()))
        for future in running:
            take(future)
            future.release()
            while queue and running.count() < limit:
                running.add(submit(next_bundle()))
    except BaseException:
        client.cancel(futures)
        raise
    return rows


def sweep(vary: Mapping[str, Any], config: Any, overrides: Mapping[str, Any] | None, *, jobs: int, client: Any,
          retries: int, progress: bool | Callable[[int, int], Any] | None, arguments: Callable, toml_value: Callable,
          task_seconds: float = TASK_SECONDS):
    """rotbeam.sweep's work (its docstring says what it does)."""
    from . import _xarray
    if isinstance(jobs, bool) or not isinstance(jobs, int):
        raise TypeError(f"jobs must be a whole number of threads (0: all cores), not {jobs!r}")
    if isinstance(retries, bool) or not isinstance(retries, int) or retries < 0:
        raise TypeError(f"retries must be a whole number >= 0, not {retries!r}")
    path, sets = arguments(config, overrides)
    axes = axes_of(vary, toml_value)
    values, description, metrics = _core.sweep_plan(path, sets, axes)
    total = len(values)
    shown = _Progress(progress, total)
    try:
        if client is None:
            got = _core.sweep_run(path, None, "", sets, axes, list(range(total)), jobs, shown)
            rows = {i: tuple(r[:3]) for i, r in enumerate(got)}
        else:
            rows = run_on_dask(client, path, sets, axes, total, retries, shown, task_seconds)
    finally:
        shown.close()
    return _xarray.sweep_dataset(description, metrics, rows)


def open_sweep(folder: str | os.PathLike) -> Any:
    """A sweep folder's Dataset from its sweep.json and sweep.csv (rotbeam.open_sweep's work)."""
    from . import _xarray
    folder = os.fspath(folder)
    description = _xarray.read_description(os.path.join(folder, "sweep.json"))
    metrics = _core.sweep_metrics(bool(description["brush"]))
    index = os.path.join(folder, "sweep.csv")
    with open(index, encoding="utf-8", newline="") as f:
        rows = _xarray.read_index(description, metrics, f.read(), index)
    return _xarray.sweep_dataset(description, metrics, rows)
