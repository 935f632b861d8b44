"""Builds and installs rotbeam's Python package (issue 20):

    pip install --no-build-isolation .

CMake (with the Debian packages of scripts/install-deps.sh) builds only the pybind11 extension
rotbeam._core (the target rotbeam_python and the static library it links, Release) in
build-pip/; setuptools puts it inside the package rotbeam (python/rotbeam: the pure-Python modules,
the type stubs and py.typed). Nothing is downloaded. The version is project(VERSION) in
CMakeLists.txt, the one place it is set.

Environment: CMAKE_BUILD_PARALLEL_LEVEL, the compile jobs (default: every core);
ROTBEAM_CMAKE_ARGS, more arguments for CMake's configure step (e.g. "-DROTBEAM_LTO=OFF");
ROTBEAM_CMAKE_BUILD_DIR, an existing CMake build folder of this checkout (configured for this
Python) to build the target in instead (the test suite packs its own build's module this way).
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
BUILD_BASE = "build-pip"  # beside the CMake build folders (build/, build-asan/), never inside them


def version():
    """project(rotbeam VERSION x.y.z) in CMakeLists.txt."""
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    found = re.search(r"project\(\s*rotbeam\s+VERSION\s+([0-9][0-9.]*)", text)
    if not found:
        sys.exit("setup.py: no project(rotbeam VERSION …) in CMakeLists.txt")
    return found.group(1)


class CMakeExtension(Extension):
    """An extension that CMake builds (no sources for setuptools to compile)."""

    def __init__(self, name, target):
        super().__init__(name, sources=[])
        self.target = target


class CMakeBuild(build_ext):
    """Configures the project in build-pip/cmake (tests and benchmarks off, Release, for this
    Python), builds the extension's target alone, and copies the module where setuptools packs it."""

    def build_extension(self, ext):
        if shutil.which("cmake") is None:
            sys.exit("setup.py: cmake not found (Debian: bash scripts/install-deps.sh, or apt-get install cmake g++)")
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        if os.environ.get("ROTBEAM_CMAKE_BUILD_DIR"):
            build_dir = Path(os.environ["ROTBEAM_CMAKE_BUILD_DIR"]).resolve()
            if not (build_dir / "CMakeCache.txt").exists():
                sys.exit(f"setup.py: ROTBEAM_CMAKE_BUILD_DIR={build_dir}: not a configured CMake build folder")
        else:
            build_dir = (ROOT / BUILD_BASE / "cmake").resolve()
            build_dir.mkdir(parents=True, exist_ok=True)
            configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                         f"-DPython3_EXECUTABLE={sys.executable}", "-DROTBEAM_BUILD_TESTS=OFF",
                         "-DROTBEAM_BUILD_BENCH=OFF", "-DROTBEAM_BUILD_PYTHON=ON",
                         *shlex.split(os.environ.get("ROTBEAM_CMAKE_ARGS", ""))]
            subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", ext.target, "-j", jobs], check=True)
        suffix = self.get_ext_filename("_core")[len("_core"):]  # .cpython-311-x86_64-linux-gnu.so
        built = build_dir / "python" / "rotbeam" / ("_core" + suffix)
        if not built.exists():
            sys.exit(f"setup.py: CMake did not make {built}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


(ROOT / BUILD_BASE).mkdir(exist_ok=True)
setup(
    version=version(),
    packages=["rotbeam"],
    package_dir={"rotbeam": "python/rotbeam"},
    package_data={"rotbeam": ["py.typed", "*.pyi"]},
    ext_modules=[CMakeExtension("rotbeam._core", "rotbeam_python")],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": BUILD_BASE}, "egg_info": {"egg_base": BUILD_BASE}},
    zip_safe=False,
)
