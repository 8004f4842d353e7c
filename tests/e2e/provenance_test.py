#!/usr/bin/env python3
"""Every program names the same build: `--version` of fnet-simd, fnet-server, fnet-analyze,
fnet-analyze-io, fnetctl and `python3 -m fnet` print one version (CMake's project version, the
Python package's) and one commit (the source checkout's HEAD, "-dirty" with uncommitted changes,
when built from a git checkout), and a running fnet-server reports the same in server.status's
`build`; CITATION.cff cites this version and the paper, LICENSE is the licence it names. Exit 0
when every check holds.

usage: provenance_test.py SOURCE_DIR BUILD_DIR WORK_DIR"""
import json
import os
import re
import shutil
import socket
import subprocess
import sys
import time

source, build, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


cmake = open(os.path.join(source, "CMakeLists.txt")).read()
project_version = re.search(r"project\(fnet VERSION (\d+\.\d+\.\d+)", cmake).group(1)
try:
    head = subprocess.run(["git", "-C", source, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
except OSError:
    head = ""

# The licence and the citation file: the citation names this version, the licence file's licence
# and the paper the method comes from.
try:
    import yaml
    cff = yaml.safe_load(open(os.path.join(source, "CITATION.cff")))
    check(cff["cff-version"] == "1.2.0" and cff["version"] == project_version and cff["license"] == "MIT"
          and cff["type"] == "software", f"CITATION.cff cites fnet {project_version} under MIT")
    check(any(r.get("doi") == "10.1103/PhysRevE.90.052203" for r in cff.get("references", [])),
          "CITATION.cff cites the paper (Kramar et al. 2014, doi 10.1103/PhysRevE.90.052203)")
except Exception as e:  # noqa: BLE001 - any failure to read it is the finding
    check(False, f"CITATION.cff reads as YAML with python3-yaml ({e})")
licence = open(os.path.join(source, "LICENSE")).read()
check(licence.startswith("MIT License") and "Permission is hereby granted, free of charge" in licence,
      "LICENSE holds the MIT licence")

programs = {
    "fnet-simd": [os.path.join(build, "bin/fnet-simd")],
    "fnet-server": [os.path.join(build, "bin/fnet-server")],
    "fnet-analyze": [os.path.join(build, "bin/fnet-analyze")],
    "fnet-analyze-io": [os.path.join(build, "bin/fnet-analyze-io")],
    "fnetctl": [os.path.join(build, "bin/fnetctl")],
    "fnet": ["/usr/bin/python3", "-m", "fnet"],
}
env = dict(os.environ, PYTHONPATH=os.path.join(source, "client", "python"), PYTHONDONTWRITEBYTECODE="1")
seen = {}
for name, argv in programs.items():
    res = subprocess.run([*argv, "--version"], capture_output=True, text=True, env=env, timeout=60)
    m = re.fullmatch(re.escape(name) + r" (\d+\.\d+\.\d+) \(commit ([0-9a-f]{40}(?:-dirty)?|unknown)\)\n", res.stdout)
    check(res.returncode == 0 and m is not None, f"{name} --version: '{res.stdout.strip()}' (rc {res.returncode})")
    if m:
        seen[name] = (m.group(1), m.group(2))
check(len(set(seen.values())) == 1, f"every program names the same build: {seen}")
for name, (version, commit) in seen.items():
    check(version == project_version, f"{name}: version {version} is CMake's project version {project_version}")
    if head:
        check(commit.split("-")[0] == head, f"{name}: commit {commit} is the checkout's HEAD {head}")

# server.status names the build that computes its answers.
server = subprocess.Popen([programs["fnet-server"][0], "--data-dir", os.path.join(work, "data"), "--port", "0",
                           "--domain", "59"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          env=dict(os.environ, CYCLONEDDS_URI="file://" + os.path.join(source, "deploy",
                                                                                         "cyclonedds-loopback.xml")))
try:
    port = None
    deadline = time.time() + 30
    while port is None and time.time() < deadline:
        line = server.stdout.readline()
        m = re.search(r"listening on 127\.0\.0\.1:(\d+) ", line)
        if m:
            port = int(m.group(1))
    check(port is not None, "fnet-server started")
    if port:
        with socket.create_connection(("127.0.0.1", port), timeout=30) as s:
            s.sendall(b'{"jsonrpc":"2.0","id":1,"method":"server.status"}\n')
            reply = b""
            while not reply.endswith(b"\n"):
                reply += s.recv(65536)
        build_info = json.loads(reply)["result"]["build"]
        version, commit = seen.get("fnet-server", ("?", "?"))
        check(build_info["version"] == version and build_info["commit"] == commit
              and build_info["store_schema"] == "fnet-store-3" and build_info["convention"] == "floor",
              f"server.status build {build_info} equals fnet-server --version")
finally:
    server.terminate()
    server.wait(timeout=30)

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
