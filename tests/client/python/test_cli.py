"""`python3 -m fnet plot ...` as users run it, against a real fnet-server (the LAMMPS frames of
tests/data) and a real fnet-simd run file: each kind writes its image; bad options exit 2 naming
the option, before any work; an unreachable server exits 3, an unknown run 4."""

import pytest

from conftest import expect_png, plot, simd_run_file

DOMAIN = 95
RUN = "lammps"


@pytest.fixture(scope="module")
def run_file(processes):
    return simd_run_file(processes, DOMAIN, frames=3)


def test_distances_of_a_run(server, tmp_path):
    out = tmp_path / "distances.png"
    expect_png(plot("distances", "--run", RUN, "--metric", "wasserstein2", "--dim", "1", "--out", out,
                    "--port", server.port), out)
    out = tmp_path / "newest.png"  # the newest run, the server's port from FNET_PORT
    expect_png(plot("distances", "--metric", "bottleneck", "--from", 2, "--to", 8, "--out", out, port=server.port),
               out)


def test_diagram_from_the_server_and_from_a_store(server, tmp_path):
    out = tmp_path / "diagram.png"
    expect_png(plot("diagram", "--run", RUN, "--frame", 4, "--force", "tangential", "--out", out,
                    "--port", server.port), out)
    out = tmp_path / "stored.png"
    expect_png(plot("diagram", "--store", server.store_path(RUN), "--frame", 4, "--out", out), out)


def test_network_and_its_change(run_file, tmp_path):
    out = tmp_path / "network.png"
    expect_png(plot("network", "--run-file", run_file, "--frame", 2, "--out", out), out)
    out = tmp_path / "change.png"
    expect_png(plot("network", "--run-file", run_file, "--frame", 1, "--other-frame", 2, "--force", "tangential",
                    "--out", out), out)


@pytest.mark.parametrize("args,option", [
    (("distances", "--metric", "bottlenek"), "--metric"),
    (("distances", "--metric", "bottleneck", "--dim", "2"), "--dim"),
    (("distances", "--metric", "bottleneck", "--force", "shear"), "--force"),
    (("distances", "--metric", "wasserstein"), "--q"),
    (("distances", "--metric", "bottleneck", "--q", "2"), "--q"),
    (("distances", "--metric", "bottleneck", "--bins", "0", "--ensemble", "E"), "--bins"),
    (("distances", "--metric", "bottleneck", "--bin-count", "0", "--ensemble", "E"), "--bin-count"),
    (("distances", "--metric", "bottleneck", "--bins", "0.01", "--bin-count", "3", "--ensemble", "E"),
     "--bin-count"),
    (("distances", "--metric", "bottleneck", "--bins", "0.01", "--from", "2"), "--from"),
    (("distances", "--metric", "bottleneck", "--axis", "z", "--ensemble", "E"), "--axis"),
    (("distances", "--metric", "bottleneck", "--run", "a", "--ensemble", "E"), "--ensemble"),
    (("distances", "--metric", "bottleneck", "--port", "70000"), "--port"),
    (("diagram", "--frame", "-1"), "--frame"),
    (("diagram",), "--frame"),
    (("blocks", "--frame", "1", "--other-frame", "2", "--k", "17"), "--k"),
    (("ratio", "--ratio", "wasserstein3"), "--ratio"),
    (("ensemble", "--metric", "bottleneck"), "--ensemble"),
    (("network", "--run-file", "/nonexistent.h5", "--frame", "0"), "--run-file"),
])
def test_bad_options_exit_2_naming_the_option(tmp_path, args, option):
    out = tmp_path / "never.png"
    server = () if args[0] == "network" else ("--port", 1)  # nothing listens there: no work may be tried
    r = plot(*args, "--out", out, *server)
    assert r.returncode == 2, r.stderr
    assert option in r.stderr
    assert not out.exists()


def test_unknown_image_format_exits_2(server, tmp_path):
    r = plot("distances", "--metric", "bottleneck", "--out", tmp_path / "x.docx", "--port", server.port)
    assert r.returncode == 2 and "--out" in r.stderr and "docx" in r.stderr


def test_unreachable_server_exits_3(tmp_path):
    r = plot("distances", "--metric", "bottleneck", "--out", tmp_path / "x.png", "--port", 1)
    assert r.returncode == 3 and "127.0.0.1:1" in r.stderr and "--port" in r.stderr


def test_unknown_run_and_frame_exit_4(server, tmp_path):
    r = plot("distances", "--metric", "bottleneck", "--run", "nope", "--out", tmp_path / "x.png", "--port", server.port)
    assert r.returncode == 4 and "nope" in r.stderr
    r = plot("diagram", "--run", RUN, "--frame", 99, "--out", tmp_path / "x.png", "--port", server.port)
    assert r.returncode == 4 and "99" in r.stderr
    assert not (tmp_path / "x.png").exists()


def test_help_lists_every_kind():
    r = plot("--help")
    assert r.returncode == 0
    for kind in ("network", "diagram", "distances", "ensemble", "ratio", "blocks"):
        assert kind in r.stdout
