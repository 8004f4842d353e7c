#!/usr/bin/env bash
# deploy/demo.sh on a port another fnet-server already owns: the demo must fail loudly, naming the
# address, and must not stream its run to the other server nor claim a store it never wrote.
# usage: demo_port_taken_test.sh SOURCE_DIR BUILD_DIR
set -uo pipefail
src=$1 build=$2
tmp=$(mktemp -d)
occupant=
cleanup() {
  [ -n "$occupant" ] && kill "$occupant" 2>/dev/null && wait "$occupant" 2>/dev/null
  rm -rf "$tmp"
}
trap cleanup EXIT
export CYCLONEDDS_URI="file://$src/deploy/cyclonedds-loopback.xml"
domain=53

"$build/bin/fnet-server" --data-dir "$tmp/other" --port 0 --domain "$domain" > "$tmp/other.log" 2>&1 &
occupant=$!
port=
for _ in $(seq 300); do
  port=$(sed -n 's/.*listening on 127\.0\.0\.1:\([0-9]*\) .*/\1/p' "$tmp/other.log")
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || { echo "FAIL: the occupying fnet-server did not start"; cat "$tmp/other.log"; exit 1; }

PORT=$port DOMAIN_ID=$domain DATA_DIR="$tmp/demo" BIN_DIR="$build" PARTICLES=50 FRAMES=3 \
  timeout 300 bash "$src/deploy/demo.sh" > "$tmp/demo.out" 2>&1
rc=$?
status=0
if [ "$rc" -eq 0 ]; then echo "FAIL: demo.sh exited 0 with port $port taken"; status=1; fi
if ! grep -q "127.0.0.1:$port" "$tmp/demo.out"; then echo "FAIL: demo.sh did not name 127.0.0.1:$port"; status=1; fi
if grep -q "run store:" "$tmp/demo.out"; then echo "FAIL: demo.sh printed a store path"; status=1; fi
if ls "$tmp/other"/demo-*.h5 > /dev/null 2>&1; then echo "FAIL: the demo streamed its run to the other server"; status=1; fi
if [ "$status" -ne 0 ]; then
  echo "--- demo.sh output (rc $rc)"
  cat "$tmp/demo.out"
fi
exit "$status"
