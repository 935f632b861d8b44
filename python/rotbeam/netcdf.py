"""sweep.nc, a sweep's netCDF4 file (issue 20): what `rotbeam sweep --format netcdf` and `rotbeam merge
--format netcdf` run.

    python3 -m rotbeam.netcdf DIR [--index CSV] [--then TEXT]   # DIR/sweep.nc from DIR/sweep.json and the index
    python3 -m rotbeam.netcdf --check [--then T]   # exit 0 when xarray and netCDF4 can write it, else one line and 2

The file holds rotbeam.open_sweep's Dataset (the swept keys as dimensions, every metric a variable
with its units, status and message; the configuration and the version in the attributes) and is
read back whole by xarray.open_dataset. It is made in memory, then written by Python under a
temporary name and renamed: a full disk or a folder that cannot be written is one line naming
DIR/sweep.nc and why (netCDF's own writer crashed on a full disk, and refused a folder whose name
is not UTF-8). `--then TEXT` ends that line with what the caller does next ("every case is done …").
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


def netcdf_image(ds) -> bytes:
    """The bytes of the netCDF4 file of the Dataset `ds`, made in memory (netCDF4's diskless mode):
    nothing of netCDF's or HDF5's touches the disk, whose errors they report badly or not at all."""
    import netCDF4
    from xarray.backends import NetCDF4DataStore

    nc = netCDF4.Dataset("sweep.nc", mode="w", format="NETCDF4", memory=1)  # the size grows as needed
    try:
        ds.dump_to_store(NetCDF4DataStore(nc))
    except BaseException:
        nc.close()
        raise
    return bytes(nc.close())


def write_dataset(ds, path: str | os.PathLike) -> str:
    """Writes the Dataset `ds` to `path` as netCDF4 under a temporary name beside it
    (`<name>.tmp.<pid>`), then renames it into place: no reader sees a partial file. The file is
    made in memory and written by Python, so a full disk or a folder that cannot be written raises
    an OSError naming `path` (not the temporary) with its cause, and any path the system takes (a
    name that is not UTF-8, as os.fsdecode gives it) is written. Returns the path."""
    path = os.fspath(path)
    image = netcdf_image(ds)
    tmp = f"{path}.tmp.{os.getpid()}"
    try:
        with open(tmp, "wb") as f:
            f.write(image)
        os.replace(tmp, path)
    except OSError as e:  # the temporary's name means nothing to the user: theirs, and why
        raise OSError(e.errno, e.strerror, path) from None
    finally:
        if os.path.lexists(tmp):
            try:
                os.remove(tmp)
            except OSError:
                pass
    return path


def _shown(path: str) -> str:
    """A path for a message as rotbeam shows it: a byte that is not UTF-8 (a surrogate here) as \\xNN."""
    return os.fsencode(path).decode("utf-8", "backslashreplace")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m rotbeam.netcdf", description="A sweep folder's sweep.nc")
    parser.add_argument("folder", nargs="?", help="a sweep folder (sweep.json, sweep.csv)")
    parser.add_argument("--index", help="the index to read (default FOLDER/sweep.csv)")
    parser.add_argument("--check", action="store_true", help="only check that sweep.nc can be written")
    parser.add_argument("--then", default="", help="what the caller does when sweep.nc is not written (ends the line)")
    args = parser.parse_args(argv)
    why = missing_writer()
    from rotbeam import _interrupt
    if why and _interrupt.interrupted:  # a Ctrl-C broke the import: the interruption, not a missing package
        return 130
    then = f"; {args.then}" if args.then else ""
    if why:
        # One line: with --check, the refusal of `--format netcdf` itself (the caller adds none).
        print(f"rotbeam: error: {'--format netcdf: ' if args.check else ''}{why}{then if args.check else ''}",
              file=sys.stderr)
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
        print(f"rotbeam: error: {e}{then}", file=sys.stderr)
        return 2
    except FileNotFoundError as e:
        print(f"rotbeam: error: {e.filename}: no such file{then}", file=sys.stderr)
        return 2
    target = os.path.join(folder, "sweep.nc")
    try:
        write_dataset(ds, target)
    except OSError as e:
        print(f"rotbeam: error: {_shown(target)}: cannot write ({e.strerror or e}){then}", file=sys.stderr)
        return 1
    except (RuntimeError, ValueError) as e:
        print(f"rotbeam: error: {_shown(target)}: cannot write ({' '.join(str(e).split())}){then}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    from rotbeam._interrupt import run_main

    run_main(main, "the netCDF writer")
