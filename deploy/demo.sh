#!/usr/bin/env bash
# The main job on a small default, after `deploy/build.sh`: fnet-server and fnet-simd on loopback,
# a compression of a few hundred disks watched live with fnetctl and in a browser (the dashboard's
# address is printed), then its W2 series.
# Override with environment variables: PARTICLES (400 disks), SPEED (v_c, 5e-4 d/tau_c), FRAMES (60),
# PORT (7707, the JSON API's), HTTP_PORT (7708, the dashboard's), DOMAIN_ID (0: the DDS domain
# fnet-simd publishes on and fnet-server reads; another value keeps two demos on one machine apart),
# DATA_DIR (build/demo-data: the server's stores) and BIN_DIR (build: where the programs were built).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BIN_DIR:-build}
particles=${PARTICLES:-400}
speed=${SPEED:-5e-4}
frames=${FRAMES:-60}
port=${PORT:-7707}
http_port=${HTTP_PORT:-7708}
domain=${DOMAIN_ID:-0}
data=${DATA_DIR:-build/demo-data}
export CYCLONEDDS_URI="file://$PWD/deploy/cyclonedds-loopback.xml"

run_id="demo-$(date +%Y%m%d-%H%M%S)"
mkdir -p "$data"

pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT

fail() {
  echo "demo: $*" >&2
  exit 1
}

# Talk to the port only once our own server said it listens there: if the port is taken, another
# process (perhaps another fnet-server with other data) would answer and the demo would lie.
"$build/bin/fnet-server" --data-dir "$data" --port "$port" --http-port "$http_port" --domain "$domain" \
  > "$data/server.log" 2>&1 &
server_pid=$!
pids+=("$server_pid")
for _ in $(seq 300); do
  grep -q "listening on 127.0.0.1:$port " "$data/server.log" 2>/dev/null && break
  kill -0 "$server_pid" 2>/dev/null || break
  sleep 0.1
done
if ! grep -q "listening on 127.0.0.1:$port " "$data/server.log" 2>/dev/null || ! kill -0 "$server_pid" 2>/dev/null; then
  sed 's/^/  /' "$data/server.log" >&2
  fail "fnet-server did not start on 127.0.0.1:$port (dashboard :$http_port; log above, in $data/server.log); set PORT and HTTP_PORT to free ports"
fi
echo "fnet-server: $(grep listening "$data/server.log")"
for _ in $(seq 50); do grep -q "dashboard on" "$data/server.log" && break; sleep 0.1; done
echo "dashboard: $(sed -n 's/.*dashboard on //p' "$data/server.log") (open it in a browser to watch the run)"

# The box is sized so that the disks start at rho 0.63 (fnet-simd's --rho-initial), as the paper's.
echo "fnet-simd: $particles disks, wall speed $speed d/tau_c, $frames frames, run $run_id"
"$build/bin/fnet-simd" --particles "$particles" --compression-speed "$speed" --frames "$frames" \
  --run-id "$run_id" --domain "$domain" --out "$data/$run_id.run.h5" --quiet > "$data/simd.log" 2>&1 &
simd_pid=$!
pids+=("$simd_pid")

# Wait for the run to appear, then watch it live until its last frame.
for _ in $(seq 600); do
  "$build/bin/fnetctl" --port "$port" runs 2>/dev/null | grep -q "$run_id" && break
  kill -0 "$server_pid" 2>/dev/null || fail "fnet-server stopped (see $data/server.log)"
  kill -0 "$simd_pid" 2>/dev/null || { wait "$simd_pid" && break || fail "fnet-simd failed (see $data/simd.log)"; }
  sleep 0.2
done
if [ -t 1 ]; then watch_mode=(); else watch_mode=(--plain); fi
"$build/bin/fnetctl" --port "$port" watch --run "$run_id" --until-complete "${watch_mode[@]}"

echo
echo "== fnetctl query --metric wasserstein2 --run $run_id (PD1, normal forces) =="
"$build/bin/fnetctl" --port "$port" query --metric wasserstein2 --run "$run_id"
kill -0 "$server_pid" 2>/dev/null || fail "fnet-server stopped during the demo (see $data/server.log)"
for f in "$data/$run_id.h5" "$data/$run_id.run.h5"; do [ -f "$f" ] || fail "$f was not written"; done
echo
echo "run store: $data/$run_id.h5 (schema proto/store.md); frames: $data/$run_id.run.h5 (proto/run_file.md)"
