"""fnet.figures drawing what a real fnet-server serves (the LAMMPS frames of tests/data) and what a
real fnet-simd run wrote: each figure is rendered to PNG, and the data of its artists is the data
it was given, point for point."""

import json
import subprocess

import numpy as np
import pytest

import fnet
import fnet.figures as figures
from conftest import LAMMPS_FRAMES, PNG_SIGNATURE, binary, simd_run_file

DOMAIN = 92
RUN = "lammps"


@pytest.fixture(scope="module")
def run_file(processes):
    return simd_run_file(processes, DOMAIN, frames=4)


def render(fig, path):
    fig.savefig(path)
    with open(path, "rb") as f:
        assert f.read(8) == PNG_SIGNATURE


def artists(fig, gid):
    found = [a for ax in fig.axes for a in ax.get_children() if a.get_gid() == gid]
    assert found, f"no artist {gid!r}"
    return found


def test_network_draws_every_contact_of_the_force_network(run_file, tmp_path):
    with fnet.store.open_run_file(run_file) as f:
        frame = f.frame(3)
    for force in ("normal", "tangential"):
        fig = figures.network(frame, force=force)
        render(fig, tmp_path / f"network-{force}.png")
        (lines,) = artists(fig, "contacts")
        forces = np.abs(frame.contact_forces[:, 0 if force == "normal" else 1])
        keep = forces > 0
        pairs = frame.contact_pairs[keep]
        xy = frame.particles[:, :2]
        segments = np.array(lines.get_segments())
        np.testing.assert_array_equal(segments[:, 0], xy[pairs[:, 0]])
        np.testing.assert_array_equal(segments[:, 1], xy[pairs[:, 1]])
        np.testing.assert_allclose(lines.get_array(), forces[keep] / forces[keep].mean(), rtol=1e-15)
        (grains,) = artists(fig, "grains")
        assert len(grains.get_paths()) == len(frame.particles)


def test_network_is_the_force_network_fnet_analyzes(run_file, tmp_path):
    # A real frame with contacts planted that carry no force (and tensile ones): the figure draws
    # exactly the edges fnet-analyze counts in its force network, normalized as it normalizes them.
    with fnet.store.open_run_file(run_file) as f:
        frame = f.frame(3)
    forces = frame.contact_forces.copy()
    forces[::5, 0] = 0.0
    forces[1::6, 0] *= -1.0
    forces[::7, 1] = 0.0
    frame.contact_forces = forces
    contacts = tmp_path / "contacts.csv"
    with open(contacts, "w") as out:
        out.write("i,j,fn,ft\n")
        for (i, j), (fn, ft) in zip(frame.contact_pairs.tolist(), forces.tolist()):
            out.write(f"{i},{j},{fn!r},{ft!r}\n")
    particles = tmp_path / "particles.csv"
    with open(particles, "w") as out:
        out.write("id,x,y,r\n")
        for k, (x, y, r) in enumerate(frame.particles.tolist()):
            out.write(f"{k},{x!r},{y!r},{r!r}\n")
    for force in ("normal", "tangential"):
        r = subprocess.run([binary("FNET_ANALYZE"), "diagram", "--contacts", contacts, "--particles", particles,
                            "--force", force], capture_output=True, text=True, timeout=120)
        assert r.returncode == 0, r.stderr
        analyzed = json.loads(r.stdout)
        (lines,) = artists(figures.network(frame, force=force), "contacts")
        assert len(lines.get_segments()) == analyzed["edges"] < len(frame.contact_pairs)
        # The strongest contact gives birth to the first component, at its normalized force.
        np.testing.assert_allclose(lines.get_array().max(), max(p[0] for p in analyzed["pd0"]), rtol=1e-12)


def test_network_change_is_after_minus_before(run_file, tmp_path):
    with fnet.store.open_run_file(run_file) as f:
        a, b = f.frame(2), f.frame(3)
    fig = figures.network_change(a, b)
    render(fig, tmp_path / "change.png")
    (lines,) = artists(fig, "contacts")
    before = dict(zip(map(tuple, figures.normalized_network(a)[0].tolist()), figures.normalized_network(a)[1]))
    after = dict(zip(map(tuple, figures.normalized_network(b)[0].tolist()), figures.normalized_network(b)[1]))
    keys = sorted(set(before) | set(after))
    np.testing.assert_array_equal(lines.get_array(), [after.get(k, 0.0) - before.get(k, 0.0) for k in keys])
    xy = b.particles[:, :2]
    np.testing.assert_array_equal(np.array(lines.get_segments())[:, 0], xy[[k[0] for k in keys]])
    unchanged = figures.network_change(b, b)
    assert not np.any(artists(unchanged, "contacts")[0].get_array())


def test_diagrams_draw_the_served_points_and_never_dying_ones_apart(client, tmp_path):
    for frame in (4, 10):
        pd0, pd1 = client.diagram(frame, run=RUN, dim=0), client.diagram(frame, run=RUN, dim=1)
        fig = figures.diagrams(pd0, pd1, title=f"frame {frame}")
        render(fig, tmp_path / f"diagram-{frame}.png")
        for ax, points in zip(fig.axes, (pd0, pd1)):
            (finite,) = [a for a in ax.get_children() if a.get_gid() == "finite"]
            (forever,) = [a for a in ax.get_children() if a.get_gid() == "never_dies"]
            essential = points[:, 1] == -1
            assert len(points) and essential.any()  # every diagram here has both kinds of point
            assert ax is fig.axes[1] or not essential.all()  # PD0 has finite points too
            np.testing.assert_array_equal(finite.get_offsets(), points[~essential])
            level = figures.never_dies_level(points)
            np.testing.assert_array_equal(forever.get_offsets(),
                                          np.column_stack([points[essential, 0], np.full(essential.sum(), level)]))
            assert level < points[~essential, 1].min(initial=0.0)


def test_distances_against_rho_with_z_on_a_second_axis(client, tmp_path):
    series = [client.series("bottleneck", run=RUN, dim=1), client.series("wasserstein2", run=RUN, dim=1)]
    fig = figures.distances(series)
    render(fig, tmp_path / "distances.png")
    lines = artists(fig, "distance")
    assert len(lines) == 2
    for line, s in zip(lines, series):
        keep = np.isfinite(s.value)
        assert keep.sum() == LAMMPS_FRAMES - 1
        np.testing.assert_array_equal(line.get_xydata(), np.column_stack([s.rho[keep], s.value[keep]]))
    (z,) = artists(fig, "z")
    np.testing.assert_array_equal(z.get_xydata(), np.column_stack([series[0].rho, series[0].z]))
    assert len(fig.axes) == 2 and fig.axes[1].get_ylabel() == "Z"


def test_infinite_distances_are_left_out_of_the_line(client, tmp_path):
    s = client.series("bottleneck", run=RUN, dim=1, essential="separate")
    assert s.infinite.any()
    fig = figures.distances(s)
    render(fig, tmp_path / "separate.png")
    (line,) = artists(fig, "distance")
    keep = np.isfinite(s.value)
    np.testing.assert_array_equal(drawn_points(line), np.column_stack([s.rho[keep], s.value[keep]]))
    # The line breaks where an infinite distance was left out: it joins only consecutive frames.
    rho = list(s.rho)
    for a, b in joined_pairs(line):
        assert rho.index(b[0]) == rho.index(a[0]) + 1
    assert len(joined_pairs(line)) == sum(keep[k] and keep[k + 1] for k in range(len(keep) - 1))


def test_store_series_plot_like_served_ones(server, client, tmp_path):
    with fnet.store.open_store(server.store_path(RUN)) as st:
        fig = figures.distances(st.series("wasserstein1", 0, "tangential"))
    render(fig, tmp_path / "stored.png")
    s = client.series("wasserstein1", run=RUN, dim=0, force="tangential")
    (line,) = artists(fig, "distance")
    np.testing.assert_array_equal(line.get_xydata(), np.column_stack([s.rho[1:], s.value[1:]]))


# ---- binned curves on log axes: gaps, values <= 0, clipped bars, rho_J -------------------------

def curve(means, stderr, bins, width=0.01, z=None):
    """An ensemble.series-like curve over the grid bins `bins` (k: [k w, (k+1) w))."""
    bins = np.asarray(bins)
    return {"rho_lo": bins * width, "rho_hi": (bins + 1) * width, "rho": (bins + 0.5) * width,
            "mean": np.asarray(means, dtype=float), "stderr": np.asarray(stderr, dtype=float),
            "n": np.full(len(bins), 4), "z": np.asarray(z if z is not None else np.linspace(1, 4, len(bins))),
            "bin_width": width}


def drawn_points(line):
    xy = line.get_xydata()
    return xy[~np.isnan(xy).any(axis=1)]


def joined_pairs(line):
    """The pairs of consecutive points a line joins (no NaN between them)."""
    xy = line.get_xydata()
    return [(xy[k], xy[k + 1]) for k in range(len(xy) - 1) if not np.isnan(xy[k:k + 2]).any()]


def test_log_axes_never_draw_values_at_or_below_zero_nor_join_across_empty_bins(tmp_path):
    # Bins 60-63 and 65-68 hold samples, 64 none; bin 62's mean is 0 (nothing changed), bin 66's
    # standard error exceeds its mean, bin 61's is undefined.
    c = curve([2.0, 1.5, 0.0, 1.0, 0.5, 0.2, 0.1, 0.05], [0.1, np.nan, 0.0, 0.2, 0.1, 0.3, 0.01, 0.01],
              [60, 61, 62, 63, 65, 66, 67, 68])
    fig = figures.ensemble(c, labels=["$d_B$"], log=True, rho_j={"mean": 0.645, "standard_error": 0.002, "n": 5},
                           title="system")
    render(fig, tmp_path / "log.png")
    ax = fig.axes[0]
    (line,) = artists(fig, "mean")
    keep = c["mean"] > 0
    np.testing.assert_array_equal(drawn_points(line), np.column_stack([c["rho"][keep], c["mean"][keep]]))
    assert (drawn_points(line)[:, 1] > 0).all()
    # No joined pair spans a bin that is empty (64) or left out (62).
    for a, b in joined_pairs(line):
        assert round((b[0] - a[0]) / 0.01) == 1, (a, b)
    assert len(joined_pairs(line)) == 4  # 60-61, 65-66, 66-67, 67-68
    # The zero mean is marked on the bottom edge, in axes coordinates.
    (zero,) = artists(fig, "nonpositive")
    np.testing.assert_array_equal(zero.get_xydata(), [[c["rho"][2], 0.0]])
    # Error bars: mean ± stderr, the lower end clipped at the axis' bottom, never <= 0.
    bottom = ax.get_ylim()[0]
    assert bottom > 0
    (bars,) = ax.containers
    segments = np.array(bars.lines[2][0].get_segments())
    se = np.nan_to_num(c["stderr"][keep])
    np.testing.assert_allclose(segments[:, 1, 1], c["mean"][keep] + se, rtol=1e-15)
    np.testing.assert_allclose(segments[:, 0, 1], np.maximum(c["mean"][keep] - se, bottom), rtol=1e-15)
    assert segments[:, 0, 1].min() >= bottom and segments[4, 0, 1] == bottom  # bin 66: 0.2 - 0.3 < 0
    # rho_J: a vertical line at its value, value ± standard error in the legend; Z in the legend.
    (rho_j,) = artists(fig, "rho_j")
    assert rho_j.get_xdata()[0] == 0.645
    texts = [t.get_text() for t in fig.legends[0].get_texts()] if fig.legends else \
        [t.get_text() for a in fig.axes if a.get_legend() for t in a.get_legend().get_texts()]
    assert texts == ["$d_B$", r"$\rho_J$ = 0.6450 ± 0.0020", "Z"]
    # Z follows the bins too: no line across the empty bin 64.
    (z,) = artists(fig, "z")
    np.testing.assert_array_equal(drawn_points(z), np.column_stack([c["rho"], c["z"]]))
    assert len(joined_pairs(z)) == 6
    assert ax.get_title() == "system"


def test_linear_axes_draw_every_finite_mean_and_break_at_gaps():
    c = curve([2.0, 0.0, -0.5, 1.0], [0.1, 0.1, 0.1, 0.1], [10, 11, 13, 14])
    (line,) = artists(figures.ensemble(c), "mean")
    np.testing.assert_array_equal(drawn_points(line), np.column_stack([c["rho"], c["mean"]]))
    assert len(joined_pairs(line)) == 2  # 10-11 and 13-14, not 11-13


def test_ratio_curves_on_log_axes_and_against_rho_minus_rho_j():
    c = curve([0.7, np.nan, 0.6, 0.0, 0.5], [np.nan] * 5, [70, 71, 72, 73, 74])
    c.update(ratio="wasserstein2", axis="rho_minus_rho_j")
    fig = figures.ratio(c, log=True, rho_j=[{"mean": 0.81, "standard_error": 0.001, "label": "a"},
                                            {"mean": 0.83, "standard_error": None, "label": "b"}])
    (line,) = artists(fig, "ratio")
    np.testing.assert_array_equal(drawn_points(line), [[c["rho"][k], c["mean"][k]] for k in (0, 2, 4)])
    assert joined_pairs(line) == []  # 71 undefined and 73 zero: every neighbour is missing
    marks = artists(fig, "rho_j")
    assert [m.get_xdata()[0] for m in marks] == [0.0, 0.0]  # against rho - rho_J, rho_J is at 0
    assert fig.axes[0].get_xlabel() == figures.AXIS_LABELS["rho_minus_rho_j"]
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert labels[1:] == [r"$\rho_J$ = 0.8100 ± 0.0010 (a)", r"$\rho_J$ = 0.8300 (b)"]


def test_a_runs_distances_on_log_axes_break_where_a_frame_is_left_out():
    s = {"run": "r", "rho": np.array([0.60, 0.61, 0.62, 0.63, 0.64, 0.65]), "z": np.linspace(0, 3, 6),
         "value": np.array([np.nan, 1.0, np.inf, 0.5, 0.0, 0.2]), "metric": "bottleneck", "dim": 1}
    fig = figures.distances(s, log=True, rho_j=0.625)
    (line,) = artists(fig, "distance")
    np.testing.assert_array_equal(drawn_points(line), [[0.61, 1.0], [0.63, 0.5], [0.65, 0.2]])
    assert joined_pairs(line) == []  # the infinite and the zero distance leave gaps
    (zero,) = artists(fig, "nonpositive")
    np.testing.assert_array_equal(zero.get_xydata(), [[0.64, 0.0]])
    assert artists(fig, "rho_j")[0].get_xdata()[0] == 0.625
    assert fig.axes[0].get_legend_handles_labels()[1][0] == "r $d_B$ PD1, normal forces"
