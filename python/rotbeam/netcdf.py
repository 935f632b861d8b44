"""sweep.nc, a sweep's netCDF4 file (issue 20): what `rotbeam sweep --format netcdf` and `rotbeam merge
--format netcdf` run.

    python3 -m rotbeam.netcdf DIR [--index CSV]   # DIR/sweep.nc from DIR/sweep.json and the index (default DIR/sweep.csv)
    python3 -m rotbeam.netcdf --check              # exit 0 when xarray and netCDF4 can write it, else one line and 2

The file holds rotbeam.open_sweep's Dataset (the swept keys as dimensions, every metric a variable
with its units, status and message; the configuration and the version in the attributes) and is
read back whole by xarray.open_dataset. It is written under a temporary name and renamed.
"""

from __future__ import annotations

import argparse
import os
import sys

if __name__ == "__main__":
    from rotbeam._interrupt import announce_start, stop_quietly_on_interrupt

    stop_quietly_on_interrupt()
    announce_start()

_NEEDS = ("writing sweep.nc needs xarray and netCDF4 for {python} (Debian: apt-get install python3-xarray "
          "python3-netcdf4): {missing}")


def missing_writer() -> str | None:
    """Why this Python cannot write netCDF4 files through xarray, or None when it can."""
    try:
        import netCDF4  # noqa: F401
        import xarray  # noqa: F401
    except ImportError as e:
        return _NEEDS.format(python=sys.executable, missing=e)
    return None


def write_dataset(ds, path: str | os.PathLike) -> str:
    """Writes the Dataset `ds` to `path` as netCDF4 (engine netcdf4) under a temporary name beside it
    (`<name>.tmp.<pid>`), then renames it into place: no reader sees a partial file. Returns the path."""
    path = os.fspath(path)
    tmp = f"{path}.tmp.{os.getpid()}"
    try:
        ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4")
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return path


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m rotbeam.netcdf", description="A sweep folder's sweep.nc")
    parser.add_argument("folder", nargs="?", help="a sweep folder (sweep.json, sweep.csv)")
    parser.add_argument("--index", help="the index to read (default FOLDER/sweep.csv)")
    parser.add_argument("--check", action="store_true", help="only check that sweep.nc can be written")
    args = parser.parse_args(argv)
    why = missing_writer()
    if why:
        print(f"rotbeam: error: {why}", file=sys.stderr)
        return 2
    if args.check:
        return 0
    if not args.folder:
        print("rotbeam: error: give a sweep folder", file=sys.stderr)
        return 2
    from rotbeam import _core, _xarray
    folder = args.folder
    index = args.index or os.path.join(folder, "sweep.csv")
    try:
        description = _xarray.read_description(os.path.join(folder, "sweep.json"))
        metrics = _core.sweep_metrics(bool(description["brush"]))
        with open(index, encoding="utf-8", newline="") as f:
            rows = _xarray.read_index(description, metrics, f.read(), index)
        ds = _xarray.sweep_dataset(description, metrics, rows)
    except _xarray.DamagedSweep as e:
        print(f"rotbeam: error: {e}", file=sys.stderr)
        return 2
    except FileNotFoundError as e:
        print(f"rotbeam: error: {e.filename}: no such file", file=sys.stderr)
        return 2
    try:
        write_dataset(ds, os.path.join(folder, "sweep.nc"))
    except (OSError, RuntimeError, ValueError) as e:
        print(f"rotbeam: error: {os.path.join(folder, 'sweep.nc')}: cannot write ({e})", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    from rotbeam._interrupt import run_main

    run_main(main, "the netCDF writer")
