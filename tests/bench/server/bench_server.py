#!/usr/bin/env python3
"""fnet-server throughput, lag and query latency on 2 000-particle frames (not run by CTest).

usage: bench_server.py BUILD_DIR [--frames 100] [--threads 2] [--particles 2000] [--speed 1e-3]

1. fnet-simd runs a compression of PARTICLES disks (--no-dds, CSV export) to make a realistic run.
2. fnet-analyze publish replays it onto DDS as fast as DDS takes it; the server analyzes every
   frame (validation, PD0 + PD1 of both force networks, the twelve exact distances to the
   previous frame, the store): sustained frames/s = frames / (last commit - first arrival).
3. fnet-simd runs the same compression live, publishing to the server: lag = time from the
   daemon's exit (its last frame) to the server's last commit, and the largest number of frames
   waiting (server.status) - the simulation's frame rate is the anchor the server must keep up with.
4. series.get on the 100-frame run: median and 99th percentile of 300 calls.
"""
import argparse, os, shutil, statistics, subprocess, tempfile, time

from fnet_service import DDS_ENV as env, Binaries, start_server as start_fnet_server, stop

p = argparse.ArgumentParser()
p.add_argument("build")
p.add_argument("--frames", type=int, default=100)
p.add_argument("--threads", type=int, default=2)
p.add_argument("--particles", type=int, default=2000)
p.add_argument("--speed", type=float, default=1e-3)
p.add_argument("--domain", type=int, default=77)
a = p.parse_args()

bins = Binaries(a.build)
simd, analyze = bins.simd, bins.analyze
box = 50 * (a.particles / 2000) ** 0.5
sim_args = ["--particles", str(a.particles), "--box", f"{box:.4f}", "--compression-speed", str(a.speed),
            "--frames", str(a.frames), "--seed", "5", "--quiet"]
work = tempfile.mkdtemp(prefix="fnet-bench-server-")


def start_server(name, domain):
    return start_fnet_server(bins, os.path.join(work, name), os.path.join(work, name + ".log"), domain, a.threads)


def wait_run(rpc, run, frames, poll=0.01, watch=None):
    first = None
    while True:
        status = rpc.call("server.status")
        if watch is not None:
            watch.append(status["lag"]["frames_in_flight"])
        for r in status["runs"]:
            if r["run"] == run:
                if first is None and (r["frames"] + r["pending"]) > 0:
                    first = time.perf_counter()
                if r["frames"] + r["rejected"] >= frames and r["pending"] == 0:
                    return first, time.perf_counter()
        time.sleep(poll)


try:
    t = time.perf_counter()
    subprocess.run([simd, *sim_args, "--no-dds", "--export-csv", os.path.join(work, "csv")], check=True, env=env)
    sim_seconds = time.perf_counter() - t
    rows = []

    # Throughput: a recorded run replayed at full speed.
    proc, rpc = start_server("replay", a.domain)
    pub = subprocess.Popen([analyze, "publish", "--csv-dir", os.path.join(work, "csv"), "--run-id", "replay",
                            "--domain", str(a.domain)], env=env, stderr=subprocess.DEVNULL)
    inflight = []
    first, last = wait_run(rpc, "replay", a.frames, watch=inflight)
    pub.wait()
    fps = (a.frames - 1) / (last - first)
    lat = []
    for _ in range(300):
        t = time.perf_counter()
        rpc.call("series.get", {"run": "replay", "metric": "wasserstein2", "dim": 1})
        lat.append(1e3 * (time.perf_counter() - t))
    lat.sort()
    stop(proc)

    # Lag behind the simulation running live at full speed.
    proc, rpc = start_server("live", a.domain + 1)
    t0 = time.perf_counter()
    sim = subprocess.Popen([simd, *sim_args, "--run-id", "live", "--domain", str(a.domain + 1), "--ack-timeout", "0"], env=env)
    live_inflight = []
    sim.wait()
    sim_end = time.perf_counter()
    _, live_last = wait_run(rpc, "live", a.frames, watch=live_inflight)
    stop(proc)
    sim_fps = a.frames / sim_seconds

    print(f"fnet-server on {a.frames} frames of {a.particles} disks (v_c = {a.speed}), {a.threads} analysis threads, "
          f"{os.cpu_count()} cores")
    print(f"{'measure':52s} {'fnet-server':>12s} {'anchor':>12s}")
    print(f"{'sustained frames/s (replayed run, 12 exact distances)':52s} {fps:12.1f} {'>= 50 goal':>12s}")
    print(f"{'frames/s the simulation produces (fnet-simd alone)':52s} {'':12s} {sim_fps:12.2f}")
    print(f"{'lag: last commit after the live daemon ended (s)':52s} {live_last - sim_end:12.3f} {'':>12s}")
    print(f"{'frames waiting, max (replay / live)':52s} {max(inflight):6d} / {max(live_inflight):3d} {'':>12s}")
    label = f"series.get, {a.frames} frames: median / p99 (ms)"
    print(f"{label:52s} {statistics.median(lat):5.2f} / {lat[int(0.99 * len(lat))]:4.2f} {'< 5 goal':>12s}")
finally:
    shutil.rmtree(work, ignore_errors=True)
