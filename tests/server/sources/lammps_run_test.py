#!/usr/bin/env python3
"""proto/lammps.md run as written, against the numbers LAMMPS itself reports.

For pair_style gran/hooke/history and for granular: writes a 2D input (tests/support/lammps_inputs.py:
196 polydisperse disks in a periodic box compressed by fix deform, then relaxed), adds the page's
lammps blocks to it, runs
Debian's lmp, runs the page's sh blocks (fnet-analyze store) in the dumps' folder, and checks the
stores against LAMMPS: the contacts of each frame against compute contact/atom, rho against the
disks' area over the box LAMMPS computes, the forces against the pair/local dump read here, the
force columns' meaning against LAMMPS's per-atom forces, Z
against the contacts' normal forces, the force balance holding (--check-balance in the page's
line) and failing when the normal force is read as the whole pair force, the grains dumped
with their z (one value, fix enforce2d) read as the same 2D frames, the page's dumps written
gzip-compressed by LAMMPS (custom/gz, local/gz) read as the same frames, and --rho column on a
dumped per-atom copy of LAMMPS's rho. Exit status 0 when every check
holds, 1 otherwise.
"""
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
import lammps_inputs  # noqa: E402
from lammps_doc import blocks, test_arguments, thermo_values  # noqa: E402

# After the disks: squeezed and relaxed, then the page's lines, LAMMPS's own counts, and the test's
# dumps: the per-atom forces, and the grains with their z (one value in a 2D run).
PROTOCOL = lammps_inputs.DISKS_SQUEEZE + """run 8000 post no
unfix squeeze
run 6000 post no
compute fnet_contacts all contact/atom
compute fnet_pairs_touching all reduce sum c_fnet_contacts
{rho}
fix fnet_numbers all ave/time 1000 1 1000 c_fnet_pairs_touching v_fnet_rho file lammps_numbers.txt format " %.12g"
{doc}
dump fnet_test_forces all custom 1000 forces.*.txt id fx fy
dump fnet_test_z all custom 1000 atoms-z.*.txt id type x y z radius
variable fnet_rho_atom atom v_fnet_rho
dump fnet_test_rho all custom 1000 atoms-rho.*.txt id type x y radius v_fnet_rho_atom
dump_modify fnet_test_rho format float %.12g
{gz}
run 3000 post no
"""


def gz_dumps(doc_lines):
    """The page's two dumps again, gzip-compressed by LAMMPS itself (custom/gz, local/gz)."""
    out = []
    for line in doc_lines.splitlines():
        for name, style in (("fnet_atoms", "custom"), ("fnet_pairs", "local")):
            if line.startswith(f"dump {name} all {style} "):
                out.append(line.replace(f"dump {name} all {style} ", f"dump {name}_gz all {style}/gz ")
                           .replace(".*.txt", ".*.txt.gz"))
    return "\n".join(out)

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


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


def source_config(path):
    """The "source" of the store's last announcement's config_json."""
    with h5py.File(path, "r") as f:
        announcement = json.loads(f["announcements"][-1].decode().rstrip("\0"))
    return json.loads(announcement["config_json"])["source"]


def run_style(style, args, doc, work):
    print(f"== pair_style {style}")
    os.makedirs(work)
    lines = "\n".join(blocks(doc, "lammps"))
    text = lammps_inputs.disks(4711, style) + PROTOCOL.format(doc=lines, rho=blocks(doc, "lammps rho")[0],
                                                              gz=gz_dumps(lines))
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
    printed = thermo_values(os.path.join(work, "log.lammps"), "v_fnet_rho")
    from_log = stored(os.path.join(work, "stores", "packing-rho.h5"))
    check([g["rho"] for g in from_log] == [printed.get(g["step"]) for g in from_log],
          f"--rho log: the log's values {[printed.get(g['step']) for g in from_log]}")
    # (the dump's radii have 6 digits: fnet's own rho is as close as that)
    check(all(abs(g["rho"] - f["rho"]) < 1e-5 * f["rho"] for f, g in zip(frames, from_log)),
          "--rho log: fnet's own rho of the periodic box within the dump's digits")
    # --rho column: the per-atom copy of the same variable, dumped with 12 digits.
    store_lines = [b for b in blocks(doc, "sh") if "--follow" not in b and "--run-id packing " in b]
    variants = {"packing-column": ("atoms.*.txt", "atoms-rho.*.txt", " --rho column:v_fnet_rho_atom"),
                "packing-gz": ("'atoms.*.txt' --lammps-pairs 'pairs.*.txt'",
                               "'atoms.*.txt.gz' --lammps-pairs 'pairs.*.txt.gz'", "")}
    for run, (old, new, extra) in variants.items():
        line = store_lines[0].strip().replace(old, new).replace("--run-id packing ", f"--run-id {run} ") + extra
        r = subprocess.run(line, shell=True, cwd=work, env=env, capture_output=True, text=True)
        check(r.returncode == 0, f"{line}: exit {r.returncode} {r.stderr.strip()}")
    if os.path.exists(os.path.join(work, "stores", "packing-column.h5")):
        column = stored(os.path.join(work, "stores", "packing-column.h5"))
        check([g["step"] for g in column] == steps and all(
            abs(g["rho"] - lammps[g["step"]][1]) < 1e-11 * g["rho"] for g in column if g["step"] in lammps),
            f"--rho column: LAMMPS's rho to 12 digits {[g['rho'] for g in column]}")
        check(source_config(os.path.join(work, "stores", "packing-column.h5"))["rho"] == "column:v_fnet_rho_atom",
              "--rho column: recorded in the announcement")
    # Dumps LAMMPS wrote compressed (custom/gz, local/gz): the same frames as the plain ones.
    if os.path.exists(os.path.join(work, "stores", "packing-gz.h5")):
        gz = stored(os.path.join(work, "stores", "packing-gz.h5"))
        check(len(gz) == len(frames) and all(
            g["step"] == f["step"] and g["rho"] == f["rho"] and g["z"] == f["z"]
            and np.array_equal(g["pairs"], f["pairs"]) and np.array_equal(g["forces"], f["forces"])
            for f, g in zip(frames, gz)), "gzip dumps written by LAMMPS: the same frames as the plain dumps")
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
    # The grains dumped with their z, one value in a 2D run (fix enforce2d): the same frames, 2D.
    r = subprocess.run(["fnet-analyze", "store", "--lammps-atoms", "atoms-z.*.txt", "--lammps-pairs", "pairs.*.txt",
                        "--run-id", "packing-z", "--data-dir", "stores"], cwd=work, env=env, capture_output=True,
                       text=True)
    check(r.returncode == 0, f"store of the dumps with z: exit {r.returncode} {r.stderr.strip()}")
    if r.returncode == 0:
        with_z = stored(os.path.join(work, "stores", "packing-z.h5"))
        same = len(with_z) == len(frames) and all(
            g["rho"] == f["rho"] and g["z"] == f["z"] and np.array_equal(g["pairs"], f["pairs"])
            and np.array_equal(g["forces"], f["forces"]) for f, g in zip(frames, with_z))
        check(same, "a z column of one value: the same frames as without it")
        dims = [source_config(os.path.join(work, "stores", f"{run}.h5"))["dimension"] for run in ("packing", "packing-z")]
        with h5py.File(os.path.join(work, "stores", "packing-z.h5"), "r") as h:
            flat = np.all(h["dimension"][:] == 2) and not np.any(h["particle_z"][:])
        check(dims == [2, 2] and flat, f"the runs' dimension, without and with z: {dims}; every frame 2D, z = 0")
    # The normal force read as the whole pair force (the tangential columns forgotten): the balance
    # fails, naming a frame.
    wrong = "--columns 'fx=c_fnet_force[1],fy=c_fnet_force[2]'"
    line = blocks(doc, "sh")[0].replace("--run-id packing", wrong + " --run-id packing-wrong")
    r = subprocess.run(line, shell=True, cwd=work, env=env, capture_output=True, text=True)
    check(r.returncode == 1 and "out of force balance" in r.stderr and "atoms." in r.stderr,
          f"columns swapped: exit {r.returncode}, {r.stderr.strip()[:200]}")
    check(not os.path.exists(os.path.join(work, "stores", "packing-wrong.h5")), "nothing stored for the swapped columns")


def main():
    a = test_arguments(__doc__)
    shutil.rmtree(a.workdir, ignore_errors=True)
    doc = open(a.doc).read()
    for k, style in enumerate(lammps_inputs.PAIR_STYLES):
        run_style(style, a, doc, os.path.join(a.workdir, f"style{k}"))
    print("FAILED: " + "; ".join(failures) if failures else "all checks hold")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
