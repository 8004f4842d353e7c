"""fnet vs Hera (gudhi.hera) vs POT's exact network simplex vs GUDHI's exact bottleneck, one run.

usage: compare_anchors.py FNET_ANALYZE [--sizes 1000,5000,20000] A.json B.json [A2.json B2.json ...]

1. Each LAMMPS pair on pd0 and pd1 (floor convention: never-dying classes die at 0, so every tool
   sees the same finite diagrams), with d_B + W1 + W2 against Hera per pair and dimension, fnet's
   computation and its whole process (`fnet-analyze distance`, median of 5 runs of each metric);
   then the sum of fnet's twelve distances per frame pair.
2. Larger pairs built from the last pair's pd1 (copies with jitter, then a perturbed copy: what
   consecutive frames look like): ~1 000, 5 000 and 20 000 points; then random pairs of those sizes
   shaped like consecutive frames (random_pair: few points on a common line).
3. The approximate mode on the LAMMPS pairs' pd1, then at 1 000, 5 000 and 20 000 points: delta, time,
   the certified bound, the true relative error against the exact value, fnet and Hera at the same
   delta.

fnet's time is the "seconds" it reports (computation only, JSON parsing excluded); the anchors are
timed around their call. Hera runs at relative error 0.01 (it has no exact Wasserstein). The
diagrams are handed to GUDHI and Hera as (death, birth): the superlevel diagrams lie below the
diagonal, and GUDHI's bottleneck silently ignores such points (it returned 0.0 in 0.0 ms);
swapping the coordinates keeps every L-infinity distance. POT needs the dense (n+1) x (m+1)
matrix and GUDHI's exact bottleneck takes ~30 s at 5 000 points, so both run up to 5 000 only.
"""
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

POT_MAX_POINTS = 5000
FNET_TIMEOUT = 60  # seconds per fnet call; a timeout prints as nan (the 20 000-point exact W1/W2)
APPROX_TIMEOUT = 600  # the approximate-mode table needs the exact value at 20 000 points


def finite(points):
    return np.array([[b, 0.0 if d == -1 else d] for b, d in points if b != (0.0 if d == -1 else d)],
                    dtype=float).reshape(-1, 2)


def fnet(exe, fa, fb, dim, metric, delta=0.0, timeout=FNET_TIMEOUT):
    try:
        out = subprocess.run([exe, "distance", fa, fb, "--metric", metric, "--dim", str(dim), "--delta", str(delta)],
                             capture_output=True, text=True, check=True, timeout=timeout).stdout
    except subprocess.TimeoutExpired:
        nan = float("nan")
        return nan, nan, nan, nan
    j = json.loads(out)
    return j["value"], j["seconds"], j["lower"], j["upper"]


def timed(f):
    t = time.perf_counter()
    v = f()
    return v, time.perf_counter() - t


def pot_wasserstein(a, b, q):
    import ot
    n, m = len(a), len(b)
    c = np.zeros((n + 1, m + 1))
    c[:n, :m] = np.max(np.abs(a[:, None, :] - b[None, :, :]), axis=2) ** q
    c[:n, m] = ((a[:, 0] - a[:, 1]) / 2) ** q
    c[n, :m] = ((b[:, 0] - b[:, 1]) / 2) ** q
    wa = np.append(np.ones(n), m)
    wb = np.append(np.ones(m), n)
    return float(ot.emd2(wa, wb, c, numItermax=100_000_000)) ** (1 / q)


def swapped(points):
    """(birth, death) rows as (death, birth): GUDHI and Hera ignore points below the diagonal."""
    return np.ascontiguousarray(points[:, ::-1])


def hera(a, b, q, delta=0.01):
    """Hera's distance between two finite diagrams at relative error delta (q None: bottleneck)."""
    import gudhi.hera
    if q is None:
        return gudhi.hera.bottleneck_distance(swapped(a), swapped(b), delta=delta)
    return gudhi.hera.wasserstein_distance(swapped(a), swapped(b), order=q, internal_p=np.inf, delta=delta)


def gudhi_bottleneck(a, b):
    """GUDHI's exact bottleneck distance between two finite diagrams."""
    import gudhi
    return gudhi.bottleneck_distance(swapped(a), swapped(b), 0)


def anchors(a, b, q):
    """(hera value, hera s, POT value, POT s, gudhi value, gudhi s) for q (None: bottleneck)."""
    nan = float("nan")
    if q is None:
        hv, ht = timed(lambda: hera(a, b, None))
        gv, gt = nan, nan
        if max(len(a), len(b)) <= POT_MAX_POINTS:  # 30 s at 5 000 points
            gv, gt = timed(lambda: gudhi_bottleneck(a, b))
        return hv, ht, nan, nan, gv, gt
    hv, ht = timed(lambda: hera(a, b, q))
    pv, pt = nan, nan
    if max(len(a), len(b)) <= POT_MAX_POINTS:
        pv, pt = timed(lambda: pot_wasserstein(a, b, q))
    return hv, ht, pv, pt, nan, nan


HEADER = (f"{'pair':<36}{'dim':>4}{'pts':>7}  {'metric':<11}{'fnet ms':>10}{'hera ms':>10}{'POT ms':>10}"
          f"{'gudhi ms':>10}{'hera/fnet':>11}  {'fnet value':>14}{'hera/fnet-1':>13}{'POT/fnet-1':>12}{'gudhi/fnet-1':>13}")


def rel(x, v):
    return (x / v - 1) if v and x == x else (0.0 if x == v else float("nan"))


def pair_name(fa, fb):
    """"A->B" from two diagram files' paths."""
    return fa.split("/")[-1].replace(".json", "") + "->" + fb.split("/")[-1].replace(".json", "")


def whole_process(exe, fa, fb, dim, metric, runs):
    """Median wall time of `fnet-analyze distance` as a user runs it: start-up, reading the two
    documents, the computation, writing the answer."""
    cmd = [exe, "distance", fa, fb, "--metric", metric, "--dim", str(dim)]
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        subprocess.run(cmd, capture_output=True, check=True)
        times.append(time.perf_counter() - t)
    return sorted(times)[len(times) // 2]


WHOLE_RUNS = 5


def compare(exe, name, fa, fb, a, b, dim, whole=False):
    """The three metrics' rows; with whole, then the line d_B + W1 + W2 against Hera, fnet's
    computation and its whole process (median of WHOLE_RUNS runs of each command)."""
    total, whole_total, hera_total = 0.0, 0.0, 0.0
    for metric, q in (("bottleneck", None), ("W1", 1), ("W2", 2)):
        cli = {"bottleneck": "bottleneck", "W1": "wasserstein1", "W2": "wasserstein2"}[metric]
        v, t, _, _ = fnet(exe, fa, fb, dim, cli)
        total += t
        hv, ht, pv, pt, gv, gt = anchors(a, b, q)
        hera_total += ht
        if whole:
            whole_total += whole_process(exe, fa, fb, dim, cli, WHOLE_RUNS)
        print(f"{name:<36}{dim:>4}{max(len(a), len(b)):>7}  {metric:<11}{t*1e3:>10.1f}{ht*1e3:>10.1f}{pt*1e3:>10.1f}"
              f"{gt*1e3:>10.1f}{ht / t if t else float('inf'):>10.1f}x  {v:>14.8g}{rel(hv, v):>13.2e}{rel(pv, v):>12.2e}"
              f"{rel(gv, v):>13.2e}", flush=True)
    if whole:
        print(f"{name:<36}{dim:>4}  d_B + W1 + W2: Hera {hera_total*1e3:.1f} ms; fnet computation {total*1e3:.1f} ms "
              f"({hera_total / total:.1f}x), whole process {whole_total*1e3:.1f} ms ({hera_total / whole_total:.1f}x)",
              flush=True)
    return total


def write_pd1(path, points):
    with open(path, "w") as f:
        json.dump({"pd0": [], "pd1": [[float(x), float(y)] for x, y in points]}, f)


def scaled_pair(base, size, rng):
    """A: copies of base, each point's coordinates scaled by 1 + 5% noise (distinct values, same
    structure: most points on y = 0 under floor); B: A moved by up to 1% of the mean birth, 2% of the
    points dropped and as many small new ones added."""
    reps = int(np.ceil(size / len(base)))
    a = np.concatenate([base * (1 + 0.05 * rng.random((len(base), 1))) for _ in range(reps)])[:size]
    scale = float(np.mean(a[:, 0]))
    b = a + rng.uniform(-0.01, 0.01, a.shape) * scale
    b[a[:, 1] == 0, 1] = 0  # floor'ed classes stay at 0
    b[:, 0] = np.maximum(b[:, 0], b[:, 1])
    keep = rng.random(len(b)) > 0.02
    b = b[keep]
    extra = rng.random((size - len(b), 1)) * 0.2 * scale
    b = np.concatenate([b, np.hstack([extra, np.zeros_like(extra)])])
    b = b[b[:, 0] > b[:, 1]]
    return a, b


def random_pair(size, rng):
    """Births uniform in [0, 5], deaths uniform below, 15 % never-dying (death 0 under floor), 10 %
    duplicates; B moved by up to 0.001, 3 % dropped, 3 % added near the diagonal (the shape of
    tests/common/distance/large_inputs_test.cpp): few points on one line, no line start."""
    births = rng.random(size) * 5
    deaths = births * rng.random(size)
    deaths[rng.random(size) < 0.15] = 0.0
    a = np.stack([births, deaths], axis=1)
    dup = rng.random(size) < 0.1
    a[dup] = a[rng.integers(0, size, int(dup.sum()))]
    b = a + rng.uniform(-0.001, 0.001, a.shape)
    b[a[:, 1] == 0, 1] = 0.0
    b[:, 0] = np.maximum(b[:, 0], 0.0)
    b[:, 1] = np.clip(b[:, 1], 0.0, b[:, 0])
    b = b[rng.random(size) > 0.03]
    picked = a[rng.integers(0, size, size // 30)]
    picked = picked[picked[:, 1] > 0]  # as tests/common/distance: never-dying classes spawn none
    mids = (picked[:, 0] + picked[:, 1]) / 2
    b = np.concatenate([b, np.stack([mids + 0.001 * rng.random(len(mids)), mids], axis=1)])
    return a[a[:, 0] > a[:, 1]], b[b[:, 0] > b[:, 1]]


def main(argv):
    exe = argv[1]
    files = argv[2:]
    sizes = (1000, 5000, 20000)
    if files[:1] == ["--sizes"]:
        sizes = tuple(int(s) for s in files[1].split(","))
        files = files[2:]
    print("== LAMMPS frame pairs (floor) ==")
    print(HEADER)
    sums = {}
    approx = []  # the approximate-mode pairs: the LAMMPS pairs' pd1 first, then the perturbed copies
    for k in range(0, len(files), 2):
        fa, fb = files[k], files[k + 1]
        name = pair_name(fa, fb)
        frames = name.replace("_normal", "").replace("_tangential", "")
        da, db = json.load(open(fa)), json.load(open(fb))
        for dim in (0, 1):
            a, b = finite(da[f"pd{dim}"]), finite(db[f"pd{dim}"])
            sums[frames] = sums.get(frames, 0.0) + compare(exe, name, fa, fb, a, b, dim, whole=True)
        approx.append((name, fa, fb, a, b, APPROX_DELTAS_LAMMPS))  # a, b: the pd1s
    for frames, s in sums.items():
        print(f"fnet, twelve exact distances of {frames} (d_B, W1, W2 x pd0, pd1 x normal, tangential): "
              f"{s*1e3:.1f} ms")

    base = finite(json.load(open(files[-1]))["pd1"])
    rng = np.random.default_rng(2026)
    print("\n== Larger pairs: jittered copies of the last pair's pd1 (then random pairs), B a perturbed copy of A ==")
    print(HEADER)
    with tempfile.TemporaryDirectory() as tmp:
        for size in sizes:
            a, b = scaled_pair(base, size, rng)
            fa, fb = os.path.join(tmp, f"a{size}.json"), os.path.join(tmp, f"b{size}.json")
            write_pd1(fa, a)
            write_pd1(fb, b)
            compare(exe, f"perturbed copies {size}", fa, fb, a, b, 1)
            if size in APPROX_DELTAS:
                approx.append((f"perturbed copies {size}", fa, fb, a, b, APPROX_DELTAS[size]))
        for size in sizes:
            a, b = random_pair(size, rng)
            fa, fb = os.path.join(tmp, f"ra{size}.json"), os.path.join(tmp, f"rb{size}.json")
            write_pd1(fa, a)
            write_pd1(fb, b)
            compare(exe, f"random {size}", fa, fb, a, b, 1)

        approximate_mode(exe, approx)


APPROX_DELTAS = {1000: (0.5, 0.1, 0.01, 0.001), 5000: (0.1, 0.01, 0.001), 20000: (0.1, 0.01)}
APPROX_DELTAS_LAMMPS = (0.2, 0.1, 0.05, 0.01)


def approximate_mode(exe, pairs):
    """delta, time, the certified bound reached and the true error against the exact value, fnet
    and Hera at the same delta: pairs is a list of (label, A.json, B.json, a, b, deltas), pd1."""
    print("\n== Approximate mode (pd1): certified bounds against the exact value ==")
    print(f"{'pair':<36}{'metric':<8}{'delta':>8}{'fnet ms':>10}{'hera ms':>10}{'value':>16}{'lower':>16}"
          f"{'true rel err':>14}{'bound (u-l)/l':>15}{'hera rel err':>14}")
    for label, fa, fb, a, b, deltas in pairs:
        for metric, q in (("W1", 1), ("W2", 2)):
            cli = {"W1": "wasserstein1", "W2": "wasserstein2"}[metric]
            exact, et, _, _ = fnet(exe, fa, fb, 1, cli, timeout=APPROX_TIMEOUT)
            print(f"{label:<36}{metric:<8}{0:>8g}{et*1e3:>10.1f}{float('nan'):>10.1f}{exact:>16.10g}{exact:>16.10g}"
                  f"{0:>14.2e}{0:>15.2e}{float('nan'):>14.2e}", flush=True)
            for delta in deltas:
                v, t, lo, up = fnet(exe, fa, fb, 1, cli, delta, timeout=APPROX_TIMEOUT)
                hv, ht = timed(lambda: hera(a, b, q, delta))
                print(f"{label:<36}{metric:<8}{delta:>8g}{t*1e3:>10.1f}{ht*1e3:>10.1f}{v:>16.10g}{lo:>16.10g}"
                      f"{v / exact - 1:>14.2e}{(up - lo) / lo if lo else 0:>15.2e}{hv / exact - 1:>14.2e}", flush=True)


if __name__ == "__main__":
    main(sys.argv)
