"""fnet.figures drawing what a real fnet-server serves (the LAMMPS frames of tests/data) and what a
real fnet-simd run wrote: each figure is rendered to PNG, and the data of its artists is the data
it was given, point for point."""

import collections
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


def caption(fig):
    return fig._supxlabel.get_text()


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
        frame, walls = f.frame(3), figures.run_walls(f)
    for force in ("normal", "tangential"):
        fig = figures.network(frame, force=force, walls=walls)
        render(fig, tmp_path / f"network-{force}.png")
        (lines,) = artists(fig, "contacts")
        forces = np.abs(frame.contact_forces[:, 0 if force == "normal" else 1])
        keep = forces > 0
        pairs = frame.contact_pairs[keep]
        xy = frame.particles[:, :2]
        segments = np.array(lines.get_segments())
        np.testing.assert_array_equal(segments[:, 0], xy[pairs[:, 0]])
        np.testing.assert_array_equal(segments[:, 1], xy[pairs[:, 1]])
        values = forces[keep] / forces[keep].mean()
        np.testing.assert_allclose(lines.get_array(), values, rtol=1e-15)
        (grains,) = artists(fig, "grains")
        assert len(grains.get_paths()) == len(frame.particles)
        # The colour scale ends at the 99th percentile, below the strongest contact, whose value the
        # colour bar's label states; lengths are in d.
        assert lines.norm.vmin == 0 and lines.norm.vmax == np.percentile(values, 99) < values.max()
        assert f"max {values.max():.3g}" in fig.axes[1].get_ylabel()
        assert fig.axes[0].get_xlabel() == "$x / d$" and fig.axes[0].get_ylabel() == "$y / d$"


def grain_wall_overlaps(frame, disks):
    """How far each grain overlaps its nearest wall disk (> 0: they touch)."""
    p = frame.particles
    gap = np.hypot(p[:, None, 0] - disks[None, :, 0], p[:, None, 1] - disks[None, :, 1]) - p[:, None, 2] - disks[:, 2]
    return -gap.min(axis=1)


def test_walls_are_where_the_run_recorded_its_grains_touching_them(run_file, tmp_path):
    # The wall disks are placed from the run's box and each frame's rho alone; fnet-simd recorded
    # which grains touch a wall: exactly those overlap a drawn wall disk.
    with fnet.store.open_run_file(run_file) as f:
        walls = figures.run_walls(f)
        assert walls == {"box": f.config["box"], "wall_diameter": f.config.get("wall_diameter", 1.0)}
        touching = 0
        for index in f.frames:
            frame = f.frame(index)
            disks = figures.wall_disks(frame, walls)
            overlap = grain_wall_overlaps(frame, disks)
            recorded = set(frame.wall_contact_particles.tolist())
            # (1e-3 d: the contacts were found at the integrator's predicted positions, the frame
            # records the corrected ones)
            assert set(np.flatnonzero(overlap > 1e-3).tolist()) <= recorded <= set(
                np.flatnonzero(overlap > -1e-3).tolist()), f"frame {index}"
            touching += len(recorded)
            lo, hi = figures.free_interior(frame, walls)
            np.testing.assert_allclose((hi - lo) ** 2 * frame.rho, np.pi * np.sum(frame.particles[:, 2] ** 2),
                                       rtol=1e-12)
        assert touching > 0  # the walls were touched: the check above had something to check
    fig = figures.network(frame, walls=walls)
    render(fig, tmp_path / "walls.png")
    (drawn,) = artists(fig, "walls")
    np.testing.assert_allclose([p.get_extents().bounds for p in drawn.get_paths()],
                               np.column_stack([disks[:, :2] - disks[:, 2:], 2 * disks[:, 2:], 2 * disks[:, 2:]]),
                               atol=1e-9)
    assert "the walls" in caption(fig)
    with pytest.raises(ValueError, match="box"):
        figures.wall_disks(frame, {"box": 1.0, "wall_diameter": 1.0})


def test_without_walls_the_grains_bounding_box_is_drawn_and_said(run_file, tmp_path):
    with fnet.store.open_run_file(run_file) as f:
        frame = f.frame(3)
    fig = figures.network(frame)
    render(fig, tmp_path / "no-walls.png")
    (box,) = artists(fig, "walls")
    p = frame.particles
    np.testing.assert_allclose(box.get_xy(), (p[:, :2] - p[:, 2:]).min(axis=0))
    assert "bounding box" in caption(fig)


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
        a, b, walls = f.frame(2), f.frame(3), figures.run_walls(f)
    fig = figures.network_change(a, b, walls=walls)
    render(fig, tmp_path / "change.png")
    before = dict(zip(map(tuple, figures.normalized_network(a)[0].tolist()), figures.normalized_network(a)[1]))
    after = dict(zip(map(tuple, figures.normalized_network(b)[0].tolist()), figures.normalized_network(b)[1]))
    keys = sorted(set(before) | set(after))
    pairs, change = figures.contact_change(a, b)
    np.testing.assert_array_equal(pairs, keys)
    np.testing.assert_array_equal(change, [after.get(k, 0.0) - before.get(k, 0.0) for k in keys])
    # Contacts in both frames are coloured by their change; created and broken ones are drawn apart.
    xy = b.particles[:, :2]
    kinds = {"contacts": [k for k in keys if k in before and k in after],
             "created": [k for k in keys if k not in before], "broken": [k for k in keys if k not in after]}
    assert kinds["created"] and kinds["broken"] and kinds["contacts"]
    for gid, which in kinds.items():
        (lines,) = artists(fig, gid)
        segments = np.array(lines.get_segments())
        np.testing.assert_array_equal(segments[:, 0], xy[[k[0] for k in which]])
        np.testing.assert_array_equal(segments[:, 1], xy[[k[1] for k in which]])
    (kept,) = artists(fig, "contacts")
    np.testing.assert_array_equal(kept.get_array(), [after[k] - before[k] for k in kinds["contacts"]])
    (created,) = artists(fig, "created")
    (broken,) = artists(fig, "broken")
    assert created.get_linestyle()[0][1] is None and broken.get_linestyle()[0][1] is not None  # solid, dashed
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert legend[:2] == [f"created ({len(kinds['created'])})", f"broken ({len(kinds['broken'])})"]
    unchanged = figures.network_change(b, b)
    assert not np.any(artists(unchanged, "contacts")[0].get_array())
    assert not len(artists(unchanged, "created")[0].get_segments()) and not len(artists(unchanged, "broken")[0]
                                                                                 .get_segments())


def panel(fig, k):
    """(the diagram axes, the never-dies strip) of PDk."""
    (ax,) = [a for a in fig.axes if a.get_label() == f"PD{k}"]
    (strip,) = [a for a in fig.axes if a.get_label() == f"PD{k} never dies"]
    return ax, strip


def gid_in(ax, gid):
    return [a for a in ax.get_children() if a.get_gid() == gid]


def expect_counted(ax, gid, points):
    """The `gid` scatter of `ax` draws each distinct point of `points` once, its marker area by its
    count, and writes every count above 1 beside its point."""
    counts = collections.Counter(map(tuple, np.asarray(points).tolist()))
    distinct = sorted(counts)
    (scatter,) = gid_in(ax, gid)
    np.testing.assert_array_equal(scatter.get_offsets(), np.array(distinct).reshape(-1, 2))
    np.testing.assert_array_equal(scatter.get_sizes(), figures.marker_area([counts[p] for p in distinct]))
    labels = sorted((a.xy, a.get_text()) for a in gid_in(ax, "count"))
    assert labels == sorted((p, f"×{n}") for p, n in counts.items() if n > 1)


def test_diagrams_draw_the_served_points_and_never_dying_ones_apart(client, tmp_path):
    for frame in (4, 10):
        pd0, pd1 = client.diagram(frame, run=RUN, dim=0), client.diagram(frame, run=RUN, dim=1)
        fig = figures.diagrams(pd0, pd1, title=f"frame {frame}")
        render(fig, tmp_path / f"diagram-{frame}.png")
        for k, points in enumerate((pd0, pd1)):
            ax, strip = panel(fig, k)
            essential = points[:, 1] == -1
            assert len(points) and essential.any()  # every diagram here has both kinds of point
            assert k == 1 or not essential.all()  # PD0 has finite points too
            expect_counted(ax, "finite", points[~essential])
            expect_counted(strip, "never_dies", np.column_stack([points[essential, 0], np.zeros(essential.sum())]))
            assert not gid_in(ax, "never_dies") and ax.get_ylim()[0] > -0.05 * ax.get_ylim()[1]
            (diagonal,) = gid_in(ax, "diagonal")
            assert np.all(diagonal.get_xdata() == diagonal.get_ydata())
            legend = " ".join(t.get_text() for t in ax.get_legend().get_texts())
            assert f"finite: {(~essential).sum()} " in legend and f"(death −1): {essential.sum()} " in legend
            assert ax.get_xlabel().startswith("birth") and ax.get_ylabel().startswith("death")


def test_diagrams_count_coinciding_points(tmp_path):
    # Thirty rattlers born at 0 that never die are one marker that says 30, not an anonymous one.
    pd0 = np.array([[0.0, -1.0]] * 30 + [[2.5, -1.0]] + [[1.0, 0.5]] * 3 + [[2.0, 1.0]])
    pd1 = np.zeros((0, 2))
    fig = figures.diagrams(pd0, pd1)
    render(fig, tmp_path / "counted.png")
    ax, strip = panel(fig, 0)
    expect_counted(strip, "never_dies", [[0.0, 0.0]] * 30 + [[2.5, 0.0]])
    expect_counted(ax, "finite", [[1.0, 0.5]] * 3 + [[2.0, 1.0]])
    assert [a.get_text() for a in gid_in(strip, "count")] == ["×30"]
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert legend[:2] == ["finite: 4 (2 distinct)", "never die (death −1): 31 (2 distinct)"]
    ax1, strip1 = panel(fig, 1)  # an empty diagram draws empty panels
    assert not len(gid_in(ax1, "finite")[0].get_offsets()) and not len(gid_in(strip1, "never_dies")[0].get_offsets())


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


def test_blocks_over_the_packing_state_each_cells_normalization(client, server, tmp_path):
    b = client.blocks(9, 10, run=RUN, k=2, metric="bottleneck", dim=0)
    whole = client.distance(9, 10, "bottleneck", run=RUN, dim=0).value
    with fnet.store.open_store(server.store_path(RUN)) as st:
        network, other, unrelated = st.network(9), st.network(10), st.network(5)
    for frame, which in ((network, 0), (other, 1)):
        fig = figures.blocks(b, network=frame, whole=whole)
        render(fig, tmp_path / f"blocks-over-{frame.index}.png")
        (cells,) = artists(fig, "cells")
        np.testing.assert_array_equal(cells.get_array(), b.value.reshape(-1))
        for path, bounds in zip(cells.get_paths(), b.bounds[:, :, which].reshape(-1, 4)):
            np.testing.assert_allclose(path.get_extents().bounds, (bounds[0], bounds[2], bounds[1] - bounds[0],
                                                                   bounds[3] - bounds[2]), rtol=1e-12)
        ax = fig.axes[0]
        for r in range(2):
            for c in range(2):
                (text,) = [a for a in ax.texts if a.get_gid() == f"block_{r}_{c}"]
                x_lo, x_hi, y_lo, y_hi = b.bounds[r, c, which]
                assert text.get_position() == (0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi))
                assert text.get_text() == figures.block_text(float(b.value[r, c]))
        (contacts,) = artists(fig, "contacts")
        assert len(contacts.get_segments()) == len(figures.normalized_network(frame)[0])
        note = caption(fig)
        assert "normalized by its own mean force" in note and figures.block_text(whole) in note
    with pytest.raises(ValueError, match="frame 5 is neither frame"):
        figures.blocks(b, network=unrelated)


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
