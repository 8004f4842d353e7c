"""Ensembles through fnet.Client, fnet.figures and the command line, against a real fnet-server fed
by real fnet-simd realizations (--ensemble E, one seed each): the binned curves are the members'
series binned by hand (each realization's mean first, then the mean and standard error across the
realizations), ratio curves the ratio of bin means, the plotted data the served data, and
an ensemble subscription an iterator of changed bins that unsubscribes on exit."""

import numpy as np
import pytest

import fnet.figures as figures
from conftest import expect_png, plot, simd_args, start_server, wait_for, wait_for_frames

DOMAIN = 93
ENSEMBLE = "ens"
SEEDS = (1, 2, 3)
FRAMES = 8


@pytest.fixture(scope="module")
def server(processes):
    s = start_server(processes, DOMAIN)
    for seed in SEEDS:  # two at a time: the machine has two cores
        processes.start(simd_args(DOMAIN, frames=FRAMES, seed=seed, ensemble=ENSEMBLE), f"simd-{seed}.log")
        if seed % 2 == 0:
            wait_for_frames(s, f"{ENSEMBLE}-s{seed}", FRAMES)
    for seed in SEEDS:
        wait_for_frames(s, f"{ENSEMBLE}-s{seed}", FRAMES)
    return s


def members():
    return [f"{ENSEMBLE}-s{seed}" for seed in SEEDS]


def samples(client, runs, metric, dim=0, force="normal"):
    """(rho, z, value, run) of every frame with a previous frame, over the runs; run is the run's
    place in `runs`."""
    rho, z, value, run = [], [], [], []
    for k, name in enumerate(runs):
        s = client.series(metric, run=name, dim=dim, force=force)
        keep = s.previous >= 0
        rho += list(s.rho[keep])
        z += list(s.z[keep])
        value += list(s.value[keep])
        run += [k] * int(keep.sum())
    return np.array(rho), np.array(z), np.array(value), np.array(run)


def over_runs(inside, run, *columns):
    """Per column, the mean over the runs present of each run's mean over `inside`; then the
    number of runs and the standard error of the first column's run means (NaN for one run)."""
    present = np.unique(run[inside])
    means = [np.array([c[inside & (run == r)].mean() for r in present]) for c in columns]
    se = means[0].std(ddof=1) / np.sqrt(len(present)) if len(present) > 1 else np.nan
    return [m.mean() for m in means], len(present), se


def test_ensembles_list_names_the_realizations(client):
    (e,) = client.ensembles()
    assert e["ensemble"] == ENSEMBLE and e["runs"] == members()
    assert e["frames"] == FRAMES * len(SEEDS) and e["particles"] == 150


def test_curve_arrays_are_the_served_arrays(client):
    c = client.ensemble_series(ensemble=ENSEMBLE, metric="bottleneck", dim=1, bins=4)
    raw = client.call("ensemble.series", {"ensemble": ENSEMBLE, "metric": "bottleneck", "dim": 1, "bins": 4})
    assert c.runs == members() and c.ensemble == ENSEMBLE
    for key in ("rho_lo", "rho_hi", "rho", "mean", "z", "n_runs", "n"):
        np.testing.assert_array_equal(c[key], np.array(raw[key], dtype=c[key].dtype))
    np.testing.assert_array_equal(c.stderr, [np.nan if v is None else v for v in raw["stderr"]])
    assert c.n.dtype == np.int64 and c.n_runs.dtype == np.int64 and c.mean.dtype == np.float64


@pytest.mark.parametrize("metric,dim,force", [("bottleneck", 0, "normal"), ("wasserstein2", 1, "tangential")])
def test_bins_hold_the_members_series(client, metric, dim, force):
    c = client.ensemble_series(ensemble=ENSEMBLE, metric=metric, dim=dim, force=force, bins=5)
    rho, z, value, run = samples(client, members(), metric, dim, force)
    assert c.n.sum() == len(value)
    last = len(c.rho_lo) - 1
    for k in range(len(c.rho_lo)):
        inside = (rho >= c.rho_lo[k]) & ((rho < c.rho_hi[k]) | ((k == last) & (rho <= c.rho_hi[k])))
        assert inside.sum() == c.n[k] > 0
        (mean, mean_rho, mean_z), runs, se = over_runs(inside, run, value, rho, z)
        assert c.n_runs[k] == runs
        np.testing.assert_allclose(c.mean[k], mean, rtol=1e-12)
        np.testing.assert_allclose(c.rho[k], mean_rho, rtol=1e-12)
        np.testing.assert_allclose(c.z[k], mean_z, rtol=1e-12)
        if runs > 1:
            np.testing.assert_allclose(c.stderr[k], se, rtol=1e-9)
        else:
            assert np.isnan(c.stderr[k])
    # Bins where averaging over the runs is not pooling the frames: the check tells them apart.
    assert ((c.n_runs >= 2) & (c.n > c.n_runs)).sum() >= 2


@pytest.mark.parametrize("ratio", ["wasserstein1", "wasserstein2"])
def test_ratio_curve_is_the_ratio_of_bin_means(client, ratio):
    r = client.ensemble_series(ensemble=ENSEMBLE, ratio=ratio, dim=1, bin_width=0.05)
    b = client.ensemble_series(ensemble=ENSEMBLE, metric="bottleneck", dim=1, bin_width=0.05)
    w = client.ensemble_series(ensemble=ENSEMBLE, metric=ratio, dim=1, bin_width=0.05)
    assert r.ratio == ratio
    np.testing.assert_array_equal(r.rho_lo, b.rho_lo)
    np.testing.assert_array_equal(r.n_runs, np.minimum(b.n_runs, w.n_runs))
    np.testing.assert_array_equal(r.n, np.minimum(b.n, w.n))
    assert np.isnan(r.stderr).all()
    with np.errstate(invalid="ignore"):  # 0 / 0 where no loop changed: null, as the server serves it
        np.testing.assert_allclose(r.mean, b.mean / w.mean, rtol=1e-12)
    s = client.series("bottleneck", run=members()[0], dim=1, ratio=ratio)
    sb = client.series("bottleneck", run=members()[0], dim=1)
    sw = client.series(ratio, run=members()[0], dim=1)
    with np.errstate(invalid="ignore"):
        np.testing.assert_allclose(s.value[1:], sb.value[1:] / sw.value[1:], rtol=1e-12)


def test_one_run_curve_and_rho_minus_rho_j(client):
    c = client.ensemble_series(run=members()[0], metric="bottleneck", bins=3)
    assert c.run == members()[0] and c.runs == [members()[0]]
    assert (c.n_runs == 1).all() and np.isnan(c.stderr).all()
    j = client.ensemble_series(ensemble=ENSEMBLE, metric="bottleneck", axis="rho_minus_rho_j", bins=3)
    assert j.axis == "rho_minus_rho_j"
    fig = figures.ensemble(j)
    assert fig.axes[0].get_xlabel() == figures.AXIS_LABELS["rho_minus_rho_j"]


def test_ensemble_figure_draws_mean_and_standard_error(client, tmp_path):
    curves = [client.ensemble_series(ensemble=ENSEMBLE, metric="wasserstein1", dim=0, force=f, bins=5)
              for f in ("normal", "tangential")]
    fig = figures.ensemble(curves)
    fig.savefig(tmp_path / "fig6.png")
    ax = fig.axes[0]
    means = [a for a in ax.get_children() if a.get_gid() == "mean"]
    assert len(means) == 2
    for line, c in zip(means, curves):
        keep = np.isfinite(c.mean)
        np.testing.assert_array_equal(drawn(line), np.column_stack([c.rho[keep], c.mean[keep]]))
    bars = ax.containers
    for container, c in zip(bars, curves):
        keep = np.isfinite(c.mean)
        segments = np.array(container.lines[2][0].get_segments())
        se = np.nan_to_num(c.stderr[keep])
        np.testing.assert_allclose(segments[:, 0, 1], c.mean[keep] - se, rtol=1e-15)
        np.testing.assert_allclose(segments[:, 1, 1], c.mean[keep] + se, rtol=1e-15)
    (z,) = [a for a in fig.axes[1].get_children() if a.get_gid() == "z"]
    np.testing.assert_array_equal(drawn(z), np.column_stack([curves[0].rho, curves[0].z]))


def test_ratio_figure_draws_the_served_ratios(client, tmp_path):
    curves = [client.ensemble_series(ensemble=ENSEMBLE, ratio=r, dim=1, bins=5)
              for r in ("wasserstein1", "wasserstein2")]
    fig = figures.ratio(curves)
    fig.savefig(tmp_path / "fig7.png")
    lines = [a for a in fig.axes[0].get_children() if a.get_gid() == "ratio"]
    for line, c in zip(lines, curves):
        keep = np.isfinite(c.mean)
        np.testing.assert_array_equal(drawn(line), np.column_stack([c.rho[keep], c.mean[keep]]))


def test_served_curves_on_log_axes_draw_no_value_at_or_below_zero_and_span_no_empty_bin(client, tmp_path):
    # Bins of 0.002 over 8-frame runs: most of the grid is empty, so the lines must break.
    curves = [client.ensemble_series(ensemble=ENSEMBLE, metric=m, dim=1, bin_width=0.002)
              for m in ("bottleneck", "wasserstein1")]
    (e,) = client.ensembles()
    fig = figures.ensemble(curves, log=True, rho_j=e["rho_j"])
    fig.savefig(tmp_path / "log.png")
    gaps = 0
    for line, c in zip([a for a in fig.axes[0].get_children() if a.get_gid() == "mean"], curves):
        keep = np.isfinite(c.mean) & (c.mean > 0)
        np.testing.assert_array_equal(drawn(line), np.column_stack([c.rho[keep], c.mean[keep]]))
        assert (drawn(line)[:, 1] > 0).all()
        xy = line.get_xydata()
        for k in range(len(xy) - 1):
            if np.isnan(xy[k:k + 2]).any():
                gaps += 1
                continue
            a, b = (int(np.flatnonzero(c.rho == x)[0]) for x in (xy[k, 0], xy[k + 1, 0]))
            assert b == a + 1 and c.rho_hi[a] == c.rho_lo[b], "a line spans an empty bin"
    assert gaps > 0
    bottom = fig.axes[0].get_ylim()[0]
    for container in fig.axes[0].containers:
        assert np.array(container.lines[2][0].get_segments())[:, 0, 1].min() >= bottom > 0


def drawn(line):
    """The points a line draws (the NaN rows that break it left out)."""
    xy = line.get_xydata()
    return xy[~np.isnan(xy).any(axis=1)]


def test_ensemble_subscription_pushes_the_bins_a_new_realization_changes(server, processes, client):
    params = dict(ensemble=ENSEMBLE, metric="bottleneck", dim=1, bin_width=0.05)
    got = []
    with client.subscribe_ensemble(**params) as sub:
        assert sub.reply["subscription"] == sub.id
        assert client.status()["subscriptions"] == 1
        processes.start(simd_args(DOMAIN, frames=FRAMES, seed=4, ensemble=ENSEMBLE), "simd-4.log")
        wait_for_frames(server, f"{ENSEMBLE}-s4", FRAMES)
        while (n := sub.next(timeout=5)) is not None:
            got.append(n)
        assert sub.reply.rho_lo.dtype == np.float64  # the curve when subscribing, as numpy arrays
    wait_for(lambda: client.status()["subscriptions"] == 0, "the subscription to end")
    assert got and all(n.ensemble == ENSEMBLE for n in got)
    final = client.ensemble_series(**params)
    latest = {}
    for n in got:
        for k, lo in enumerate(n.rho_lo):
            latest[lo] = (n.mean[k], n.n[k], n.n_runs[k])
    for lo, (mean, count, runs) in latest.items():
        k = int(np.flatnonzero(final.rho_lo == lo)[0])
        assert count == final.n[k] and runs == final.n_runs[k]
        np.testing.assert_allclose(mean, final.mean[k], rtol=1e-12)
    # The notifications applied over the curve at subscription give the curve served now.
    for key in ("rho_lo", "rho_hi", "rho", "mean", "stderr", "n_runs", "n", "z"):
        np.testing.assert_array_equal(sub.curve[key], final[key], err_msg=key)
    assert sub.curve.runs == final.runs == members() + [f"{ENSEMBLE}-s4"]
    (e,) = client.ensembles()
    assert len(e["runs"]) == 4 and final.n.sum() == e["frames"] - 4  # every frame but each run's first


def test_command_line_draws_ensemble_figures(server, tmp_path):
    port = ("--port", server.port)
    for name, args in [("fig6", ("distances", "--ensemble", ENSEMBLE, "--metric", "bottleneck", "--bin-count", 4)),
                       ("fig9", ("ensemble", "--ensemble", ENSEMBLE, "--metric", "wasserstein2", "--force", "normal",
                                 "--force", "tangential", "--dim", 1, "--bins", 0.05)),
                       ("fig10", ("ensemble", "--ensemble", ENSEMBLE, "--metric", "bottleneck", "--axis",
                                  "rho-minus-rho-j")),
                       ("run-binned", ("distances", "--run", members()[0], "--metric", "bottleneck", "--bins", 0.05)),
                       ("fig7", ("ratio", "--ensemble", ENSEMBLE, "--dim", 1)),
                       ("run-ratio", ("ratio", "--run", members()[1], "--ratio", "wasserstein2")),
                       ("run-ratio-binned", ("ratio", "--run", members()[1], "--bin-count", 3))]:
        out = tmp_path / f"{name}.png"
        expect_png(plot(*args, *port, "--out", out), out)
    r = plot("ensemble", "--ensemble", "nope", "--metric", "bottleneck", *port, "--out", tmp_path / "x.png")
    assert r.returncode == 4 and "nope" in r.stderr
