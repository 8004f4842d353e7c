"""The LAMMPS inputs fnet's tests run with Debian's lmp (LAMMPS 29 Sep 2021), in one place.

disks(): 196 polydisperse disks (diameters uniform in [0.8, 1.2]) on a square lattice in a periodic
2D box of side 16.8, with fix enforce2d and viscous damping; DISKS_SQUEEZE shrinks the box to 13.4
(rho from about 0.52 to 0.82). The 2D tests add their protocol after it (runs, the page's lines).

spheres(doc): 343 polydisperse spheres (diameters uniform in [0.8, 1.2]) on a simple cubic lattice
in a periodic box of side 7.5, compressed by fix deform to side 6.3 over 8 time units (rho from 0.45
to 0.76, Z from 0 to about 7.5), then left at rest under viscous damping, all in one run of 12000
steps, with `doc` (the lines proto/lammps.md has a user add) before it. One run because, measured
with this LAMMPS, a `run` after a run with fix deform in 3D leaves many touching pairs out of the
neighbour lists of the history pair styles (gran/hooke/history, granular with linear_history: the
pair dump, contact/atom and the forces alike), while the same positions read afresh have them;
spheres(doc, rest_apart=True) is the input with that fault: the rest in a second run.

disks_between_planes(fix, dump): 48 disks (diameters uniform in [1.0, 1.1]) squeezed between two
planes of fix wall/gran (`fix`, its ID w; periodic in x) come to rest over 20000 steps, then 2000
more with `dump` (the per-atom dump of the grains and the fix's contacts), the pair dump of the
page's lines and LAMMPS's count of wall contacts every 1000 steps.

PAIR_STYLES: the two granular pair styles of proto/lammps.md, frictional (mu = 0.5).
"""

PAIR_STYLES = {
    "gran/hooke/history": "pair_style gran/hooke/history 2000.0 NULL 50.0 NULL 0.5 1\npair_coeff * *",
    "granular": "pair_style granular\npair_coeff * * hooke 2000.0 50.0 tangential linear_history 1000.0 1.0 0.5",
}

# Polydisperse grains, diameters uniform in [0.8, 1.2], of unit density, on the lattice of the box.
_GRAINS = """create_box 1 box
create_atoms 1 box
velocity all create 0.5 {seed} loop geom
variable d atom 0.8+0.4*random(0,1,{seed})
set group all diameter v_d
set group all density 1.0
{pair}
neighbor 0.3 bin
"""

_DISKS = """dimension 2
boundary p p p
atom_style sphere
comm_modify vel yes
lattice sq 0.694
region box block 0 16.8 0 16.8 -0.5 0.5 units box
""" + _GRAINS + """timestep 0.001
fix move all nve/sphere
fix flat all enforce2d
fix calm all viscous 2.0
"""

DISKS_SQUEEZE = "fix squeeze all deform 1 x final 0 13.4 y final 0 13.4 remap x units box\n"

_SPHERES = """dimension 3
boundary p p p
atom_style sphere
comm_modify vel yes
lattice sc 0.8
region box block 0 7.5 0 7.5 0 7.5 units box
""" + _GRAINS + """neigh_modify delay 0
timestep 0.001
fix move all nve/sphere
fix calm all viscous 2.0
{doc}
variable squeezed equal elaplong*dt/8.0
variable shrink equal "-1.2*(v_squeezed*(v_squeezed<1)+(v_squeezed>=1))"
variable shrink_rate equal "-0.15*(v_squeezed<1)"
fix squeeze all deform 1 x variable v_shrink v_shrink_rate y variable v_shrink v_shrink_rate z variable v_shrink v_shrink_rate remap x
{after}{runs}
"""

_PLANES = """dimension 2
boundary p f p
atom_style sphere
comm_modify vel yes
region box block 0 10 0 4 -0.5 0.5 units box
create_box 1 box
lattice sq 1.23
region fill block 0 10 0.5 3.7 -0.5 0.5 units box
create_atoms 1 region fill
variable d atom 1.0+0.1*random(0,1,4711)
set group all diameter v_d
set group all density 1.0
pair_style gran/hooke/history 2000.0 NULL 50.0 NULL 0.5 1
pair_coeff * *
timestep 0.001
fix move all nve/sphere
fix flat all enforce2d
fix calm all viscous 2.0
{fix}
run 20000 post no
compute fnet_pair all property/local patom1 patom2 cutoff radius
compute fnet_force all pair/local fx fy fz p1 p2 p3 cutoff radius
compute fnet_walls all reduce sum f_w[1]
fix fnet_numbers all ave/time 1000 1 1000 c_fnet_walls file wall_numbers.txt
{dump}
dump fnet_pairs all local 1000 pairs.*.txt c_fnet_pair[1] c_fnet_pair[2] c_fnet_force[1] c_fnet_force[2] c_fnet_force[3] c_fnet_force[4] c_fnet_force[5] c_fnet_force[6]
run 2000 post no
"""

SPHERES_SQUEEZED_AT = 8000  # the step the squeeze ends at; the spheres are at rest some steps later
SPHERES_STEPS = 12000


def disks(seed=4711, pair="granular"):
    """The 2D system, up to its protocol."""
    return _DISKS.format(seed=seed, pair=PAIR_STYLES[pair])


def spheres(doc, after="", seed=4711, pair="granular", rest_apart=False):
    """The whole 3D input: `doc` (LAMMPS lines) before the squeeze, `after` after it, then its run
    (with `rest_apart`, one run of the squeeze and one of the rest after it, without fix deform).
    A fix in `after` sees each step's box as the dumps do, after fix deform has changed it."""
    runs = (f"run {SPHERES_SQUEEZED_AT} post no\nunfix squeeze\nrun {SPHERES_STEPS - SPHERES_SQUEEZED_AT} post no"
            if rest_apart else f"run {SPHERES_STEPS} post no")
    return _SPHERES.format(seed=seed, pair=PAIR_STYLES[pair], doc=doc.rstrip("\n"), after=after, runs=runs)


def disks_between_planes(fix, dump):
    """The whole input of the disks at rest between two wall planes."""
    return _PLANES.replace("{fix}", fix).replace("{dump}", dump)
