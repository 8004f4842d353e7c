#!/usr/bin/env python3
"""fnet-simd against LAMMPS on the same system and protocol, one run each, side by side.

fnet-simd runs the protocol (relaxation, compression from rho 0.63 to 0.90) and writes its start as
a LAMMPS data file; LAMMPS runs tests/server/dem/lammps/in.compress from it (gran/hooke/history, wall
particles moved with fix move linear, the same damped relaxation to the same translational-energy
target). Prints steps/s and particle-steps/s of both (all steps, relaxation included: LAMMPS's "Loop time" lines, fnet-simd's
summary line) and the ratio; then the projected wall time of the paper's full protocol
(v_c = 2.5e-5: ~8.1 million compression steps) at fnet-simd's measured rate.

fnet-simd runs with 1 and with 2 threads (--threads; both must export the same frames, bit for
bit), LAMMPS serially (the issue's anchor) and, with --lammps-ranks 2, also on 2 MPI ranks, the
like-for-like comparison on 2 cores.

usage: bench_vs_lammps.py FNET_SIMD [--lmp lmp] [--particles 2000] [--mu 0.5] [--compression-speed 1e-3]
                          [--lammps-ranks 2]
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("fnet_simd")
ap.add_argument("--lmp", default="lmp")
ap.add_argument("--particles", type=int, default=2000)
ap.add_argument("--mu", type=float, default=0.5)
ap.add_argument("--compression-speed", type=float, default=1e-3)
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--workdir", default=None)
ap.add_argument("--lammps-ranks", type=int, default=1, help="also run LAMMPS on this many MPI ranks (> 1)")
a = ap.parse_args()
work = a.workdir or tempfile.mkdtemp(prefix="fnet-bench-sim-")
os.makedirs(work, exist_ok=True)
common = ["--particles", str(a.particles), "--mu", str(a.mu), "--compression-speed", str(a.compression_speed),
          "--seed", str(a.seed), "--frames", "101"]
info = json.loads(subprocess.run([a.fnet_simd, *common, "--show-params"], capture_output=True, text=True, check=True).stdout)
p, d = info["params"], info["derived"]
data = os.path.join(work, "initial.data")
fnet_runs = {}
for threads in (1, 2):
    extra = ["--write-lammps-data", data] if threads == 1 else []
    res = subprocess.run([a.fnet_simd, *common, "--no-dds", "--quiet", "--threads", str(threads), "--export-csv",
                          os.path.join(work, f"fnet{threads}"), *extra], capture_output=True, text=True, check=True)
    m = re.search(r"(\d+) steps in ([\d.]+) s", res.stderr)
    fnet_runs[threads] = (int(m.group(1)), float(m.group(2)))
same = subprocess.run(["diff", "-r", "-q", os.path.join(work, "fnet1"), os.path.join(work, "fnet2")],
                      capture_output=True).returncode == 0
shutil.rmtree(os.path.join(work, "fnet"), ignore_errors=True)
os.rename(os.path.join(work, "fnet1"), os.path.join(work, "fnet"))
with open(os.path.join(work, "fnet", "index.csv")) as f:
    steps = int(f.read().strip().splitlines()[-1].split(",")[1])
lvars = {"data": data, "mu": p["mu"], "kn": p["kn"], "kt": d["kt"], "gamma": d["gamma_n"], "dt": d["dt"],
         "vwall": d["wall_speed_internal"], "relax_ke": p["relax_energy"] / d["tau_c"] ** 2,
         "relax_damp": d["tau_c"] / p["relax_damping"] if p["relax_damping"] > 0 else 1e300,
         "relax_max": int(p["relax_max_time"] * p["dt_divisor"]), "steps": steps, "every": max(1, steps // 100),
         "ngrains": a.particles, "out": os.path.join(work, "lammps_pairs.dump")}
cmd = [a.lmp, "-in", os.path.join(here, "..", "..", "server", "dem", "lammps", "in.compress"), "-log", os.path.join(work, "log.lammps"),
       "-screen", "none"]
for k, v in lvars.items():
    cmd += ["-var", k, repr(v) if isinstance(v, float) else str(v)]


def run_lammps(ranks):
    log = os.path.join(work, f"log{ranks}.lammps")
    c = list(cmd)
    c[c.index("-log") + 1] = log
    if ranks > 1:
        c = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), *c]
    subprocess.run(c, check=True)
    sec = nsteps = 0
    with open(log) as f:
        for line in f:
            mm = re.match(r"Loop time of ([\d.eE+-]+) on \d+ procs for (\d+) steps", line)
            if mm:
                sec += float(mm.group(1))
                nsteps += int(mm.group(2))
    return nsteps, sec


lammps_runs = {1: run_lammps(1)}
if a.lammps_ranks > 1:
    lammps_runs[a.lammps_ranks] = run_lammps(a.lammps_ranks)
n = a.particles
lr = lammps_runs[1][0] / lammps_runs[1][1]
print(f"same system and protocol: N = {n}, mu = {a.mu}, v_c = {a.compression_speed} d/tau_c, relaxation + {steps} compression steps")
print(f"{'':22} {'steps':>10} {'seconds':>9} {'steps/s':>9} {'particle-steps/s':>17} {'vs LAMMPS serial':>17}")
rows = [(f"fnet-simd, {t} thread" + ("s" if t > 1 else ""), *fnet_runs[t]) for t in (1, 2)]
rows += [(f"LAMMPS, {r} MPI rank" + ("s" if r > 1 else ""), *lammps_runs[r]) for r in sorted(lammps_runs)]
for name, st, sec in rows:
    print(f"{name:22} {st:10d} {sec:9.1f} {st / sec:9.0f} {st / sec * n:17.4g} {st / sec / lr:16.2f}x")
print(f"fnet-simd's frames with 1 and 2 threads identical bit for bit: {'yes' if same else 'NO'}")
full = steps * a.compression_speed / 2.5e-5
for t in (1, 2):
    fr = fnet_runs[t][0] / fnet_runs[t][1]
    print(f"paper's protocol (v_c = 2.5e-5, {full / 1e6:.1f} M compression steps) at fnet-simd's rate, {t} thread"
          f"{'s' if t > 1 else ''}: {full / fr / 60:.1f} min")
