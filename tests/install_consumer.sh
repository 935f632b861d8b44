#!/usr/bin/env bash
# The installed package from a program's side (docs/library.md): installs the build into a scratch
# prefix, builds examples/cpp against it with find_package(rotbeam) and with pkg-config, and runs both.
#   tests/install_consumer.sh BUILD_DIR SOURCE_DIR CXX_COMPILER
set -euo pipefail
build=$1 source=$2 cxx=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/rotbeam-install-XXXXXX")
trap 'rm -rf "$work"' EXIT
expect="first impact at θ = -8.1096°"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"

cmake -S "$source/examples/cpp" -B "$work/cmake" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log" || { cat "$work/configure.log"; exit 1; }
cmake --build "$work/cmake" > "$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }
out=$("$work/cmake/example_first_pass")
grep -qF "$expect" <<< "$out" || { echo "find_package consumer: no '$expect' in:"; echo "$out"; exit 1; }

pc=$(find "$work/prefix" -name rotbeam.pc -printf '%h\n' | head -n 1)
[ -n "$pc" ] || { echo "no rotbeam.pc installed"; exit 1; }
flags=$(PKG_CONFIG_PATH="$pc" pkg-config --cflags --libs rotbeam)
# shellcheck disable=SC2086
"$cxx" -std=c++20 -O1 "$source/examples/cpp/first_pass.cpp" $flags -o "$work/first_pass_pc"
out=$("$work/first_pass_pc")
grep -qF "$expect" <<< "$out" || { echo "pkg-config consumer: no '$expect' in:"; echo "$out"; exit 1; }
echo "the installed package builds and runs examples/cpp with find_package(rotbeam) and with pkg-config ($flags)"
