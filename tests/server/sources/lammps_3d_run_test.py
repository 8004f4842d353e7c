#!/usr/bin/env python3
"""proto/lammps.md's 3D lines run as written on a real 3D LAMMPS run, against LAMMPS and GUDHI.

Debian's lmp compresses 343 polydisperse frictional spheres in a periodic box and lets them come to
rest (tests/support/lammps_inputs.py), with the page's blocks marked `lammps 3d`; the page's `sh 3d`
blocks then run in the dumps' folder (fnet-analyze store, diagram, explain). Checked:
- the run is read as 3D (the dimension its log names), each frame stored 3D with its grains' x, y,
  z and r as dumped;
- each frame's contacts against LAMMPS's compute contact/atom, and the dumped pairs against the
  spheres that touch by their dumped positions and radii (every pair dumped touches; every pair
  overlapping by more than 1e-3 of its radii's sum is dumped);
- rho against the spheres' volume over the box LAMMPS computes (within the dump's 6 digits), and
  --rho log: as the log prints it;
- Z against the count of the dump's pairs whose normal force pushes (F_n along the line of centres,
  worked out here from the dumped positions);
- PD0 and PD1 of several frames, normal and tangential, against GUDHI: the flag complex of the
  contact graph built here from the dumps (edge values |F_n| and |F_t| over their mean, F_n the
  normal force vector's component along the line of centres of the dumped positions, F_t the
  tangential vector's length; vertices the max of their edges; expansion(2)), the same points to
  rounding, the same counts of vertices, edges and triangles; the contact graphs of the dense frames
  are certified non-planar (more than 3V - 6 edges). (While the box shrinks, LAMMPS's normal vector
  of a pair across a periodic side lies along the line of centres of the step before: its length
  and its component differ by up to about 1e-8, checked here too.)
- the force balance of the frames at rest (--check-balance), and its failure when the normal force is
  read as the whole pair force;
- diagram of one file = diagram of the pattern at its TIMESTEP; explain from two TIMESTEPs;
- the page's warning: the same input with the rest in a run after the squeeze's keeps the pairs the
  page says, and the frames of that rest fail the force balance.
Exit status 0 when every check holds, 1 otherwise.
"""
import json
import math
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
import lammps_inputs  # noqa: E402
from gudhi_flag import flag_diagrams  # noqa: E402
from lammps_doc import blocks, commands, fresh_workdir, run_lammps, test_arguments, thermo_values  # noqa: E402

# LAMMPS's own counts beside the page's lines: contacts (twice each), and the page's v_fnet_rho;
# after fix deform, as the dumps are written.
COUNTS = """compute fnet_contacts all contact/atom
compute fnet_pairs_touching all reduce sum c_fnet_contacts
fix fnet_numbers all ave/time 1000 1 1000 c_fnet_pairs_touching v_fnet_rho file lammps_numbers.txt format " %.12g"
"""
GUDHI_STEPS = (3000, 5000, 7000, 8000, 12000)  # from a few contacts to the packing at rest
RELATIVE = 1e-12  # diagram points: the same values but for the mean's rounding

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def read_dump(path):
    """(box lo, box hi, periodic, columns, rows) of a text dump of one snapshot."""
    lines = open(path).read().split("\n")
    n = int(lines[3])
    flags = lines[4].split()[3:]
    bounds = np.array([[float(v) for v in lines[5 + k].split()] for k in range(3)])
    columns = lines[8].split()[2:]
    rows = np.array([[float(v) for v in l.split()] for l in lines[9:9 + n]]).reshape(n, len(columns))
    return bounds[:, 0], bounds[:, 1], [f == "pp" for f in flags], columns, rows


class Frame:
    """A snapshot pair read here: grains by sorted id, pairs with their vectors and line of centres."""

    def __init__(self, work, step):
        lo, hi, periodic, acols, atoms = read_dump(os.path.join(work, f"atoms.{step}.txt"))
        atoms = atoms[np.argsort(atoms[:, acols.index("id")])]
        self.side = hi - lo
        self.periodic = periodic
        self.index = {int(i): k for k, i in enumerate(atoms[:, acols.index("id")])}
        self.x = atoms[:, [acols.index(c) for c in ("x", "y", "z")]]
        self.r = atoms[:, acols.index("radius")]
        _, _, _, _, pairs = read_dump(os.path.join(work, f"pairs.{step}.txt"))
        self.i = np.array([self.index[int(v)] for v in pairs[:, 0]], dtype=np.int64)
        self.j = np.array([self.index[int(v)] for v in pairs[:, 1]], dtype=np.int64)
        self.normal, self.tangential = pairs[:, 2:5], pairs[:, 5:8]

    def offsets(self, a, b):
        d = self.x[a] - self.x[b]
        for k in range(3):
            if self.periodic[k]:
                d[..., k] -= self.side[k] * np.round(d[..., k] / self.side[k])
        return d

    def touching(self, overlap):
        """The pairs (a < b) whose spheres overlap by more than `overlap` x the sum of their radii."""
        n = len(self.r)
        a, b = np.triu_indices(n, 1)
        gap = np.linalg.norm(self.offsets(a, b), axis=1) - (self.r[a] + self.r[b])
        keep = gap < -overlap * (self.r[a] + self.r[b])
        return set(zip(a[keep].tolist(), b[keep].tolist()))

    def pairs(self):
        return set(zip(np.minimum(self.i, self.j).tolist(), np.maximum(self.i, self.j).tolist()))

    def normal_component(self):
        """F_n of each pair: its normal vector's component along the line of centres, from j to i."""
        d = self.offsets(self.i, self.j)
        return np.einsum("ij,ij->i", self.normal, d) / np.linalg.norm(d, axis=1)

    def pushing(self):
        """How many pairs' normal force pushes i away from j."""
        return int(np.count_nonzero(self.normal_component() > 0))


def entries(pair_dump):
    """NUMBER OF ENTRIES of a local dump of one snapshot."""
    return int(open(pair_dump).read().split("\n")[3])


def spaced(n):
    """n as the page writes it: 1 357."""
    return f"{n:,}".replace(",", " ")


def gudhi_diagrams(frame, force):
    """GUDHI's diagrams of the frame read here: |F_n| (along the line of centres) or |F_t|."""
    value = np.abs(frame.normal_component()) if force == "normal" else np.linalg.norm(frame.tangential, axis=1)
    return flag_diagrams(len(frame.r), frame.i, frame.j, value)


def same_points(got, want):
    """Both diagrams sorted by (birth, death) descending: the same points within RELATIVE."""
    return len(got) == len(want) and all(
        math.isclose(a, c, rel_tol=RELATIVE, abs_tol=RELATIVE) and math.isclose(b, d, rel_tol=RELATIVE, abs_tol=RELATIVE)
        for (a, b), (c, d) in zip(got, want))


def stored(path):
    with h5py.File(path, "r") as f:
        announcement = json.loads(f["announcements"][-1].decode().rstrip("\0"))
        return ([int(s) for s in f["step"]], [float(v) for v in f["rho"]], [float(v) for v in f["z"]],
                json.loads(announcement["config_json"])["source"])


def stored_grains(path):
    """Per frame of a store: its dimension and its grains' x, y, z, r as stored."""
    with h5py.File(path, "r") as f:
        out = []
        for k, (p0, p1, _, _) in enumerate(f["network_offsets"][:]):
            xyr, z = f["particles"][p0:p1], f["particle_z"][p0:p1]
            out.append((int(f["dimension"][k]), np.column_stack([xyr[:, 0], xyr[:, 1], z, xyr[:, 2]])))
        return out


def main():
    a = test_arguments(__doc__)
    work, doc = fresh_workdir(a)
    wrong = run_lammps(a.lmp, work, lammps_inputs.spheres("".join(blocks(doc, "lammps 3d")), COUNTS))
    check(not wrong, f"lmp ran {wrong}")
    if wrong:
        return 1
    env = dict(os.environ, PATH=os.path.dirname(os.path.abspath(a.fnet_analyze)) + os.pathsep + os.environ["PATH"])
    for line in commands(doc, "sh 3d"):
        r = subprocess.run(line, shell=True, cwd=work, env=env, capture_output=True, text=True)
        check(r.returncode == 0, f"{line}: exit {r.returncode} {r.stderr.strip()[:300]}")

    lammps = {}  # step: (contacts, rho)
    for l in open(os.path.join(work, "lammps_numbers.txt")):
        if not l.startswith("#"):
            s, c, rho = l.split()
            lammps[int(s)] = (float(c) / 2, float(rho))
    steps, rho, z, source = stored(os.path.join(work, "stores", "spheres.h5"))
    want_steps = list(range(0, lammps_inputs.SPHERES_STEPS + 1, 1000))
    check(steps == want_steps, f"frames stored: {steps}")
    check(source["dimension"] == 3, f"the run read as 3D: {source}")
    worst_rho = 0.0
    grains = stored_grains(os.path.join(work, "stores", "spheres.h5"))
    for step, rho_k, z_k, (dimension, xyzr) in zip(steps, rho, z, grains):
        f = Frame(work, step)
        check(dimension == 3 and np.array_equal(xyzr, np.column_stack([f.x, f.r])),
              f"step {step}: stored 3D, each grain's x, y, z, r as dumped")
        contacts, rho_lammps = lammps[step]
        pairs = f.pairs()
        check(len(pairs) == len(f.i) == contacts, f"step {step}: {len(pairs)} pairs, contact/atom {contacts:.0f}")
        missing = f.touching(1e-3) - pairs
        strays = pairs - f.touching(-1e-6)
        check(not missing and not strays,
              f"step {step}: the dumped pairs are the spheres that touch ({len(missing)} missing, {len(strays)} apart)")
        worst_rho = max(worst_rho, abs(rho_k - rho_lammps) / rho_lammps)
        along = np.abs(f.normal_component()) / np.linalg.norm(f.normal, axis=1)
        check(np.all(np.abs(along - 1) < 1e-7), f"step {step}: the normal vectors lie along the lines of centres "
              f"within {np.max(np.abs(along - 1)):.1e}")
        pushing = f.pushing()
        check(abs(z_k - 2 * pushing / len(f.r)) < 1e-12, f"step {step}: Z {z_k:.6f} = 2 x {pushing} / {len(f.r)}")
    check(worst_rho < 1e-5, f"rho within {worst_rho:.2e} of LAMMPS's sum of 4/3 pi r^3 / vol at every step "
          f"({rho[0]:.4f} to {rho[-1]:.4f})")
    printed = thermo_values(os.path.join(work, "log.lammps"), "v_fnet_rho")
    _, from_log, _, _ = stored(os.path.join(work, "stores", "spheres-rho.h5"))
    check(from_log == [printed.get(s) for s in steps], "--rho log: the log's values")

    # GUDHI on the 2-skeleton of the flag complex of each contact graph.
    agree = 0
    for step in GUDHI_STEPS:
        f = Frame(work, step)
        for force in ("normal", "tangential"):
            r = subprocess.run(["fnet-analyze", "diagram", "--lammps-atoms", "atoms.*.txt", "--lammps-pairs",
                                "pairs.*.txt", "--timestep", str(step), "--force", force], cwd=work, env=env,
                               capture_output=True, text=True)
            if r.returncode != 0:
                check(False, f"diagram of step {step}: {r.stderr.strip()}")
                continue
            ours, theirs = json.loads(r.stdout), gudhi_diagrams(f, force)
            counts = [(ours[k], theirs[k]) for k in ("vertices", "edges", "triangles")]
            same = all(x == y for x, y in counts) and all(same_points(ours[d], theirs[d]) for d in ("pd0", "pd1"))
            agree += same
            check(same, f"step {step} {force}: fnet = GUDHI (vertices, edges, triangles {counts}; "
                  f"{len(ours['pd0'])} + {len(ours['pd1'])} points)")
        edges = len(f.pairs())
        if step >= 7000:
            check(edges > 3 * len(f.r) - 6, f"step {step}: {edges} contacts > 3V - 6 = {3 * len(f.r) - 6}: non-planar")
    print(f"GUDHI agrees on {agree} of {2 * len(GUDHI_STEPS)} diagram pairs")

    one = json.load(open(os.path.join(work, "diagram-8000.json")))
    check(one == json.load(open(os.path.join(work, "diagram-8000-of-run.json"))),
          "diagram: one file's frame = the pattern's frame of its TIMESTEP")
    ex = json.load(open(os.path.join(work, "explain-6000-8000.json")))
    check(len(ex["explain"]) == 3 and ex["value"] > 0, f"explain: 3 terms, {ex['value']}")

    # The frames at rest are balanced (the page's line, and far tighter than it asks); the normal
    # force read as the whole pair force is not.
    rest = next(l for l in commands(doc, "sh 3d") if "--check-balance" in l)
    tight = rest.replace("--check-balance 0.05", "--check-balance 1e-4").replace("spheres-at-rest", "spheres-tight")
    r = subprocess.run(tight, shell=True, cwd=work, env=env, capture_output=True, text=True)
    check(r.returncode == 0, f"the frames at rest balanced within 1e-4 of the mean force: {r.stderr.strip()[:200]}")
    wrong = rest.replace("--run-id spheres-at-rest", "--columns 'fx=c_fnet_force[1],fy=c_fnet_force[2],"
                         "fz=c_fnet_force[3]' --run-id spheres-wrong")
    r = subprocess.run(wrong, shell=True, cwd=work, env=env, capture_output=True, text=True)
    check(r.returncode == 1 and "out of force balance" in r.stderr, f"columns swapped: {r.stderr.strip()[:200]}")

    # The page's warning: the rest in a run of its own after fix deform's keeps fewer pairs than
    # touch (the counts the page gives), and the force balance of its frames at rest fails.
    apart = os.path.join(work, "rest-apart")
    os.makedirs(apart)
    wrong = run_lammps(a.lmp, apart, lammps_inputs.spheres("".join(blocks(doc, "lammps 3d")), rest_apart=True))
    check(not wrong, f"lmp ran the rest apart {wrong}")
    squeezed, rested = (entries(os.path.join(apart, f"pairs.{step}.txt"))
                        for step in (lammps_inputs.SPHERES_SQUEEZED_AT, lammps_inputs.SPHERES_STEPS))
    check(f"{spaced(rested)} of {spaced(squeezed)}" in doc,
          f"the rest apart: {rested} of the {squeezed} pairs kept, as the page says")
    r = subprocess.run(rest, shell=True, cwd=apart, env=env, capture_output=True, text=True)
    check(r.returncode == 1 and "out of force balance" in r.stderr,
          f"the rest apart fails the force balance: {r.stderr.strip()[:200]}")
    print("FAILED: " + "; ".join(failures) if failures else "all checks hold")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
