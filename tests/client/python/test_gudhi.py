"""fnet's diagrams in GUDHI's sublevel form (`fnet-analyze diagram --format gudhi`, `fnet.to_gudhi`)
read by Debian's python3-gudhi: on consecutive LAMMPS frames of tests/data, GUDHI's bottleneck
distance and Hera's Wasserstein distances (order 1 and 2, internal_p = inf) equal fnet's own
(`fnet-analyze distance`, floor convention; with `inf`, its `separate` one), Hera's within its
relative error delta. Also runs the documents' examples: client/README.md's sh block and
client/python/README.md's python block. Starts no server and uses no DDS domain."""

import json
import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest

from conftest import LAMMPS, SOURCE_DIR, binary

import fnet

gudhi = pytest.importorskip("gudhi")  # Debian's python3-gudhi; deploy/setup.sh installs it
import gudhi.hera  # noqa: E402

DELTA = 1e-3
PAIRS = [(5, 6), (8, 9), (9, 10)]  # from a few contacts to jammed frames


def frame_files(k):
    return ["--contacts", str(LAMMPS / f"frame_{k:04d}_contacts.csv"),
            "--particles", str(LAMMPS / f"frame_{k:04d}_particles.csv")]


def analyze(*args):
    r = subprocess.run([binary("FNET_ANALYZE"), *map(str, args)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return r.stdout


@pytest.fixture(scope="module")
def frames(tmp_path_factory):
    """Per frame and force: its diagram document, and its GUDHI files under both conventions."""
    tmp = tmp_path_factory.mktemp("frames")
    out = {}
    for k in sorted({k for pair in PAIRS for k in pair}):
        for force in ("normal", "tangential"):
            base = tmp / f"{force}_{k}"
            files = {"json": base.with_suffix(".json")}
            files["json"].write_text(analyze("diagram", *frame_files(k), "--force", force))
            for essential in ("inf", "floor"):
                files[essential] = tmp / f"{force}_{k}.{essential}.pers"
                files[essential].write_text(
                    analyze("diagram", *frame_files(k), "--force", force, "--format", "gudhi", "--essential", essential))
            out[k, force] = files
    return out


def read_gudhi(path, dim):
    return gudhi.read_persistence_intervals_in_dimension(persistence_file=str(path), only_this_dim=dim)


def fnet_distance(a, b, dim, metric, essential="floor"):
    r = json.loads(analyze("distance", a, b, "--metric", metric, "--dim", dim, "--essential", essential))
    return math.inf if r["value"] is None else r["value"]


@pytest.mark.parametrize("force", ["normal", "tangential"])
@pytest.mark.parametrize("essential", ["inf", "floor"])
def test_the_file_and_to_gudhi_give_the_same_arrays(frames, force, essential):
    for k in (9, 10):
        document = json.loads(frames[k, force]["json"].read_text())
        for dim in (0, 1):
            from_file = read_gudhi(frames[k, force][essential], dim)
            in_memory = fnet.to_gudhi(document[f"pd{dim}"], essential=essential)
            assert in_memory.dtype == np.float64 and in_memory.shape[1] == 2
            np.testing.assert_array_equal(from_file.reshape(-1, 2), in_memory)
            assert np.all(in_memory[:, 0] <= in_memory[:, 1]), "sublevel form: birth <= death"
            never = sum(1 for b, d in document[f"pd{dim}"] if d == -1)
            if essential == "inf":
                assert len(in_memory) == len(document[f"pd{dim}"])
                assert np.count_nonzero(np.isinf(in_memory[:, 1])) == never
            else:
                rattlers = sum(1 for b, d in document[f"pd{dim}"] if d == -1 and b == 0)
                assert len(in_memory) == len(document[f"pd{dim}"]) - rattlers
                assert np.all(np.isfinite(in_memory))


@pytest.mark.parametrize("force", ["normal", "tangential"])
@pytest.mark.parametrize("dim", [0, 1])
@pytest.mark.parametrize("pair", PAIRS)
def test_gudhi_and_hera_give_fnets_distances_under_floor(frames, force, dim, pair):
    fa, fb = frames[pair[0], force], frames[pair[1], force]
    a, b = read_gudhi(fa["floor"], dim), read_gudhi(fb["floor"], dim)
    d_b = fnet_distance(fa["json"], fb["json"], dim, "bottleneck")
    # GUDHI's default e lets the last bits of the mantissa be wrong.
    assert gudhi.bottleneck_distance(a, b) == pytest.approx(d_b, rel=1e-12, abs=1e-15)
    for order, metric in ((1, "wasserstein1"), (2, "wasserstein2")):
        exact = fnet_distance(fa["json"], fb["json"], dim, metric)
        hera = gudhi.hera.wasserstein_distance(a, b, order=order, internal_p=np.inf, delta=DELTA)
        # Hera's guarantee: within a relative error delta of the true distance.
        assert exact / (1 + DELTA) * (1 - 1e-12) <= hera <= exact * (1 + DELTA) * (1 + 1e-12), (order, exact, hera)
        assert exact > 0


@pytest.mark.parametrize("dim", [0, 1])
@pytest.mark.parametrize("pair", PAIRS)
def test_inf_form_matches_fnets_separate_convention(frames, dim, pair):
    fa, fb = frames[pair[0], "normal"], frames[pair[1], "normal"]
    a, b = read_gudhi(fa["inf"], dim), read_gudhi(fb["inf"], dim)
    d_b = fnet_distance(fa["json"], fb["json"], dim, "bottleneck", essential="separate")
    assert gudhi.bottleneck_distance(a, b) == pytest.approx(d_b, rel=1e-12, abs=1e-15)
    for order, metric in ((1, "wasserstein1"), (2, "wasserstein2")):
        exact = fnet_distance(fa["json"], fb["json"], dim, metric, essential="separate")
        hera = gudhi.hera.wasserstein_distance(a, b, order=order, internal_p=np.inf, delta=DELTA)
        if math.isinf(exact):
            assert math.isinf(hera)
        else:
            assert exact / (1 + DELTA) * (1 - 1e-12) <= hera <= exact * (1 + DELTA) * (1 + 1e-12), (order, exact, hera)


def test_to_gudhi_refuses_an_unknown_convention():
    with pytest.raises(ValueError, match="floor"):
        fnet.to_gudhi([[1.0, 0.5]], essential="sentinel")
    np.testing.assert_array_equal(fnet.to_gudhi([]), np.zeros((0, 2)))


def code_block(document, heading, language):
    text = (SOURCE_DIR / document).read_text()
    section = text[text.index(f"\n{heading}\n"):]
    end = re.search(r"\n##+ ", section[1:])
    section = section[:end.start() + 1] if end else section
    blocks = re.findall(rf"```{language}\n(.*?)\n```", section, re.S)
    assert len(blocks) == 1, f"{document}'s section '{heading}' must have exactly one {language} example"
    return blocks[0] + "\n"


def tools_on_path(tmp_path):
    """A PATH whose fnet-analyze is the built one and whose python3 is this test's (Debian's, with gudhi)."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "fnet-analyze").symlink_to(binary("FNET_ANALYZE"))
    (bin_dir / "python3").symlink_to(sys.executable)
    return f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '')}"


def test_the_client_readmes_sh_example_prints_fnets_bottleneck(tmp_path):
    script = code_block("client/README.md", "### Diagrams for GUDHI, Hera and persim: `--format gudhi`", "sh")
    (tmp_path / "tests").symlink_to(SOURCE_DIR / "tests")  # the example runs from the repository's root
    env = dict(os.environ, PATH=tools_on_path(tmp_path))
    r = subprocess.run(["bash", "-euo", "pipefail", "-c", script], cwd=tmp_path, env=env, capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    for k in (9, 10):
        (tmp_path / f"{k}.json").write_text(analyze("diagram", *frame_files(k)))
    expected = fnet_distance(tmp_path / "9.json", tmp_path / "10.json", 1, "bottleneck")
    assert float(r.stdout) == pytest.approx(expected, rel=1e-12)


def test_the_python_readmes_example_prints_fnets_distances(tmp_path):
    script = code_block("client/python/README.md", "## With GUDHI, Hera and persim", "python")
    (tmp_path / "A.json").write_text(analyze("diagram", *frame_files(9)))
    (tmp_path / "B.json").write_text(analyze("diagram", *frame_files(10)))
    (tmp_path / "example.py").write_text(script)
    env = dict(os.environ, PYTHONPATH=str(SOURCE_DIR / "client" / "python"))
    r = subprocess.run([sys.executable, "example.py"], cwd=tmp_path, env=env, capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr
    bottleneck, w2 = (float(w) for w in r.stdout.split())
    assert bottleneck == pytest.approx(fnet_distance(tmp_path / "A.json", tmp_path / "B.json", 1, "bottleneck"),
                                       rel=1e-12)
    exact = fnet_distance(tmp_path / "A.json", tmp_path / "B.json", 1, "wasserstein2")
    assert abs(w2 - exact) <= 1e-3 * exact * (1 + 1e-12)
