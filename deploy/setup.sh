#!/usr/bin/env bash
# Installs every Debian package that fnet's build, tests and benchmarks need.
# Idempotent and non-interactive; run as root (or through sudo) on Debian 12.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake pkg-config git ca-certificates
  # libraries of the design
  libeigen3-dev libhdf5-dev libboost-dev libboost-program-options-dev zlib1g-dev
  nlohmann-json3-dev cyclonedds-dev cyclonedds-tools libssl-dev
  # TLS test certificates are made by the tests
  openssl
  # tests
  libgtest-dev libgmock-dev googletest clang-format
  # the fuzz targets (tests/fuzz): clang with libFuzzer and the sanitizers' runtimes, llvm-symbolizer;
  # clang and llvm give the unversioned names (clang, clang++, llvm-symbolizer) that they call
  clang-14 libclang-rt-14-dev libfuzzer-14-dev llvm-14 clang llvm
  # independent oracles used by tests and benchmarks
  libgudhi-dev python3 python3-gudhi python3-numpy python3-scipy python3-pot python3-h5py
  # the Python client (client/python) and its tests; pip install ./client/python into a venv
  python3-matplotlib python3-pytest python3-yaml python3-venv python3-wheel
  lammps
  # process tools used by end-to-end tests
  procps iproute2 netcat-openbsd
  # the dashboard's tests in a real browser (tests/e2e/dashboard_browser_test.py)
  chromium chromium-driver python3-selenium
)

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update
  "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
fi
