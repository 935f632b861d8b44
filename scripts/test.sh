#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (ctest). Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh -DROTBEAM_BUILD_TESTS=ON
cd build
ctest --output-on-failure -j "$(nproc)" --timeout 900
