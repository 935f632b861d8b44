#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test. Exits non-zero on any failure.
#   1. the Release build: every ctest test (C++, CLI, examples, Python);
#   2. the same suite built with AddressSanitizer + UndefinedBehaviorSanitizer, but the tests labelled
#      `long` (tests/CMakeLists.txt says which and why; they run in step 1);
#   3. the configuration fuzz target (libFuzzer) for ROTBEAM_FUZZ_SECONDS (default 60).
# Steps 2 and 3 share one build (clang: the library is compiled once for both). It runs beside the
# Release tests, at a lower priority: the tests come first, the build takes the time they leave the
# cores idle. The fuzzing (one process) runs beside the sanitizer tests in the same way. Each stage
# prints its time ("== stage: N s"), and the whole its total.
# ROTBEAM_QUICK=1 runs only step 1.
set -euo pipefail
set -m  # the background build in a process group of its own, ended with the script on a failure
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs="$(nproc)"
quick="${ROTBEAM_QUICK:-0}"
fuzz_seconds="${ROTBEAM_FUZZ_SECONDS:-60}"
started=$SECONDS
background=()
end_background() {
  local p
  for p in "${background[@]}"; do kill -- -"$p" 2>/dev/null || true; done
}
trap end_background EXIT

# stage NAME COMMAND...: runs the command, then prints "== NAME: N s"; returns the command's status
# (also where it is called as `stage … || …`, which turns `set -e` off inside it).
stage() {
  local name=$1 t0=$SECONDS
  shift
  "$@" || return
  echo "== $name: $((SECONDS - t0)) s"
}

sanitizer_build() {
  cmake -S . -B build-asan -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DROTBEAM_SANITIZE=ON \
    -DROTBEAM_FUZZ=ON -DROTBEAM_BUILD_PYTHON=OFF -DROTBEAM_BUILD_TESTS=ON
  cmake --build build-asan -j "$jobs"
}

sanitizer_tests() {
  (cd build-asan && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --output-on-failure -j "$jobs" --timeout 1800 -LE long)
}

fuzz() {
  rm -rf build-asan/corpus && mkdir -p build-asan/corpus && cp fuzz/corpus/* build-asan/corpus/
  ./build-asan/fuzz/fuzz_config build-asan/corpus -max_total_time="$fuzz_seconds" \
    -rss_limit_mb=4096 -timeout=30 -print_final_stats=1 2>&1 | grep -E "^(Done|stat::number_of_executed_units|stat::new_units_added)|ERROR|SUMMARY" || true
  test "${PIPESTATUS[0]}" -eq 0
  echo "fuzz: no crash"
}

echo "== release build and tests"
stage "release build" bash scripts/build.sh -DROTBEAM_BUILD_TESTS=ON
if [ "$quick" != 1 ]; then
  # The sanitizer build, beside the Release tests: its output in build-asan.log, shown on a failure.
  (renice -n 10 "$BASHPID" > /dev/null
   stage "sanitizer build" sanitizer_build > build-asan.log 2>&1 || { tail -n 60 build-asan.log; exit 1; }
   grep "^== " build-asan.log) &
  background+=("$!")
fi
stage "release tests" bash -c "cd build && ctest --output-on-failure -j $jobs --timeout 900"
if [ "$quick" = 1 ]; then
  echo "== total: $((SECONDS - started)) s"
  exit 0
fi

renice -n 0 -g "${background[0]}" > /dev/null 2>&1 || true  # nothing to give way to any more (as root)
wait "${background[0]}"
background=()
rm -f build-asan.log

echo "== fuzzing the configuration parser for $fuzz_seconds s, beside the sanitizer tests"
# At a lower priority than the tests: it takes the time they leave a core idle (at their priority it
# ran four times the inputs and made the sanitizer stage a minute longer).
(renice -n 10 "$BASHPID" > /dev/null
 stage "fuzz" fuzz > build-asan/fuzz.log 2>&1 || { cat build-asan/fuzz.log; exit 1; }
 cat build-asan/fuzz.log) &
background+=("$!")
echo "== AddressSanitizer + UndefinedBehaviorSanitizer tests (all but the tests labelled long)"
stage "sanitizer tests" sanitizer_tests
wait "${background[0]}"
background=()
echo "== total: $((SECONDS - started)) s"
