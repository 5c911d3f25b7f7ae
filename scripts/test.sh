#!/usr/bin/env bash
# Builds skyview and runs the whole test suite: a Release build, then the same tests under
# AddressSanitizer and UBSan, then a short fuzzing run of the LAS reader when available.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs=$(nproc)

# The options are given, not left to the cache: the Quick start's first command configures the same
# build folder without tests, and ctest then found none and passed.
# SKYVIEW_PYTHON adds the Python module and its pytest suite (python/tests) to ctest.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSKYVIEW_SANITIZE=OFF -DSKYVIEW_BUILD_TESTS=ON \
  -DSKYVIEW_BUILD_BENCH=ON -DSKYVIEW_PYTHON=ON >/dev/null
cmake --build build -j"$jobs"
(cd build && ctest --output-on-failure --no-tests=error -j"$jobs")

# Without the Python module: an instrumented extension needs the sanitizer runtime preloaded into python.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKYVIEW_SANITIZE=ON -DSKYVIEW_BUILD_TESTS=ON \
  -DSKYVIEW_BUILD_BENCH=OFF -DSKYVIEW_PYTHON=OFF >/dev/null
cmake --build build-asan -j"$jobs"
(cd build-asan &&
  ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure --no-tests=error -j"$jobs")

if [ -f scripts/fuzz.sh ]; then
  bash scripts/fuzz.sh
fi
