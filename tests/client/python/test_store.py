"""fnet.store against files fnet writes: a run file of a real fnet-simd run (checked against the
same run's CSV export, the daemon's other output), the first schema's run file kept in tests/data
(against its CSV), and the analysis store fnet-server wrote for that run (against what the server
serves, and the run file's contacts)."""

import csv
import os
import subprocess
import sys
import time

import numpy as np
import pytest

import fnet
import fnet.figures
from conftest import (LAMMPS_FRAMES, SOURCE_DIR, publish_lammps, simd_args, start_server, wait_for, wait_for_frames,
                      wait_for_run_file)

DOMAIN = 91
LIVE_DOMAIN = 97
RUN = "simd"
FRAMES = 8
LEGACY = SOURCE_DIR / "tests" / "data" / "run-file-v1"
LEGACY_V2 = SOURCE_DIR / "tests" / "data" / "run-file-v2"


@pytest.fixture(scope="module")
def simd_run(processes):
    server = start_server(processes, DOMAIN)
    out, csv_dir = processes.tmp / "run.h5", processes.tmp / "csv"
    processes.start(simd_args(DOMAIN, out=out, frames=FRAMES, run_id=RUN) + ["--export-csv", csv_dir], "simd.log")
    wait_for_frames(server, RUN, FRAMES)
    wait_for_run_file(out, FRAMES)
    return server, out, csv_dir


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(v) for v in r] for r in rows[1:]]).reshape(-1, len(rows[0]))


def expect_frame_is_csv(frame, csv_dir):
    _, index = read_csv(csv_dir / "index.csv")
    row = index[index[:, 0] == frame.index][0]
    assert (frame.step, frame.time, frame.rho, frame.z) == tuple(row[1:5])
    _, particles = read_csv(csv_dir / f"frame_{frame.index:04d}_particles.csv")
    np.testing.assert_array_equal(frame.particles, particles[:, 1:4])
    _, contacts = read_csv(csv_dir / f"frame_{frame.index:04d}_contacts.csv")
    np.testing.assert_array_equal(frame.contact_pairs, contacts[:, 0:2])
    np.testing.assert_array_equal(frame.contact_forces, contacts[:, 2:4])
    _, walls = read_csv(csv_dir / f"frame_{frame.index:04d}_wall_contacts.csv")
    np.testing.assert_array_equal(frame.wall_contact_particles, walls[:, 0])
    np.testing.assert_array_equal(frame.wall_contact_forces, walls[:, 3:5])


def test_run_file_frames_are_the_csv_export(simd_run):
    _, out, csv_dir = simd_run
    with fnet.store.open_run_file(out) as f:
        assert f.schema == "fnet-run-3" and f.run_id == RUN
        assert f.attrs["particles"] == 150 and f.attrs["frames_planned"] == FRAMES
        assert f.config["particles"] == 150 and f.attrs["ensemble"] == ""
        np.testing.assert_array_equal(f.frames, np.arange(FRAMES))
        for index in f.frames:
            frame = f.frame(index)
            expect_frame_is_csv(frame, csv_dir)
            # Z as the documents define it, from the contacts themselves.
            assert frame.z == 2 * np.count_nonzero(frame.contact_forces[:, 0] > 0) / len(frame.particles)
        with pytest.raises(KeyError):
            f.frame(FRAMES)


def test_first_schema_run_file_is_read_like_the_current_one():
    with fnet.store.open_run_file(LEGACY / "legacy-v1.run.h5") as f:
        assert f.schema == "fnet-run-1" and f.run_id == "legacy-v1" and f.attrs["ensemble"] == ""
        np.testing.assert_array_equal(f.frames, [0, 1, 2])
        for index in f.frames:
            frame = f.frame(index)
            expect_frame_is_csv(frame, LEGACY / "csv")
            assert frame.dimension == 2 and np.all(frame.particle_z == 0)


def test_second_schema_files_are_read_as_two_dimensional():
    with fnet.store.open_run_file(LEGACY_V2 / "legacy-v2.run.h5") as f:
        assert f.schema == "fnet-run-2" and f.run_id == "legacy-v2"
        for index in f.frames:
            frame = f.frame(index)
            expect_frame_is_csv(frame, LEGACY_V2 / "csv")
            assert frame.dimension == 2 and frame.particle_z.shape == (60,) and np.all(frame.particle_z == 0)
    with fnet.store.open_store(LEGACY_V2.parent / "store-v2" / "legacy-v2.h5") as st:
        assert st.schema == "fnet-store-2"
        network = st.network(2)
        assert network.dimension == 2 and network.particles.shape == (60, 3) and np.all(network.particle_z == 0)
        assert len(network.contact_pairs) > 0


def test_store_holds_what_the_server_serves(simd_run):
    server, out, _ = simd_run
    with server.client() as c, fnet.store.open_store(server.store_path(RUN)) as st, \
            fnet.store.open_run_file(out) as run_file:
        assert st.run_id == RUN and st.announcement()["particles"] == 150 and st.rejected() == []
        np.testing.assert_array_equal(st.frames, np.arange(FRAMES))
        for metric in fnet.store.METRICS:
            for dim in (0, 1):
                for force in fnet.store.FORCES:
                    served, stored = c.series(metric, run=RUN, dim=dim, force=force), st.series(metric, dim, force)
                    for key in ("frame", "rho", "z", "previous", "value", "step", "time"):
                        np.testing.assert_array_equal(served[key], stored[key])
        for index in st.frames:
            frame = run_file.frame(index)
            for force in fnet.store.FORCES:
                # The server's force network has the contacts whose force magnitude is > 0: the
                # ones fnet.figures draws.
                vertices, edges, _ = st.counts(index, force)
                pairs, values = fnet.figures.normalized_network(frame, force)
                assert (vertices, edges) == (len(frame.particles), len(pairs))
                assert len(pairs) == 0 or np.isclose(values.mean(), 1.0)
                for dim in (0, 1):
                    np.testing.assert_array_equal(st.diagram(index, dim, force),
                                                  c.diagram(int(index), run=RUN, dim=dim, force=force))


def test_store_columns_follow_its_series_attribute(simd_run, tmp_path):
    """A copy of the store with its distance columns (and the attribute naming them) reversed reads
    back the same series: the reader follows the attribute, not a formula of its own."""
    import h5py
    server, _, _ = simd_run
    copy = tmp_path / "reversed.h5"
    # Copied member by member: the live store is open for SWMR writing, so it cannot be opened to write.
    with h5py.File(server.store_path(RUN), "r", libver="latest", swmr=True) as src, h5py.File(copy, "w",
                                                                                            libver="latest") as f:
        for name in src:
            src.copy(name, f)
        f.attrs.update(src.attrs)
        f["distances"][...] = np.flip(f["distances"][...], axis=1)
        f.attrs["series"] = ",".join(reversed(str(f.attrs["series"]).split(",")))
    with fnet.store.open_store(server.store_path(RUN)) as st, fnet.store.open_store(copy) as rev:
        for metric in fnet.store.METRICS:
            for dim in (0, 1):
                for force in fnet.store.FORCES:
                    np.testing.assert_array_equal(st.series(metric, dim, force)["value"],
                                                  rev.series(metric, dim, force)["value"])


def test_store_keeps_the_networks_the_daemon_sent(simd_run):
    server, out, _ = simd_run
    with fnet.store.open_store(server.store_path(RUN)) as st, fnet.store.open_run_file(out) as run_file:
        assert st.schema == "fnet-store-3"
        for index in st.frames:
            stored, sent = st.network(index), run_file.frame(index)
            for key in ("particles", "contact_pairs", "contact_forces", "rho", "z", "step"):
                np.testing.assert_array_equal(stored[key], sent[key], err_msg=f"frame {index} {key}")


def test_store_read_while_the_server_writes_it(processes):
    server = start_server(processes, LIVE_DOMAIN, name="live")
    publish_lammps(processes, "slow", LIVE_DOMAIN, rate=4)
    wait_for(lambda: server.store_path("slow").exists(), "the store to appear")
    with fnet.store.open_store(server.store_path("slow")) as st:
        seen = [len(st.frames)]
        deadline = time.monotonic() + 300
        while seen[-1] < LAMMPS_FRAMES and time.monotonic() < deadline:
            time.sleep(0.05)
            seen.append(st.refresh())
        assert seen[-1] == LAMMPS_FRAMES
        assert seen == sorted(seen)  # frames only ever appear, in order
        assert len(set(seen)) > 2, seen  # and the reader saw them appear while the server wrote
        with server.client() as c:
            np.testing.assert_array_equal(st.series("bottleneck", 1, "normal").value,
                                          c.series("bottleneck", run="slow", dim=1).value)


def test_bad_arguments_name_what_was_wrong(simd_run):
    server, out, _ = simd_run
    with fnet.store.open_store(server.store_path(RUN)) as st:
        with pytest.raises(ValueError, match="metric"):
            st.series("wasserstein", 1)
        with pytest.raises(ValueError, match="force"):
            st.diagram(0, 0, "shear")
        with pytest.raises(KeyError, match="frame 99"):
            st.diagram(99)
    with pytest.raises(ValueError, match="schema"):
        fnet.store.open_store(out)  # a run file is not a store
    with pytest.raises(ValueError, match="schema"):
        fnet.store.open_run_file(server.store_path(RUN))


def test_fnet_imports_without_h5py_and_the_store_readers_say_what_they_need(simd_run):
    # h5py blocked: the RPC client works; opening a file names h5py and the package that brings it.
    server, out, _ = simd_run
    script = (
        "import sys\n"
        "sys.modules['h5py'] = None\n"
        "import fnet\n"
        f"with fnet.Client('127.0.0.1', {server.port}) as c:\n"
        "    print(c.runs()[0]['run'])\n"
        "try:\n"
        f"    fnet.store.open_run_file({str(out)!r})\n"
        "except ImportError as e:\n"
        "    print(e)\n")
    env = dict(os.environ, PYTHONPATH=str(SOURCE_DIR / "client" / "python"))
    r = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode == 0, r.stderr
    run, error = r.stdout.splitlines()
    assert run == RUN
    assert "h5py" in error and "python3-h5py" in error
