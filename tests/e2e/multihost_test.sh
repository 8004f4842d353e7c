#!/usr/bin/env bash
# Two hosts, made here as network namespaces joined by a veth pair: fnet-analyze publish on one,
# fnet-server on the other, with deploy/cyclonedds-hosts.xml (unicast peers, no multicast).
# Exit 77 (skipped) where network namespaces cannot be created (not root).
set -euo pipefail
src=$1 server=$2 analyze=$3 fnetctl=$4
tag=fn$$
a=${tag}a b=${tag}b
ip netns add "$a" 2>/dev/null || { echo "cannot create network namespaces: skipped"; exit 77; }
work=$(mktemp -d)
cleanup() {
  for p in $(ip netns pids "$a" 2>/dev/null) $(ip netns pids "$b" 2>/dev/null); do kill "$p" 2>/dev/null || true; done
  sleep 0.5
  for p in $(ip netns pids "$a" 2>/dev/null) $(ip netns pids "$b" 2>/dev/null); do kill -9 "$p" 2>/dev/null || true; done
  ip netns del "$a" 2>/dev/null || true
  ip netns del "$b" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
ip netns add "$b"
ip link add "v${tag}a" type veth peer name "v${tag}b"
ip link set "v${tag}a" netns "$a"
ip link set "v${tag}b" netns "$b"
ip -n "$a" addr add 10.231.0.1/24 dev "v${tag}a"
ip -n "$b" addr add 10.231.0.2/24 dev "v${tag}b"
for ns in "$a" "$b"; do ip -n "$ns" link set lo up; done
ip -n "$a" link set "v${tag}a" up
ip -n "$b" link set "v${tag}b" up

uri="file://$src/deploy/cyclonedds-hosts.xml"
ip netns exec "$a" env CYCLONEDDS_URI="$uri" FNET_IFACE="v${tag}a" FNET_PEER1=10.231.0.2 FNET_PEER2=10.231.0.2 FNET_PEER3=10.231.0.2 \
  "$server" --data-dir "$work/data" --port 7707 > "$work/server.out" 2> "$work/server.err" &
for _ in $(seq 100); do grep -q listening "$work/server.out" 2>/dev/null && break; sleep 0.1; done

# Frames 0..3 of the LAMMPS reference run, from the other host.
mkdir -p "$work/csv"
head -5 "$src/tests/data/lammps-mu0.5-seed777/index.csv" > "$work/csv/index.csv"
cp "$src"/tests/data/lammps-mu0.5-seed777/frame_000[0-3]_*.csv "$work/csv/"
ip netns exec "$b" env CYCLONEDDS_URI="$uri" FNET_IFACE="v${tag}b" FNET_PEER1=10.231.0.1 FNET_PEER2=10.231.0.1 FNET_PEER3=10.231.0.1 \
  "$analyze" publish --csv-dir "$work/csv" --run-id across --wait-for-reader 30 2> "$work/publish.err"

for _ in $(seq 300); do
  if ip netns exec "$a" "$fnetctl" --port 7707 runs 2>/dev/null | grep -Eq "^across +4 +0 +0 "; then
    echo "ok: 4 frames published in namespace $b analyzed by fnet-server in namespace $a"
    exit 0
  fi
  sleep 0.2
done
echo "FAILED: the server did not analyze the 4 frames"; cat "$work/server.err" "$work/publish.err"
ip netns exec "$a" "$fnetctl" --port 7707 runs || true
exit 1
