"""The Python examples of the documents, taken from them at test time and run as written (with
PYTHONPATH=client/python and FNET_PORT naming a real fnet-server holding the LAMMPS frames of
tests/data): README's, and the package's own in client/python/README.md. Each prints what the
server serves and writes its figure."""

import os
import re
import subprocess
import sys

import numpy as np
import pytest

from conftest import PNG_SIGNATURE, SOURCE_DIR

DOMAIN = 96
RUN = "lammps"

# (document, the heading of the section holding its one python example)
DOCUMENTS = [("README.md", "## Python"), ("client/python/README.md", "## Using it")]


def python_example(document, heading):
    text = (SOURCE_DIR / document).read_text()
    section = text[text.index(f"\n{heading}\n"):]
    section = section[:section.index("\n## ", 1)]
    blocks = re.findall(r"```python\n(.*?)\n```", section, re.S)
    assert len(blocks) == 1, f"{document}'s section '{heading}' must have exactly one python example"
    return blocks[0] + "\n"


@pytest.mark.parametrize("document,heading", DOCUMENTS)
def test_the_python_example_runs_against_a_real_server(server, document, heading, tmp_path):
    example = python_example(document, heading)
    assert len(example.strip().splitlines()) == 5  # what a notebook needs, as the documents say
    script = tmp_path / "example.py"
    script.write_text(example)
    env = dict(os.environ, PYTHONPATH=str(SOURCE_DIR / "client" / "python"), FNET_PORT=str(server.port))
    env.pop("FNET_HOST", None)
    r = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr
    words = r.stdout.split()
    with server.client() as c:
        s = c.series("wasserstein2", run=RUN, dim=1)
    assert words[0] == RUN and int(words[1]) == s.frame[-1]
    assert [float(w) for w in words[2:]] == [s.rho[-1], s.z[-1], s.value[-1]]
    assert np.isfinite(s.value[-1])
    with open(tmp_path / "distances.png", "rb") as f:
        assert f.read(8) == PNG_SIGNATURE
