#!/usr/bin/env python3
"""Wall contacts from fix wall/gran ... contacts, read with --columns wall=ID, against a real run:
proto/lammps.md's blocks marked `walls`, run as written.

Debian's lmp squeezes 48 disks between two fix wall/gran planes (periodic in x) and lets them come
to rest; the per-atom dump holds the fix's contacts array. At rest every grain's contact forces,
pairs and walls, add up to nothing: fnet-analyze store --check-balance holds with the walls read,
and fails without them (the grains touching a wall are out of balance), which checks the
columns' meaning (the force on the grain, the contact point) as LAMMPS fills them. LAMMPS's own
count of wall contacts is compared with the grains fnet finds out of balance without them.
Exit 0 when every check holds, 1 otherwise.
"""
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
import lammps_inputs  # noqa: E402
from lammps_doc import test_arguments  # noqa: E402

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def main():
    a = test_arguments(__doc__)
    work = os.path.abspath(a.workdir)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    doc = open(a.doc).read()
    lines = re.findall(r"```lammps walls\n(.*?)```", doc, re.S)[0].splitlines()
    store_line = re.findall(r"```sh walls\n(.*?)```", doc, re.S)[0].strip()
    fix = next(l for l in lines if l.startswith("fix "))
    dump = next(l for l in lines if l.startswith("dump "))
    open(os.path.join(work, "in.fnet"), "w").write(lammps_inputs.disks_between_planes(fix, dump))
    r = subprocess.run([a.lmp, "-in", "in.fnet", "-log", "log.lammps", "-screen", "none", "-nocite"], cwd=work,
                       capture_output=True, text=True)
    check(r.returncode == 0, f"lmp ran ({r.returncode})")
    if r.returncode != 0:
        return 1
    walls = {int(l.split()[0]): float(l.split()[1]) for l in open(os.path.join(work, "wall_numbers.txt"))
             if not l.startswith("#")}
    check(all(v > 0 for v in walls.values()), f"LAMMPS counts wall contacts: {walls}")
    env = dict(os.environ, PATH=os.path.dirname(os.path.abspath(a.fnet_analyze)) + os.pathsep + os.environ["PATH"])
    r = subprocess.run(store_line, shell=True, cwd=work, env=env, capture_output=True, text=True)
    check(r.returncode == 0, f"{store_line}: balanced with the walls read: exit {r.returncode} {r.stderr.strip()[:300]}")
    base = store_line.replace("--columns wall=w ", "").replace("--run-id walls", "").split()
    r = subprocess.run(" ".join(base + ["--run-id", "no-walls"]), shell=True, cwd=work, env=env,
                       capture_output=True, text=True)
    m = re.search(r"timestep (\d+): (\d+) of (\d+) grains out of force balance", r.stderr)
    check(r.returncode == 1 and m is not None, f"out of balance without the walls: exit {r.returncode} {r.stderr[:200]}")
    if m:
        step, unbalanced = int(m.group(1)), int(m.group(2))
        check(unbalanced == walls.get(step), f"timestep {step}: {unbalanced} grains out of balance without the walls, "
              f"LAMMPS counts {walls.get(step)} wall contacts")
    r = subprocess.run(" ".join(base + ["--columns", "wall=nosuchfix", "--run-id", "bad"]), shell=True, cwd=work,
                       env=env, capture_output=True, text=True)
    check(r.returncode == 1 and "f_nosuchfix[1]" in r.stderr and "atoms." in r.stderr,
          f"a fix not in the dump is named: {r.stderr.strip()[:200]}")
    print("FAILED: " + "; ".join(failures) if failures else "all checks hold")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
