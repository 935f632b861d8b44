"""How the command-line modules (rotbeam.plots, rotbeam.animate) stop on SIGINT/SIGTERM."""

import signal


def _interrupted(signum, frame):
    raise SystemExit(130)


def stop_quietly_on_interrupt():
    """SIGINT/SIGTERM end the process quietly with exit 130 at any point, imports included (no
    traceback): pictures and animations are written whole through temporary names, and `rotbeam`,
    which ran the module, says what happened."""
    signal.signal(signal.SIGINT, _interrupted)
    signal.signal(signal.SIGTERM, _interrupted)
