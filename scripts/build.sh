#!/usr/bin/env bash
# Configures and builds rotbeam (Release) in ./build. Extra arguments go to CMake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
# Debian's python3-* packages belong to /usr/bin/python3; build the Python module against it.
python_args=()
if [ -x /usr/bin/python3 ]; then python_args=(-DPython3_EXECUTABLE=/usr/bin/python3); fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${python_args[@]}" "$@" > build.log 2>&1 || { cat build.log; exit 1; }
# The compiler's output goes to build.log; the console gets a line at every tenth of the build.
cmake --build build -j "$(nproc)" 2>&1 | tee -a build.log |
  awk 'match($0, /^\[ *[0-9]+%\]/) { p = substr($0, RSTART + 1, RLENGTH - 3) + 0
         if (p >= next_p) { printf "  build %3d %%\n", p; fflush(); next_p = p - p % 10 + 10 } }' ||
  { tail -n 60 build.log; exit 1; }
rm -f build.log
