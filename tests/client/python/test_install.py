"""`pip install ./client/python` as client/python/README.md writes it, without network: its shell
example run line by line (Debian's python3 for `python3`) in a temporary directory that holds a
copy of the package at the same relative path, so that the build leaves nothing in the source
tree. The installed package is then imported from outside any source tree, from the virtual
environment, and names the project's version: CMake's, which fnet/version.py and pyproject.toml
must state as well."""

import os
import re
import shutil
import subprocess
import sys
import tomllib

from conftest import SOURCE_DIR

PACKAGE = SOURCE_DIR / "client" / "python"


def project_version():
    cmake = (SOURCE_DIR / "CMakeLists.txt").read_text()
    return re.search(r"project\(fnet VERSION (\d+\.\d+\.\d+)", cmake).group(1)


def install_example():
    text = (PACKAGE / "README.md").read_text()
    section = text[text.index("\n## Using it\n"):]
    section = section[:section.index("\n## ", 1)]
    blocks = re.findall(r"```sh\n(.*?)\n```", section, re.S)
    assert len(blocks) == 1, "client/python/README.md's 'Using it' must have exactly one sh example"
    return blocks[0].splitlines()


def test_the_versions_agree():
    version = project_version()
    scope = {}
    exec((PACKAGE / "fnet" / "version.py").read_text(), scope)
    assert scope["__version__"] == version, "fnet/version.py against CMakeLists.txt's project(fnet VERSION ...)"
    project = tomllib.loads((PACKAGE / "pyproject.toml").read_text())
    stated = project["project"].get("version")
    if stated is None:  # dynamic: read from fnet/version.py, checked above
        assert "version" in project["project"]["dynamic"]
        assert project["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "fnet.version.__version__"}
    else:
        assert stated == version, "pyproject.toml's version against CMakeLists.txt's"


def test_pip_installs_the_package_into_a_virtual_environment_without_network(tmp_path):
    work = tmp_path / "checkout"
    shutil.copytree(PACKAGE, work / "client" / "python",
                    ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info"))
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "PIP_", "VIRTUAL_ENV"))}
    env.update(PIP_CONFIG_FILE=os.devnull, PIP_DISABLE_PIP_VERSION_CHECK="1", PYTHONDONTWRITEBYTECODE="1")
    lines = install_example()
    assert any("pip install --no-build-isolation --no-index ./client/python" in line for line in lines), lines
    out = ""
    for line in lines:
        command = re.sub(r"^python3 ", f"{sys.executable} ", line)
        r = subprocess.run(["bash", "-c", command], cwd=work, env=env, capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, f"{line}\n{r.stdout}\n{r.stderr}"
        out = r.stdout
    version = project_version()
    # The last line, python -m fnet --version; the commit is that of a git checkout around the virtual
    # environment, if any (the build directory may lie in one), else "unknown".
    assert re.fullmatch(re.escape(f"fnet {version} (commit ") + r"([0-9a-f]{40}(-dirty)?|unknown)\)\n", out), out

    # Imported from elsewhere, fnet is the installed copy, and its metadata the project's version.
    venv = work / "fnet-venv"
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    r = subprocess.run([str(venv / "bin" / "python"), "-c",
                        "import importlib.metadata, fnet, fnet.store, fnet.figures, fnet.version\n"
                        "print(fnet.__file__)\n"
                        "print(importlib.metadata.version('fnet'), fnet.version.__version__)"],
                       cwd=outside, env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    where, versions = r.stdout.splitlines()
    assert os.path.realpath(where).startswith(os.path.realpath(venv / "lib")), where
    assert "site-packages" in where and not os.path.realpath(where).startswith(os.path.realpath(PACKAGE)), where
    assert versions.split() == [version, version]
