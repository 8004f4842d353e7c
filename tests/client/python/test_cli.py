"""`python3 -m fnet plot ...` as users run it, against a real fnet-server (the LAMMPS frames of
tests/data) and a real fnet-simd run file: each kind writes its image, a PNG with where it came
from in its text chunks; the figure options do what they say; bad options exit 2 naming the
option, before any work; an unreachable server exits 3, an unknown run or frame 4, an input file
that is not what it should be 1, each with one line on stderr."""

import struct

import pytest

import fnet
from conftest import expect_png, plot, png_text, simd_run_file
from fnet import cli, provenance

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
    # A slab or a projection is for 3D frames: on a 2D run it is an error that says so, not ignored.
    r = plot("network", "--run-file", run_file, "--frame", 2, "--projection", "--out", tmp_path / "x.png")
    assert r.returncode != 0 and "draw 3D frames" in one_line(r) and "is 2D" in one_line(r)
    assert not (tmp_path / "x.png").exists()


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
    (("distances", "--metric", "bottleneck", "--size", "6"), "--size"),
    (("distances", "--metric", "bottleneck", "--size", "6,0"), "--size"),
    (("distances", "--metric", "bottleneck", "--dpi", "0"), "--dpi"),
    (("distances", "--metric", "bottleneck", "--log", "--linear"), "--linear"),
    (("diagram", "--frame", "1", "--log"), "--log"),
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


def one_line(r):
    """The command failed with one line on stderr (no traceback)."""
    assert len(r.stderr.strip().splitlines()) == 1 and "Traceback" not in r.stderr, r.stderr
    return r.stderr


def test_unreachable_server_exits_3(tmp_path):
    r = plot("distances", "--metric", "bottleneck", "--out", tmp_path / "x.png", "--port", 1)
    assert r.returncode == 3 and "127.0.0.1:1" in one_line(r) and "--port" in r.stderr


def test_unknown_run_and_frame_exit_4(server, run_file, tmp_path):
    r = plot("distances", "--metric", "bottleneck", "--run", "nope", "--out", tmp_path / "x.png", "--port", server.port)
    assert r.returncode == 4 and "nope" in one_line(r)
    r = plot("diagram", "--run", "lammsp", "--frame", 1, "--out", tmp_path / "x.png", "--port", server.port)
    assert r.returncode == 4 and "'lammsp'" in one_line(r) and f"close: {RUN}" in r.stderr
    r = plot("diagram", "--run", RUN, "--frame", 99, "--out", tmp_path / "x.png", "--port", server.port)
    assert r.returncode == 4 and "99" in one_line(r)
    r = plot("network", "--run-file", run_file, "--frame", 7, "--out", tmp_path / "x.png")
    assert r.returncode == 4 and "frame 7" in one_line(r) and "'" not in r.stderr.split(":", 1)[1][:3]
    r = plot("diagram", "--store", server.store_path(RUN), "--frame", 99, "--out", tmp_path / "x.png")
    assert r.returncode == 4 and "frame 99" in one_line(r)
    assert not (tmp_path / "x.png").exists()


def test_input_that_is_not_what_it_should_be_exits_1(server, tmp_path):
    text = tmp_path / "not-hdf5.h5"
    text.write_text("not an HDF5 file\n")
    r = plot("network", "--run-file", text, "--frame", 0, "--out", tmp_path / "x.png")
    assert r.returncode == 1 and str(text) in one_line(r)
    r = plot("network", "--run-file", server.store_path(RUN), "--frame", 0, "--out", tmp_path / "x.png")
    assert r.returncode == 1 and "schema" in one_line(r)  # a store is not a run file
    r = plot("distances", "--metric", "bottleneck", "--out", tmp_path / "missing" / "x.png", "--port", server.port)
    assert r.returncode == 1 and "--out" in one_line(r)  # output it cannot write
    assert not (tmp_path / "x.png").exists()


def png_size(path):
    with open(path, "rb") as f:
        header = f.read(24)
    return struct.unpack(">II", header[16:24])


def test_png_carries_its_provenance(server, run_file, tmp_path):
    out = tmp_path / "distances.png"
    args = ("distances", "--metric", "wasserstein", "--q", "3", "--dim", "1", "--essential", "sentinel", "--out", out)
    expect_png(plot(*args, port=server.port), out)  # the newest run
    meta = png_text(out)
    with fnet.Client("127.0.0.1", server.port) as c:
        expected = provenance.describe(server_status=c.status(), convention="sentinel")
    for key in ("fnet_version", "fnet_commit", "method", "server_version", "server_commit", "convention"):
        assert meta[f"fnet:{key}"] == expected[key], key
    assert meta["fnet:run"] == RUN and meta["fnet:metric"] == "wasserstein" and meta["fnet:q"] == "3.0"
    assert meta["fnet:dim"] == "1" and meta["fnet:figure"] == "distances"
    assert meta["fnet:command"].startswith("python3 -m fnet plot distances --metric wasserstein")
    assert meta["Software"].startswith(f"fnet {expected['fnet_version']}") and meta["Source"] == provenance.SOURCE
    out = tmp_path / "network.png"
    expect_png(plot("network", "--run-file", run_file, "--frame", 2, "--out", out), out)
    meta = png_text(out)
    assert meta["fnet:source"] == str(run_file) and meta["fnet:run"] == "net" and meta["fnet:frame"] == "2"
    assert "fnet:server_version" not in meta  # no server was asked


def test_figure_options(server, tmp_path):
    out = tmp_path / "sized.png"
    expect_png(plot("ratio", "--run", RUN, "--size", "5,3", "--dpi", "80", "--log", "--title", "Fig. 7", "--out", out,
                    "--port", server.port), out)
    assert png_size(out) == (400, 240)
    assert png_text(out)["fnet:y_scale"] == "log"
    parser = cli.build_parser()
    for argv, scale, title in ((["--log", "--title", "Fig. 7"], "log", "Fig. 7"), ([], "linear", ""),
                               (["--linear", "--title", ""], "linear", "")):
        args = parser.parse_args(["plot", "distances", "--run", RUN, "--metric", "bottleneck", "--out", "x.png",
                                  "--port", str(server.port), *argv])
        fig = cli.figure(args)
        assert fig.axes[0].get_yscale() == scale and fig.axes[0].get_title() == title
    args = parser.parse_args(["plot", "diagram", "--run", RUN, "--frame", "3", "--out", "x.png", "--port",
                              str(server.port), "--size", "7.5,4"])
    fig = cli.figure(args)
    assert fig._suptitle.get_text() == f"{RUN} frame 3, normal forces" and tuple(fig.get_size_inches()) == (7.5, 4)
    args = parser.parse_args(["plot", "diagram", "--run", RUN, "--frame", "3", "--out", "x.png", "--port",
                              str(server.port), "--title", "Fig. 3"])
    assert cli.figure(args)._suptitle.get_text() == "Fig. 3"


def test_blocks_over_the_stored_packing(server, tmp_path):
    out = tmp_path / "blocks.png"
    expect_png(plot("blocks", "--run", RUN, "--frame", 9, "--other-frame", 10, "--k", 3, "--store",
                    server.store_path(RUN), "--port", server.port, "--out", out), out)
    args = cli.build_parser().parse_args(["plot", "blocks", "--run", RUN, "--frame", "9", "--other-frame", "10",
                                          "--store", str(server.store_path(RUN)), "--out", "x.png", "--port",
                                          str(server.port)])
    fig = cli.figure(args)
    assert [a for a in fig.axes[0].get_children() if a.get_gid() == "cells"]
    with fnet.Client("127.0.0.1", server.port) as c:
        whole = c.distance(9, 10, "bottleneck", run=RUN).value
    assert f"whole frame: {cli.figures.block_text(whole)}" in fig._supxlabel.get_text()


def test_help_lists_every_kind():
    r = plot("--help")
    assert r.returncode == 0
    for kind in ("network", "diagram", "distances", "ensemble", "ratio", "blocks"):
        assert kind in r.stdout
