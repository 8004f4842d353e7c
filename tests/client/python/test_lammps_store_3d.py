"""A real 3D LAMMPS run through an analysis store into the figures: Debian's lmp compresses 343
spheres with proto/lammps.md's 3D dump lines (tests/support/lammps_inputs.py; a frame every 2000
steps), `fnet-analyze store --lammps-atoms ... --lammps-pairs ...` stores it, and
fnet.store.Store(...).network(k) reads each frame back. Checked against the dumps read here: every
grain's x, y, z and r, and the contacts with their forces. figures.network and figures.network_change
draw those stored frames (the contacts in the slab, worked out here, with their force or its change);
figures.blocks draws the k x k x k table fnet-server serves from the same store (DDS domain 202, on
which nothing is published), whose cells hold the contacts counted here in the stored frames."""

import subprocess
import sys

import numpy as np
import pytest

import fnet
import fnet.figures as figures
from conftest import SOURCE_DIR, artists, binary, canonical, expect_png, plot, render, start_server

sys.path.insert(0, str(SOURCE_DIR / "tests" / "support"))
import lammps_inputs  # noqa: E402
from lammps_doc import blocks, run_lammps  # noqa: E402

DOMAIN = 202  # CONTRIBUTING.md: this file's fnet-server
RUN = "spheres"
EVERY = 2000
STEPS = list(range(0, lammps_inputs.SPHERES_STEPS + 1, EVERY))


@pytest.fixture(scope="module")
def dumps(tmp_path_factory):
    """The folder of the run's dumps and of `stores/`, the store fnet-analyze made of them."""
    work = tmp_path_factory.mktemp("lammps")
    lines = blocks((SOURCE_DIR / "proto" / "lammps.md").read_text(), "lammps 3d")[0].replace(" 1000 ", f" {EVERY} ")
    wrong = run_lammps("lmp", str(work), lammps_inputs.spheres(lines))
    assert not wrong, wrong
    r = subprocess.run([binary("FNET_ANALYZE"), "store", "--lammps-atoms", "atoms.*.txt", "--lammps-pairs",
                        "pairs.*.txt", "--lammps-log", "log.lammps", "--run-id", RUN, "--data-dir", "stores"],
                       cwd=work, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return work


@pytest.fixture(scope="module")
def stored(dumps):
    """{frame: fnet.store.Frame} of every frame of the store, read back with Store.network."""
    with fnet.store.open_store(dumps / "stores" / f"{RUN}.h5") as s:
        return {int(k): s.network(int(k)) for k in s.frames}


def read_dump(path):
    """(columns, rows) of a one-snapshot text dump."""
    lines = path.read_text().splitlines()
    head = next(k for k, line in enumerate(lines) if line.startswith(("ITEM: ATOMS", "ITEM: ENTRIES")))
    columns = lines[head].split()[2:]
    return columns, np.array([[float(v) for v in line.split()] for line in lines[head + 1:]]).reshape(-1, len(columns))


def dumped(work, step):
    """(x, y, z, r by grain, {(i, j) i < j: (|normal vector|, |tangential vector|)}) of a step's
    dumps: grain k the k-th atom by id."""
    columns, atoms = read_dump(work / f"atoms.{step}.txt")
    atoms = atoms[np.argsort(atoms[:, columns.index("id")])]
    grain = {int(a): k for k, a in enumerate(atoms[:, columns.index("id")])}
    xyzr = atoms[:, [columns.index(c) for c in ("x", "y", "z", "radius")]]
    _, pairs = read_dump(work / f"pairs.{step}.txt")
    forces = {}
    for row in pairs:
        i, j = grain[int(row[0])], grain[int(row[1])]
        forces[(min(i, j), max(i, j))] = (np.linalg.norm(row[2:5]), np.linalg.norm(row[5:8]))
    return xyzr, forces


def contact_z(xyzr, pairs):
    """The z of each pair's contact point, worked out here: r_i from grain i's centre towards j."""
    i, j = pairs[:, 0], pairs[:, 1]
    d = xyzr[j, :3] - xyzr[i, :3]
    return xyzr[i, 2] + xyzr[i, 3] * d[:, 2] / np.linalg.norm(d, axis=1)


def middle_slab(xyzr, half=1.0):
    mid = 0.5 * ((xyzr[:, 2] - xyzr[:, 3]).min() + (xyzr[:, 2] + xyzr[:, 3]).max())
    return mid - half, mid + half


def test_the_store_holds_each_grains_z_and_the_contacts_as_dumped(dumps, stored):
    assert sorted(stored) == list(range(len(STEPS)))
    for k, frame in stored.items():
        assert frame.dimension == 3 and frame.step == STEPS[k]
        xyzr, forces = dumped(dumps, frame.step)
        np.testing.assert_array_equal(frame.particle_z, xyzr[:, 2])
        np.testing.assert_array_equal(frame.particles, xyzr[:, [0, 1, 3]])
        pairs = [(min(i, j), max(i, j)) for i, j in frame.contact_pairs.tolist()]
        assert sorted(pairs) == sorted(forces), f"step {frame.step}: the stored contacts are the dumped pairs"
        # fnet's F_n is the normal vector's component along the 3D line of centres (their directions
        # differ by up to about 1e-8 while the box shrinks); F_t the tangential vector's length.
        want = np.array([forces[p] for p in pairs]).reshape(-1, 2)
        np.testing.assert_allclose(np.abs(frame.contact_forces), want, rtol=1e-6, atol=1e-12)
    assert len(stored[len(STEPS) - 1].contact_pairs) > 1000, "the last frame is a packing"


def test_a_stored_frame_is_drawn_with_its_stored_contacts(dumps, stored, tmp_path):
    frame = stored[len(STEPS) - 1]
    xyzr, _ = dumped(dumps, frame.step)
    fn = np.abs(frame.contact_forces[:, 0])
    pairs, values = frame.contact_pairs[fn > 0], fn[fn > 0] / fn[fn > 0].mean()
    segments = np.stack([xyzr[pairs[:, 0], :2], xyzr[pairs[:, 1], :2]], axis=1)
    lo, hi = middle_slab(xyzr)
    z = contact_z(xyzr, pairs)
    inside = (z >= lo) & (z <= hi)
    assert 100 < inside.sum() < len(pairs) / 2
    for name, options, keep in (("slab", {}, inside), ("projection", {"projection": True}, np.ones(len(pairs), bool))):
        fig = figures.network(frame, **options)
        render(fig, tmp_path / f"network-{name}.png")
        (lines,) = artists(fig, "contacts")
        np.testing.assert_array_equal(canonical(lines.get_segments(), lines.get_array()),
                                      canonical(segments[keep], values[keep]))


def test_the_change_between_two_stored_frames_is_drawn_in_the_slab(dumps, stored, tmp_path):
    before, after = stored[3], stored[4]  # steps 6000 and 8000: the packing jams as it is squeezed
    xyzr, _ = dumped(dumps, after.step)
    normalized = []
    for frame in (before, after):
        fn = np.abs(frame.contact_forces[:, 0])
        pairs = frame.contact_pairs[fn > 0]
        normalized.append(dict(zip(map(tuple, np.sort(pairs, axis=1).tolist()), fn[fn > 0] / fn[fn > 0].mean())))
    a, b = normalized
    every = sorted(set(a) | set(b))
    pairs = np.array(every)
    lo, hi = middle_slab(xyzr)
    z = contact_z(xyzr, pairs)
    inside = {p for p, zp in zip(every, z) if lo <= zp <= hi}
    kinds = {"contacts": [p for p in every if p in a and p in b and p in inside],
             "created": [p for p in every if p not in a and p in inside],
             "broken": [p for p in every if p not in b and p in inside]}
    assert len(kinds["contacts"]) > 100 and len(kinds["created"]) > 10, {k: len(v) for k, v in kinds.items()}

    fig = figures.network_change(before, after)
    render(fig, tmp_path / "change-slab.png")
    for gid, which in kinds.items():
        (lines,) = artists(fig, gid)
        which = np.array(which, dtype=np.int64).reshape(-1, 2)
        want = np.stack([xyzr[which[:, 0], :2], xyzr[which[:, 1], :2]], axis=1)
        change = [b[p] - a[p] for p in map(tuple, which.tolist())] if gid == "contacts" else np.zeros(len(which))
        got = lines.get_array() if gid == "contacts" else np.zeros(len(lines.get_segments()))
        np.testing.assert_array_equal(canonical(lines.get_segments(), got), canonical(want, change), err_msg=gid)
    (lines,) = artists(fig, "contacts")
    assert np.all(np.diff(np.abs(lines.get_array())) >= 0), "the largest changes drawn on top"
    # The scale is that of the changes of every contact in both networks, not only those drawn.
    span = np.percentile(np.abs([b[p] - a[p] for p in every if p in a and p in b]), 99)
    assert lines.norm.vmax == pytest.approx(span, rel=1e-12) and lines.norm.vmin == pytest.approx(-span, rel=1e-12)
    caption = fig._supxlabel.get_text()
    assert f"the {len(inside)} of {len(every)} contacts of either network" in caption, caption
    assert "(volume fraction)" in fig.axes[0].get_title() and "3D" in fig.axes[0].get_title()
    assert fig.axes[0].get_xlabel() == "$x / d$" and "over the whole networks" in fig.axes[1].get_ylabel()
    (grains,) = artists(fig, "grains")
    assert len(grains.get_paths()) == len(figures.slab_discs(after, (lo, hi))[0]) > 50

    projected = figures.network_change(before, after, projection=True)
    render(projected, tmp_path / "change-projection.png")
    assert not artists(projected, "grains")
    (lines,) = artists(projected, "contacts")
    assert len(lines.get_segments()) == len([p for p in every if p in a and p in b])
    with pytest.raises(ValueError, match="one dimension"):
        figures.network_change(before, fnet.store.Frame(dict(after, dimension=2)))


def test_the_command_line_draws_the_change_between_two_stored_3d_frames(dumps, tmp_path):
    for name, view in (("slab", ["--slab", "1.5"]), ("projection", ["--projection"])):
        out = tmp_path / f"change-{name}.png"
        expect_png(plot("network", "--store", dumps / "stores" / f"{RUN}.h5", "--frame", 3, "--other-frame", 4,
                        *view, "--out", out), out)


def test_the_served_block_table_of_the_store_is_drawn_layer_by_layer(dumps, stored, processes, tmp_path):
    server = start_server(processes, DOMAIN, data=dumps / "stores")
    k, first, second = 2, 4, 5
    with server.client() as c:
        table = c.blocks(first, second, run=RUN, k=k, metric="bottleneck", dim=1)
    assert table["dimension"] == 3 and table.value.shape == (k, k, k)
    # Each cell's contacts, counted here in the stored frames: those whose contact point lies in
    # the cell of a k x k x k grid over the spheres' box (a point on a boundary in the higher cell).
    for which, index in enumerate((first, second)):
        frame = stored[index]
        xyzr = np.column_stack([frame.particles[:, :2], frame.particle_z, frame.particles[:, 2]])
        lo = (xyzr[:, :3] - xyzr[:, 3:]).min(axis=0)
        hi = (xyzr[:, :3] + xyzr[:, 3:]).max(axis=0)
        pairs = frame.contact_pairs
        i, j = pairs[:, 0], pairs[:, 1]
        d = xyzr[j, :3] - xyzr[i, :3]
        point = xyzr[i, :3] + xyzr[i, 3:] * d / np.linalg.norm(d, axis=1)[:, None]
        cell = np.clip(np.floor((point - lo) / (hi - lo) * k).astype(int), 0, k - 1)
        counts = np.zeros((k, k, k), dtype=np.int64)
        np.add.at(counts, (cell[:, 2], cell[:, 1], cell[:, 0]), 1)
        np.testing.assert_array_equal(table.contacts[..., which], counts, err_msg=f"frame {index}")
    fig = figures.blocks(table)
    render(fig, tmp_path / "blocks-3d.png")
    images = artists(fig, "blocks")
    assert len(images) == k
    for layer, image in enumerate(images):
        np.testing.assert_array_equal(image.get_array().filled(np.nan), table.value[layer])
    assert np.all(np.isfinite(table.value)) and table.value.max() > 0
