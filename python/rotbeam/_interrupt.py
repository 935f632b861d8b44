"""How the command-line modules (rotbeam.plots, rotbeam.animate, rotbeam.reproduce) stop on
SIGINT/SIGTERM, and tell `rotbeam`, which runs them, that they started and how they ended."""

import os
import signal

# The write end of the pipe `rotbeam` gave this process (ROTBEAM_RESULT_FD), None when run by hand.
_result_fd = None

# Set once SIGINT/SIGTERM arrived: an import that the SystemExit below broke may surface as an
# ImportError (a module's `except` turns it into one), which is then the interruption, not a
# missing package.
interrupted = False


def _interrupted(signum, frame):
    global interrupted
    interrupted = True
    raise SystemExit(130)


def stop_quietly_on_interrupt():
    """SIGINT/SIGTERM end the process quietly with exit 130 at any point, imports included (no
    traceback): pictures and animations are written whole through temporary names, and `rotbeam`,
    which ran the module, says what happened."""
    signal.signal(signal.SIGINT, _interrupted)
    signal.signal(signal.SIGTERM, _interrupted)


def _send(line):
    if _result_fd is not None:
        try:
            os.write(_result_fd, line.encode())
        except OSError:
            pass


def announce_start():
    """Tells `rotbeam` that the module runs: the line `started` on the pipe ROTBEAM_RESULT_FD names
    (an interpreter that never ran the module sends nothing, and `rotbeam` says so). The variable is
    taken out of the environment, so that no program this one starts writes there."""
    global _result_fd
    fd = os.environ.pop("ROTBEAM_RESULT_FD", None)
    try:
        _result_fd = int(fd) if fd is not None else None
    except ValueError:
        _result_fd = None
    _send("started\n")


def announce_result(code):
    """Tells `rotbeam` the exit code the module chose (`result CODE`): an exit without it (a crash,
    a signal) is reported as such instead of passed on as one of rotbeam's codes."""
    _send(f"result {0 if code is None else code}\n")
