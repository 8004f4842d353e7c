#!/usr/bin/env bash
# A bounded libFuzzer run of every fuzz target (deploy/test.sh runs it): builds the targets with
# clang, AddressSanitizer and UndefinedBehaviorSanitizer in build-fuzz/ (FNET_FUZZ=ON), then runs
# each for FUZZ_SECONDS (default 20) from its corpus. New inputs go to build-fuzz/fuzz-work/TARGET/,
# never into the repository; a crash, a leak, an input slower than 10 s, an allocation over 512 MiB
# or an error that names no input fails the run, leaving the input in build-fuzz/fuzz-work/TARGET/
# and its report in .../log. Arguments: the targets to run (default: all); FUZZ_SECONDS and
# FUZZ_BUILD_DIR override the time and the build directory.
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${FUZZ_SECONDS:-20}
build=${FUZZ_BUILD_DIR:-build-fuzz}

cmake -S . -B "$build" -DFNET_FUZZ=ON -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" -DCMAKE_C_FLAGS_DEBUG="-g -O1" -DCMAKE_UNITY_BUILD=ON >/dev/null
cmake --build "$build" -j"$(nproc)" --target fnet_fuzz

if [ $# -gt 0 ]; then
  targets=("$@")
else
  mapfile -t targets < <(sed -n 's/^fnet_fuzz_target(\([a-z0-9_]*\) .*/\1/p' tests/fuzz/CMakeLists.txt)
fi
# AddressSanitizer's quarantine (freed memory held back to catch a use after it is freed) at
# 32 MiB, not 256: far more than one input frees, and memory that stays mapped and warm instead of
# fresh pages each input (a third of the file-reading targets' time).
export ASAN_OPTIONS="${ASAN_OPTIONS:-quarantine_size_mb=32}"
failed=()
for t in "${targets[@]}"; do
  work="$build/fuzz-work/$t"
  rm -rf "$work"
  mkdir -p "$work/corpus"
  flags=(-max_total_time="$seconds" -timeout=10 -malloc_limit_mb=512 -rss_limit_mb=2048 -print_final_stats=1
    -artifact_prefix="$work/" "$work/corpus" "tests/fuzz/corpus/$t")
  if [ "$t" = store ]; then
    # HDF5 1.10.8 loops forever on some damaged global heaps (README, store; fnet-server reads such
    # a store only in a child process under a deadline): libFuzzer runs this target in a child it
    # restarts past a timeout, and the run fails on any crash, sanitizer report or memory bound,
    # read from its log (its exit status at the time limit says nothing).
    "$build/tests/fuzz/fnet_fuzz_$t" -fork=1 -ignore_timeouts=1 "${flags[@]}" >"$work/log" 2>&1 || true
    if grep -qE "ERROR: (AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|libFuzzer: (deadly|out-of-memory|malloc))|runtime error:|oom/timeout/crash: ([1-9][0-9]*/[0-9]+/[0-9]+|[0-9]+/[0-9]+/[1-9])" "$work/log"; then
      store_ok=false
    else
      store_ok=true
    fi
  fi
  if { [ "$t" = store ] && $store_ok; } || { [ "$t" != store ] && "$build/tests/fuzz/fnet_fuzz_$t" "${flags[@]}" >"$work/log" 2>&1; }; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log")
    [ -n "$runs" ] || runs=$(grep -oE "^#[0-9]+" "$work/log" | tail -1 | tr -d '#')
    echo "fuzz $t: ${runs:-?} inputs in ${seconds} s, no finding"
  else
    echo "fuzz $t: FAILED (report: $work/log)"
    grep -E "ERROR|fuzz: |SUMMARY|Test unit written" "$work/log" | head -20 || true
    failed+=("$t")
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: findings in ${failed[*]}"
  exit 1
fi
