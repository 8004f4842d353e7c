#!/usr/bin/env bash
# README's test command: installs what is missing, builds, runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/setup.sh
bash deploy/build.sh -DFNET_BUILD_TESTS=ON
ctest --test-dir build --output-on-failure --timeout 600 -j"$(nproc)"
