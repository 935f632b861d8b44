"""Waiting until a process or a call is under way, instead of sleeping a fixed time, before a test
interrupts it: a fixed sleep fails on a slow machine and, on a fast one, may signal a process that
has already finished or not yet started, so that the test passes without testing anything."""

import contextlib
import os
import signal
import threading
import time


def wait_until(ready, deadline=300.0):
    """Polls ready() until it holds or deadline seconds have passed: whether it held."""
    end = time.monotonic() + deadline
    while not ready():
        if time.monotonic() > end:
            return False
        time.sleep(0.005)
    return True


def catches(pid, sig=signal.SIGINT):
    """True when process pid has a handler of its own for sig (/proc/PID/status, SigCgt)."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("SigCgt:"):
                    return bool(int(line.split()[1], 16) >> (sig - 1) & 1)
    except OSError:
        pass
    return False


@contextlib.contextmanager
def interrupt_once_a_thread_starts():
    """Within the block, sends SIGINT to this process once a thread other than those running before
    it has started: the library's worker, once a call into it is under way (rotbeam runs a long call
    on a thread of its own while the calling thread waits, watching for Ctrl-C)."""
    before = set(os.listdir("/proc/self/task"))
    done = threading.Event()

    def send():
        me = str(threading.get_native_id())
        if wait_until(lambda: done.is_set() or set(os.listdir("/proc/self/task")) - before - {me}) and not done.is_set():
            os.kill(os.getpid(), signal.SIGINT)

    sender = threading.Thread(target=send, daemon=True)
    sender.start()
    try:
        yield
    finally:
        done.set()
        sender.join()
