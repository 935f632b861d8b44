"""Reliability III: Ctrl-C while `sweep`/`merge --format netcdf` check their writer, sweep.nc into a
folder whose name is not UTF-8, a pass's Dataset that xarray can select on, full disks and
read-only folders under `merge`, `animate` and the netCDF writer, and the edges of the Python
API's arguments (numpy numbers, huge numbers, jobs, client, progress, open_sweep's statuses).
Run by ctest with PYTHONPATH=<build>/python and ROTBEAM_CLI=<rotbeam>."""

import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import rotbeam
from process_support import catches, wait_until

xr = pytest.importorskip("xarray")
pytest.importorskip("netCDF4")

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")
# Cheap passes (3 modes, coarse sampling, ended at 0°): a few kilobytes of files per case.
QUICK_ARGS = ["--set", "beam.modes=3", "--set", "output.interval_s=1e-3", "--set", "simulation.end_angle_deg=0"]
QUICK = {"beam.modes": 3, "output.interval_s": 1e-3, "simulation.end_angle_deg": 0}


def cli(*args, **kwargs):
    return subprocess.run([CLI, *args], capture_output=True, text=True, **kwargs)


def one_line(done):
    """The one line of standard error (asserted to be one), without `rotbeam: error: `."""
    lines = done.stderr.splitlines()
    assert len(lines) == 1, done.stderr
    assert lines[0].startswith("rotbeam: error: "), done.stderr
    return lines[0][len("rotbeam: error: "):]


# --- 5: Ctrl-C while sweep/merge --format netcdf check their writer -------------------------------

def children(pid):
    try:
        with open(f"/proc/{pid}/task/{pid}/children") as f:
            return [int(c) for c in f.read().split()]
    except OSError:
        return []


def interrupt_the_check(args, tmp_path, env=None, ready=None):
    """Starts `rotbeam ARGS`, waits until its netCDF writer's check runs (a child process for which
    ready(child) holds), sends SIGINT to rotbeam alone (as `kill` does; a terminal's Ctrl-C reaches
    rotbeam alone too, the module runs in a process group of its own): (exit code, stderr)."""
    err = tmp_path / "stderr"
    with open(err, "w") as e:
        proc = subprocess.Popen([CLI, *args], stdout=subprocess.DEVNULL, stderr=e, env=env)
    child = []

    def under_way():
        if proc.poll() is not None:
            return True  # no use waiting on
        kids = children(proc.pid)
        if kids and ready(kids[0]):
            child.append(kids[0])
            return True
        return False

    wait_until(under_way)
    proc.send_signal(signal.SIGINT if child else signal.SIGKILL)
    code = proc.wait(timeout=600)
    assert child, "the check of the netCDF writer did not get under way"
    return code, err.read_text()


def runs_the_module(pid):
    """Whether process pid runs Python's rotbeam.netcdf (not still rotbeam, between fork and exec)
    and has its handler for SIGTERM installed."""
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            argv = f.read().split(b"\0")
    except OSError:
        return False
    return b"rotbeam.netcdf" in argv and catches(pid, signal.SIGTERM)


def sleeping_python(tmp_path):
    """A stand-in for the interpreter (ROTBEAM_PYTHON) that writes its process id and sleeps: the
    check is under way, for certain, when the signal comes."""
    script = tmp_path / "python"
    script.write_text(f"#!/bin/sh\necho $$ > {tmp_path / 'pid'}\nexec sleep 600\n")
    script.chmod(0o755)
    return str(script)


def shards(tmp_path):
    """Two shard folders of a two-case grid, for merge."""
    folders = []
    for i in range(2):
        folder = tmp_path / f"s{i}"
        done = cli("sweep", "--vary", "surface.friction=0.1,0.2", *QUICK_ARGS, "--shard", f"{i}/2", "-o", str(folder),
                   "--quiet")
        assert done.returncode == 0, done.stderr
        folders.append(str(folder))
    return folders


@pytest.mark.parametrize("command", ["sweep", "merge"])
def test_ctrl_c_while_the_netcdf_writer_is_checked_is_130_and_one_line(tmp_path, command):
    # It exited 2, as if the input were bad, with two lines ("interrupted while the netCDF writer
    # ran" and "--format netcdf: interrupted while checking the netCDF writer"). Now 130 and one
    # line, nothing written: the stand-in interpreter sleeps, so the signal comes during the check.
    out = tmp_path / "out"
    args = (["sweep", "--vary", "surface.friction=0.1,0.2", *QUICK_ARGS] if command == "sweep"
            else ["merge", *shards(tmp_path)]) + ["--format", "netcdf", "-o", str(out)]
    env = {**os.environ, "ROTBEAM_PYTHON": sleeping_python(tmp_path)}
    code, err = interrupt_the_check(args, tmp_path, env, ready=lambda child: (tmp_path / "pid").exists())
    assert code == 130, err
    assert err.count("\n") == 1, err
    assert err == {"sweep": "rotbeam: error: sweep interrupted before any case ran: nothing written\n",
                   "merge": "rotbeam: error: merge interrupted before anything was written\n"}[command], err
    assert not out.exists()


def test_ctrl_c_while_python_imports_the_netcdf_writer_is_130_and_one_line(tmp_path):
    # The same with the real interpreter, signalled once the module's handler is installed (it
    # catches SIGTERM, which rotbeam passes on) while it imports xarray and netCDF4 (≥ 0.3 s): an
    # import the interruption broke is not reported as a missing xarray.
    out = tmp_path / "out"
    code, err = interrupt_the_check(["sweep", "--vary", "surface.friction=0.1", *QUICK_ARGS, "--format", "netcdf",
                                     "-o", str(out)], tmp_path, ready=runs_the_module)
    assert code == 130, err
    assert err == "rotbeam: error: sweep interrupted before any case ran: nothing written\n", err
    assert not out.exists()


# --- 10: sweep.nc into a folder whose name is not UTF-8 -------------------------------------------

def test_netcdf_is_written_into_a_folder_whose_name_is_not_utf8(tmp_path):
    # A name with the byte 0xff (valid on Linux, not UTF-8): every case ran, then netCDF refused the
    # name ("surrogates not allowed"). sweep and merge now write sweep.nc there, the same Dataset
    # as open_sweep reads from the folder.
    base = os.fsencode(tmp_path)
    for command, args in (("sweep", ["sweep", "--vary", "surface.friction=0.1,0.2", *QUICK_ARGS]),
                          ("merge", ["merge", *shards(tmp_path)])):
        out = base + b"/" + command.encode() + b"-\xff"
        done = subprocess.run([os.fsencode(CLI), *(os.fsencode(a) for a in args), b"--format", b"netcdf", b"-o", out,
                               b"--quiet"], capture_output=True)
        assert done.returncode == 0, done.stderr.decode(errors="replace")
        assert done.stderr == b""
        assert b"-\\xff/sweep.nc" in done.stdout, done.stdout  # named as rotbeam names such a path
        readable = tmp_path / f"{command}-copy.nc"  # netCDF opens UTF-8 names only
        shutil.copyfile(out + b"/sweep.nc", readable)
        nc = xr.open_dataset(readable).load()
        xr.testing.assert_identical(nc, rotbeam.open_sweep(os.fsdecode(out)))
        assert list(nc["status"].values) == ["done", "done"]


# --- 11: a pass's Dataset that xarray selects on ----------------------------------------------------

def test_a_pass_dataset_has_a_unique_t_to_select_and_interpolate_on():
    # An impact writes two rows at one t (the states before and after it): `t` had duplicates, and
    # ds.sel(t=…, method="nearest") and ds.interp(t=…) raised. `t` keeps the state after each
    # impact, unique and increasing; every_row=True keeps every row over `row`.
    r = rotbeam.run(overrides={"hub.speed_rpm": 3000, **QUICK})
    t = r.history["t_s"]
    shared = np.flatnonzero(t[1:] == t[:-1])  # the first of each pair
    assert len(shared) >= r.summary["impacts"] > 0  # the pass has the pairs this is about
    ds = r.to_xarray()
    assert ds.indexes["t"].is_unique and ds.indexes["t"].is_monotonic_increasing
    assert ds.sizes["t"] == len(t) - len(shared)
    # The row kept at an impact's t is the state after it: its vx is the event's vx_after.
    impacts = [e for e in r.events if e["kind"] == "impact"]
    for e in impacts:
        kept = ds.sel(t=e["t_s"])
        assert float(kept["vx_m_s"]) == e["vx_after_m_s"]
    # What raised before: the nearest state, and interpolation between states (its values lie
    # between those of the rows around it; the times chosen are not rows' times).
    near = ds.sel(t=impacts[0]["t_s"] + 1e-9, method="nearest")
    assert float(near["t"]) == impacts[0]["t_s"]
    between = (ds["t"].values[:-1] + ds["t"].values[1:]) / 2
    theta = ds.interp(t=between)["theta_deg"].values
    lo = np.minimum(ds["theta_deg"].values[:-1], ds["theta_deg"].values[1:])
    hi = np.maximum(ds["theta_deg"].values[:-1], ds["theta_deg"].values[1:])
    assert np.all((theta >= lo) & (theta <= hi))
    assert float(ds["normal_force_n"].to_pandas().sort_index().index[-1]) == t[-1]  # the documented Series over t
    # every_row=True: the history as it is, t a coordinate along `row` (not an index).
    rows = r.to_xarray(every_row=True)
    assert rows["normal_force_n"].dims == ("row",) and "t" not in rows.indexes
    np.testing.assert_array_equal(rows["t"].values, t)
    np.testing.assert_array_equal(rows["vx_m_s"].values, r.history["vx_m_s"])
    assert list(rows["phase"].values) == list(r.history["phase"])
    assert rows.sizes["event"] == ds.sizes["event"] == len(r.events)


# --- 15: the Python API's arguments ------------------------------------------------------------------

def test_numpy_numbers_are_accepted_wherever_python_numbers_are():
    # np.float32(0.2) was refused by static ("give a number of newtons"), np.int64 jobs by brush
    # and sweep: numpy's numbers are accepted as the docs say, and give what Python's give (the
    # float32's value is the float it holds, 0.2 to float32's precision, 1e-8).
    assert rotbeam.static(np.float32(0.2))["tip_y_m"] == pytest.approx(rotbeam.static(0.2)["tip_y_m"], rel=1e-6)
    assert rotbeam.static(np.int64(0))["tip_y_m"] == rotbeam.static(0)["tip_y_m"]
    ds = rotbeam.sweep({"hub.speed_rpm": [3000]}, overrides=QUICK, jobs=np.int64(1), retries=np.int32(0),
                       progress=np.bool_(False))
    assert list(ds["status"].values.ravel()) == ["done"]
    assert rotbeam.modes(overrides={"beam.modes": 2}, speeds_rpm=np.float32(100))["speeds_rpm"][0] == 100.0


def test_numbers_beyond_a_float_are_one_line_naming_the_argument():
    # 10**400 gave a raw OverflowError ("int too large to convert to float").
    with pytest.raises(rotbeam.ConfigError, match=r"^tip_load_n = 1\.00000e\+400: must be a finite number of newtons$"):
        rotbeam.static(10**400)
    with pytest.raises(rotbeam.ConfigError, match=r"^tip_load_n = -1\.00000e\+400: must be a finite number of newtons$"):
        rotbeam.static(-10**400)
    with pytest.raises(rotbeam.ConfigError, match=r"^speeds_rpm: 1\.00000e\+400 must be in \[0, 1000000\] rpm$"):
        rotbeam.modes(speeds_rpm=10**400)
    with pytest.raises(rotbeam.ConfigError, match=r"^speeds_rpm: 1\.00000e\+400 must be in \[0, 1000000\] rpm$"):
        rotbeam.modes(speeds_rpm=[550, 10**400])
    with pytest.raises(rotbeam.ConfigError, match=r"^tip_load_n = .*True: give a number of newtons$"):
        rotbeam.static(np.bool_(True))  # numpy's boolean is no more a number than Python's


@pytest.mark.parametrize("call", ["sweep", "sweep with a client", "brush"])
def test_jobs_out_of_range_is_refused_the_same_way_everywhere(call):
    # jobs=10**20 gave pybind11's "incompatible function arguments" (a list of signatures); jobs=-1
    # was refused on threads but accepted (and ignored) with a Dask client.
    class Client:  # never asked for anything: the arguments are refused before any case is sent
        def submit(self, *a, **k):
            raise AssertionError("a task was submitted")

        nthreads = cancel = submit

    def call_with(jobs):
        if call == "brush":
            return rotbeam.brush(overrides={"brush.filaments": 2}, jobs=jobs)
        return rotbeam.sweep({"hub.speed_rpm": [3000]}, overrides=QUICK, jobs=jobs, progress=False,
                             client=Client() if call == "sweep with a client" else None)

    with pytest.raises(rotbeam.ConfigError, match=r"^jobs = 100000000000000000000: must be in 0\.\.2147483647 \(0: all cores\)$"):
        call_with(10**20)
    with pytest.raises(rotbeam.ConfigError, match=r"^jobs = -1: must be in 0\.\.2147483647 \(0: all cores\)$"):
        call_with(-1)
    with pytest.raises(rotbeam.ConfigError, match=r"^jobs = -1: must be in 0\.\.2147483647"):
        call_with(np.int64(-1))
    with pytest.raises(TypeError, match=r"^jobs must be a whole number of threads \(0: all cores\), not 1\.5$"):
        call_with(1.5)


def test_client_progress_and_retries_that_are_not_such_are_refused_in_one_line():
    # client="tcp://nowhere:1" raised AttributeError ("'str' object has no attribute 'nthreads'"),
    # progress=5 was accepted and ignored.
    vary = {"hub.speed_rpm": [3000]}
    with pytest.raises(TypeError, match=r"^client must be a dask\.distributed\.Client \(e\.g\. "
                                        r"Client\('tcp://nowhere:1'\) for an address\), not 'tcp://nowhere:1'$"):
        rotbeam.sweep(vary, overrides=QUICK, client="tcp://nowhere:1")
    with pytest.raises(TypeError, match=r"^client must be a dask\.distributed\.Client, not 5$"):
        rotbeam.sweep(vary, overrides=QUICK, client=5)
    for progress in (5, "yes", 0.5):
        with pytest.raises(TypeError, match=r"^progress must be a callable progress\(finished, total\), True, False or "
                                            rf"None, not {progress!r}$"):
            rotbeam.sweep(vary, overrides=QUICK, progress=progress)
    with pytest.raises(rotbeam.ConfigError, match=r"^retries = -1: must be in 0\.\.2147483647$"):
        rotbeam.sweep(vary, overrides=QUICK, retries=-1)
    with pytest.raises(TypeError, match=r"^retries must be a whole number of retries of a Dask task, not '2'$"):
        rotbeam.sweep(vary, overrides=QUICK, retries="2")


def test_open_sweep_refuses_a_status_rotbeam_never_writes(tmp_path):
    # A sweep.csv whose status read `finished` (no status rotbeam writes) was taken as such: the
    # Dataset showed it, with NaN in every metric. It is damage, named with its line and value,
    # by open_sweep and by the netCDF writer (`rotbeam sweep --format netcdf` reads the same index).
    out = tmp_path / "grid"
    assert cli("sweep", "--vary", "surface.friction=0.1,0.2", *QUICK_ARGS, "-o", str(out), "--quiet").returncode == 0
    text = (out / "sweep.csv").read_text()
    assert rotbeam.open_sweep(out)["status"].values.tolist() == ["done", "done"]
    (out / "sweep.csv").write_text(text.replace(",done,", ",finished,", 1))
    expected = (f"{out / 'sweep.csv'}: line 2, column status: 'finished' is not one of done, resumed, failed, error, "
                "interrupted")
    with pytest.raises(ValueError) as refused:
        rotbeam.open_sweep(out)
    assert str(refused.value) == expected
    done = subprocess.run([sys.executable, "-m", "rotbeam.netcdf", str(out)], capture_output=True, text=True)
    assert done.returncode == 2 and one_line(done) == expected
    assert not (out / "sweep.nc").exists()


# --- 14: full disks and read-only folders ------------------------------------------------------------

def on_small_disk(mount_point, kib, script, *args, read_only=False):
    """Runs the shell `script` (arguments $1 …) with a file system of `kib` KiB (a tmpfs) mounted at
    mount_point, in a mount namespace of its own (`unshare -rm`: no root needed, nothing outside
    sees it, and it goes when the script ends); `read_only` remounts it read-only before the script's
    last command. Skips the test, saying why, where the system permits no such namespace."""
    mount_point.mkdir(exist_ok=True)
    setup = f'mount -t tmpfs -o size={kib}k tmpfs "$0" || exit 99'
    body = script if not read_only else script.replace("@READ_ONLY@", 'mount -o remount,ro "$0" &&')
    done = subprocess.run(["unshare", "-rm", "sh", "-c", f"{setup}\n{body}", str(mount_point), *map(str, args)],
                          capture_output=True, text=True)
    if done.returncode == 99 or "unshare failed" in done.stderr:
        pytest.skip(f"no small file system can be mounted here (unshare -rm, mount -t tmpfs: {done.stderr.strip()})")
    return done


def used_kib(folder):
    """What a folder's files take on a tmpfs: whole 4 KiB pages."""
    return sum(-(-f.stat().st_size // 4096) * 4 for f in Path(folder).rglob("*") if f.is_file())


def test_sweep_nc_on_a_full_disk_is_one_line_naming_it_and_sweep_csv_is_kept(tmp_path):
    # netCDF's writer crashed (SIGSEGV) on a full disk, or said "NetCDF: HDF error", or, with no
    # byte left, "Permission denied". The finished sweep is copied onto a disk with 16 KiB left:
    # its cases resume, and sweep.nc (made in memory: at least 64 KiB) cannot be written, while
    # sweep.csv (4 KiB) can.
    grid = tmp_path / "grid"
    # end_when_clear: the history's size is only bounded, so the disk is not checked for the
    # histories of the cases before it is seen that they are done.
    args = ["--vary", "surface.friction=0.1,0.2", *QUICK_ARGS, "--set", "simulation.end_when_clear=true"]
    assert cli("sweep", *args, "-o", str(grid), "--quiet").returncode == 0
    (grid / "sweep.csv").unlink()
    disk = tmp_path / "disk"
    done = on_small_disk(disk, used_kib(grid) + 16, 'src="$1" cli="$2"; shift 2; cp -a "$src" "$0/grid" && exec "$cli" sweep "$@"',
                         grid, CLI, *args, "--format", "netcdf", "-o", disk / "grid", "--quiet")
    assert done.returncode == 1, done.stderr
    assert one_line(done) == (f"{disk / 'grid' / 'sweep.nc'}: cannot write (No space left on device); "
                              "sweep.csv is written without it")
    assert "2 already done" in done.stdout and f"wrote {disk / 'grid' / 'sweep.csv'} and a folder per case" in done.stdout


def test_merge_onto_a_full_disk_is_one_line_naming_the_file(tmp_path):
    # The shards' files are copied onto another file system, of 8 KiB and of 64 KiB (a history.csv
    # fills it part way: that said "Input/output error"): the file that does not fit is named with
    # the cause, exit 1, and nothing is left; with room for the cases but not for sweep.nc, the
    # netCDF writer's line names it.
    folders = shards(tmp_path)
    disk = tmp_path / "disk"
    merge = '"$1" merge "$2" "$3" {} -o "$0/out" --quiet; code=$?; ls -A "$0"; exit $code'
    for kib in (8, 64):
        done = on_small_disk(disk, kib, merge.format(""), CLI, *folders)
        assert done.returncode == 1, done.stderr
        line = one_line(done)
        assert line.startswith(f"{disk / 'out'}/case-000") and line.endswith("(No space left on device)"), line
        assert done.stdout == ""  # what ls -A found on the disk: nothing
    need = sum(used_kib(f) for f in folders)
    done = on_small_disk(disk, need + 16, merge.format("--format netcdf"), CLI, *folders)
    assert done.returncode == 1, done.stderr
    assert one_line(done) == (f"{disk / 'out' / 'sweep.nc'}: cannot write (No space left on device); "
                              f"merge: nothing written ({disk / 'out'} removed)")
    assert done.stdout == ""


def test_animate_names_the_users_file_on_a_full_disk_and_in_a_read_only_folder(tmp_path):
    # A full disk said "No space left on device", naming no file; a folder that cannot be written
    # named the temporary file (.a.PID.tmp.gif). Both name the user's -o path and the cause now.
    run = tmp_path / "run"
    assert cli("run", "--set", "hub.speed_rpm=3000", *QUICK_ARGS, "-o", str(run)).returncode == 0
    full = tmp_path / "a.gif"
    full.symlink_to("/dev/full")  # writing there fails with ENOSPC, as on a full disk
    done = cli("animate", str(run), "--frames", "2", "-o", str(full))
    assert done.returncode == 1, done.stderr
    assert one_line(done) == f"{full}: No space left on device"
    disk = tmp_path / "disk"
    done = on_small_disk(disk, 64, '@READ_ONLY@ exec "$1" animate "$2" --frames 2 -o "$0/a.gif"', CLI, run,
                         read_only=True)
    assert done.returncode == 1, done.stderr
    assert one_line(done) == f"{disk / 'a.gif'}: Read-only file system"
