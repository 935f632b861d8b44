"""Studies from the command line: `rotbeam sweep` (progress, interruption, resumption),
`rotbeam plot` and `rotbeam modes --plot` (pictures written, of a real size)."""

import csv
import os
import signal
import subprocess
import time

import pytest

CLI = os.environ.get("ROTBEAM_CLI", "rotbeam")


def run(*args, **kwargs):
    return subprocess.run([CLI, *args], capture_output=True, text=True, **kwargs)


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_sweep_reports_progress_lines_off_a_terminal(tmp_path):
    done = run("sweep", "--vary", "hub.speed_rpm=2000,3000", "--vary", "surface.friction=0.1,0.5",
               "--set", "output.interval_s=1e-3", "-o", str(tmp_path / "s"), "--jobs", "2")
    assert done.returncode == 0, done.stderr
    lines = [l for l in done.stderr.splitlines() if l.startswith("case-")]
    assert len(lines) == 4 and all("ETA" in l for l in lines)
    assert "4 cases: 4 run" in done.stdout
    rows = read_rows(tmp_path / "s" / "sweep.csv")
    assert [r["status"] for r in rows] == ["done"] * 4
    assert {r["hub.speed_rpm"] for r in rows} == {"2000", "3000"}


def test_an_interrupted_sweep_resumes(tmp_path):
    out = tmp_path / "s"
    args = [CLI, "sweep", "--vary", "beam.modes=8,9,10", "--vary", "surface.friction=0.1,0.3,0.5,0.7",
            "--set", "output.interval_s=1e-3", "-o", str(out), "--jobs", "2"]
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # Interrupt once at least one case has finished (whatever the machine's speed).
    deadline = time.time() + 120
    while time.time() < deadline and not list(out.glob("case-*/summary.json")):
        time.sleep(0.05)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert "run the same command again to resume" in err
    rows = read_rows(out / "sweep.csv")
    finished = [r for r in rows if r["status"] in ("done", "failed")]
    assert 0 < len(finished) < 12
    assert all(r["status"] == "interrupted" for r in rows if r not in finished)
    # No case folder holds a half-written file, and interrupted cases are redone on resume.
    for folder in out.iterdir():
        if folder.is_dir():
            assert not [p for p in folder.iterdir() if ".tmp" in p.name]
    again = subprocess.run(args, capture_output=True, text=True, timeout=600)
    assert again.returncode == 0, again.stderr
    assert f"{len(finished)} already done" in again.stdout
    assert all(r["status"] in ("done", "failed", "resumed") for r in read_rows(out / "sweep.csv"))


def test_plot_writes_the_pictures_of_a_run_and_a_sweep(tmp_path):
    assert run("run", "--set", "output.interval_s=1e-4", "-o", str(tmp_path / "r")).returncode == 0
    done = run("plot", str(tmp_path / "r"))
    assert done.returncode == 0, done.stderr
    for name in ("normal_force_vs_y", "tip_path", "modal_coordinates", "energy", "impacts"):
        png = tmp_path / "r" / f"{name}.png"
        assert png.exists() and png.stat().st_size > 20_000, name
    assert run("sweep", "--vary", "hub.speed_rpm=550,3000", "--set", "output.interval_s=1e-4",
               "-o", str(tmp_path / "s")).returncode == 0
    done = run("plot", str(tmp_path / "s"), "-o", str(tmp_path / "pics"))
    assert done.returncode == 0, done.stderr
    for name in ("sweep_metrics", "sweep_normal_force_vs_y"):
        assert (tmp_path / "pics" / f"{name}.png").stat().st_size > 20_000, name
    bad = run("plot", str(tmp_path))
    assert bad.returncode == 2 and "neither a run folder" in bad.stderr
    # Pictures into a path that is a file: one line naming it, nothing written.
    (tmp_path / "a-file").write_text("mine")
    bad = run("plot", str(tmp_path / "r"), "-o", str(tmp_path / "a-file"))
    assert bad.returncode == 2 and bad.stderr.strip() == f"rotbeam: error: -o {tmp_path / 'a-file'}: exists and is not a folder"
    assert (tmp_path / "a-file").read_text() == "mine"


def test_modes_draws_a_campbell_diagram(tmp_path):
    png = tmp_path / "campbell.png"
    done = run("modes", "--speeds-rpm", "0:5000:51", "--plot", str(png))
    assert done.returncode == 0, done.stderr
    assert png.stat().st_size > 20_000
    assert not (tmp_path / "campbell.png.csv").exists()


def test_one_sweep_at_a_time_in_a_folder(tmp_path):
    out = tmp_path / "s"
    first = subprocess.Popen([CLI, "sweep", "--vary", "hub.speed_rpm=550,600", "--set", "simulation.revolutions=10",
                              "--jobs", "1", "-o", str(out)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                             text=True)
    try:
        deadline = time.monotonic() + 30
        while not (out / ".rotbeam.lock").exists() and time.monotonic() < deadline:
            time.sleep(0.01)
        assert (out / ".rotbeam.lock").exists()
        for args in (["sweep", "--vary", "hub.speed_rpm=3000"], ["reproduce"]):
            second = run(*args, "-o", str(out))
            assert second.returncode == 2
            assert second.stderr.strip() == f"rotbeam: error: -o {out}: another rotbeam run is writing into this folder; choose another -o"
    finally:
        _, err = first.communicate(timeout=120)
    assert first.returncode == 0, err
    assert not (out / ".rotbeam.lock").exists()
    assert len(read_rows(out / "sweep.csv")) == 2


@pytest.mark.parametrize("summary", ["[]", "null", '{"files": "x"}', '{"config": {}, "files": {"history.csv": 5}}'])
def test_plot_of_an_odd_summary_is_one_line(tmp_path, summary):
    # A summary.json that parses but is not a run's: one line naming it, exit 2 (it was a traceback).
    assert run("run", "--set", "output.interval_s=1e-4", "-o", str(tmp_path / "r")).returncode == 0
    (tmp_path / "r" / "summary.json").write_text(summary)
    done = run("plot", str(tmp_path / "r"))
    assert done.returncode == 2, done.stderr
    assert done.stderr.count("\n") == 1 and "summary.json: not a rotbeam run summary" in done.stderr, done.stderr


def test_plot_says_what_it_cannot_write(tmp_path):
    assert run("run", "--set", "output.interval_s=1e-4", "-o", str(tmp_path / "r")).returncode == 0
    # An output folder that cannot be made: exit 2, as for `run -o`.
    done = run("plot", str(tmp_path / "r"), "-o", "/proc/rotbeam-cannot-be-here")
    assert done.returncode == 2 and "cannot create the output folder" in done.stderr, done.stderr
    # A picture whose name is a folder: refused before drawing (exit 2, as run and sweep refuse a
    # folder under one of their files' names), naming the user's path, not a temporary's.
    (tmp_path / "p").mkdir()
    (tmp_path / "p" / "tip_path.png").mkdir()
    done = run("plot", str(tmp_path / "r"), "-o", str(tmp_path / "p"))
    assert done.returncode == 2 and done.stderr.count("\n") == 1, done.stderr
    assert f"{tmp_path / 'p' / 'tip_path.png'}: is a folder, where plot writes its file tip_path.png" in done.stderr, done.stderr
    assert not [p for p in (tmp_path / "p").iterdir() if ".tmp" in p.name]
    # Standard output that cannot be written: one line, exit 1.
    with open("/dev/full", "w") as full:
        done = subprocess.run([CLI, "plot", str(tmp_path / "r"), "-o", str(tmp_path / "q")], stdout=full,
                              stderr=subprocess.PIPE, text=True)
    assert done.returncode == 1 and done.stderr.count("\n") == 1, done.stderr
    assert "standard output: the results could not be written" in done.stderr


def test_plot_of_a_sweep_names_a_missing_case(tmp_path):
    out = tmp_path / "s"
    assert run("sweep", "--vary", "hub.speed_rpm=550,3000", "--set", "output.interval_s=1e-3", "-o", str(out)).returncode == 0
    rows = read_rows(out / "sweep.csv")
    missing = out / rows[1]["folder"]
    for p in missing.iterdir():
        p.unlink()
    missing.rmdir()
    done = run("plot", str(out), "--cases")
    assert done.returncode == 2, done.stderr
    assert f"{missing / 'summary.json'}: missing" in done.stderr, done.stderr


def test_a_killed_writers_temporaries_are_removed_by_the_next(tmp_path):
    # `plot` killed with SIGKILL leaves `.tip_path.png.PID.tmp`; the next plot into the folder
    # removes those of dead processes, and nothing else.
    assert run("run", "--set", "output.interval_s=1e-4", "-o", str(tmp_path / "r")).returncode == 0
    dead = subprocess.Popen(["true"])
    dead.wait()
    stale = tmp_path / "r" / f".tip_path.png.{dead.pid}.tmp"
    alive = tmp_path / "r" / f".tip_path.png.{os.getpid()}.tmp"
    mine = tmp_path / "r" / ".tip_path.png.notes.tmp"
    for p in (stale, alive, mine):
        p.write_text("x")
    assert run("plot", str(tmp_path / "r")).returncode == 0
    assert not stale.exists() and alive.exists() and mine.exists()
