#!/usr/bin/env bash
# A longer fuzzing campaign of the configuration parser than CI's minute:
#   bash bench/fuzz-config.sh [SECONDS=1800]
# Builds the libFuzzer target with clang (ASan + UBSan) in build-fuzz/ and keeps the grown corpus
# in build-fuzz/corpus between campaigns. Crash inputs are written to build-fuzz/ (crash-*).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-1800}"
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROTBEAM_FUZZ=ON \
  -DROTBEAM_BUILD_TESTS=OFF -DROTBEAM_BUILD_PYTHON=OFF > /dev/null
cmake --build build-fuzz -j "$(nproc)" --target fuzz_config > /dev/null
mkdir -p build-fuzz/corpus
cp -n fuzz/corpus/* build-fuzz/corpus/ 2>/dev/null || true
cd build-fuzz
./fuzz/fuzz_config corpus -max_total_time="$seconds" -rss_limit_mb=4096 -timeout=30 -print_final_stats=1 \
  -jobs="$(nproc)" -workers="$(nproc)"
