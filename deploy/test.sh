#!/usr/bin/env bash
# README's test command (and CI's): installs what is missing, builds with warnings as errors, runs
# the whole test suite; then builds again in Debug with AddressSanitizer and
# UndefinedBehaviorSanitizer and runs the tests of the maths, the codecs, the stores and the API
# there; then fuzzes every decoder of outside input for a bounded time (tests/fuzz).
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/setup.sh
jobs=$(nproc)

# Both builds compile the sources of each target in batches (unity build): the headers every file
# includes (JSON, Asio, GoogleTest) are parsed once per batch, which halves the build; the
# quick start's build, file by file, still checks that each file includes what it uses.
bash deploy/build.sh -DFNET_BUILD_TESTS=ON -DFNET_WERROR=ON -DCMAKE_UNITY_BUILD=ON
ctest --test-dir build --output-on-failure --timeout 900 -j"$jobs"

# -O1 keeps the sanitized distance and persistence tests within minutes, -g1 (line tables) names
# the lines of a sanitizer's report; benchmarks are not built. The cases labelled heavy (over
# ~15 s under the sanitizers: large inputs of code the smaller cases cover) ran above.
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" -DCMAKE_C_FLAGS_DEBUG="-g1 -O1" \
  -DFNET_SANITIZE=ON -DFNET_WERROR=ON -DFNET_BUILD_TESTS=ON -DFNET_BUILD_BENCH=OFF -DCMAKE_UNITY_BUILD=ON
cmake --build build-sanitize -j"$jobs"
ctest --test-dir build-sanitize --output-on-failure --timeout 900 -j"$jobs" \
  -L '^(topology|distance|analysis|codec|store|e2e|fuzz)$' -LE '^(slow|oracle|heavy)$'

# Every decoder of outside input under libFuzzer, 20 s each from its corpus (tests/fuzz/README.md):
# a clang build of the fuzz targets alone, then a bounded run; any finding fails.
FUZZ_SECONDS=20 bash tests/fuzz/run_fuzzers.sh
