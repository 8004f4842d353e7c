#!/usr/bin/env bash
# The paper in one command: an ensemble of compressions for mu = 0.5 and one for mu = 0, analyzed
# live by fnet-server, then the report folder: the figures, curves.csv and report.md, which states
# each finding of the paper's Sec. IV with the numbers measured here and whether it holds.
#
# Defaults (10 realizations per friction of 2 000 disks at v_c = 1e-4, 4x the paper's speed) finish
# in about 15 minutes on 2 cores. The paper's setting:
#   REALIZATIONS=20 SPEED=2.5e-5 bash deploy/reproduce-paper.sh
# Environment: REALIZATIONS (10), PARTICLES (2000), SPEED (v_c, 1e-4), FRAMES (100), JOBS (2),
# BIN_WIDTH (0.005), REPORT_DIR (paper-report), PORT (7717), DOMAIN_ID (7), BIN_DIR (build).
# Interrupted (Ctrl-C), the same command resumes every realization from its checkpoint.
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
bin=${BIN_DIR:-build}
python=/usr/bin/python3
export CYCLONEDDS_URI="file://$PWD/deploy/cyclonedds-loopback.xml"

fail() {
  echo "reproduce-paper: $*" >&2
  exit 1
}
[[ $realizations =~ ^[1-9][0-9]*$ ]] || fail "REALIZATIONS must be a positive integer (got '$realizations')"
[[ $jobs =~ ^[1-9][0-9]*$ ]] || fail "JOBS must be a positive integer (got '$jobs')"

if [ ! -x "$bin/server/analysis/fnet-server" ] || [ ! -x "$bin/server/sim/fnet-simd" ]; then
  echo "== set-up and build (fnet binaries not found in $bin)"
  [ "$bin" = build ] || fail "no fnet binaries in BIN_DIR=$bin: build them there first"
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

"$bin/server/analysis/fnet-server" --data-dir "$report/store" --port "$port" --domain "$domain" \
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

ensembles=()
for mu in 0.5 0; do
  name="paper-mu${mu/./}-n$particles-v$speed"
  ensembles+=("$mu=$name")
  echo "== ensemble $name: mu = $mu, $realizations realizations of $particles disks, v_c = $speed, $frames frames, $jobs at a time"
  t0=$(date +%s)
  "$bin/server/sim/fnet-simd" --ensemble "$name" --seeds "1-$realizations" --jobs "$jobs" --mu "$mu" \
    --particles "$particles" --compression-speed "$speed" --frames "$frames" --domain "$domain" \
    --out "$report/runs/{run}.run.h5" --checkpoint "$report/runs/{run}.fnetsim" --quiet &
  simd_pid=$!
  pids+=("$simd_pid")
  # fnet-simd prints each realization's start and end; every 30 s, what the server has analyzed.
  ticks=0
  while kill -0 "$simd_pid" 2>/dev/null; do
    sleep 1
    if (( ++ticks % 30 == 0 )); then
      analyzed=$("$bin/client/fnetctl" --port "$port" ensembles --format csv 2>/dev/null |
        awk -F, -v e="$name" '$1 == e { print $3 }')
      echo "   [$(($(date +%s) - t0)) s] fnet-server: ${analyzed:-0} of $((realizations * frames)) frames of $name analyzed"
    fi
  done
  wait "$simd_pid" || fail "fnet-simd ensemble $name failed (logs: $report/runs/*.log)"
  echo "   simulated in $(($(date +%s) - t0)) s"
done

# Wait until the server has analyzed every frame of every realization (it keeps pace, but the
# last frames may still be in flight).
echo "== waiting for fnet-server to analyze the last frames"
"$python" - "$port" "$realizations" "$frames" "${ensembles[@]}" <<'EOF'
import sys, time
sys.path.insert(0, "client/python")
import fnet
port, realizations, frames = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
names = [e.split("=", 1)[1] for e in sys.argv[4:]]
with fnet.Client(port=port) as c:
    deadline = time.time() + 600
    while True:
        listed = {e["ensemble"]: e for e in c.ensembles()}
        done = [listed.get(n, {}).get("frames", 0) for n in names]
        if all(d >= realizations * frames for d in done):
            break
        if time.time() > deadline:
            sys.exit(f"reproduce-paper: the server analyzed only {done} of {realizations * frames} frames per ensemble")
        time.sleep(1)
EOF

echo "== report"
args=()
for e in "${ensembles[@]}"; do args+=(--ensemble "$e"); done
PYTHONPATH=client/python "$python" -m fnet paper-report --port "$port" "${args[@]}" --bins "$bin_width" \
  --out "$report" --setting "realizations=$realizations" --setting "particles=$particles" \
  --setting "compression speed v_c=$speed d/tau_c" --setting "frames per realization=$frames" \
  --setting "jobs=$jobs" --setting "rho bin width=$bin_width" \
  --setting "simulation and analysis time=$(($(date +%s) - started)) s"
kill -0 "$server_pid" 2>/dev/null || fail "fnet-server stopped (see $report/server.log)"
echo "report: $report/report.md ($(($(date +%s) - started)) s in all)"
