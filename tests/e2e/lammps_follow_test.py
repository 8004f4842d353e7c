#!/usr/bin/env python3
"""proto/lammps.md's live follow, run as written: a real LAMMPS compression followed by
`fnet-analyze publish --follow` into a real fnet-server on loopback DDS.

Writes a small 2D compression (tests/support/lammps_inputs.py: 196 polydisperse disks, a periodic
box squeezed by fix deform, then relaxed), or with --dimension 3 a 3D one (343 spheres), with the
page's dump lines (its 3D lines in 3D) every 500 steps, starts fnet-server, runs the page's follow
block for the case (`serial`: lmp, one file per snapshot; `mpi`: mpirun -np 2 lmp, one file of
every snapshot), and checks that frames reached the server while LAMMPS ran, that every frame
arrived, and that every one of the twelve served series equals, value for value, the offline
`fnet-analyze store` of the same dumps, and so does every network the server kept (particles,
their z in 3D, the run's dimension, contacts and forces). Every process it starts is stopped. Exit
0 when every check holds, 1 otherwise.
"""
import argparse
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import lammps_inputs  # noqa: E402
from lammps_doc import blocks  # noqa: E402

# After the disks: the page's lines, then squeezed and relaxed.
PROTOCOL = "{doc}\n" + lammps_inputs.DISKS_SQUEEZE + """run 10000 post no
unfix squeeze
run 3000 post no
"""
FRAMES = {2: 27, 3: 25}  # steps 0, 500, ..., 13000 (2D) or 12000 (3D)
METRICS = ("bottleneck", "wasserstein1", "wasserstein2")

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def follow_block(doc, case):
    """The page's follow block for the case: the one that runs lmp alone, or under mpirun."""
    for b in blocks(doc, "sh"):
        if "--follow" in b and (b.startswith("mpirun") == (case == "mpi")):
            return b
    raise SystemExit(f"proto/lammps.md has no follow block for {case}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", choices=("serial", "mpi", "input"),
                    help="input: only write the mpi case's in.fnet into the workdir (for another test)")
    ap.add_argument("--dimension", type=int, choices=(2, 3), default=2,
                    help="3: the spheres of tests/support/lammps_inputs.py with the page's 3D lines")
    ap.add_argument("--source-dir", required=True)
    ap.add_argument("--build-dir", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--domain", type=int, required=True)
    a = ap.parse_args()
    a.source_dir = os.path.abspath(a.source_dir)
    bin_dir = os.path.join(os.path.abspath(a.build_dir), "bin")
    work = os.path.abspath(a.workdir)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    doc = open(os.path.join(a.source_dir, "proto", "lammps.md")).read()
    lines = blocks(doc, "lammps" if a.dimension == 2 else "lammps 3d")[0].replace(" 1000 ", " 500 ")
    block = follow_block(doc, "serial" if a.case == "serial" else "mpi")
    if a.case != "serial":  # the page's mpi block reads one file of every snapshot
        lines = lines.replace("atoms.*.txt", "atoms.txt").replace("pairs.*.txt", "pairs.txt")
        if os.geteuid() == 0:
            block = block.replace("mpirun ", "mpirun --allow-run-as-root --oversubscribe ", 1)
    text = lammps_inputs.disks() + PROTOCOL.format(doc=lines.rstrip("\n")) if a.dimension == 2 else \
        lammps_inputs.spheres(lines)
    open(os.path.join(work, "in.fnet"), "w").write(text)
    frames, a_dimension = FRAMES[a.dimension], a.dimension
    if a.case == "input":
        return 0
    sys.path.insert(0, os.path.join(a.source_dir, "client", "python"))
    import fnet  # noqa: E402
    run_id = re.search(r"--run-id (\S+)", block).group(1)
    block = block.replace(f"--run-id {run_id}", f"--run-id {run_id} --domain {a.domain} --wait-for-reader 30")
    env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ["PATH"],
               CYCLONEDDS_URI="file://" + os.path.join(a.source_dir, "deploy", "cyclonedds-loopback.xml"))

    started = []
    try:
        server = subprocess.Popen([os.path.join(bin_dir, "fnet-server"), "--data-dir", os.path.join(work, "data"),
                                   "--port", "0", "--domain", str(a.domain), "--threads", "2"],
                                  stdout=subprocess.PIPE, stderr=open(os.path.join(work, "server.log"), "w"),
                                  env=env, text=True, start_new_session=True)
        started.append(server)
        m = re.search(r":(\d+) ", server.stdout.readline())
        if not m:
            check(False, "fnet-server started")
            return 1
        port = int(m.group(1))
        follow = subprocess.Popen(block, shell=True, cwd=work, env=env, stdout=open(os.path.join(work, "follow.out"), "w"),
                                  stderr=open(os.path.join(work, "follow.log"), "w"), start_new_session=True)
        started.append(follow)
        # Frames reach the server while LAMMPS runs: seen before its log says it finished.
        seen_live = 0
        finished = False
        with fnet.Client("127.0.0.1", port) as c:
            deadline = time.monotonic() + 45
            while follow.poll() is None and time.monotonic() < deadline:
                log = os.path.join(work, "log.lammps")
                # The count is live only if the log still says LAMMPS runs after it was read.
                analyzed = max([r["frames"] for r in c.runs() if r["run"] == run_id], default=0)
                finished = finished or (os.path.exists(log) and "Total wall time" in open(log).read())
                if not finished:
                    seen_live = max(seen_live, analyzed)
                time.sleep(0.05)
            check(follow.poll() == 0, f"the follow block ran: exit {follow.poll()} "
                  f"({open(os.path.join(work, 'follow.log')).read()[-600:]})")
            # All of them may be: LAMMPS writes its last lines after its last snapshot, and a
            # loaded machine may take longer over that than fnet-server over the last frame.
            check(seen_live > 0, f"{seen_live} frames analyzed before LAMMPS finished")
            deadline = time.monotonic() + 20
            summary = None
            while time.monotonic() < deadline:
                summary = next((r for r in c.runs() if r["run"] == run_id), None)
                if summary and summary["frames"] + summary["rejected"] >= frames and summary["pending"] == 0:
                    break
                time.sleep(0.1)
            check(summary is not None and summary["frames"] == frames and summary["rejected"] == 0,
                  f"every frame analyzed: {summary}")

            # The offline analysis of the same dumps, after the run.
            pattern = re.search(r"--lammps-atoms (\S+) --lammps-pairs (\S+)", block)
            r = subprocess.run(f"fnet-analyze store --lammps-atoms {pattern.group(1)} --lammps-pairs "
                               f"{pattern.group(2)} --run-id {run_id} --data-dir offline",
                               shell=True, cwd=work, env=env, capture_output=True, text=True)
            check(r.returncode == 0, f"fnet-analyze store: exit {r.returncode} {r.stderr.strip()}")
            with fnet.store.open_store(os.path.join(work, "offline", run_id + ".h5")) as store:
                for metric in METRICS:
                    for dim in (0, 1):
                        for force in ("normal", "tangential"):
                            served = c.call("series.get", {"run": run_id, "metric": metric, "dim": dim, "force": force})
                            offline = store.series(metric, dim, force)
                            what = f"{metric} pd{dim} {force}"
                            check(served["frame"] == [int(f) for f in offline.frame], f"{what}: the same frames")
                            check(served["rho"] == [float(v) for v in offline.rho], f"{what}: the same rho")
                            same = all((v is None and math.isnan(w)) or v == w
                                       for v, w in zip(served["value"], [float(x) for x in offline.value]))
                            check(same and len(served["value"]) == frames, f"{what}: the same values, bit for bit")
                # The networks the server kept, as they came over DDS: the offline ones, with the
                # run's dimension and its grains' z.
                with fnet.store.open_store(os.path.join(work, "data", run_id + ".h5")) as live:
                    kept = [(live.network(k), store.network(k)) for k in range(frames)]
                same = all(a is not None and b is not None and a.dimension == b.dimension == a_dimension
                           and np.array_equal(a.particles, b.particles) and np.array_equal(a.particle_z, b.particle_z)
                           and np.array_equal(a.contact_pairs, b.contact_pairs)
                           and np.array_equal(a.contact_forces, b.contact_forces) for a, b in kept)
                lifted = sum(1 for a, _ in kept if a is not None and np.any(a.particle_z != 0))
                check(same and lifted == (frames if a_dimension == 3 else 0),
                      f"the served networks are the offline ones, {a_dimension}D, {lifted} frames with z")
    finally:
        for p in reversed(started):
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGTERM)
                try:
                    p.wait(10)
                except subprocess.TimeoutExpired:
                    os.killpg(p.pid, signal.SIGKILL)
                    p.wait(10)
    print("FAILED: " + "; ".join(failures) if failures else "all checks hold")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
