#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the thesis's base case.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
echo
./build/rotbeam run examples/thesis-base.toml -o out/base
./build/rotbeam plot out/base
./build/rotbeam modes examples/thesis-base.toml --speeds-rpm 0:5000:51 --plot out/base/campbell.png
./build/rotbeam animate out/base
echo
./build/rotbeam impact examples/thesis-base.toml
echo
echo "Pictures of the pass: out/base/*.png (normal force against the tip position, tip path, modal"
echo "coordinates, energy audit, impacts; Campbell diagram) and its animation, out/base/animation.gif"
echo "(and .mp4 where ffmpeg is installed). The thesis's chapter 5, regenerated with a"
echo "report: ./build/rotbeam reproduce -o out/reproduction (about 13 s on two cores, 22 MB)."

