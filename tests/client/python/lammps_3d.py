"""Real 3D packings from Debian's LAMMPS (lmp), for the figures of 3D frames: polydisperse spheres
(diameters 0.8-1.1, or 0.8-1.0 compressed; lengths in LAMMPS's units, about a diameter) with pair
gran/hooke/history, either settled under gravity along -y in a
box with granular walls (one frame with a force gradient in y), or compressed through jamming in
a periodic box by fix deform (a run of frames). The dumps are read here into fnet.store.Frame
(particles x, y, r and particle_z; atom id k is grain k - 1) or written as a run folder of contacts CSVs
(proto/frames.md) with the volume fraction as rho."""

import subprocess
from pathlib import Path

import numpy as np

from fnet.store import Frame

HEADER = """units lj
dimension 3
atom_style sphere
atom_modify map array
newton off
comm_modify vel yes
"""
# After create_atoms: diameters 0.8 + spread·U(0, 1), mass d³ (density 6/π), a small random
# velocity, and Newton's equations for spheres.
GRAINS = """variable d atom 0.8+{spread}*random(0,1,{seed})
set type 1 diameter v_d
set type 1 density 1.9098593
velocity all create {speed} {seed} loop geom
neighbor {skin} bin
neigh_modify delay 0 every 1 check yes
timestep 0.0007
fix integrate all nve/sphere
"""
PAIR = "pair_style gran/hooke/history 4000 3200 38.5 38.5 0.5 1\npair_coeff * *"

# 7 x 7 d in x and z, open at the top: shrink-wrapped in y so that no grain is lost.
SETTLE = HEADER + """boundary f m f
region box block 0 7 0 14 0 7
create_box 1 box
{pair}
lattice sc 1.15
region cloud block 0.6 6.4 0.6 13.4 0.6 6.4 units box
create_atoms 1 region cloud
""" + GRAINS.format(spread=0.3, speed=0.05, skin=0.3, seed="{seed}") + """fix down all gravity 1.0 vector 0 -1 0
fix floor all wall/gran hooke/history 4000 3200 38.5 38.5 0.5 1 yplane 0 NULL
fix xwalls all wall/gran hooke/history 4000 3200 38.5 38.5 0.5 1 xplane 0 7
fix zwalls all wall/gran hooke/history 4000 3200 38.5 38.5 0.5 1 zplane 0 7
run {steps}
compute pairs all property/local patom1 patom2
compute force all pair/local force p1 p2 p3 p4
dump atoms all custom 1 atoms.dump id x y z radius
dump_modify atoms format float %.12g
dump contacts all local 1 pairs.dump c_pairs[1] c_pairs[2] c_force[1] c_force[5]
dump_modify contacts format float %.12g
run 0
"""

# 512 spheres on a cubic lattice, squeezed to a volume fraction of about 0.57 unrecorded, then
# through jamming to about 0.69, a frame every `every` steps.
COMPRESS = HEADER + """boundary p p p
region box block 0 7.6 0 7.6 0 7.6
create_box 1 box
{pair}
lattice sc 0.95
create_atoms 1 box
""" + GRAINS.format(spread=0.2, speed=0.01, skin=0.2, seed="{seed}") + """fix drag all viscous 0.2
fix squeeze all deform 1 x final 0 7.0 y final 0 7.0 z final 0 7.0 remap x
run 10000
reset_timestep 0
unfix squeeze
fix squeeze all deform 1 x final 0 6.55 y final 0 6.55 z final 0 6.55 remap x
write_dump all custom radii.dump id radius modify format float %.12g
compute pairs all property/local patom1 patom2
compute force all pair/local force p1 p2 p3 p4
dump contacts all local {every} pairs.*.dump c_pairs[1] c_pairs[2] c_force[1] c_force[5]
dump_modify contacts format float %.12g
run {steps}
"""


def run_lammps(script, folder, **values):
    """Writes the input into `folder` and runs lmp there; raises with its log when it fails."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "in.lammps").write_text(script.format(pair=PAIR, **values))
    r = subprocess.run(["lmp", "-in", "in.lammps", "-log", "log.lammps", "-screen", "none"], cwd=folder,
                       capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        log = (folder / "log.lammps").read_text() if (folder / "log.lammps").exists() else r.stdout + r.stderr
        raise RuntimeError(f"lmp failed in {folder}:\n{log[-3000:]}")
    return folder


def read_dump(path):
    """(columns, rows, box) of a one-snapshot dump: box the (3, 2) lo, hi bounds."""
    lines = Path(path).read_text().splitlines()
    at = next(k for k, line in enumerate(lines) if line.startswith("ITEM: BOX BOUNDS"))
    box = np.array([[float(v) for v in lines[at + k].split()[:2]] for k in (1, 2, 3)])
    head = next(k for k, line in enumerate(lines) if line.startswith(("ITEM: ATOMS", "ITEM: ENTRIES")))
    columns = lines[head].split()[2:]
    rows = np.array([[float(v) for v in line.split()] for line in lines[head + 1:]], dtype=np.float64)
    return columns, rows.reshape(-1, len(columns)), box


def touching(pairs_dump):
    """(pairs (m, 2) of 0-based grains, forces (m, 2) fn, ft): the pair dump's rows with a force."""
    _, p, _ = read_dump(pairs_dump)
    keep = p[:, 2] != 0
    return p[keep, :2].astype(np.int64) - 1, p[keep, 2:4]


def settled_frame(folder, seed=4711, steps=25000):
    """The settled packing as a 3D fnet.store.Frame: rho its volume fraction below the highest
    sphere's top, Z its mean contact number among grains."""
    folder = run_lammps(SETTLE, folder, seed=seed, steps=steps)
    columns, a, box = read_dump(folder / "atoms.dump")
    a = a[np.argsort(a[:, columns.index("id")])]
    assert np.array_equal(a[:, columns.index("id")], np.arange(1, len(a) + 1)), "atom ids 1..n"
    x, y, z, r = (a[:, columns.index(c)] for c in ("x", "y", "z", "radius"))
    pairs, forces = touching(folder / "pairs.dump")
    height = float((y + r).max())
    return Frame(index=0, run="lammps-3d-settled", step=steps, time=0.0, dimension=3,
                 rho=float(np.sum(4 / 3 * np.pi * r ** 3)) / (7 * 7 * height), z=2 * len(pairs) / len(r),
                 particles=np.column_stack([x, y, r]), particle_z=z, contact_pairs=pairs, contact_forces=forces,
                 wall_contact_particles=np.zeros(0, dtype=np.int64), wall_contact_forces=np.zeros((0, 2)))


def compression_run(folder, seed=4711, every=1500, steps=30000):
    """The compression as a run folder for fnet-analyze (index.csv, frame_KKKK_contacts.csv; no
    particles: the distances need none): rho the spheres' volume over the box's, Z = 2 contacts
    / grains. Returns (folder, rho, z)."""
    folder = run_lammps(COMPRESS, folder, seed=seed, every=every, steps=steps)
    columns, radii, _ = read_dump(folder / "radii.dump")
    volume = float(np.sum(4 / 3 * np.pi * radii[:, columns.index("radius")] ** 3))
    grains = len(radii)
    run = folder / "run"
    run.mkdir(exist_ok=True)
    rhos, zs = [], []
    with open(run / "index.csv", "w") as index:
        index.write("frame,step,rho,z\n")
        for k, step in enumerate(range(0, steps + 1, every)):
            pairs, forces = touching(folder / f"pairs.{step}.dump")
            _, _, box = read_dump(folder / f"pairs.{step}.dump")
            rho, z = volume / float(np.prod(box[:, 1] - box[:, 0])), 2 * len(pairs) / grains
            rhos.append(rho)
            zs.append(z)
            index.write(f"{k},{step},{rho!r},{z!r}\n")
            with open(run / f"frame_{k:04d}_contacts.csv", "w") as f:
                f.write("i,j,fn,ft\n")
                for (i, j), (fn, ft) in zip(pairs.tolist(), forces.tolist()):
                    f.write(f"{i},{j},{fn!r},{ft!r}\n")
    return run, np.array(rhos), np.array(zs)
