"""fnet.figures on 3D frames from a real LAMMPS run (lammps_3d.py): a slab of the network seen from
+z draws exactly the contacts whose contact point lies in it, coloured by force over the mean, and
each sphere's part inside it; the projection draws every contact; a 3D run's distances are drawn
against its volume fraction, and a 3D block table layer by layer. Every figure is rendered to PNG."""

import json
import math
import subprocess

import numpy as np
import pytest

import fnet
import fnet.figures as figures
from conftest import artists, binary, canonical, render
from fnet.rpc import _blocks
from fnet.store import Frame
from lammps_3d import compression_run, settled_frame


@pytest.fixture(scope="module")
def settled(tmp_path_factory):
    return settled_frame(tmp_path_factory.mktemp("settle"))


def test_a_slab_draws_exactly_the_contacts_whose_contact_point_lies_in_it(settled, tmp_path):
    f = settled
    assert len(f.particles) > 400 and len(f.contact_pairs) > 800, "a packing, not a gas"
    p = np.column_stack([f.particles, f.particle_z])  # x, y, r, z
    forces = np.abs(f.contact_forces[:, 0])
    network = forces > 0
    pairs, values = f.contact_pairs[network], forces[network] / forces[network].mean()
    # The slab and the contact points worked out here: the middle of the spheres' z extent, +-1 d;
    # the contact point at r_i from grain i's centre towards j.
    z_lo, z_hi = (p[:, 3] - p[:, 2]).min(), (p[:, 3] + p[:, 2]).max()
    lo, hi = (z_lo + z_hi) / 2 - 1, (z_lo + z_hi) / 2 + 1
    i, j = pairs[:, 0], pairs[:, 1]
    zi, zj = p[i, 3], p[j, 3]
    distance = np.sqrt((p[j, 0] - p[i, 0]) ** 2 + (p[j, 1] - p[i, 1]) ** 2 + (zj - zi) ** 2)
    contact_z = zi + p[i, 2] * (zj - zi) / distance
    inside = (contact_z >= lo) & (contact_z <= hi)
    assert 100 < inside.sum() < len(pairs) / 2

    fig = figures.network(f)
    render(fig, tmp_path / "slab.png")
    (lines,) = artists(fig, "contacts")
    expected = np.stack([p[i[inside]][:, :2], p[j[inside]][:, :2]], axis=1)
    np.testing.assert_array_equal(canonical(lines.get_segments(), lines.get_array()),
                                  canonical(expected, values[inside]))
    assert np.all(np.diff(lines.get_array()) >= 0), "weakest first: the strong chains are drawn on top"
    # The colour scale is the whole network's, to its 99th percentile.
    assert lines.norm.vmin == 0 and lines.norm.vmax == np.percentile(values, 99)
    # Each sphere that reaches into the slab is one disc: its part inside, seen from +z.
    (grains,) = artists(fig, "grains")
    gap = np.maximum(np.maximum(lo - p[:, 3], p[:, 3] - hi), 0)
    reaching = gap < p[:, 2]
    radii = sorted(0.5 * path.get_extents().width for path in grains.get_paths())
    np.testing.assert_allclose(radii, np.sort(np.sqrt(p[reaching, 2] ** 2 - gap[reaching] ** 2)), rtol=1e-9)
    caption = fig._supxlabel.get_text()
    assert f"the {int(inside.sum())} of {len(pairs)} contacts" in caption and "2 d thick" in caption
    assert "volume fraction" in fig.axes[0].get_title()
    assert fig.axes[0].get_xlabel() == "$x / d$" and fig.axes[0].get_ylabel() == "$y / d$"
    assert "over the whole network" in fig.axes[1].get_ylabel()
    # Under gravity along -y the strongest contacts sit low: the figure shows the gradient.
    strong = values[inside] > np.percentile(values[inside], 80)
    assert p[i[inside][strong], 1].mean() < p[i[inside]][:, 1].mean()


def test_a_thicker_slab_and_the_projection_draw_more(settled, tmp_path):
    f = settled
    forces = np.abs(f.contact_forces[:, 0])
    drawn = []
    for name, options in (("slab1", {}), ("slab2", {"slab": 2.0}), ("projection", {"projection": True})):
        fig = figures.network(f, **options)
        render(fig, tmp_path / f"{name}.png")
        (lines,) = artists(fig, "contacts")
        drawn.append(len(lines.get_segments()))
        if name == "projection":
            assert not artists(fig, "grains")
            assert "every contact of the network" in fig._supxlabel.get_text()
    assert drawn[0] < drawn[1] < drawn[2] == int((forces > 0).sum())


def small_frame():
    """Three spheres of radius 0.5 at z 0, 1.3 and 2, the first two touching along z."""
    return Frame(index=4, run="hand", dimension=3, rho=0.5, z=0.67, particle_z=np.array([0.0, 0.95, 2.0]),
                 particles=np.array([[0.0, 0.0, 0.5], [0.0, 0.1, 0.5], [3.0, 0.0, 0.5]]),
                 contact_pairs=np.array([[0, 1]]), contact_forces=np.array([[2.0, 0.5]]))


def test_slab_discs_and_contact_points_by_hand():
    f = small_frame()
    point = figures.contact_points(f, f.contact_pairs)[0]
    length = math.sqrt(0.1 ** 2 + 0.95 ** 2)
    np.testing.assert_allclose(point, [0.0, 0.5 * 0.1 / length, 0.5 * 0.95 / length], rtol=1e-15)
    indices, radii = figures.slab_discs(f, (-1.0, 1.0))
    # Sphere 0 is inside (its whole disc); sphere 1's centre is 0.95 <= 1 inside too; sphere 2
    # is 1 away from the slab, farther than its radius.
    assert indices.tolist() == [0, 1] and radii.tolist() == [0.5, 0.5]
    indices, radii = figures.slab_discs(f, (-1.0, 0.7))
    np.testing.assert_allclose(radii, [0.5, math.sqrt(0.25 - 0.25 ** 2)])
    assert figures.slab_of(f, 1.0) == (0.0, 2.0)  # the spheres span z from -0.5 to 2.5
    assert figures.in_slab(f, f.contact_pairs, (0.4, 1.0)).tolist() == [True]
    assert figures.in_slab(f, f.contact_pairs, (0.5, 1.0)).tolist() == [False]
    with pytest.raises(ValueError, match="walls"):
        figures.network(f, walls={"box": 10.0, "wall_diameter": 1.0})
    with pytest.raises(ValueError, match="walls"):
        figures.network_change(f, f, walls={"box": 10.0, "wall_diameter": 1.0})
    with pytest.raises(ValueError, match="needs particle_z"):
        figures.network(Frame({k: v for k, v in f.items() if k != "particle_z"}))


@pytest.fixture(scope="module")
def compressed_series(tmp_path_factory):
    """The compression's d_B(PD1) between consecutive frames, each from fnet-analyze on the two
    frames' contacts (positions play no part in a distance), as a series of a 3D run."""
    run, rho, z = compression_run(tmp_path_factory.mktemp("compress"))
    value = [math.nan]
    for k in range(1, len(rho)):
        r = subprocess.run([binary("FNET_ANALYZE"), "explain", str(run / f"frame_{k - 1:04d}_contacts.csv"),
                            str(run / f"frame_{k:04d}_contacts.csv"), "--metric", "bottleneck", "--dim", "1", "--k",
                            "1", "--format", "json"], capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, r.stderr
        value.append(json.loads(r.stdout)["value"])
    return fnet.Result(run="lammps-3d", metric="bottleneck", dim=1, force="normal", essential="floor", dimension=3,
                       frame=np.arange(len(rho)), rho=rho, z=z, value=np.array(value, dtype=np.float64))


def test_a_3d_runs_distances_are_drawn_against_its_volume_fraction(compressed_series, tmp_path):
    series = compressed_series
    assert series.rho[0] < 0.62 < 0.66 < series.rho[-1], "the run goes through jamming"
    assert series.z[0] < 4 < 6 < series.z[-1]
    assert np.all(series.value[1:] >= 0) and np.any(series.value[1:] > 0)
    fig = figures.distances(series, log=True)
    render(fig, tmp_path / "distances-3d.png")
    assert fig.axes[0].get_xlabel() == r"$\rho$ (volume fraction)"
    (line,) = artists(fig, "distance")
    x, y = line.get_data()
    keep = np.isfinite(series.value) & (series.value > 0)
    np.testing.assert_array_equal(x[np.isfinite(y)], series.rho[keep])
    np.testing.assert_array_equal(y[np.isfinite(y)], series.value[keep])
    (zline,) = artists(fig, "z")
    np.testing.assert_array_equal(zline.get_data()[1], series.z)
    # `dimension` given wins over what the series carries; a 2D series keeps the plain rho.
    assert figures.distances(series, dimension=2).axes[0].get_xlabel() == r"$\rho$"
    flat = fnet.Result({k: v for k, v in series.items() if k != "dimension"})
    assert figures.distances(flat).axes[0].get_xlabel() == r"$\rho$"
    assert figures.ensemble(dict(flat, mean=flat.value, stderr=np.zeros(len(flat.value))),
                            dimension=3).axes[0].get_xlabel() == r"$\rho$ (volume fraction)"


def test_a_3d_block_table_is_drawn_layer_by_layer(tmp_path):
    # blocks.get of a 3D run as proto/api.md writes it: cells layer by layer, each with its layer.
    k = 2
    cells = [{"layer": n // 4, "row": n // 2 % 2, "col": n % 2, "bounds": [[0, 1, 0, 1, 0, 1]] * 2,
              "contacts": [n, n + 1], "points": [2 * n, 2 * n + 1], "value": 0.1 * n, "infinite": False}
             for n in range(8)]
    cells[6]["value"], cells[6]["infinite"] = None, True
    table = _blocks({"run": "r", "frame": 3, "other_frame": 4, "k": k, "dimension": 3, "metric": "bottleneck",
                     "dim": 1, "force": "normal", "essential": "separate", "cells": cells,
                     "largest": {"layer": 1, "row": 1, "col": 0, "value": None}})
    assert table.value.shape == (2, 2, 2) and table.bounds.shape == (2, 2, 2, 2, 6)
    assert table.value[0, 1, 0] == 0.1 * 2 and table.value[1, 0, 1] == 0.1 * 5 and table.value[1, 1, 0] == math.inf
    assert table.contacts[1, 1, 1].tolist() == [7, 8]
    fig = figures.blocks(table)
    render(fig, tmp_path / "blocks-3d.png")
    images = artists(fig, "blocks")
    assert len(images) == 2
    for layer, image in enumerate(images):
        np.testing.assert_array_equal(image.get_array().filled(np.nan),
                                      np.where(np.isfinite(table.value[layer]), table.value[layer], np.nan))
    texts = {t.get_gid(): t.get_text() for ax in fig.axes for t in ax.texts}
    assert texts["block_1_1_0"] == "∞" and texts["block_0_0_1"] == "0.1"
    (largest,) = artists(fig, "largest")
    assert largest.axes is fig.axes[1] and largest.get_xy() == (-0.5, 0.5)
    with pytest.raises(ValueError, match="3D table"):
        figures.blocks(table, network=small_frame())
