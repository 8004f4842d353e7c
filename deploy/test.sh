#!/usr/bin/env bash
# README's test command (and CI's): installs what is missing, builds with warnings as errors, runs
# the whole test suite; then builds again in Debug with AddressSanitizer and
# UndefinedBehaviorSanitizer and runs the tests of the maths, the codecs, the stores and the API
# there.
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/setup.sh
jobs=$(nproc)

bash deploy/build.sh -DFNET_BUILD_TESTS=ON -DFNET_WERROR=ON
ctest --test-dir build --output-on-failure --timeout 900 -j"$jobs"

# -O1 keeps the sanitized distance and persistence tests within minutes; benchmarks are not built.
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" -DCMAKE_C_FLAGS_DEBUG="-g -O1" \
  -DFNET_SANITIZE=ON -DFNET_WERROR=ON -DFNET_BUILD_TESTS=ON -DFNET_BUILD_BENCH=OFF
cmake --build build-sanitize -j"$jobs"
ctest --test-dir build-sanitize --output-on-failure --timeout 900 -j"$jobs" \
  -L '^(topology|distance|analysis|codec|store|e2e)$' -LE '^(slow|oracle)$'
