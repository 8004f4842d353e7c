"""README's Python example, taken from the document at test time and run as written (with
PYTHONPATH=client/python and FNET_PORT naming a real fnet-server holding the LAMMPS frames of
tests/data): it prints what the server serves and writes its figure."""

import os
import re
import subprocess
import sys

import numpy as np

from conftest import PNG_SIGNATURE, SOURCE_DIR, serve_lammps

DOMAIN = 96
RUN = "lammps"


def readme_example():
    text = (SOURCE_DIR / "README.md").read_text()
    section = text[text.index("\n## Python\n"):]
    section = section[:section.index("\n## ", 1)]
    blocks = re.findall(r"```python\n(.*?)\n```", section, re.S)
    assert len(blocks) == 1, "README's Python section must have exactly one python example"
    return blocks[0] + "\n"


def test_readme_example_runs_against_a_real_server(processes, tmp_path):
    example = readme_example()
    assert len(example.strip().splitlines()) == 5  # what a notebook needs, as the README says
    server = serve_lammps(processes, DOMAIN, RUN)
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
