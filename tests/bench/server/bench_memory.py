#!/usr/bin/env python3
"""fnet-server's peak memory against the number of runs it serves: for each count of runs, a
fresh fnet-server is fed that many runs of FRAMES frames of PARTICLES disks over DDS, then asked
for every frame's diagram (diagram.get) and every run's series (series.get); printed, its peak
resident memory (VmHWM) once fed and once every diagram was read, for each count.

usage: bench_memory.py BUILD_DIR [--runs 10,100] [--frames 100] [--particles 2000]
                       [--batch 10] [--domain 218] [--server-arg=--cache-mib=64 ...]

fnet-simd records one compression of PARTICLES disks (--no-dds, CSV export); `fnet-analyze
publish` replays it onto DDS under as many run ids, BATCH publishers at a time, each batch waited
for (every frame acknowledged and stored). --server-arg passes an option to fnet-server.
"""
import argparse, os, re, shutil, subprocess, tempfile, time

from fnet_service import DDS_ENV, Binaries, Rpc, record_compression

p = argparse.ArgumentParser()
p.add_argument("build")
p.add_argument("--runs", default="10,100")
p.add_argument("--frames", type=int, default=100)
p.add_argument("--particles", type=int, default=2000)
p.add_argument("--batch", type=int, default=10)
p.add_argument("--domain", type=int, default=218)
p.add_argument("--server-arg", action="append", default=[])
a = p.parse_args()
bins = Binaries(a.build)


def peak_rss_mib(pid):
    with open(f"/proc/{pid}/status") as f:
        return int(re.search(r"VmHWM:\s+(\d+)", f.read()).group(1)) / 1024


def measure(work, csv, runs):
    """Feeds `runs` runs to a fresh fnet-server, reads them all back; its peak RSS (MiB), its
    frames committed, and its last server.status."""
    data = os.path.join(work, f"data-{runs}")
    server = subprocess.Popen([bins.server, "--data-dir", data, "--port", "0", "--domain", str(a.domain),
                               "--threads", "2", *a.server_arg], stdout=subprocess.PIPE,
                              stderr=open(os.path.join(work, f"server-{runs}.log"), "w"), env=DDS_ENV, text=True)
    try:
        port = int(re.search(r":(\d+) ", server.stdout.readline()).group(1))
        names = [f"mem-{k:03d}" for k in range(runs)]
        for first in range(0, runs, a.batch):
            batch = [subprocess.Popen([bins.analyze, "publish", "--csv-dir", csv, "--run-id", run, "--domain",
                                       str(a.domain), "--wait-for-reader", "60", "--ack-timeout", "600"],
                                      env=DDS_ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                     for run in names[first:first + a.batch]]
            for proc in batch:
                proc.wait()
        rpc = Rpc(port)  # connected now: a connection without a request is closed after 10 s
        while True:
            listed = rpc.call("runs.list")["runs"]
            if len(listed) == runs and all(r["pending"] == 0 and r["unstored"] == 0 and
                                           r["frames"] + r["rejected"] >= a.frames for r in listed):
                break
            time.sleep(0.2)
        fed = peak_rss_mib(server.pid)
        for run in names:
            rpc.call("series.get", {"run": run, "metric": "bottleneck"})
            for frame in range(a.frames):
                rpc.call("diagram.get", {"run": run, "frame": frame})
        status = rpc.call("server.status")
        return fed, peak_rss_mib(server.pid), sum(r["frames"] for r in listed), status
    finally:
        server.terminate()
        server.wait()


work = tempfile.mkdtemp(prefix="fnet-bench-memory-")
try:
    csv = os.path.join(work, "csv")
    record_compression(bins, csv, a.particles, a.frames)
    print(f"fnet-server peak RSS, runs of {a.frames} frames of {a.particles} disks, every diagram read back"
          + (f" ({' '.join(a.server_arg)})" if a.server_arg else ""))
    print(f"{'runs':>5} {'frames':>7} {'fed: peak RSS MiB':>18} {'read: peak RSS MiB':>19}  cache")
    for runs in (int(n) for n in a.runs.split(",")):
        fed, read, frames, status = measure(work, csv, runs)
        cache = status.get("cache")
        print(f"{runs:5d} {frames:7d} {fed:18.1f} {read:19.1f}  {cache if cache is not None else '-'}", flush=True)
finally:
    shutil.rmtree(work, ignore_errors=True)
