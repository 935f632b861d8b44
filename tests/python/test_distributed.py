"""Sweeps beyond one machine's threads (issue 20, docs/distributed.md): one 24-case grid gives
identical Datasets through threads, `rotbeam sweep` (threads, sweep.nc), three `--shard`s plus
`rotbeam merge`, and a Dask LocalCluster of worker processes; a Dask worker killed mid-sweep and a
shard process killed mid-sweep lose no finished case; merge refuses what does not fit, in one line."""

import os
import shutil
import signal
import subprocess
import sys
import time

import pytest

import rotbeam

xr = pytest.importorskip("xarray")
pytest.importorskip("netCDF4")
distributed = pytest.importorskip("distributed")

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")

# 4 speeds × 3 depths × 2 frictions of cheap passes (3 modes, coarse sampling), four of which stop
# on a diagnosed failure (more than 30 impacts): they must come out alike, NaN with `failed`.
GRID = {"hub.speed_rpm": [550, 1000, 2000, 3000], "surface.depth_fraction": [0.01, 0.02, 0.03],
        "surface.friction": [0.1, 0.4]}
BASE = {"beam.modes": 3, "output.interval_s": 1e-3, "output.near_surface_interval_s": 1e-4,
        "simulation.max_impacts": 30}
GRID_ARGS = ["--vary", "hub.speed_rpm=550,1000,2000,3000", "--vary", "surface.depth_fraction=0.01,0.02,0.03",
             "--vary", "surface.friction=0.1,0.4", "--set", "beam.modes=3", "--set", "output.interval_s=1e-3",
             "--set", "output.near_surface_interval_s=1e-4", "--set", "simulation.max_impacts=30"]

# Slower cases (8 modes, ~0.2–0.4 s each) for killing a worker or a shard while cases run.
SLOW = {"hub.speed_rpm": [550, 650, 750, 850], "surface.friction": [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]}
SLOW_BASE = {"beam.modes": 8, "output.interval_s": 1e-3, "output.near_surface_interval_s": 1e-4}
SLOW_ARGS = ["--vary", "hub.speed_rpm=550,650,750,850", "--vary", "surface.friction=0.1,0.2,0.3,0.4,0.5,0.6",
             "--set", "beam.modes=8", "--set", "output.interval_s=1e-3", "--set", "output.near_surface_interval_s=1e-4"]


def cli(*args, **kwargs):
    return subprocess.run([CLI, *args], capture_output=True, text=True, **kwargs)


def results(ds):
    """The Dataset without the machine's wall times: what must be identical whichever way it ran."""
    return ds.drop_vars("wall_time_s")


@pytest.fixture(scope="module")
def cluster():
    from distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as c, \
            Client(c) as client:
        yield client


@pytest.fixture(scope="module")
def threads():
    return rotbeam.sweep(GRID, overrides=BASE, jobs=2, progress=False)


@pytest.fixture(scope="module")
def slow_threads():
    return rotbeam.sweep(SLOW, overrides=SLOW_BASE, jobs=2, progress=False)


def test_threads_shards_merge_and_dask_give_identical_datasets(tmp_path, threads, cluster):
    assert threads.sizes == {"hub.speed_rpm": 4, "surface.depth_fraction": 3, "surface.friction": 2}
    statuses = threads["status"].values.ravel().tolist()
    assert statuses.count("failed") == 4 and statuses.count("done") == 20, statuses
    # The command line's threads, with sweep.nc.
    done = cli("sweep", *GRID_ARGS, "--format", "netcdf", "-o", str(tmp_path / "whole"), "--quiet")
    assert done.returncode == 0, done.stderr
    whole = xr.open_dataset(tmp_path / "whole" / "sweep.nc").load()
    xr.testing.assert_identical(results(whole), results(threads))
    # Three shards (as a job array would run them), then merge.
    for i in range(3):
        shard = cli("sweep", *GRID_ARGS, "--shard", f"{i}/3", "-o", str(tmp_path / f"shard{i}"), "--quiet")
        assert shard.returncode == 0, shard.stderr
        assert f"shard {i}/3 of a grid of 24 cases, 8 cases: 8 run" in shard.stdout
    merged = cli("merge", *[str(tmp_path / f"shard{i}") for i in range(3)], "-o", str(tmp_path / "merged"),
                 "--format", "netcdf")
    assert merged.returncode == 0, merged.stderr
    assert "merged 3 shards: 24 cases (4 stopped on a diagnosed failure)" in merged.stdout
    nc = xr.open_dataset(tmp_path / "merged" / "sweep.nc").load()
    xr.testing.assert_identical(results(nc), results(threads))
    xr.testing.assert_identical(nc, rotbeam.open_sweep(tmp_path / "merged"))
    # The merged index is the unsharded sweep's, but the wall times.
    def rows(path):
        lines = path.read_text().splitlines()
        wall = lines[0].split(",").index("wall_time_s")
        return [line.split(",")[:wall] for line in lines]
    assert rows(tmp_path / "merged" / "sweep.csv") == rows(tmp_path / "whole" / "sweep.csv")
    # A Dask LocalCluster of worker processes, cases bundled into tasks.
    bundles = []
    dask = rotbeam.sweep(GRID, overrides=BASE, client=cluster, progress=lambda n, total: bundles.append(n))
    xr.testing.assert_identical(results(dask), results(threads))
    assert bundles[-1] == 24 and len(bundles) < 24  # fewer tasks than cases: these cases take ~10 ms


def test_dask_bundles_cases_into_tasks_of_at_least_a_tenth_of_a_second(cluster):
    from rotbeam import _sweep
    # 160 cases of a few ms (about 1 s in all): the first four run as one task and their times
    # size the next, each of which runs >= 0.1 s.
    path, sets = rotbeam._arguments(None, BASE)
    axes = _sweep.axes_of({"hub.speed_rpm": list(range(2000, 3000, 25)), "surface.friction": [0.1, 0.2, 0.3, 0.4]},
                          rotbeam._toml_value)
    log = []
    rows = _sweep.run_on_dask(cluster, path, sets, axes, 160, 0, _sweep._Progress(False, 160), _sweep.TASK_SECONDS, log)
    assert sorted(rows) == list(range(160))
    assert log[0][0] == list(range(4))
    later = log[1:]
    assert 1 <= len(later) < 40 and all(len(cases) > 1 for cases, _ in later), log
    assert all(cases == list(range(cases[0], cases[-1] + 1)) for cases, _ in log)  # consecutive cases
    assert all(seconds >= 0.1 for _, seconds in later), [(len(c), s) for c, s in log]
    assert sorted(i for cases, _ in log for i in cases) == list(range(160))


def test_a_dask_worker_killed_mid_sweep_loses_nothing(slow_threads):
    # Two worker processes; once four cases are in, the worker with a task under way is killed
    # (SIGKILL). Its nanny starts another, the scheduler reruns the lost task, and the sweep ends
    # with every case, identical to the threads' results.
    from distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as c, \
            Client(c) as client:
        killed, seen = [], []

        def progress(finished, total):
            seen.append(finished)
            if finished >= 4 and not killed:
                busy = [w for w, tasks in client.processing().items() if tasks]
                pids = client.run(os.getpid)
                if busy:
                    killed.append(pids[busy[0]])
                    os.kill(pids[busy[0]], signal.SIGKILL)
        ds = rotbeam.sweep(SLOW, overrides=SLOW_BASE, client=client, progress=progress)
        assert killed and killed[0] not in client.run(os.getpid).values()  # it was killed, and replaced
    assert killed, "no worker was busy to be killed"
    assert seen[-1] == 24 and seen == sorted(seen) and len(seen) > 2
    xr.testing.assert_identical(results(ds), results(slow_threads))


def test_a_killed_shard_resumes_and_merges(tmp_path, slow_threads):
    # Shard 1/3 killed (SIGKILL, as a job array's node lost) once a case is written: merge refuses
    # it (no sweep.csv), the same command resumes it, and the merge equals the threads' sweep.
    args = [CLI, "sweep", *SLOW_ARGS, "--shard", "1/3", "--jobs", "1", "-o", str(tmp_path / "shard1"), "--quiet"]
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 120
    while time.time() < deadline and not list((tmp_path / "shard1").glob("case-*/summary.json")):
        time.sleep(0.02)
    proc.send_signal(signal.SIGKILL)
    proc.communicate(timeout=60)
    finished = len(list((tmp_path / "shard1").glob("case-*/summary.json")))
    assert 1 <= finished < 8
    for i in (0, 2):
        assert cli("sweep", *SLOW_ARGS, "--shard", f"{i}/3", "-o", str(tmp_path / f"shard{i}"), "--quiet").returncode == 0
    dirs = [str(tmp_path / f"shard{i}") for i in range(3)]
    refused = cli("merge", *dirs, "-o", str(tmp_path / "merged"))
    assert refused.returncode == 2
    assert refused.stderr == (f"rotbeam: error: {dirs[1]}: no sweep.csv: its sweep (shard 1/3) has not finished "
                              "(stopped, killed, or still running); run it again to resume it\n")
    assert not (tmp_path / "merged").exists()
    again = subprocess.run(args, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    assert f"{finished} already done" in again.stdout
    merged = cli("merge", *dirs, "-o", str(tmp_path / "merged"), "--format", "netcdf")
    assert merged.returncode == 0, merged.stderr
    nc = xr.open_dataset(tmp_path / "merged" / "sweep.nc").load()
    xr.testing.assert_identical(results(nc), results(slow_threads))


def test_merge_and_shard_refuse_bad_input_in_one_line(tmp_path):
    small = ["--vary", "hub.speed_rpm=2000,3000", "--vary", "surface.friction=0.1,0.4", "--set", "beam.modes=3",
             "--set", "output.interval_s=1e-3"]
    for text, why in (("3/3", "I must be from 0 to 2"), ("x", "expected I/N"), ("1/0", "N must be from 1"),
                      ("-1/2", "I must be from 0 to 1")):
        bad = cli("sweep", *small, "--shard", text, "-o", str(tmp_path / "bad"))
        assert bad.returncode == 2 and bad.stderr.startswith(f"rotbeam: error: --shard {text}: {why}"), bad.stderr
        assert bad.stderr.count("\n") == 1 and not (tmp_path / "bad").exists()
    for i in range(2):
        assert cli("sweep", *small, "--shard", f"{i}/2", "-o", str(tmp_path / f"s{i}"), "--quiet").returncode == 0
    assert cli("sweep", *small, "--set", "surface.depth_fraction=0.03", "--shard", "1/2", "-o", str(tmp_path / "other"),
               "--quiet").returncode == 0
    out = str(tmp_path / "merged")

    def refused(*dirs, output=out):
        done = cli("merge", *[str(tmp_path / d) for d in dirs], "-o", output)
        assert done.returncode == 2 and done.stderr.count("\n") == 1, done.stderr
        return done.stderr

    assert "not a shard of the sweep in" in refused("s0", "other")
    assert "another configuration (surface.depth_fraction = 0.02 in " in refused("s0", "other")
    assert refused("s0").endswith("cases missing, the folders of these shards were not given: shard 1/2: case-0002, "
                                  "case-0004 (2 cases); nothing written\n")
    shutil.copytree(tmp_path / "s0", tmp_path / "s0-copy")
    assert refused("s0", "s1", "s0-copy").endswith("s0 and " + str(tmp_path / "s0-copy") + " are both shard 0/2\n")
    assert refused("s0", "nowhere").endswith("nowhere: no such folder\n")
    assert not os.path.exists(out)
    # A case not finished (stopped by Ctrl-C) is named, with the shard to run again.
    (tmp_path / "s1" / "sweep.csv").write_text((tmp_path / "s1" / "sweep.csv").read_text().replace(",done,", ",interrupted,", 1))
    assert "cases not finished in" in refused("s0", "s1") and "run shard 1/2's sweep again" in refused("s0", "s1")
    assert not os.path.exists(out)
    # Never into a folder that holds anything.
    os.makedirs(out)
    with open(os.path.join(out, "keep.txt"), "w") as f:
        f.write("mine")
    assert "the folder exists and holds files" in refused("s0", "s1")
    assert open(os.path.join(out, "keep.txt")).read() == "mine" and os.listdir(out) == ["keep.txt"]


def test_ctrl_c_stops_a_sweep_on_threads_at_once(tmp_path):
    # SIGINT while the cases run: the running cases stop within a step and KeyboardInterrupt is
    # raised, before the sweep has finished (24 cases of ~0.3 s on one thread: the cases reported
    # finished are fewer than 24).
    script = ("import rotbeam, sys\n"
              "try:\n"
              f"    rotbeam.sweep({SLOW!r}, overrides={SLOW_BASE!r}, jobs=1, progress=lambda n, t: print(n, flush=True))\n"
              "except KeyboardInterrupt:\n"
              "    print('interrupted', flush=True); sys.exit(3)\n")
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                            text=True, env=os.environ)
    assert proc.stdout.readline().strip() == "1"  # a case has finished: the sweep is under way
    proc.send_signal(signal.SIGINT)
    out, _ = proc.communicate(timeout=600)
    assert proc.returncode == 3 and out.strip().endswith("interrupted"), out
    assert all(int(n) < 24 for n in out.split()[:-1]), out
