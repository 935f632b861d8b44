#!/usr/bin/env python3
"""Wall time of `rotbeam reproduce` (the thesis's Table 5-3 and Figures 4-13 with report.md) and
of how quickly it, a pass and a sweep stop on Ctrl-C: measured and reported, never asserted (the
tests check what these commands write and that SIGINT stops them; the time they take depends on
the machine and on what else runs on it).

    /usr/bin/python3 bench/reproduce_time.py build/rotbeam [--repeat N] [--jobs J] [--keep-history]

Each reproduction writes into a temporary folder that is removed afterwards. The time splits into
the 62 runs and the figures (the progress line's "figure" stage); --keep-history times the
reproduction that keeps every history row as well.
"""
import argparse
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time


def catches_sigint(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("SigCgt:"):
                    return bool(int(line.split()[1], 16) >> (signal.SIGINT - 1) & 1)
    except OSError:
        pass
    return False


def reproduce_seconds(binary, jobs, keep_history):
    out = tempfile.mkdtemp(prefix="rotbeam-reproduce-")
    try:
        cmd = [binary, "reproduce", "--quiet", "-o", os.path.join(out, "rep")]
        if jobs:
            cmd += ["--jobs", str(jobs)]
        if keep_history:
            cmd.append("--keep-history")
        t0 = time.monotonic()
        p = subprocess.run(cmd, capture_output=True, text=True)
        seconds = time.monotonic() - t0
        if p.returncode != 0:
            sys.exit(f"{' '.join(cmd)}: exit {p.returncode}\n{p.stderr[-2000:]}")
        return seconds
    finally:
        shutil.rmtree(out, ignore_errors=True)


def interrupt_seconds(binary, args):
    """Seconds from SIGINT (sent once the command catches it and is under way) to its exit."""
    out = tempfile.mkdtemp(prefix="rotbeam-interrupt-")
    try:
        proc = subprocess.Popen([binary, *args, "-o", os.path.join(out, "o")], stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 300
        while not catches_sigint(proc.pid) and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.005)
        time.sleep(0.2)  # well into the work
        t0 = time.monotonic()
        proc.send_signal(signal.SIGINT)
        code = proc.wait()
        return time.monotonic() - t0, code
    finally:
        shutil.rmtree(out, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("binary")
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--jobs", type=int, default=0, help="reproduce --jobs (0: its default, every core)")
    parser.add_argument("--keep-history", action="store_true")
    a = parser.parse_args()
    print(f"rotbeam reproduce on {os.cpu_count()} cores (load average {os.getloadavg()[0]:.1f} at the start)")
    for keep in (False, True) if a.keep_history else (False,):
        times = [reproduce_seconds(a.binary, a.jobs, keep) for _ in range(a.repeat)]
        what = "reproduce --keep-history" if keep else "reproduce"
        print(f"{what:26s} median {statistics.median(times):7.1f} s  (runs: {', '.join(f'{t:.1f}' for t in times)})")
    for what, args in (("run (SIGINT)", ["run", "--set", "hub.speed_rpm=5", "--set", "simulation.end_angle_deg=270"]),
                       ("sweep (SIGINT)", ["sweep", "--vary", "hub.speed_rpm=5,6,7,8", "--jobs", "1"]),
                       ("reproduce (SIGINT)", ["reproduce", "--quiet"])):
        seconds, code = interrupt_seconds(a.binary, args)
        print(f"{what:26s} ended {seconds * 1000:7.0f} ms after SIGINT (exit {code})")


if __name__ == "__main__":
    main()
