"""blocks.get through fnet.Client, fnet.figures.blocks and the command line, against a real
fnet-server holding the LAMMPS frames of tests/data: the k x k arrays are the served cells, the
heat map and its numbers are those arrays, and an unchanged frame's blocks are at distance 0."""

import numpy as np
import pytest

import fnet
import fnet.figures as figures
from conftest import LAMMPS, expect_png, plot

DOMAIN = 94
RUN = "lammps"


def test_block_arrays_are_the_served_cells(client):
    b = client.blocks(9, 10, run=RUN, k=2, metric="bottleneck", dim=1)
    raw = client.call("blocks.get", {"run": RUN, "frame": 9, "other_frame": 10, "k": 2, "metric": "bottleneck",
                                     "dim": 1})
    assert b.value.shape == (2, 2) and b.contacts.shape == (2, 2, 2) and b.bounds.shape == (2, 2, 2, 4)
    assert len(raw["cells"]) == 4
    for cell in raw["cells"]:
        r, c = cell["row"], cell["col"]
        assert b.value[r, c] == cell["value"]
        assert list(b.contacts[r, c]) == cell["contacts"] and list(b.points[r, c]) == cell["points"]
        np.testing.assert_array_equal(b.bounds[r, c], cell["bounds"])
    # row 0 is the lowest y, col 0 the lowest x
    assert b.bounds[0, 0, 0, 2] < b.bounds[1, 0, 0, 2] and b.bounds[0, 0, 0, 0] < b.bounds[0, 1, 0, 0]
    r, c = np.unravel_index(np.nanargmax(b.value), b.value.shape)
    assert (b.largest["row"], b.largest["col"]) == (r, c) and b.largest["value"] == b.value[r, c]


def test_unchanged_frame_blocks_are_at_distance_zero(client):
    b = client.blocks(5, 5, run=RUN, k=3, metric="wasserstein2", dim=0, force="tangential")
    assert b.value.shape == (3, 3)
    np.testing.assert_array_equal(b.value, np.zeros((3, 3)))


def test_bad_block_parameters_are_rpc_errors(client):
    with pytest.raises(fnet.RpcError) as e:
        client.blocks(1, 2, run=RUN, k=0)
    assert e.value.code == -32602 and e.value.data["parameter"] == "k"
    with pytest.raises(fnet.RpcError) as e:
        client.blocks(1, 99, run=RUN)
    assert e.value.code == -32002


def test_block_table_figure_shows_the_served_values(client, tmp_path):
    b = client.blocks(8, 10, run=RUN, k=3, metric="wasserstein1", dim=1)
    fig = figures.blocks(b)
    fig.savefig(tmp_path / "blocks.png")
    ax = fig.axes[0]
    (image,) = [a for a in ax.get_children() if a.get_gid() == "blocks"]
    np.testing.assert_array_equal(image.get_array(), b.value)
    assert image.origin == "lower"
    for r in range(3):
        for c in range(3):
            (text,) = [a for a in ax.texts if a.get_gid() == f"block_{r}_{c}"]
            assert text.get_position() == (c, r) and text.get_text() == figures.block_text(float(b.value[r, c]))
    (frame,) = [a for a in ax.patches if a.get_gid() == "largest"]
    assert frame.get_xy() == (b.largest["col"] - 0.5, b.largest["row"] - 0.5)


def test_command_line_draws_the_block_table(server, tmp_path):
    out = tmp_path / "table2.png"
    expect_png(plot("blocks", "--run", RUN, "--frame", "9", "--other-frame", "10", "--k", "2", "--metric", "bottleneck",
                    "--dim", "1", "--port", server.port, "--out", out), out)


def test_store_keeps_each_frame_network_and_the_figure_draws_it(server, tmp_path):
    with fnet.store.open_store(server.store_path(RUN)) as st:
        assert st.schema == "fnet-store-3"
        frame = st.network(7)
    particles = np.loadtxt(LAMMPS / "frame_0007_particles.csv", delimiter=",", skiprows=1).reshape(-1, 4)
    contacts = np.loadtxt(LAMMPS / "frame_0007_contacts.csv", delimiter=",", skiprows=1).reshape(-1, 4)
    np.testing.assert_array_equal(frame.particles, particles[np.argsort(particles[:, 0]), 1:4])

    def canonical(pairs, forces):  # rows as (min, max, fn, ft), sorted: order and orientation aside
        rows = np.column_stack([np.sort(pairs, axis=1), forces])
        return rows[np.lexsort((rows[:, 1], rows[:, 0]))]
    np.testing.assert_array_equal(canonical(frame.contact_pairs, frame.contact_forces),
                                  canonical(contacts[:, 0:2], contacts[:, 2:4]))
    out = tmp_path / "network.png"
    expect_png(plot("network", "--store", server.store_path(RUN), "--frame", "6", "--other-frame", "7", "--out", out),
               out)
