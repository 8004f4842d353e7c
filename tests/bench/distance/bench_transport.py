"""Exact W1 and W2 on the 30 000-point stacked pair (stacked_pair.py) against Hera, one run.

usage: bench_transport.py BENCH_TRANSPORT FNET_ANALYZE FRAMES_DIR [--deltas 1,0.1,0.01,0.001] [--skip-hera]

For W1 and W2: fnet's whole process (`fnet-analyze distance`, reading the documents included) and
its computation (`seconds`), exact; then fnet's approximate mode at each delta (computation,
certified bounds) and Hera (gudhi.hera.wasserstein_distance, internal_p = inf) at the same delta,
timed around its call only, in a child process; the true relative errors against fnet's exact
value. In-process work counters of the exact solve from BENCH_TRANSPORT (pivots, pricing rounds,
pair arcs in the final graph). The load average is printed before and after.
"""
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def fnet_process(exe, fa, fb, metric, delta=0.0):
    t = time.perf_counter()
    out = subprocess.run([exe, "distance", fa, fb, "--metric", metric, "--dim", "1", "--delta", str(delta)],
                         capture_output=True, text=True, check=True).stdout
    wall = time.perf_counter() - t
    j = json.loads(out)
    return j["value"], j["lower"], j["seconds"], wall


def hera(fa, fb, q, delta):
    code = ("import json, sys, time\nimport numpy as np\nimport gudhi.hera\n"
            "def load(p):\n    return np.array([[d, b] for b, d in json.load(open(p))['pd1']], dtype=float).reshape(-1, 2)\n"
            f"a, b = load({fa!r}), load({fb!r})\nt = time.perf_counter()\n"
            f"v = gudhi.hera.wasserstein_distance(a, b, order={q}, internal_p=np.inf, delta={delta})\n"
            "print(v, time.perf_counter() - t)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    return float(out[0]), float(out[1])


def counters(bench, fa, fb, q):
    out = subprocess.run([bench, "--q", str(q), "--solver", "auto", fa, fb], capture_output=True, text=True,
                         check=True).stdout.split()
    return {"pivots": int(out[4]), "rounds": int(out[5]), "arcs": int(out[6]), "solver": out[8]}


def main(argv):
    bench, exe, frames = argv[1:4]
    deltas, skip_hera = (1.0, 0.1, 0.01, 0.001), False
    rest = argv[4:]
    for k, arg in enumerate(rest):
        if arg == "--deltas":
            deltas = tuple(float(d) for d in rest[k + 1].split(","))
        elif arg == "--skip-hera":
            skip_hera = True
    print(f"load average before: {os.getloadavg()[0]:.2f}")
    with tempfile.TemporaryDirectory() as tmp:
        fa, fb = os.path.join(tmp, "stacked_a.json"), os.path.join(tmp, "stacked_b.json")
        subprocess.run([sys.executable, os.path.join(HERE, "stacked_pair.py"), exe, frames, fa, fb], check=True)
        na, nb = (len(json.load(open(f))["pd1"]) for f in (fa, fb))
        print(f"stacked pair: {na} + {nb} points")
        print(f"{'metric':<7}{'delta':>7}{'fnet ms':>10}{'process ms':>12}{'hera ms':>11}{'hera/process':>14}"
              f"{'value':>20}{'lower':>20}{'true err':>10}{'hera err':>10}")
        for metric, q in (("wasserstein1", 1), ("wasserstein2", 2)):
            exact, _, secs, wall = fnet_process(exe, fa, fb, metric)
            c = counters(bench, fa, fb, q)
            hv, ht = hera(fa, fb, q, 0.01) if not skip_hera else (float("nan"), float("nan"))
            print(f"W{q:<6}{'exact':>7}{secs*1e3:>10.1f}{wall*1e3:>12.1f}{ht*1e3:>11.1f}{ht / wall:>13.1f}x"
                  f"{exact:>20.12g}{exact:>20.12g}{0:>10.1e}{hv / exact - 1:>10.1e}   (Hera at delta 0.01; "
                  f"{c['solver']}: {c['pivots']} pivots, {c['rounds']} pricing rounds, {c['arcs']} pair arcs)",
                  flush=True)
            for delta in deltas:
                v, lo, secs, wall = fnet_process(exe, fa, fb, metric, delta)
                hv, ht = hera(fa, fb, q, delta) if not skip_hera else (float("nan"), float("nan"))
                print(f"W{q:<6}{delta:>7g}{secs*1e3:>10.1f}{wall*1e3:>12.1f}{ht*1e3:>11.1f}{ht / wall:>13.1f}x"
                      f"{v:>20.12g}{lo:>20.12g}{v / exact - 1:>10.1e}{hv / exact - 1:>10.1e}", flush=True)
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main(sys.argv)
