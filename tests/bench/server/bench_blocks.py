#!/usr/bin/env python3
"""blocks.get on a 2 000-disk pair with k = 2 (not run by CTest).

usage: bench_blocks.py BUILD_DIR [--frames 10] [--particles 2000] [--speed 1e-3] [--k 2] [--calls 30]

fnet-simd runs a compression of PARTICLES disks (--no-dds, CSV export); fnet-analyze publish
replays it to a fresh fnet-server (DDS domain 85), which stores every frame with its network.
Then blocks.get between the last two frames (the most contacts), for bottleneck and W2 of PD0 and
PD1: the median and the largest of CALLS round trips, and the server's own `seconds` (reading both
networks back from the store, cutting them into blocks, the cells' diagrams and distances).
"""
import argparse, os, shutil, statistics, subprocess, tempfile, time

from fnet_service import DDS_ENV as env, Binaries, start_server, stop

p = argparse.ArgumentParser()
p.add_argument("build")
p.add_argument("--frames", type=int, default=10)
p.add_argument("--particles", type=int, default=2000)
p.add_argument("--speed", type=float, default=1e-3)
p.add_argument("--k", type=int, default=2)
p.add_argument("--calls", type=int, default=30)
p.add_argument("--domain", type=int, default=85)
a = p.parse_args()

bins = Binaries(a.build)
simd, analyze = bins.simd, bins.analyze
box = 50 * (a.particles / 2000) ** 0.5
work = tempfile.mkdtemp(prefix="fnet-bench-blocks-")

proc = None
try:
    subprocess.run([simd, "--particles", str(a.particles), "--box", f"{box:.4f}", "--compression-speed", str(a.speed),
                    "--frames", str(a.frames), "--seed", "5", "--quiet", "--no-dds", "--export-csv",
                    os.path.join(work, "csv")], check=True, env=env)
    proc, rpc = start_server(bins, os.path.join(work, "data"), os.path.join(work, "server.log"), a.domain, threads=2)
    subprocess.run([analyze, "publish", "--csv-dir", os.path.join(work, "csv"), "--run-id", "bench", "--domain",
                    str(a.domain)], check=True, env=env, stderr=subprocess.DEVNULL)
    while True:
        run = rpc.call("run.get", {"run": "bench"}) if any(r["run"] == "bench" for r in rpc.call("runs.list")["runs"]) else None
        if run and run["frames"] + run["rejected"] >= a.frames and run["pending"] == 0:
            break
        time.sleep(0.05)
    last = run["last_frame"]
    store = os.path.join(work, "data", "bench.h5")
    print(f"blocks.get, k = {a.k}, frames {last - 1} and {last} of a {a.particles}-disk fnet-simd run "
          f"(rho {run['rho']:.4f}, Z {run['z']:.3f}); {a.calls} calls each; {os.cpu_count()} cores, shared machine")
    print(f"store: {os.path.getsize(store) / 1e6:.2f} MB for {run['frames']} frames")
    print(f"{'metric':14s} {'dim':>3s} {'round trip median / max (ms)':>30s} {'server seconds median (ms)':>28s} "
          f"{'contacts per cell':>20s}")
    for metric in ["bottleneck", "wasserstein2"]:
        for dim in [0, 1]:
            params = {"run": "bench", "frame": last - 1, "other_frame": last, "k": a.k, "metric": metric, "dim": dim}
            trips, server = [], []
            for _ in range(a.calls):
                t = time.perf_counter()
                r = rpc.call("blocks.get", params)
                trips.append(1e3 * (time.perf_counter() - t))
                server.append(1e3 * r["seconds"])
            contacts = "/".join(str(c["contacts"][1]) for c in r["cells"])
            print(f"{metric:14s} {dim:3d} {statistics.median(trips):17.2f} / {max(trips):8.2f} "
                  f"{statistics.median(server):28.2f} {contacts:>20s}")
finally:
    if proc:
        stop(proc)
    shutil.rmtree(work, ignore_errors=True)
