"""fnet vs Hera (gudhi.hera) vs POT's exact network simplex on the same diagram pairs, one run.

usage: compare_anchors.py FNET_ANALYZE A.json B.json [A2.json B2.json ...]
Each pair is compared on pd0 and pd1 (floor convention: never-dying classes die at 0, so every tool
sees the same finite diagrams). fnet's time is the "seconds" it reports (computation only, JSON
parsing excluded); the anchors are timed around their call. Hera runs at its default relative
error 0.01 (it has no exact Wasserstein); GUDHI's exact bottleneck is gudhi.bottleneck_distance(e=0).
"""
import json
import subprocess
import sys
import time

import numpy as np


def finite(points):
    return np.array([[b, 0.0 if d == -1 else d] for b, d in points if b != (0.0 if d == -1 else d)],
                    dtype=float).reshape(-1, 2)


def fnet(exe, fa, fb, dim, metric, delta=0.0):
    out = subprocess.run([exe, "distance", fa, fb, "--metric", metric, "--dim", str(dim), "--delta", str(delta)],
                         capture_output=True, text=True, check=True).stdout
    j = json.loads(out)
    return j["value"], j["seconds"]


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
    return float(ot.emd2(wa, wb, c, numItermax=10_000_000)) ** (1 / q)


def main(argv):
    import gudhi
    import gudhi.hera
    exe = argv[1]
    files = argv[2:]
    print(f"{'pair':<28}{'dim':>4}{'pts':>7}  {'metric':<8}{'fnet ms':>10}{'hera ms':>10}{'POT ms':>10}"
          f"{'gudhi ms':>10}  {'fnet value':>14}{'hera/fnet-1':>13}{'POT/fnet-1':>12}")
    for k in range(0, len(files), 2):
        fa, fb = files[k], files[k + 1]
        name = fa.split("/")[-1].replace(".json", "") + "->" + fb.split("/")[-1].replace(".json", "")
        da, db = json.load(open(fa)), json.load(open(fb))
        for dim in (0, 1):
            a, b = finite(da[f"pd{dim}"]), finite(db[f"pd{dim}"])
            pts = max(len(a), len(b))
            for metric, q in (("bottleneck", None), ("W1", 1), ("W2", 2)):
                cli = {"bottleneck": "bottleneck", "W1": "wasserstein1", "W2": "wasserstein2"}[metric]
                v, t = fnet(exe, fa, fb, dim, cli)
                if q is None:
                    hv, ht = timed(lambda: gudhi.hera.bottleneck_distance(a, b, delta=0.01))
                    gv, gt = timed(lambda: gudhi.bottleneck_distance(a, b, 0))
                    pv, pt = float("nan"), float("nan")
                else:
                    hv, ht = timed(lambda: gudhi.hera.wasserstein_distance(a, b, order=q, internal_p=np.inf,
                                                                           delta=0.01))
                    pv, pt = timed(lambda: pot_wasserstein(a, b, q))
                    gt = float("nan")
                print(f"{name:<28}{dim:>4}{pts:>7}  {metric:<8}{t*1e3:>10.1f}{ht*1e3:>10.1f}{pt*1e3:>10.1f}"
                      f"{gt*1e3:>10.1f}  {v:>14.8g}{hv/v-1 if v else 0:>13.2e}"
                      f"{(pv/v-1) if v and pv == pv else float('nan'):>12.2e}", flush=True)


if __name__ == "__main__":
    main(sys.argv)
