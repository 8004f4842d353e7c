#!/usr/bin/env python3
"""ensemble.series latency over an ensemble of RUNS realizations x FRAMES frames (not run by CTest).

usage: bench_ensemble.py BUILD_DIR [--runs 20] [--frames 100] [--particles 60] [--domain 76]

1. fnet-simd runs RUNS small compressions (seeds 1..RUNS, --ensemble bench, no DDS, run files);
   fnet-analyze store analyzes each into one data directory; fnet-server loads the stores.
2. ensemble.series (bottleneck PD1, bin width 0.002) over the whole ensemble: median and 99th
   percentile of 300 calls on one connection, the answer parsed (the goal: < 50 ms); also against
   rho - rho_J, a ratio curve, and W_q for q = 3 (not stored: computed from the diagrams).
3. The anchor: numpy computing the same bins from the stores read with h5py (the samples, their
   bins, each run's means, their mean and standard error across the runs, the counts and mean
   Z), timed the same way; its bins are checked against the served ones.
"""
import argparse, os, shutil, statistics, subprocess, sys, tempfile, time

import h5py
import numpy as np

from fnet_service import Binaries, start_server, stop

p = argparse.ArgumentParser()
p.add_argument("build")
p.add_argument("--runs", type=int, default=20)
p.add_argument("--frames", type=int, default=100)
p.add_argument("--particles", type=int, default=60)
p.add_argument("--domain", type=int, default=76)
a = p.parse_args()

bins = Binaries(a.build)
simd, analyze = bins.simd, bins.analyze
work = tempfile.mkdtemp(prefix="fnet-bench-ensemble-")
data = os.path.join(work, "data")
WIDTH = 0.002


def timed(fn, calls):
    times = []
    for _ in range(calls):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    times.sort()
    return statistics.median(times) * 1e3, times[int(0.99 * (len(times) - 1))] * 1e3


def numpy_bins(paths, column):
    """The bins of ensemble.series (bin width WIDTH, axis rho) from the stores, with numpy: per bin
    each run's means first, then the mean over the runs and its standard error across them."""
    rho, z, value, run = [], [], [], []
    for k, path in enumerate(paths):
        with h5py.File(path, "r", libver="latest", swmr=True) as f:
            n = len(f["frame"])
            previous = f["previous"][:n]
            keep = previous >= 0
            keep[0] = False  # the first committed frame has no previous frame in the series
            rho.append(f["rho"][:n][keep])
            z.append(f["z"][:n][keep])
            value.append(f["distances"][:n, column][keep])
            run.append(np.full(int(keep.sum()), k))
    rho, z, value, run = (np.concatenate(x) for x in (rho, z, value, run))
    index = np.floor(rho / WIDTH).astype(np.int64)
    pairs, pair_of, frames = np.unique(np.column_stack([index, run]), axis=0, return_inverse=True,
                                       return_counts=True)
    pair_of = pair_of.ravel()
    run_means = [np.bincount(pair_of, x) / frames for x in (rho, z, value)]
    keys, bin_of, runs = np.unique(pairs[:, 0], return_inverse=True, return_counts=True)
    m_rho, m_z, mean = (np.bincount(bin_of, m) / runs for m in run_means)
    squares = np.bincount(bin_of, (run_means[2] - mean[bin_of]) ** 2)
    with np.errstate(invalid="ignore", divide="ignore"):
        stderr = np.where(runs >= 2, np.sqrt(squares / (runs - 1)) / np.sqrt(runs), np.nan)
    return {"rho_lo": keys * WIDTH, "rho": m_rho, "mean": mean, "stderr": stderr, "n_runs": runs,
            "n": np.bincount(bin_of, frames).astype(np.int64), "z": m_z}


server = None
try:
    t = time.perf_counter()
    for seed in range(1, a.runs + 1):
        run_file = os.path.join(work, f"s{seed}.h5")
        subprocess.run([simd, "--particles", str(a.particles), "--compression-speed", "1e-2", "--frames",
                        str(a.frames), "--seed", str(seed), "--ensemble", "bench", "--no-dds", "--out", run_file,
                        "--quiet"], check=True, stderr=subprocess.DEVNULL)
        subprocess.run([analyze, "store", "--run-file", run_file, "--data-dir", data], check=True,
                       stdout=subprocess.DEVNULL)
    print(f"made {a.runs} runs x {a.frames} frames of {a.particles} disks in {time.perf_counter() - t:.1f} s",
          file=sys.stderr)
    server, rpc = start_server(bins, data, os.path.join(work, "server.log"), a.domain)
    ens = rpc.call("ensembles.list")["ensembles"][0]
    assert ens["ensemble"] == "bench" and len(ens["runs"]) == a.runs, ens
    samples = ens["frames"] - a.runs
    base = {"ensemble": "bench", "dim": 1, "bin_width": WIDTH}
    cases = [("bottleneck PD1, rho", dict(base, metric="bottleneck"), 300),
             ("bottleneck PD1, rho - rho_J", dict(base, metric="bottleneck", axis="rho_minus_rho_j"), 300),
             ("d_B / d_W2 PD1 (ratio curve)", dict(base, ratio="wasserstein2"), 300),
             ("W_q q=3 PD1 (from the diagrams)", dict(base, metric="wasserstein", q=3), 10)]
    ours = [(name, timed(lambda: rpc.call("ensemble.series", params), calls)) for name, params, calls in cases]

    paths = [os.path.join(data, run + ".h5") for run in ens["runs"]]
    anchor = timed(lambda: numpy_bins(paths, 2), 30)
    served, expected = rpc.call("ensemble.series", cases[0][1]), numpy_bins(paths, 2)
    assert served["n"] == expected["n"].tolist() and served["n_runs"] == expected["n_runs"].tolist(), "the bins differ"
    worst = max(float(np.max(np.abs(np.array(served[k], dtype=float) - expected[k]))) for k in ("rho_lo", "rho", "mean", "z"))

    print(f"ensemble.series over {a.runs} runs x {a.frames} frames ({samples} samples, {len(served['n'])} bins "
          f"of width {WIDTH}), {a.particles} disks")
    print(f"{'measure':64} {'median / p99 (ms)':>20}")
    for name, (median, p99) in ours:
        print(f"{'fnet-server ensemble.series: ' + name:64} {median:9.2f} / {p99:7.2f}")
    print(f"{'anchor: numpy + h5py from the stores, same bins':64} {anchor[0]:9.2f} / {anchor[1]:7.2f}")
    print(f"goal: < 50 ms; numpy's bins match the served ones (largest difference {worst:.1e})")
finally:
    if server:
        stop(server)
    shutil.rmtree(work, ignore_errors=True)
