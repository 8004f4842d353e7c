"""deploy/reproduce-paper.sh end to end on small sizes: two ensembles simulated by fnet-simd,
analyzed live by a real fnet-server, the report folder written. curves.csv is checked against an
independent binning of the distances read from the server's stores with h5py, averaged over the
realizations (so a wrong bin, mean, standard error, count, Z or ratio fails), report.md states every finding with holds / does not
hold, and every figure is a PNG.

usage: reproduce_paper_test.py SOURCE_DIR BUILD_DIR WORK_DIR"""

import csv
import math
import os
import shutil
import socket
import subprocess
import sys

import h5py
import numpy as np

source, build, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
report = os.path.join(work, "report")
BIN_WIDTH = 0.01


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


env = dict(os.environ, REALIZATIONS="2", PARTICLES="100", SPEED="0.02", FRAMES="20", JOBS="2",
           BIN_WIDTH=str(BIN_WIDTH), REPORT_DIR=report, PORT=str(free_port()), DOMAIN_ID="57", BIN_DIR=build)
run = subprocess.run(["bash", os.path.join(source, "deploy", "reproduce-paper.sh")], cwd=source, env=env,
                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=900)
print(run.stdout)
assert run.returncode == 0, f"reproduce-paper.sh exited {run.returncode}"
# Progress was shown while it ran: the daemon's line per realization and frame, the server's start.
assert "-s2: finished (20 frames)" in run.stdout, "no progress shown"
assert "fnet-server listening on 127.0.0.1" in run.stdout

METRICS = ("bottleneck", "wasserstein1", "wasserstein2")
COLUMN = {m: k for k, m in enumerate(METRICS)}


def store_samples(ensemble):
    """(rho, z, twelve distances, store name) of every frame with a previous frame, over the
    ensemble's stores (one per realization)."""
    rows = []
    for name in sorted(os.listdir(os.path.join(report, "store"))):
        if not name.startswith(ensemble + "-s") or not name.endswith(".h5"):
            continue
        with h5py.File(os.path.join(report, "store", name), "r", libver="latest", swmr=True) as f:
            n = len(f["frame"])
            prev, rho, z, d = f["previous"][:n], f["rho"][:n], f["z"][:n], f["distances"][:n]
            for k in range(n):
                if prev[k] >= 0:
                    rows.append((rho[k], z[k], d[k], name))
    return rows


def expected_bins(samples, value):
    """Per bin: each realization's mean of rho, value and z first, then their means over the
    realizations, the standard error of the value across them, and the number of frames."""
    bins = {}
    for rho, z, d, run in samples:
        bins.setdefault(math.floor(rho / BIN_WIDTH), {}).setdefault(run, []).append((rho, z, value(d)))
    out = {}
    for b, runs in bins.items():
        rho, z, v = (np.array(m) for m in zip(*[np.mean(np.array(members), axis=0) for members in runs.values()]))
        se = float(np.std(v, ddof=1) / math.sqrt(len(v))) if len(v) > 1 else math.nan
        out[b] = (float(np.mean(rho)), float(np.mean(v)), se, sum(map(len, runs.values())), float(np.mean(z)))
    return out


with open(os.path.join(report, "curves.csv"), newline="") as f:
    reader = csv.reader(f)
    header = next(reader)
    assert header == ["mu", "force", "dim", "metric", "rho", "mean", "stderr", "n", "z"], header
    rows = list(reader)
names = {"0.5": "paper-mu05-n100-v0.02", "0": "paper-mu0-n100-v0.02"}
seen = set()
for mu, ensemble in names.items():
    samples = store_samples(ensemble)
    assert len(samples) == 2 * 19, f"{ensemble}: {len(samples)} frames with a previous one in the stores"
    for force_index, force in enumerate(("normal", "tangential")):
        for dim in (0, 1):
            for metric in METRICS + ("ratio_w1", "ratio_w2"):
                got = [r for r in rows if r[:4] == [mu, force, str(dim), metric]]
                assert got, f"no rows for {mu} {force} {dim} {metric}"
                seen.add((mu, force, dim, metric))
                col = lambda m: COLUMN[m] * 4 + dim * 2 + force_index
                if metric.startswith("ratio"):
                    other = "wasserstein1" if metric == "ratio_w1" else "wasserstein2"
                    num = expected_bins(samples, lambda d: d[col("bottleneck")])
                    den = expected_bins(samples, lambda d: d[col(other)])
                    ratio = lambda a, b: a / b if b else (math.inf if a > 0 else math.nan)
                    want = {b: (num[b][0], ratio(num[b][1], den[b][1]), math.nan, min(num[b][3], den[b][3]), num[b][4])
                            for b in num if b in den}
                else:
                    want = expected_bins(samples, lambda d, c=col(metric): d[c])
                assert len(got) == len(want), f"{mu} {force} {dim} {metric}: {len(got)} rows, {len(want)} bins"
                for r, b in zip(got, sorted(want)):
                    rho, mean, se, n, z = want[b]
                    ctx = f"{mu} {force} PD{dim} {metric} bin {b}: {r}"
                    assert math.isclose(float(r[4]), rho, rel_tol=1e-12), ctx
                    if math.isnan(mean):
                        assert r[5] == "", ctx
                    else:
                        assert math.isclose(float(r[5]), mean, rel_tol=1e-9, abs_tol=1e-300), ctx + f" mean {mean}"
                    assert int(r[7]) == n, ctx
                    assert math.isclose(float(r[8]), z, rel_tol=1e-12), ctx
                    if math.isnan(se):
                        assert r[6] == "", ctx
                    else:
                        assert math.isclose(float(r[6]), se, rel_tol=1e-9, abs_tol=1e-300), ctx + f" stderr {se}"
assert len(seen) == 2 * 2 * 2 * 5

text = open(os.path.join(report, "report.md")).read()
findings = [line for line in text.splitlines() if line.startswith("### ")]
assert len(findings) == 6, findings
verdicts = [line for line in text.splitlines()
            if line.startswith(("- **holds**", "- **holds in part: ", "- **does not hold**", "- **not measurable**"))]
assert len(verdicts) == 6, verdicts
assert text.count("- measured: ") == 6
for mu in names:
    assert f"- mu {mu}: rho_J = " in text, mu
for line in text.splitlines():
    if line.startswith("- `") and line.endswith(tuple("abcdefghijklmnopqrstuvwxyz0123456789.,)")) and ".png`" in line:
        png = os.path.join(report, line.split("`")[1])
        with open(png, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n", png
pngs = [p for p in os.listdir(report) if p.endswith(".png")]
assert len(pngs) >= 8, pngs
print(f"reproduce-paper: {len(rows)} rows of curves.csv equal the stores' bins; {len(findings)} findings; "
      f"{len(pngs)} figures")
