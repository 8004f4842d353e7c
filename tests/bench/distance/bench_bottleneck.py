"""The exact bottleneck distance against Hera's (gudhi.hera, delta 0.01), one run, same inputs.

usage: bench_bottleneck.py BENCH_BOTTLENECK A.json B.json [A2.json B2.json ...]

Inputs: the given frame pairs' pd1 (real, ~1 200 points), then pairs of 5 000, 20 000 and 50 000
points of three shapes, B always a perturbed copy of A: "pd1-like", ~95 % of the points on the
line death = 0 (never-dying loops under floor), every coordinate moved by up to 0.1 % of the
range, 3 % dropped, 3 % added near the diagonal; "stacked real", copies of the last pair's pd1
with 5 % jitter (as compare_anchors.py builds its large pairs); "random", births uniform in
[0, 5], 15 % never-dying, 10 % duplicates, moved by up to 0.001, 3 % dropped and 3 % added near
the diagonal (the shape of tests/common/distance/large_inputs_test.cpp). fnet's time is the
median of in-process repeats (JSON parsing excluded); Hera's is timed around its call, in a
child process stopped after HERA_TIMEOUT seconds (printed as >). Both are handed the same finite
diagrams; Hera gets them as (death, birth), see compare_anchors.py.
"""
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

from compare_anchors import finite, pair_name, random_pair, scaled_pair, write_pd1


def pd1_like(size, rng):
    top = 1.0
    on_line = rng.random(size) < 0.95
    births = rng.random(size) * top
    deaths = np.where(on_line, 0.0, births * rng.random(size))
    a = np.stack([births, deaths], axis=1)
    noise = 0.001 * top
    b = a + rng.uniform(-noise, noise, a.shape)
    b[on_line, 1] = 0.0
    b[:, 0] = np.maximum(b[:, 0], 0.0)
    b[:, 1] = np.clip(b[:, 1], 0.0, b[:, 0])
    b = b[rng.random(size) > 0.03]
    mids = a[rng.integers(0, size, size // 30), 0] * rng.random(size // 30)
    b = np.concatenate([b, np.stack([mids + noise * rng.random(len(mids)), mids], axis=1)])
    a = a[a[:, 0] > a[:, 1]]
    b = b[b[:, 0] > b[:, 1]]
    return a, b


HERA_TIMEOUT = 60


def ours(exe, fa, fb, repeat):
    out = subprocess.run([exe, "--repeat", str(repeat), "--dim", "1", fa, fb], capture_output=True, text=True,
                         check=True).stdout.split()
    return float(out[2]), float(out[1]) / 1e3


def hera(fa, fb):
    """Hera's value and seconds, or (nan, inf) past HERA_TIMEOUT."""
    try:
        out = subprocess.run([sys.executable, __file__, "--hera", fa, fb], capture_output=True, text=True,
                             check=True, timeout=HERA_TIMEOUT).stdout.split()
        return float(out[0]), float(out[1])
    except subprocess.TimeoutExpired:
        return float("nan"), float("inf")


def hera_child(fa, fb):
    import gudhi.hera
    a, b = finite(json.load(open(fa))["pd1"]), finite(json.load(open(fb))["pd1"])
    sa, sb = np.ascontiguousarray(a[:, ::-1]), np.ascontiguousarray(b[:, ::-1])
    t = time.perf_counter()
    v = gudhi.hera.bottleneck_distance(sa, sb, delta=0.01)
    print(v, time.perf_counter() - t)


def row(exe, name, fa, fb, a, b):
    n = max(len(a), len(b))
    v, t = ours(exe, fa, fb, 5 if n <= 5000 else 3 if n <= 20000 else 1)
    hv, ht = hera(fa, fb)
    hera_ms = f"{ht*1e3:>11.2f}" if ht != float("inf") else f"{'>' + str(HERA_TIMEOUT * 1000):>11}"
    ratio = f"{ht / t:>10.1f}x" if ht != float("inf") else f"{'>' + format(HERA_TIMEOUT / t, '.0f'):>10}x"
    print(f"{name:<36}{n:>7}{t*1e3:>11.2f}{hera_ms}{ratio}  {v:>20.17g}{hv / v - 1 if v else 0:>12.2e}", flush=True)


def main(argv):
    if argv[1] == "--hera":
        hera_child(argv[2], argv[3])
        return
    exe, files = argv[1], argv[2:]
    print("fnet exact (median of in-process repeats), Hera at delta = 0.01")
    print(f"{'pair':<36}{'pts':>7}{'fnet ms':>11}{'hera ms':>11}{'hera/fnet':>11}  {'fnet value':>20}"
          f"{'hera/fnet-1':>12}")
    for k in range(0, len(files), 2):
        fa, fb = files[k], files[k + 1]
        name = pair_name(fa, fb)
        a, b = finite(json.load(open(fa))["pd1"]), finite(json.load(open(fb))["pd1"])
        row(exe, name, fa, fb, a, b)
    base = finite(json.load(open(files[-1]))["pd1"])
    rng = np.random.default_rng(2026)
    with tempfile.TemporaryDirectory() as tmp:
        for size in (5000, 20000, 50000):
            for shape in ("pd1-like", "stacked real", "random"):
                make = {"pd1-like": pd1_like, "stacked real": lambda n, g: scaled_pair(base, n, g),
                        "random": random_pair}[shape]
                a, b = make(size, rng)
                fa, fb = os.path.join(tmp, "a.json"), os.path.join(tmp, "b.json")
                write_pd1(fa, a)
                write_pd1(fb, b)
                row(exe, f"{shape} {size}", fa, fb, a, b)


if __name__ == "__main__":
    main(sys.argv)
