"""`pip install --no-build-isolation .` of a copy of the checkout (its tracked files, as a fresh clone
has them) into a temporary folder, never the system's, then the package imported from another folder:
its version, a pass, its docstrings, type stubs and modules (issue 20). Run by ctest:

    python3 tests/pip_install.py SOURCE --version X.Y.Z [--reuse BUILD]

--reuse BUILD packs the extension of an existing CMake build folder (setup.py's ROTBEAM_CMAKE_BUILD_DIR:
seconds); without it setup.py configures and builds the library and the extension from scratch
(minutes: ROTBEAM_TEST_PIP_FRESH=ON registers that test). Exit 0 when everything holds.
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

CHECK = r"""
import os, sys
import rotbeam
site = sys.argv[1]
assert rotbeam.__file__.startswith(site), f"imported from {rotbeam.__file__}, not {site}"
assert rotbeam.__version__ == sys.argv[2], (rotbeam.__version__, sys.argv[2])
r = rotbeam.run()
assert r.summary["impacts"] == 55, r.summary["impacts"]
assert "Returns a Result" in rotbeam.run.__doc__ and "client" in rotbeam.sweep.__doc__
package = os.path.dirname(rotbeam.__file__)
for name in ("py.typed", "_core.pyi", "netcdf.py", "_sweep.py", "_xarray.py", "plots.py"):
    assert os.path.exists(os.path.join(package, name)), name
assert rotbeam.run.__annotations__["return"] == "Result"
import rotbeam.netcdf, rotbeam._sweep
print("rotbeam", rotbeam.__version__, "from", package, "impacts", r.summary["impacts"])
"""


def source_files(source: Path) -> list[str]:
    """The checkout's files as a clone has them: git's tracked and untracked-but-not-ignored files,
    or, without git, everything but build folders, outputs and caches."""
    try:
        out = subprocess.run(["git", "-C", str(source), "ls-files", "-co", "--exclude-standard", "-z"],
                             capture_output=True, check=True).stdout.decode()
        return [f for f in out.split("\0") if f and (source / f).is_file()]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for root, dirs, names in os.walk(source):
            rel = Path(root).relative_to(source)
            dirs[:] = [d for d in dirs if not (d.startswith(("build", "out", ".git")) or d == "__pycache__")]
            files += [str(rel / n) for n in names]
        return files


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("source")
    parser.add_argument("--version", required=True)
    parser.add_argument("--reuse", help="an existing CMake build folder whose extension is packed")
    args = parser.parse_args()
    source = Path(args.source).resolve()
    tmp = Path(tempfile.mkdtemp(prefix="rotbeam-pip-"))
    try:
        clone = tmp / "rotbeam"
        for f in source_files(source):
            (clone / f).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source / f, clone / f)
        env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        if args.reuse:
            env["ROTBEAM_CMAKE_BUILD_DIR"] = str(Path(args.reuse).resolve())
        env.setdefault("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        start = time.monotonic()
        install = subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-deps",
                                  "--no-index", "--quiet", "--target", str(tmp / "site"), str(clone)],
                                 env=env, capture_output=True, text=True)
        seconds = time.monotonic() - start
        if install.returncode != 0:
            print(install.stdout[-4000:], install.stderr[-4000:], sep="\n")
            print(f"pip install failed (exit {install.returncode})")
            return 1
        print(f"pip install --no-build-isolation: {seconds:.0f} s{' (extension of ' + args.reuse + ')' if args.reuse else ''}")
        elsewhere = tmp / "elsewhere"
        elsewhere.mkdir()
        check = subprocess.run([sys.executable, "-c", CHECK, str(tmp / "site"), args.version], cwd=elsewhere,
                               env={**env, "PYTHONPATH": str(tmp / "site")}, capture_output=True, text=True)
        print(check.stdout, check.stderr, sep="", end="")
        if check.returncode != 0:
            print("the installed package failed its check")
            return 1
        # Nothing was written into the checkout that was installed from but its build folder.
        made = {p.name for p in clone.iterdir()} - {Path(f).parts[0] for f in source_files(source)}
        if made - {"build-pip"}:
            print(f"pip install left {sorted(made)} in the checkout")
            return 1
        return 0
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
