#!/usr/bin/env bash
# README's first command: installs what is missing, builds, and runs the main job on a small
# default: simulate (fnet-simd) -> stream (DDS, loopback) -> analyze (fnet-server) -> query (fnetctl).
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/setup.sh
bash deploy/build.sh -DFNET_BUILD_TESTS=OFF -DCMAKE_UNITY_BUILD=OFF
bash deploy/demo.sh
