#!/usr/bin/env bash
# The main job on a small default, after `deploy/build.sh`: fnet-server and fnet-simd on loopback,
# a compression of a few hundred disks watched live with fnetctl, then its W2 series.
# Override with environment variables: PARTICLES, SPEED, FRAMES, PORT, DOMAIN_ID, DATA_DIR.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build
particles=${PARTICLES:-400}
speed=${SPEED:-5e-4}
frames=${FRAMES:-60}
port=${PORT:-7707}
domain=${DOMAIN_ID:-0}
data=${DATA_DIR:-build/demo-data}
export CYCLONEDDS_URI="file://$PWD/deploy/cyclonedds-loopback.xml"

run_id="demo-$(date +%Y%m%d-%H%M%S)"
mkdir -p "$data"

pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT

"$bin/server/analysis/fnet-server" --data-dir "$data" --port "$port" --domain "$domain" > "$data/server.log" 2>&1 &
pids+=($!)
for _ in $(seq 100); do grep -q listening "$data/server.log" 2>/dev/null && break; sleep 0.1; done
echo "fnet-server: $(head -1 "$data/server.log")"

# The box is sized so that the disks start at rho 0.63 (fnet-simd's --rho-initial), as the paper's.
echo "fnet-simd: $particles disks, wall speed $speed d/tau_c, $frames frames, run $run_id"
"$bin/server/sim/fnet-simd" --particles "$particles" --compression-speed "$speed" --frames "$frames" \
  --run-id "$run_id" --domain "$domain" --out "$data/$run_id.run.h5" --quiet > "$data/simd.log" 2>&1 &
pids+=($!)

# Wait for the run to appear, then watch it live until its last frame.
for _ in $(seq 600); do "$bin/client/fnetctl" --port "$port" runs 2>/dev/null | grep -q "$run_id" && break; sleep 0.2; done
if [ -t 1 ]; then watch_mode=(); else watch_mode=(--plain); fi
"$bin/client/fnetctl" --port "$port" watch --run "$run_id" --until-complete "${watch_mode[@]}"

echo
echo "== fnetctl query --metric wasserstein2 --run $run_id (PD0, normal forces) =="
"$bin/client/fnetctl" --port "$port" query --metric wasserstein2 --run "$run_id"
echo
echo "run store: $data/$run_id.h5 (schema proto/store.md); frames: $data/$run_id.run.h5 (proto/run_file.md)"
