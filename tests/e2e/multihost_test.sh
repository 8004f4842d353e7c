#!/usr/bin/env bash
# Three hosts, made here as network namespaces on one bridge: fnet-server on host a; on host b
# fnet-analyze publish, then one half of an ensemble (fnet-simd --seeds 1-2), on host c the other
# half (--seeds 3-4), then on host b a LAMMPS run under mpirun -np 2 followed live by fnet-analyze
# publish --follow (proto/lammps.md's cluster recipe), all with deploy/cyclonedds-hosts.xml (unicast peers, no multicast) on DDS
# domain 82. The server must receive every frame of the publication and of the four realizations,
# each announced in the one ensemble. Exit 77 (skipped) where network namespaces cannot be created.
set -euo pipefail
src=$1 server=$2 analyze=$3 fnetctl=$4 simd=$5 python=$6  # python: the one with numpy and h5py
tag=fn$$
a=${tag}a b=${tag}b c=${tag}c
ip netns add "$a" 2>/dev/null || { echo "cannot create network namespaces: skipped"; exit 77; }
work=$(mktemp -d)
cleanup() {
  for ns in "$a" "$b" "$c"; do for p in $(ip netns pids "$ns" 2>/dev/null); do kill "$p" 2>/dev/null || true; done; done
  sleep 0.5
  for ns in "$a" "$b" "$c"; do for p in $(ip netns pids "$ns" 2>/dev/null); do kill -9 "$p" 2>/dev/null || true; done; done
  for ns in "$a" "$b" "$c"; do ip netns del "$ns" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
ip netns add "$b"
ip netns add "$c"
# Host a holds the bridge (10.231.0.1); b (.2) and c (.3) each hang on it by a veth pair.
ip -n "$a" link add "br$tag" type bridge
for h in b c; do
  ip link add "v${tag}${h}" type veth peer name "p${tag}${h}"
  ip link set "v${tag}${h}" netns "${tag}${h}"
  ip link set "p${tag}${h}" netns "$a"
  ip -n "$a" link set "p${tag}${h}" master "br$tag"
  ip -n "$a" link set "p${tag}${h}" up
done
ip -n "$a" addr add 10.231.0.1/24 dev "br$tag"
ip -n "$b" addr add 10.231.0.2/24 dev "v${tag}b"
ip -n "$c" addr add 10.231.0.3/24 dev "v${tag}c"
for ns in "$a" "$b" "$c"; do ip -n "$ns" link set lo up; done
ip -n "$a" link set "br$tag" up
ip -n "$b" link set "v${tag}b" up
ip -n "$c" link set "v${tag}c" up

# On each host: its interface and the other hosts as peers (the third peer repeats one).
uri="file://$src/deploy/cyclonedds-hosts.xml"
on_a() { ip netns exec "$a" env CYCLONEDDS_URI="$uri" FNET_IFACE="br$tag" FNET_PEER1=10.231.0.2 FNET_PEER2=10.231.0.3 FNET_PEER3=10.231.0.3 "$@"; }
on_b() { ip netns exec "$b" env CYCLONEDDS_URI="$uri" FNET_IFACE="v${tag}b" FNET_PEER1=10.231.0.1 FNET_PEER2=10.231.0.3 FNET_PEER3=10.231.0.3 "$@"; }
on_c() { ip netns exec "$c" env CYCLONEDDS_URI="$uri" FNET_IFACE="v${tag}c" FNET_PEER1=10.231.0.1 FNET_PEER2=10.231.0.2 FNET_PEER3=10.231.0.2 "$@"; }

on_a "$server" --data-dir "$work/data" --port 7707 --domain 82 > "$work/server.out" 2> "$work/server.err" &
for _ in $(seq 100); do grep -q listening "$work/server.out" 2>/dev/null && break; sleep 0.1; done

analyzed() {  # run frames: true once fnet-server lists the run with that many frames, none rejected
  for _ in $(seq 600); do
    if on_a "$fnetctl" --port 7707 runs 2>/dev/null | grep -Eq "^$1 +$2 +0 +0 "; then return 0; fi
    sleep 0.2
  done
  return 1
}
fail() {
  echo "FAILED: $1"; cat "$work/server.err" "$work"/*.err 2>/dev/null || true
  on_a "$fnetctl" --port 7707 runs || true
  exit 1
}

# Frames 0..3 of the LAMMPS reference run, from host b.
mkdir -p "$work/csv"
head -5 "$src/tests/data/lammps-mu0.5-seed777/index.csv" > "$work/csv/index.csv"
cp "$src"/tests/data/lammps-mu0.5-seed777/frame_000[0-3]_*.csv "$work/csv/"
on_b "$analyze" publish --csv-dir "$work/csv" --run-id across --domain 82 --wait-for-reader 30 2> "$work/publish.err"
analyzed across 4 || fail "the server did not analyze the 4 published frames"
echo "ok: 4 frames published in namespace $b analyzed by fnet-server in namespace $a"

# One ensemble fed from two hosts: seeds 1-2 on b, 3-4 on c, at the same time: deploy/README.md's recipe.
small=(--particles 100 --box 11.2 --compression-speed 2e-3 --relax-energy 1e-5 --frames 4 --domain 82 --quiet)
mkdir -p "$work/b" "$work/c"
on_b "$simd" "${small[@]}" --ensemble mh --seeds 1-2 --jobs 2 --checkpoint "$work/b/{run}.fnetsim" 2> "$work/half-b.err" &
half_b=$!
on_c "$simd" "${small[@]}" --ensemble mh --seeds 3-4 --jobs 2 --checkpoint "$work/c/{run}.fnetsim" 2> "$work/half-c.err" &
half_c=$!
wait "$half_b" || fail "the ensemble half on $b exited $?"
wait "$half_c" || fail "the ensemble half on $c exited $?"
for s in 1 2 3 4; do analyzed "mh-s$s" 4 || fail "the server did not analyze the 4 frames of mh-s$s"; done
for s in 1 2 3 4; do
  on_a python3 - "$s" <<'PY' || fail "mh-s$s is not announced in ensemble mh"
import json, socket, sys
with socket.create_connection(("127.0.0.1", 7707)) as sock:
    sock.sendall((json.dumps({"jsonrpc": "2.0", "id": 1, "method": "run.get",
                              "params": {"run": f"mh-s{sys.argv[1]}"}}) + "\n").encode())
    params = json.loads(sock.makefile().readline())["result"]["parameters"]
sys.exit(0 if params["ensemble"] == "mh" and params["seed"] == int(sys.argv[1]) else 1)
PY
done
echo "ok: ensemble mh, seeds 1-2 from namespace $b and 3-4 from namespace $c, analyzed by fnet-server in namespace $a"

# A LAMMPS run on host b under MPI, followed as it runs: proto/lammps.md's cluster recipe, its
# mpi follow block run as written there on the node that sees the dumps.
"$python" "$src/tests/e2e/lammps_follow_test.py" input --source-dir "$src" --build-dir . --workdir "$work/lmp" --domain 82
root=(); [ "$(id -u)" = 0 ] && root=(--allow-run-as-root --oversubscribe)
block=$(python3 - "$src/proto/lammps.md" <<'PY'
import re, sys
blocks = re.findall(r"```sh\n(.*?)```", open(sys.argv[1]).read(), re.S)
print(next(b for b in blocks if b.startswith("mpirun") and "--follow" in b))
PY
)
block=${block/mpirun /mpirun ${root[*]} }
block=${block/--run-id live-mpi/--run-id live-mpi --domain 82 --wait-for-reader 30}
(cd "$work/lmp" && on_b env PATH="$(dirname "$analyze"):$PATH" bash -c "$block" > "$work/follow.out" 2> "$work/follow.err") ||
  fail "the follow block on $b exited $?"
analyzed live-mpi 27 || fail "the server did not analyze the 27 frames of the LAMMPS run followed on $b"
echo "ok: LAMMPS under mpirun -np 2 in namespace $b, followed live, analyzed by fnet-server in namespace $a"
