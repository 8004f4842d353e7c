"""fnet.paper, the report of deploy/reproduce-paper.sh: its findings judged with bootstrap intervals
over realizations on synthetic realizations whose answer is known (a clear hold, a clear failure,
an interval across the threshold, too few realizations, degenerate ratios left out and counted),
each realization binned as ensemble.series bins; then `python3 -m fnet paper-report` against a real
fnet-server holding a real fnet-simd ensemble: curves.csv with n_runs and its provenance sidecar,
report.md with its provenance and its figures, each PNG with its provenance, and a Ctrl-C while it
renders leaving the folder as it was."""

import math
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from PIL import Image

import fnet.paper as paper
from conftest import PNG_SIGNATURE, SOURCE_DIR, simd_args, start_server, wait_for_frames

DOMAIN = 98
WIDTH = 0.01
RHO = np.arange(0.6005, 0.9, 0.0025)  # four frames per bin of WIDTH, none on an edge


def series(rho, value):
    rho = np.asarray(rho, dtype=float)
    value = np.asarray(value, dtype=float).copy()
    value[0] = np.nan  # the first frame has no previous frame
    return {"frame": np.arange(len(rho)), "rho": rho, "z": np.full(len(rho), 3.0), "value": value}


def realizations(values, rho_j, name="synthetic", rho=RHO):
    """Realizations whose run i has distance values(i, key, rho) for each key, and rho_J rho_j[i]."""
    runs = [f"{name}-s{i + 1}" for i in range(len(rho_j))]
    data = {r: {key: series(rho, values(i, key, rho)) for key in paper_keys()} for i, r in enumerate(runs)}
    return paper.Realizations(name, runs, WIDTH, data, dict(zip(runs, rho_j)))


def paper_keys():
    return [(f, d, m) for f in paper.FORCES for d in paper.DIMS for m in paper.METRICS]


def jammed(large, small, jam=0.8):
    """A distance `large` below rho_J and `small` above it."""
    return lambda rho: np.where(rho < jam, large, small)


def finding(found, number):
    return found[number - 1]


def check(f, label_start):
    (c,) = [c for c in f.checks if c.label.startswith(label_start)]
    return c


# ---- binning each realization as ensemble.series bins ------------------------------------------

def test_each_run_is_binned_on_the_aligned_grid():
    rng = np.random.default_rng(1)
    rho = np.sort(rng.uniform(0.6, 0.9, 50))
    data = realizations(lambda i, key, r: rng.uniform(0, 2, len(r)), [0.8, 0.81, 0.79], rho=rho)
    key = ("normal", 1, "wasserstein2")
    for i, run in enumerate(data.runs):
        s = data.frames[run][key]
        assert len(s["value"]) == len(rho) - 1  # the first frame is no sample
        for j, k in enumerate(data.index):
            inside = (s["rho"] >= k * WIDTH) & (s["rho"] < (k + 1) * WIDTH)
            if inside.any():
                assert math.isclose(data.means[key][i, j], s["value"][inside].mean(), rel_tol=1e-12)
            else:
                assert math.isnan(data.means[key][i, j])


def test_a_resample_is_the_mean_over_its_runs_of_their_bin_means():
    rng = np.random.default_rng(2)
    data = realizations(lambda i, key, r: rng.uniform(0, 2, len(r)) * (i + 1), [0.8, 0.81, 0.79, 0.8])
    weights = paper.bootstrap_weights(len(data), np.random.default_rng(3), resamples=20)
    assert (weights.sum(axis=1) == len(data)).all() and (weights[0] == 1).all()
    got = paper.Resampled(data, weights).mean("tangential", 0, "bottleneck")
    for row, w in enumerate(weights):
        drawn = [i for i in range(len(data)) for _ in range(int(w[i]))]
        for j, k in enumerate(data.index):
            per_run = []
            for i in drawn:
                s = data.frames[data.runs[i]][("tangential", 0, "bottleneck")]
                inside = np.floor(s["rho"] / WIDTH) == k
                if inside.any():
                    per_run.append(s["value"][inside].mean())
            assert math.isclose(got[row, j], np.mean(per_run), rel_tol=1e-12)
    rho_j = paper.Resampled(data, weights).rho_j
    np.testing.assert_allclose(rho_j, weights @ data.rho_j / len(data), rtol=1e-12)


def test_weighted_median_is_the_median_of_the_repetition():
    rng = np.random.default_rng(4)
    for _ in range(200):
        values = np.sort(rng.uniform(0, 1, rng.integers(1, 9)))
        weights = rng.integers(0, 4, len(values))
        want = np.median(np.repeat(values, weights)) if weights.sum() else math.nan
        got = paper._weighted_median(values, weights)
        assert (math.isnan(want) and math.isnan(got)) or math.isclose(got, want, rel_tol=1e-15)


# ---- verdicts with bootstrap intervals ---------------------------------------------------------

def test_a_check_holds_only_when_its_interval_is_inside_the_range():
    values = lambda estimate, spread: np.concatenate([[estimate], estimate + spread * np.linspace(-1, 1, 1000)])
    assert paper.Check("x", values(0.8, 0.1), (0.5, 1.0), 10).verdict == "holds"
    assert paper.Check("x", values(0.3, 0.1), (0.5, 1.0), 10).verdict == "does not hold"
    assert paper.Check("x", values(1.3, 0.1), (0.5, 1.0), 10).verdict == "does not hold"
    assert paper.Check("x", values(0.55, 0.1), (0.5, 1.0), 10).verdict == "undetermined"
    assert paper.Check("x", values(0.8, 0.1), (0.5, 1.0), 2).verdict == "undetermined"
    # The 95 % interval: the 2.5th and 97.5th percentiles of the resamples.
    c = paper.Check("x", values(0.8, 0.1), (0.5, 1.0), 10)
    np.testing.assert_allclose(c.interval, np.percentile(values(0.8, 0.1)[1:], [2.5, 97.5]), rtol=1e-15)
    undefined = values(0.8, 0.1)
    undefined[1:40] = np.nan  # more than 2.5 % of the resamples: the interval's ends are unknown
    assert paper.Check("x", undefined, (0.5, 1.0), 10).verdict == "undetermined"
    assert "undefined in 39 of 1000 resamples" in paper.Check("x", undefined, (0.5, 1.0), 10).text()


def test_clear_hold_and_clear_failure_of_large_d_b_before_jamming():
    rng = np.random.default_rng(5)
    large = realizations(lambda i, key, r: jammed(5.0, 0.05)(r) * rng.uniform(0.8, 1.2, len(r)), [0.8] * 8)
    small = realizations(lambda i, key, r: jammed(0.4, 0.05)(r) * rng.uniform(0.8, 1.2, len(r)), [0.8] * 8)
    held = finding(paper.findings({"0.5": large}), 1)
    assert held.verdict == "holds", held.measured
    assert check(held, "PD0").estimate == 1.0 and check(held, "PD0").interval == (1.0, 1.0)
    failed = finding(paper.findings({"0.5": small}), 1)
    assert failed.verdict == "does not hold", failed.measured
    assert check(failed, "PD1").estimate == 0.0


def test_an_interval_across_the_threshold_is_undetermined():
    # Half the runs change a lot before jamming, half little: whether the ensemble's bins exceed 1
    # depends on which runs a resample draws, so the share's interval spans 0 to 1.
    data = realizations(lambda i, key, r: jammed(3.0 if i % 2 else 0.2, 0.05)(r), [0.8] * 6)
    f = finding(paper.findings({"0.5": data}), 1)
    c = check(f, "PD0")
    assert c.estimate == 1.0 and c.interval[0] < 0.5 <= c.interval[1]
    assert f.verdict == "undetermined" and "straddles" in c.text()


def test_two_realizations_leave_every_finding_undetermined():
    data = realizations(lambda i, key, r: jammed(5.0, 0.05)(r), [0.8, 0.8])
    found = paper.findings({"0.5": data, "0": realizations(lambda i, key, r: jammed(5.0, 0.1, 0.82)(r), [0.82] * 2)})
    assert len(found) == 6
    for f in found:
        assert f.verdict == "undetermined", (f.claim, f.verdict)
        assert "2 realizations, fewer than 3" in f.measured


def test_degenerate_ratios_are_left_out_and_counted():
    # PD1 before jamming: d_B / d_W2 = 0.7 in four of the first half's ten bins; in five exactly one
    # loop moved (d_B = d_W1 = d_W2) and in one nothing changed (0 / 0). Left in, the ones would make
    # the median 1 and the zero undefined; left out, it is 0.7, and the count is said.
    single = (RHO >= 0.61) & (RHO < 0.66)
    still = (RHO >= 0.66) & (RHO < 0.67)

    def values(i, key, r):
        force, dim, metric = key
        d_b = jammed(2.0, 0.02)(r)
        v = d_b / {"bottleneck": 1.0, "wasserstein1": 0.2, "wasserstein2": 0.7}[metric]
        if dim == 1:
            v = np.where(single, d_b, v)
            v = np.where(still, 0.0, v)
        return v

    data = realizations(values, [0.8] * 5)
    assert list(data.index[:10]) == list(range(60, 70))  # the first half below rho_J: rho < 0.70
    f = finding(paper.findings({"0.5": data}), 2)
    c = check(f, "PD1 d_B/d_W2 median")
    assert math.isclose(c.estimate, 0.7, rel_tol=1e-12) and c.verdict == "holds", c.text()
    assert c.excluded == {"single-feature (exactly 1)": 5, "0/0": 1}
    assert "5 single-feature (exactly 1)" in c.text() and "1 0/0" in c.text()
    assert check(f, "PD0 d_B/d_W2 median").excluded == {}
    # A ratio of zero medians: nothing changes after jamming, so "below / after" is undefined.
    flat = realizations(lambda i, key, r: jammed(1.0, 0.0)(r), [0.8] * 5)
    c = check(finding(paper.findings({"0.5": flat}), 4), "PD0 d_B below / after")
    assert math.isnan(c.estimate) and c.verdict == "undetermined"
    assert c.excluded == {"ratio of zero medians": 1}
    # ... and so is a factor from nothing: no change at all before jamming, some after.
    late = realizations(lambda i, key, r: jammed(0.0, 0.5)(r), [0.8] * 5)
    c = check(finding(paper.findings({"0.5": late}), 4), "PD1 d_W2 below / after")
    assert math.isnan(c.estimate) and c.verdict == "undetermined" and "1 ratio of zero medians" in c.text()


def test_the_frictionless_comparison_resamples_both_ensembles():
    rng = np.random.default_rng(6)
    mu05 = realizations(lambda i, key, r: jammed(2.0, 0.1)(r) * rng.uniform(0.9, 1.1, len(r)),
                        list(0.80 + rng.normal(0, 0.002, 8)))
    mu0 = realizations(lambda i, key, r: jammed(2.0, 0.2, 0.83)(r) * rng.uniform(0.9, 1.1, len(r)),
                       list(0.83 + rng.normal(0, 0.002, 8)))
    f = finding(paper.findings({"0.5": mu05, "0": mu0}), 6)
    shift = check(f, "rho_J(mu 0) - rho_J(mu 0.5)")
    assert math.isclose(shift.estimate, np.mean(mu0.rho_j) - np.mean(mu05.rho_j), rel_tol=1e-12)
    assert shift.verdict == "holds"
    twice = check(f, "PD1 d_W1")
    assert 1.8 < twice.estimate < 2.2 and twice.verdict == "holds", twice.text()
    assert f.verdict == "holds"
    # The same seed gives the same intervals.
    again = check(finding(paper.findings({"0.5": mu05, "0": mu0}), 6), "PD1 d_W1")
    assert again.interval == twice.interval


def test_compare_starts_medians_and_empty_fractions():
    rng = np.random.default_rng(7)
    a = realizations(lambda i, key, r: rng.uniform(0.1, 0.3, len(r)), [0.8] * 4, name="quiescent")
    b = realizations(lambda i, key, r: rng.uniform(0.5, 0.7, len(r)), [0.8] * 4, name="fixed400")
    empty = {}
    for data, share in ((a, 0.25), (b, 0.75)):
        for i, run in enumerate(data.runs):
            frames = data.frames[run][("normal", 1, "bottleneck")]["frame"]
            for k, f in enumerate(frames):
                empty[(run, int(f))] = (k % 4) < 4 * share
    out = paper.compare_starts(a, b, empty)
    (name_a, runs_a, frames_a, median_a, frac_a), (_, _, frames_b, median_b, frac_b) = out["rows"]
    key = ("normal", 1, "bottleneck")
    pooled = np.concatenate([a.frames[r][key]["value"][a.frames[r][key]["rho"] < 0.79] for r in a.runs])
    assert name_a == "quiescent" and runs_a == 4 and frames_a == len(pooled)
    assert math.isclose(median_a.estimate, np.median(pooled), rel_tol=1e-15)
    picked = [(r, int(f)) for r in a.runs for f, x in zip(a.frames[r][key]["frame"], a.frames[r][key]["rho"])
              if x < 0.79]
    assert math.isclose(frac_a.estimate, np.mean([empty[p] for p in picked]), rel_tol=1e-12)
    diff_median, diff_empty = out["differences"]
    assert diff_median.interval[0] > 0.2 and diff_empty.interval[0] > 0.3
    text = "\n".join(paper._comparison_markdown(out))
    assert "differs from 0" in text and "`fixed400`" in text


def test_row_percentiles_are_numpys_over_the_masked_finite_entries():
    rng = np.random.default_rng(8)
    for _ in range(100):
        v = rng.normal(size=(5, 7))
        v[rng.random(v.shape) < 0.1] = np.nan
        v[rng.random(v.shape) < 0.05] = np.inf
        mask = rng.random(v.shape) < 0.6
        for q in (10, 50, 90):
            got = paper._row_percentile(v, mask, q)
            for i in range(len(v)):
                x = v[i][mask[i] & np.isfinite(v[i])]
                if len(x):
                    assert math.isclose(got[i], np.percentile(x, q), rel_tol=1e-12, abs_tol=1e-15)
                else:
                    assert math.isnan(got[i])


# ---- python3 -m fnet paper-report against a real server ----------------------------------------

SEEDS = (1, 2, 3)
FRAMES = 12
ENSEMBLES = {"0.5": "rep05", "0": "rep0"}


@pytest.fixture(scope="module")
def server(processes):
    s = start_server(processes, DOMAIN)
    runs = [(name, mu, seed) for mu, name in ENSEMBLES.items() for seed in SEEDS]
    for k, (name, mu, seed) in enumerate(runs):  # two at a time: the machine has two cores
        processes.start(simd_args(DOMAIN, frames=FRAMES, seed=seed, ensemble=name) + ["--mu", mu],
                        f"simd-{name}-{seed}.log")
        if k % 2 == 1:
            wait_for_frames(s, f"{name}-s{seed}", FRAMES)
    for name, _, seed in runs:
        wait_for_frames(s, f"{name}-s{seed}", FRAMES)
    return s


def report_command(server, out, *extra):
    return [sys.executable, "-m", "fnet", "paper-report", "--port", str(server.port), "--bins", "0.01", "--out",
            str(out), *(a for mu, name in ENSEMBLES.items() for a in ("--ensemble", f"{mu}={name}")),
            "--setting", "start=quiescent", *extra]


def environment():
    return dict(os.environ, PYTHONPATH=str(SOURCE_DIR / "client" / "python"))


def interruptible():
    """In the child: SIGINT as a terminal delivers it (a test runner may have it ignored)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@pytest.fixture(scope="module")
def report(server, tmp_path_factory):
    out = tmp_path_factory.mktemp("report") / "paper"
    (out / "runs").mkdir(parents=True)
    (out / "runs" / "kept.txt").write_text("an earlier file\n")
    r = subprocess.run(report_command(server, out, "--compare-start", "rep05=rep0"), capture_output=True, text=True,
                       env=environment(), timeout=300)
    assert r.returncode == 0, r.stderr
    return out


def test_curves_csv_has_n_runs_and_a_provenance_sidecar(server, report):
    with server.client() as c:
        status = c.status()
        curves = paper.read_csv(report / "curves.csv")
        run_rho_j = {r["run"]: r["rho_j"] for r in c.runs()}
        for mu, name in ENSEMBLES.items():
            runs = [f"{name}-s{seed}" for seed in SEEDS]
            data = paper.collect_realizations(c, name, runs, run_rho_j, 0.01)
            for key in data.keys:
                got = curves[(mu, *key)]
                served = c.ensemble_series(ensemble=name, metric=key[2], dim=key[1], force=key[0], bin_width=0.01)
                np.testing.assert_array_equal(got["mean"], served.mean)
                assert list(got["rho"]) == list(served.rho) and len(got["rho"]) == len(data.index)
                present = (~np.isnan(data.means[key])).sum(axis=0)
                if "n_runs" in served:  # the server's count of realizations per bin, and their mean
                    np.testing.assert_array_equal(got["n_runs"], present)
                    np.testing.assert_allclose(got["mean"], np.nanmean(data.means[key], axis=0), rtol=1e-12)
                else:  # a server that does not count them: left empty
                    assert (got["n_runs"] == -1).all()
    header = (report / "curves.csv").read_text().splitlines()[0]
    assert header == "mu,force,dim,metric,rho,mean,stderr,n,n_runs,z"
    import json
    side = json.loads((report / "curves.csv.json").read_text())
    build = status.get("build") or {}
    assert side["fnet_version"] == fnet_version() and side["convention"] == "floor"
    assert side["server_version"] == str(build.get("version", "unknown"))
    assert side["server_commit"] == str(build.get("commit", "unknown"))
    assert side["bin_width"] == "0.01" and "mu 0.5: rep05 (3 realizations)" in side["ensembles"]
    assert "start=quiescent" in side["settings"] and side["date"].endswith("Z")


def fnet_version():
    from fnet.version import __version__
    return __version__


def test_report_starts_with_its_provenance_and_shows_its_figures(report):
    text = (report / "report.md").read_text()
    lines = text.splitlines()
    assert lines[:3] == ["# The paper reproduced by fnet", "", "## Provenance"]
    block = lines[4:lines.index("## Setting")]
    assert f"- fnet (the package that wrote this report): {fnet_version()}" in block
    assert any(line.startswith("- fnet-server version: ") for line in block)
    assert any(line.startswith("- date (UTC): ") for line in block)
    assert "- start: quiescent" in lines
    assert "- realizations of mu 0.5: 3 (ensemble `rep05`)" in lines
    assert "**Warning: few realizations**" in text
    images = [line for line in lines if line.startswith("![")]
    pngs = sorted(p.name for p in report.glob("*.png"))
    assert sorted(line.rsplit("](", 1)[1].rstrip(")") for line in images) == pngs and len(pngs) == 10
    for line in images:
        caption, name = line[2:].rsplit("](", 1)
        name = name.rstrip(")")
        k = lines.index(line)
        assert lines[k + 2] == f"*{caption}*"
        with open(report / name, "rb") as f:
            assert f.read(8) == PNG_SIGNATURE
        meta = Image.open(report / name).text
        assert meta["fnet:fnet_version"] == fnet_version() and meta["fnet:caption"] == caption
        assert meta["fnet:figure"] == name and meta["Software"].startswith(f"fnet {fnet_version()}")
        assert "fnet:server_version" in meta and meta["fnet:convention"] == "floor"
    assert "## Two starts compared before jamming: `rep05` and `rep0`" in text
    assert (report / "runs" / "kept.txt").read_text() == "an earlier file\n"
    assert not [p for p in os.listdir(report) if p.startswith(".")]  # no staging folder left


def interrupt_while_rendering(server, out, staging):
    """Starts the report into `out`, sends SIGINT once a figure is in a staging folder matching the
    glob `staging` (a Path pattern), and returns (process, stdout, stderr)."""
    p = subprocess.Popen(report_command(server, out), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=environment(), preexec_fn=interruptible)
    deadline = time.monotonic() + 240
    staged = []
    while not staged and p.poll() is None and time.monotonic() < deadline:
        staged = [f for d in staging.parent.glob(staging.name) for f in d.glob("*.png")]
        time.sleep(0.005)
    assert staged, "the report was not caught while rendering its figures"
    p.send_signal(signal.SIGINT)
    out_text, err = p.communicate(timeout=120)
    return p, out_text, err


def test_ctrl_c_while_rendering_leaves_the_folder_as_it_was(server, report):
    before = {p: p.read_bytes() for p in report.rglob("*") if p.is_file()}
    p, out, err = interrupt_while_rendering(server, report, report / ".paper-report-*")
    assert p.returncode == 130, (out, err)
    assert "Traceback" not in err and err.strip().count("\n") == 0, err
    assert "interrupted" in err
    after = {q: q.read_bytes() for q in report.rglob("*") if q.is_file()}
    assert after == before  # the earlier report and runs/ untouched, no staging folder left
    assert not [q for q in os.listdir(report) if q.startswith(".")]


def test_ctrl_c_into_a_new_folder_leaves_none(server, tmp_path):
    p, _, err = interrupt_while_rendering(server, tmp_path / "new-report", tmp_path / ".new-report-*")
    assert p.returncode == 130 and "Traceback" not in err, err
    assert os.listdir(tmp_path) == []


def test_unknown_ensembles_are_named(server, tmp_path):
    r = subprocess.run(report_command(server, tmp_path / "x", "--compare-start", "rep05=nope"), capture_output=True,
                       text=True, env=environment(), timeout=120)
    assert r.returncode == 4 and "no ensemble nope on the server" in r.stderr and "Traceback" not in r.stderr
