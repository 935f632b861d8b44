#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the thesis's base case.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
echo
./build/rotbeam run examples/thesis-base.toml -o out/base
echo
./build/rotbeam impact examples/thesis-base.toml
echo
./build/rotbeam modes examples/thesis-base.toml
