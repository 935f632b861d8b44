"""How the command-line modules (rotbeam.plots, rotbeam.animate, rotbeam.reproduce, rotbeam.netcdf)
stop on SIGINT/SIGTERM, tell `rotbeam`, which runs them, that they started and how they ended, and
end in one line, never a traceback."""

import os
import signal
import sys

# The write end of the pipe `rotbeam` gave this process (ROTBEAM_RESULT_FD), None when run by hand.
_result_fd = None

# Set once a command-line module started (announce_start): the process is that command.
started = False

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
    global _result_fd, started
    started = True
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


def missing_package(hint):
    """A package the module needs failed to import (hint: what to install): in a command-line
    module, one line `rotbeam: error: HINT` and exit 1 (130 when a Ctrl-C broke the import);
    otherwise the ImportError(hint) to raise."""
    if interrupted:  # a Ctrl-C broke the import: the interruption, not a missing package
        sys.exit(130)
    if started:
        error(hint)
        announce_result(1)
        sys.exit(1)
    return ImportError(hint)


def error(message, code=2):
    """Says `rotbeam: error: MESSAGE` in one line on standard error; returns the exit code `code`."""
    print(f"rotbeam: error: {message}", file=sys.stderr)
    return code


def file_error(e):
    """An OSError in one line naming its file (`rotbeam: error: FILE: why`); returns the exit code 1."""
    where = f"{e.filename}: " if e.filename else ""
    return error(f"{where}{e.strerror or e}", 1)


def wrote(paths):
    """`wrote PATH` on standard output for each file written; returns the exit code 0."""
    for path in paths:
        print(f"wrote {path}")
    return 0


def run_main(main_function, what="the plotting module"):
    """sys.exit(main_function()), with standard output that cannot be written (a full disk, a
    closed pipe) reported in one line, exit 1, as by `rotbeam` itself, and anything unexpected in
    one line naming `what` failed, exit 1; the code is announced to `rotbeam` first (announce_result)."""
    try:
        code = main_function()
        sys.stdout.flush()
    except OSError as e:
        if e.errno is None:
            raise
        print(f"rotbeam: error: standard output: the results could not be written ({e.strerror})", file=sys.stderr)
        code = 1
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # nothing left to flush at exit
    except Exception as e:  # anything else: one line and exit 1, never a traceback
        text = " ".join(f"{type(e).__name__}: {e}".split())[:300]
        print(f"rotbeam: error: {what} failed unexpectedly ({text})", file=sys.stderr)
        code = 1
    announce_result(code)
    sys.exit(code)
