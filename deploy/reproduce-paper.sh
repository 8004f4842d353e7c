#!/usr/bin/env bash
# The paper in one command: an ensemble of compressions for mu = 0.5 and one for mu = 0, analyzed
# live by fnet-server, then the report folder: the figures, curves.csv (+ curves.csv.json, its
# provenance) and report.md, which states each finding of the paper's Sec. IV with the numbers
# measured here, their bootstrap intervals over the realizations, and whether it holds.
#
# Defaults (10 realizations per friction of 2 000 disks at v_c = 1e-4, 4x the paper's speed) finish
# in about 15 minutes on 2 cores. The paper's setting:
#   REALIZATIONS=20 SPEED=2.5e-5 bash deploy/reproduce-paper.sh
# Environment: REALIZATIONS (10), PARTICLES (2000), SPEED (v_c, 1e-4), FRAMES (100), JOBS (2),
# BIN_WIDTH (0.005), REPORT_DIR (paper-report), PORT (7717), DOMAIN_ID (7), BIN_DIR (build),
# START (quiescent): how each realization starts, before the compression:
#   quiescent  relaxed until at rest (fnet-simd's default: damped until the kinetic energy is tiny)
#   fixed400   relaxed for a fixed 400 tau_c without damping (--relax-energy 0 --relax-damping 0
#              --relax-max-time 400); its ensembles are named with the suffix -fixed400.
# Both starts into the same REPORT_DIR (one run after the other) and the report of the second adds a
# section comparing them before jamming (python3 -m fnet paper-report --compare-start A=B).
# Progress: every 30 s and after each ensemble, the frames fnet-server has analyzed over all
# realizations of both ensembles, with an ETA from the rate so far. At the end it prints the time
# spent simulating (the ensembles' wall time, summed) apart from the analysis and report time; the
# report's settings hold both.
# Interrupted (Ctrl-C), the same command resumes every realization from its checkpoint; interrupted
# while the report is written, it leaves the report files as they were.
set -euo pipefail
cd "$(dirname "$0")/.."
realizations=${REALIZATIONS:-10}
particles=${PARTICLES:-2000}
speed=${SPEED:-1e-4}
frames=${FRAMES:-100}
jobs=${JOBS:-2}
bin_width=${BIN_WIDTH:-0.005}
report=${REPORT_DIR:-paper-report}
port=${PORT:-7717}
domain=${DOMAIN_ID:-7}
build=${BIN_DIR:-build}
start=${START:-quiescent}
python=/usr/bin/python3
export CYCLONEDDS_URI="file://$PWD/deploy/cyclonedds-loopback.xml"

fail() {
  echo "reproduce-paper: $*" >&2
  exit 1
}
[[ $realizations =~ ^[1-9][0-9]*$ ]] || fail "REALIZATIONS must be a positive integer (got '$realizations')"
[[ $jobs =~ ^[1-9][0-9]*$ ]] || fail "JOBS must be a positive integer (got '$jobs')"
[[ $frames =~ ^[1-9][0-9]*$ ]] || fail "FRAMES must be a positive integer (got '$frames')"
case $start in
  quiescent) start_flags=() suffix="" other_suffix="-fixed400" ;;
  fixed400) start_flags=(--relax-energy 0 --relax-damping 0 --relax-max-time 400) suffix="-fixed400" other_suffix="" ;;
  *) fail "START must be quiescent or fixed400 (got '$start')" ;;
esac

if [ ! -x "$build/bin/fnet-server" ] || [ ! -x "$build/bin/fnet-simd" ]; then
  echo "== set-up and build (fnet binaries not found in $build)"
  [ "$build" = build ] || fail "no fnet binaries in BIN_DIR=$build: build them there first"
  bash deploy/setup.sh
  bash deploy/build.sh -DFNET_BUILD_TESTS=OFF
fi
[ -x "$python" ] && "$python" -c 'import numpy, h5py, matplotlib' 2>/dev/null ||
  fail "$python with numpy, h5py and matplotlib is needed: run 'bash deploy/setup.sh'"

mkdir -p "$report/runs" "$report/store"
report=$(cd "$report" && pwd)
started=$(date +%s)

pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT
trap 'echo; echo "reproduce-paper: interrupted; the same command resumes every realization" >&2; exit 130' INT TERM

"$build/bin/fnet-server" --data-dir "$report/store" --port "$port" --domain "$domain" \
  > "$report/server.log" 2>&1 &
server_pid=$!
pids+=("$server_pid")
for _ in $(seq 300); do
  grep -q "listening on 127.0.0.1:$port " "$report/server.log" 2>/dev/null && break
  kill -0 "$server_pid" 2>/dev/null || break
  sleep 0.1
done
grep -q "listening on 127.0.0.1:$port " "$report/server.log" 2>/dev/null && kill -0 "$server_pid" 2>/dev/null ||
  fail "fnet-server did not start on 127.0.0.1:$port (see $report/server.log); set PORT to a free port"
echo "$(grep listening "$report/server.log"), stores in $report/store"

mus=(0.5 0)
names=()
for mu in "${mus[@]}"; do names+=("paper-mu${mu/./}-n$particles-v$speed$suffix"); done
total=$((${#mus[@]} * realizations * frames))

# The frames fnet-server has analyzed of the given ensembles, summed (ensembles.list).
analyzed() {
  "$build/bin/fnetctl" --port "$port" ensembles --format csv 2>/dev/null |
    awk -F, -v list="$*" 'BEGIN { n = split(list, e, " "); for (i = 1; i <= n; i++) want[e[i]] = 1 }
                          ($1 in want) { sum += $3 } END { print sum + 0 }'
}
duration() { printf '%d min %02d s' $(($1 / 60)) $(($1 % 60)); }
# One progress line: frames analyzed over all realizations of both ensembles, and the ETA from the
# rate since this command started simulating (frames analyzed before, by a resumed run, excluded).
progress() {
  local done elapsed eta
  done=$(analyzed "${names[@]}")
  elapsed=$(($(date +%s) - sim_started))
  if ((done >= total)); then
    eta="done"
  elif ((done > done_before && elapsed > 0)); then
    eta="ETA $(duration $(((total - done) * elapsed / (done - done_before))))"
  else
    eta="ETA unknown (no frame analyzed yet)"
  fi
  echo "   [$(duration "$elapsed")] fnet-server: $done of $total frames analyzed ($((100 * done / total)) %), $eta"
}

sim_started=$(date +%s)
done_before=$(analyzed "${names[@]}")
sim_seconds=0
sim_text=""
ensembles=()
for k in "${!mus[@]}"; do
  mu=${mus[$k]}
  name=${names[$k]}
  ensembles+=("$mu=$name")
  echo "== ensemble $name: mu = $mu, $realizations realizations of $particles disks, v_c = $speed, $frames frames," \
    "$start start, $jobs at a time"
  t0=$(date +%s)
  "$build/bin/fnet-simd" --ensemble "$name" --seeds "1-$realizations" --jobs "$jobs" --mu "$mu" \
    --particles "$particles" --compression-speed "$speed" --frames "$frames" --domain "$domain" \
    "${start_flags[@]}" --out "$report/runs/{run}.run.h5" --checkpoint "$report/runs/{run}.fnetsim" --quiet &
  simd_pid=$!
  pids+=("$simd_pid")
  # fnet-simd prints each realization's start and end; every 30 s, the progress line.
  ticks=0
  while kill -0 "$simd_pid" 2>/dev/null; do
    sleep 1
    if ((++ticks % 30 == 0)); then progress; fi
  done
  wait "$simd_pid" || fail "fnet-simd ensemble $name failed (logs: $report/runs/*.log)"
  seconds=$(($(date +%s) - t0))
  sim_seconds=$((sim_seconds + seconds))
  sim_text+="${sim_text:+, }mu $mu: $seconds s"
  echo "   simulated in $seconds s"
  progress
done

# Wait until the server has analyzed every frame of every realization (it keeps pace, but the
# last frames may still be in flight).
echo "== waiting for fnet-server to analyze the last frames"
t0=$(date +%s)
"$python" - "$port" "$realizations" "$frames" "${ensembles[@]}" <<'EOF'
import sys, time
sys.path.insert(0, "client/python")
import fnet
port, realizations, frames = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
names = [e.split("=", 1)[1] for e in sys.argv[4:]]
try:
    with fnet.Client(port=port) as c:
        deadline = time.time() + 600
        while True:
            listed = {e["ensemble"]: e for e in c.ensembles()}
            done = [listed.get(n, {}).get("frames", 0) for n in names]
            if all(d >= realizations * frames for d in done):
                break
            if time.time() > deadline:
                sys.exit(f"reproduce-paper: the server analyzed only {done} of {realizations * frames} frames per "
                         "ensemble")
            time.sleep(1)
except KeyboardInterrupt:
    sys.exit(130)
EOF
wait_seconds=$(($(date +%s) - t0))

echo "== report"
report_started=$(date +%s)
report_interrupted() {
  echo "reproduce-paper: interrupted while writing the report; its files are as they were (rerun to write it)" >&2
  exit 130
}
trap report_interrupted INT TERM
args=()
for e in "${ensembles[@]}"; do args+=(--ensemble "$e"); done
# The other start of the same setting, when an earlier command left its ensembles in this folder.
listed=$("$build/bin/fnetctl" --port "$port" ensembles --format csv | cut -d, -f1)
for k in "${!mus[@]}"; do
  other="paper-mu${mus[$k]/./}-n$particles-v$speed$other_suffix"
  if grep -qx -- "$other" <<< "$listed"; then
    if [ "$start" = quiescent ]; then args+=(--compare-start "${names[$k]}=$other"); else args+=(--compare-start "$other=${names[$k]}"); fi
  fi
done
status=0
PYTHONPATH=client/python "$python" -m fnet paper-report --port "$port" "${args[@]}" --bins "$bin_width" \
  --out "$report" --setting "realizations=$realizations" --setting "particles=$particles" \
  --setting "compression speed v_c=$speed d/tau_c" --setting "frames per realization=$frames" \
  --setting "start=$start" --setting "jobs=$jobs" --setting "rho bin width=$bin_width" \
  --setting "simulation wall time=$sim_seconds s ($sim_text)" \
  --setting "waiting for the last frames=$wait_seconds s" || status=$?
((status == 130)) && report_interrupted
((status == 0)) || fail "the report failed (exit $status)"
kill -0 "$server_pid" 2>/dev/null || fail "fnet-server stopped (see $report/server.log)"
finished=$(date +%s)
echo "report: $report/report.md"
echo "time: simulation $sim_seconds s ($sim_text), waiting for the analysis $wait_seconds s," \
  "report $((finished - report_started)) s; $((finished - started)) s in all"
