"""deploy/reproduce-paper.sh end to end on small sizes: two ensembles simulated by fnet-simd,
analyzed live by a real fnet-server, the report folder written. curves.csv is checked against an
independent binning of the distances read from the server's stores with h5py, averaged over the
realizations (so a wrong bin, mean,
standard error, count, realization count, Z or ratio fails), report.md starts with its provenance,
states every finding with its verdict and shows every figure (each a PNG with its provenance);
progress with an ETA and the simulation time were printed. Then the same command with
START=fixed400 into the same folder: its realizations relax for a fixed 400 tau_c without damping,
and its report compares the two starts.

usage: reproduce_paper_test.py SOURCE_DIR BUILD_DIR WORK_DIR"""

import csv
import json
import math
import os
import re
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
# Progress was shown while it ran: the daemon's line per realization and frame, the server's start,
# the frames analyzed over both ensembles with an ETA (after each ensemble at least), the times.
assert "-s2: finished (20 frames)" in run.stdout, "no progress shown"
assert "fnet-server listening on 127.0.0.1" in run.stdout
progress = re.findall(r"\] fnet-server: (\d+) of 80 frames analyzed \(\d+ %\), (ETA \d+ min \d+ s|done|ETA unknown)",
                      run.stdout)
assert len(progress) >= 2, "no progress line after each ensemble"
assert any(re.fullmatch(r"ETA \d+ min \d+ s", eta) for _, eta in progress), progress
times = re.search(r"^time: simulation (\d+) s \(mu 0.5: (\d+) s, mu 0: (\d+) s\), waiting for the analysis \d+ s, "
                  r"report \d+ s; \d+ s in all$", run.stdout, re.M)
assert times and int(times[1]) == int(times[2]) + int(times[3]), run.stdout[-400:]

METRICS = ("bottleneck", "wasserstein1", "wasserstein2")
COLUMN = {m: k for k, m in enumerate(METRICS)}


def store_samples(ensemble):
    """(run, rho, z, twelve distances) of every frame with a previous frame, over the ensemble's stores."""
    rows = []
    for name in sorted(os.listdir(os.path.join(report, "store"))):
        if not name.startswith(ensemble + "-s") or not name.endswith(".h5"):
            continue
        with h5py.File(os.path.join(report, "store", name), "r", libver="latest", swmr=True) as f:
            n = len(f["frame"])
            prev, rho, z, d = f["previous"][:n], f["rho"][:n], f["z"][:n], f["distances"][:n]
            for k in range(n):
                if prev[k] >= 0:
                    rows.append((name, rho[k], z[k], d[k]))
    return rows


def expected_bins(samples, value):
    """Per bin: (rho, mean, standard error, frame pairs, realizations, Z) as ensemble.series defines
    them: each realization's mean of rho, value and Z in the bin first, then their means over the
    realizations, and the standard error of the value across them."""
    bins = {}
    for run, rho, z, d in samples:
        bins.setdefault(math.floor(rho / BIN_WIDTH), {}).setdefault(run, []).append((rho, z, value(d)))
    out = {}
    for b, runs in bins.items():
        rho, z, v = (np.array(m) for m in zip(*[np.mean(np.array(members), axis=0) for members in runs.values()]))
        se = float(np.std(v, ddof=1) / math.sqrt(len(v))) if len(v) > 1 else math.nan
        out[b] = (float(np.mean(rho)), float(np.mean(v)), se, sum(map(len, runs.values())), len(runs),
                  float(np.mean(z)))
    return out


with open(os.path.join(report, "curves.csv"), newline="") as f:
    reader = csv.reader(f)
    header = next(reader)
    assert header == ["mu", "force", "dim", "metric", "rho", "mean", "stderr", "n", "n_runs", "z"], header
    rows = list(reader)
# The server counts the realizations per bin, and its mean is over them.
assert all(r[8] != "" for r in rows), "n_runs in every row"
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
                    want = {b: (num[b][0], ratio(num[b][1], den[b][1]), math.nan, min(num[b][3], den[b][3]),
                                num[b][4], num[b][5]) for b in num if b in den}
                else:
                    want = expected_bins(samples, lambda d, c=col(metric): d[c])
                assert len(got) == len(want), f"{mu} {force} {dim} {metric}: {len(got)} rows, {len(want)} bins"
                for r, b in zip(got, sorted(want)):
                    rho, mean, se, n, n_runs, z = want[b]
                    ctx = f"{mu} {force} PD{dim} {metric} bin {b}: {r}"
                    assert math.isclose(float(r[4]), rho, rel_tol=1e-12), ctx
                    if math.isnan(mean):
                        assert r[5] == "", ctx
                    else:
                        assert math.isclose(float(r[5]), mean, rel_tol=1e-9, abs_tol=1e-300), ctx + f" mean {mean}"
                    assert int(r[7]) == n, ctx
                    if not metric.startswith("ratio"):
                        assert int(r[8]) == n_runs, ctx
                    assert math.isclose(float(r[9]), z, rel_tol=1e-12), ctx
                    if math.isnan(se):
                        assert r[6] == "", ctx
                    else:
                        assert math.isclose(float(r[6]), se, rel_tol=1e-9, abs_tol=1e-300), ctx + f" stderr {se}"
assert len(seen) == 2 * 2 * 2 * 5

side = json.load(open(os.path.join(report, "curves.csv.json")))
assert {"fnet_version", "fnet_commit", "date", "convention", "method", "server_version", "server_commit", "bin_width",
        "ensembles", "settings"} <= set(side), side
assert side["bin_width"] == str(BIN_WIDTH) and "start=quiescent" in side["settings"]


def check_report(report, names, start):
    """report.md: its provenance first, every finding with a verdict, its figures shown with captions
    (each a PNG whose text chunks hold the provenance), the settings of this command."""
    text = open(os.path.join(report, "report.md")).read()
    lines = text.splitlines()
    assert lines[:3] == ["# The paper reproduced by fnet", "", "## Provenance"], lines[:3]
    assert lines[4].startswith("- fnet (the package that wrote this report): ")
    assert any(line.startswith("- fnet-server version: ") for line in lines[4:12])
    findings = [line for line in lines if line.startswith("### ")]
    assert len(findings) == 6, findings
    verdicts = [line for line in lines
                if re.match(r"- \*\*(holds|does not hold|undetermined|mixed: .*|not measurable)\*\* \(", line)]
    assert len(verdicts) == 6, verdicts
    # Two realizations: every verdict that was measured is undetermined, and the report says why.
    assert all("undetermined" in v or "not measurable" in v for v in verdicts), verdicts
    assert "**Warning: few realizations** — mu 0.5: 2, mu 0: 2" in text
    assert text.count("- measured (estimate [95 % interval]): ") == 6
    for mu in names:
        assert f"- mu {mu}: rho_J = " in text, mu
        assert f"- realizations of mu {mu}: 2 (ensemble `{names[mu]}`)" in lines
    assert f"- start: {start}" in lines
    assert any(re.fullmatch(r"- simulation wall time: \d+ s \(mu 0.5: \d+ s, mu 0: \d+ s\)", line) for line in lines)
    images = [re.fullmatch(r"!\[(.+)\]\((fig[-\w]+\.png)\)", line) for line in lines if line.startswith("![")]
    pngs = sorted(p for p in os.listdir(report) if p.endswith(".png"))
    assert len(pngs) >= 8 and sorted(m[2] for m in images) == pngs, (images, pngs)
    for m in images:
        assert lines[lines.index(m[0]) + 2] == f"*{m[1]}*"
        with open(os.path.join(report, m[2]), "rb") as f:
            png = f.read()
        assert png[:8] == b"\x89PNG\r\n\x1a\n", m[2]
        assert b"fnet:fnet_version" in png and b"fnet:server_commit" in png, m[2]
    assert not [p for p in os.listdir(report) if p.startswith(".")]
    return text, pngs


text, pngs = check_report(report, names, "quiescent")
assert "## Two starts compared" not in text
print(f"reproduce-paper: {len(rows)} rows of curves.csv equal the stores' bins; 6 findings; {len(pngs)} figures")

# The other start into the same folder: its realizations relax 400 tau_c undamped, and the report
# compares the two starts of each mu.
env["START"] = "fixed400"
run = subprocess.run(["bash", os.path.join(source, "deploy", "reproduce-paper.sh")], cwd=source, env=env,
                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=900)
print(run.stdout)
assert run.returncode == 0, f"reproduce-paper.sh START=fixed400 exited {run.returncode}"
fixed = {mu: name + "-fixed400" for mu, name in names.items()}
for mu, name in fixed.items():
    with h5py.File(os.path.join(report, "runs", f"{name}-s1.run.h5"), "r") as f:
        config = json.loads(f.attrs["config_json"])
    assert (config["relax_energy"], config["relax_damping"], config["relax_max_time"]) == (0, 0, 400), config
text, _ = check_report(report, fixed, "fixed400")
for mu in names:
    assert f"## Two starts compared before jamming: `{names[mu]}` and `{fixed[mu]}`" in text
assert text.count("| `paper-mu") == 4
print("reproduce-paper START=fixed400: the starts compared")
