#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test. Exits non-zero on any failure.
#   1. the Release build: every ctest test (C++, CLI, examples, Python);
#   2. the same suite built with AddressSanitizer + UndefinedBehaviorSanitizer, but the tests labelled
#      `long` (tests/CMakeLists.txt says which and why; they run in step 1);
#   3. the configuration fuzz target (libFuzzer) for ROTBEAM_FUZZ_SECONDS (default 60).
# ROTBEAM_QUICK=1 runs only step 1.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs="$(nproc)"

echo "== release build and tests"
bash scripts/build.sh -DROTBEAM_BUILD_TESTS=ON
(cd build && ctest --output-on-failure -j "$jobs" --timeout 900)

if [ "${ROTBEAM_QUICK:-0}" = 1 ]; then exit 0; fi

echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DROTBEAM_SANITIZE=ON -DROTBEAM_BUILD_PYTHON=OFF \
  -DROTBEAM_BUILD_TESTS=ON > build-asan.log 2>&1 || { cat build-asan.log; exit 1; }
cmake --build build-asan -j "$jobs" >> build-asan.log 2>&1 || { tail -n 60 build-asan.log; exit 1; }
rm -f build-asan.log
# The tests labelled `long` are left out here for time (they run in the Release pass above):
# tests/CMakeLists.txt says which and why.
(cd build-asan && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure -j "$jobs" --timeout 1800 \
    -LE long)

echo "== fuzzing the configuration parser for ${ROTBEAM_FUZZ_SECONDS:-60} s"
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROTBEAM_FUZZ=ON \
  -DROTBEAM_BUILD_TESTS=OFF -DROTBEAM_BUILD_PYTHON=OFF > build-fuzz.log 2>&1 || { cat build-fuzz.log; exit 1; }
cmake --build build-fuzz -j "$jobs" --target fuzz_config >> build-fuzz.log 2>&1 || { tail -n 60 build-fuzz.log; exit 1; }
rm -f build-fuzz.log
rm -rf build-fuzz/corpus && mkdir -p build-fuzz/corpus && cp fuzz/corpus/* build-fuzz/corpus/
./build-fuzz/fuzz/fuzz_config build-fuzz/corpus -max_total_time="${ROTBEAM_FUZZ_SECONDS:-60}" \
  -rss_limit_mb=4096 -timeout=30 -print_final_stats=1 2>&1 | grep -E "^(Done|stat::number_of_executed_units|stat::new_units_added)|ERROR|SUMMARY" || true
test "${PIPESTATUS[0]}" -eq 0
echo "fuzz: no crash"
