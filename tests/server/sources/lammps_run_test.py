#!/usr/bin/env python3
"""proto/lammps.md run as written, against the numbers LAMMPS itself reports.

For pair_style gran/hooke/history and for granular: writes a 2D input (196 polydisperse disks in
a periodic box compressed by fix deform, then relaxed), adds the page's lammps blocks to it, runs
Debian's lmp, runs the page's sh blocks (fnet-analyze store) in the dumps' folder, and checks the
stores against LAMMPS: the contacts of each frame against compute contact/atom, rho against the
disks' area over the box LAMMPS computes, the forces against the pair/local dump read here, the
force columns' meaning against LAMMPS's per-atom forces, Z
against the contacts' normal forces, the force balance holding (--check-balance in the page's
line) and failing when the normal force is read as the whole pair force. Exit status 0 when every
check holds, 1 otherwise.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys

import h5py

BASE = """dimension 2
boundary p p p
atom_style sphere
comm_modify vel yes
lattice sq 0.694
region box block 0 16.8 0 16.8 -0.5 0.5 units box
create_box 1 box
create_atoms 1 box
velocity all create 0.5 {seed} loop geom
variable d atom 0.8+0.4*random(0,1,{seed})
set group all diameter v_d
set group all density 1.0
{pair}
neighbor 0.3 bin
timestep 0.001
fix move all nve/sphere
fix flat all enforce2d
fix calm all viscous 2.0
fix squeeze all deform 1 x final 0 13.4 y final 0 13.4 remap x units box
run 8000 post no
unfix squeeze
run 6000 post no
compute fnet_contacts all contact/atom
compute fnet_pairs_touching all reduce sum c_fnet_contacts
{rho}
fix fnet_numbers all ave/time 1000 1 1000 c_fnet_pairs_touching v_fnet_rho file lammps_numbers.txt format " %.12g"
{doc}
dump fnet_test_forces all custom 1000 forces.*.txt id fx fy
run 3000 post no
"""

PAIRS = {
    "gran/hooke/history": "pair_style gran/hooke/history 2000.0 NULL 50.0 NULL 0.5 1\npair_coeff * *",
    "granular": "pair_style granular\npair_coeff * * hooke 2000.0 50.0 tangential linear_history 1000.0 1.0 0.5",
}

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def blocks(doc, lang):
    return re.findall(r"```" + lang + r"\n(.*?)```", doc, re.S)


def read_dump(path):
    """{timestep: (columns, rows)} of a LAMMPS text dump of one snapshot per file."""
    lines = open(path).read().split("\n")
    step = int(lines[1])
    head = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS") or l.startswith("ITEM: ENTRIES"))
    n = int(lines[3])
    return step, lines[head].split()[2:], [[float(v) for v in l.split()] for l in lines[head + 1:head + 1 + n]]


def stored(path):
    with h5py.File(path, "r") as f:
        off = f["network_offsets"][:]
        out = []
        for k in range(len(f["step"])):
            c0, c1 = int(off[k][2]), int(off[k][3])
            out.append({"step": int(f["step"][k]), "rho": float(f["rho"][k]), "z": float(f["z"][k]),
                        "grains": int(off[k][1] - off[k][0]),
                        "pairs": f["contact_pairs"][c0:c1], "forces": f["contact_forces"][c0:c1]})
        return out


def run_style(style, args, doc, work):
    print(f"== pair_style {style}")
    os.makedirs(work)
    text = BASE.format(seed=4711, pair=PAIRS[style], doc="\n".join(blocks(doc, "lammps")),
                       rho=re.findall(r"```lammps rho\n(.*?)```", doc, re.S)[0])
    open(os.path.join(work, "in.fnet"), "w").write(text)
    r = subprocess.run([args.lmp, "-in", "in.fnet", "-log", "log.lammps", "-screen", "none", "-nocite"], cwd=work,
                       capture_output=True, text=True)
    if r.returncode != 0:
        check(False, f"lmp ran ({r.returncode}): {open(os.path.join(work, 'log.lammps')).read()[-2000:]}")
        return
    env = dict(os.environ, PATH=os.path.dirname(args.fnet_analyze) + os.pathsep + os.environ["PATH"])
    # The blocks that follow a run live are tests/e2e/lammps_follow_test.py's, with a server.
    for line in (b for b in blocks(doc, "sh") if "--follow" not in b):
        r = subprocess.run(line, shell=True, cwd=work, env=env, capture_output=True, text=True)
        check(r.returncode == 0, f"{line.strip()}: exit {r.returncode} {r.stderr.strip()}")
    # LAMMPS's numbers: step, touching pairs x 2, rho.
    lammps = {}
    for l in open(os.path.join(work, "lammps_numbers.txt")):
        if not l.startswith("#"):
            s, c, rho = l.split()
            lammps[int(s)] = (float(c) / 2, float(rho))
    frames = stored(os.path.join(work, "stores", "packing.h5"))
    sizes = stored(os.path.join(work, "stores", "packing-sizes.h5"))
    steps = [14000, 15000, 16000, 17000]
    check([f["step"] for f in frames] == steps and [g["step"] for g in sizes] == steps,
          f"frames stored: {[f['step'] for f in frames]}, {[g['step'] for g in sizes]}")
    ids = None
    for f, g in zip(frames, sizes):
        step = f["step"]
        check(step in lammps, f"step {step}: LAMMPS reported it")
        if step not in lammps:
            continue
        pairs_lammps, rho_lammps = lammps[step]
        check(len(f["pairs"]) == pairs_lammps,
              f"step {step}: {len(f['pairs'])} contacts, contact/atom {pairs_lammps:.0f}")
        check(abs(f["rho"] - rho_lammps) < 1e-5 * rho_lammps, f"step {step}: rho {f['rho']:.8f} vs LAMMPS {rho_lammps:.8f}")
        # The magnitudes as pair/local's force and p4 give them, by atom ids (grains numbered by sorted id).
        _, acols, atoms = read_dump(os.path.join(work, f"atoms.{step}.txt"))
        if ids is None:
            ids = {int(a[acols.index("id")]): k for k, a in enumerate(sorted(atoms, key=lambda a: a[0]))}
        _, cols, rows = read_dump(os.path.join(work, f"sizes.{step}.txt"))
        want = {}
        for row in rows:
            i, j = ids[int(row[0])], ids[int(row[1])]
            want[(min(i, j), max(i, j))] = (row[2], abs(row[3]))
        mean = sum(abs(v[0]) for v in want.values()) / max(len(want), 1)
        worst = 0.0
        for store in (f, g):
            got = {(min(int(p[0]), int(p[1])), max(int(p[0]), int(p[1]))): (fo[0], fo[1])
                   for p, fo in zip(store["pairs"], store["forces"])}
            check(set(got) == set(want), f"step {step}: the stored pairs are the dump's pairs")
            for key in set(got) & set(want):
                worst = max(worst, abs(got[key][0] - want[key][0]), abs(got[key][1] - want[key][1]))
        check(worst < 1e-4 * mean, f"step {step}: forces within {worst:.2e} of pair/local's (mean {mean:.3g})")
        # The columns mean what the page says: fx fy + p1 p2 on patom1 (minus on patom2) add up to
        # the per-atom forces LAMMPS reports (fix viscous adds a little of its own).
        _, fcols, forces = read_dump(os.path.join(work, f"forces.{step}.txt"))
        net = {int(a[0]): [0.0, 0.0] for a in forces}
        _, pcols, prows = read_dump(os.path.join(work, f"pairs.{step}.txt"))
        for row in prows:
            fx, fy = row[2] + row[5], row[3] + row[6]
            net[int(row[0])][0] += fx
            net[int(row[0])][1] += fy
            net[int(row[1])][0] -= fx
            net[int(row[1])][1] -= fy
        off = max(max(abs(net[int(a[0])][0] - a[1]), abs(net[int(a[0])][1] - a[2])) for a in forces)
        check(off < 1e-3 * mean, f"step {step}: pair vectors add up to LAMMPS's per-atom forces within {off:.2e}")
        pushing = sum(1 for v in want.values() if v[0] > 0)
        check(abs(f["z"] - 2 * pushing / f["grains"]) < 1e-12, f"step {step}: Z {f['z']:.6f} = 2 x {pushing} / {f['grains']}")
    # --rho log: ρ as the log prints it, near fnet's own.
    printed, header = {}, None
    for l in open(os.path.join(work, "log.lammps")):
        w = l.split()
        if w[:1] == ["Step"]:
            header = w
        elif l.startswith("Loop time"):
            header = None
        elif header and "v_fnet_rho" in header and len(w) == len(header):
            printed.setdefault(int(w[0]), float(w[header.index("v_fnet_rho")]))
    from_log = stored(os.path.join(work, "stores", "packing-rho.h5"))
    check([g["rho"] for g in from_log] == [printed.get(g["step"]) for g in from_log],
          f"--rho log: the log's values {[printed.get(g['step']) for g in from_log]}")
    # (the dump's radii have 6 digits: fnet's own rho is as close as that)
    check(all(abs(g["rho"] - f["rho"]) < 1e-5 * f["rho"] for f, g in zip(frames, from_log)),
          "--rho log: fnet's own rho of the periodic box within the dump's digits")
    # diagram and explain read the frames store stored: the diagram's vertices are the grains, its
    # edges the contacts with F_n > 0, the same from the file and from the pattern; explain the same
    # from two files and from two TIMESTEPs of the pattern, its grains with positions.
    by_step = {f["step"]: f for f in frames}
    one = json.load(open(os.path.join(work, "diagram-15000.json")))
    check(one == json.load(open(os.path.join(work, "diagram-15000-of-run.json"))),
          "diagram: one file's frame = the pattern's frame of its TIMESTEP")
    f15 = by_step.get(15000)
    if f15 is not None:
        pushing = int(sum(1 for fo in f15["forces"] if fo[0] > 0))
        check(one["vertices"] == f15["grains"] and one["edges"] == pushing,
              f"diagram: {one['vertices']} vertices, {one['edges']} edges; stored {f15['grains']} grains, {pushing} pushing")
    ex = json.load(open(os.path.join(work, "explain-14000-17000.json")))
    ex_files = json.load(open(os.path.join(work, "explain-files.json")))
    check(ex["value"] == ex_files["value"] and ex["explain"] == ex_files["explain"] and len(ex["explain"]) == 3,
          f"explain: the same from two TIMESTEPs and from two files ({ex['value']})")
    check(all("positions" in t["a"]["birth_simplex"] for t in ex["explain"] if t["a"]),
          "explain: the grains have positions")
    # The normal force read as the whole pair force (the tangential columns forgotten): the balance
    # fails, naming a frame.
    wrong = "--columns 'fx=c_fnet_force[1],fy=c_fnet_force[2]'"
    line = blocks(doc, "sh")[0].replace("--run-id packing", wrong + " --run-id packing-wrong")
    r = subprocess.run(line, shell=True, cwd=work, env=env, capture_output=True, text=True)
    check(r.returncode == 1 and "out of force balance" in r.stderr and "atoms." in r.stderr,
          f"columns swapped: exit {r.returncode}, {r.stderr.strip()[:200]}")
    check(not os.path.exists(os.path.join(work, "stores", "packing-wrong.h5")), "nothing stored for the swapped columns")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fnet-analyze", required=True)
    ap.add_argument("--lmp", default="lmp")
    ap.add_argument("--doc", required=True)
    ap.add_argument("--workdir", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.workdir, ignore_errors=True)
    doc = open(a.doc).read()
    for k, style in enumerate(PAIRS):
        run_style(style, a, doc, os.path.join(a.workdir, f"style{k}"))
    print("FAILED: " + "; ".join(failures) if failures else "all checks hold")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
