#!/usr/bin/env python3
"""fnet-simd against LAMMPS (serial) on the same system and protocol, one run each, side by side.

fnet-simd runs the protocol (relaxation, compression from rho 0.63 to 0.90) and writes its start as
a LAMMPS data file; LAMMPS runs tests/sim/lammps/in.compress from it (gran/hooke/history, wall
particles moved with fix move linear, same relaxation criterion). Prints steps/s and
particle-steps/s of both (all steps, relaxation included: LAMMPS's "Loop time" lines, fnet-simd's
summary line) and the ratio; then the projected wall time of the paper's full protocol
(v_c = 2.5e-5: ~8.1 million compression steps) at fnet-simd's measured rate.

usage: bench_vs_lammps.py FNET_SIMD [--lmp lmp] [--particles 2000] [--mu 0.5] [--compression-speed 1e-3]
"""
import argparse
import json
import os
import re
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
a = ap.parse_args()
work = a.workdir or tempfile.mkdtemp(prefix="fnet-bench-sim-")
os.makedirs(work, exist_ok=True)
common = ["--particles", str(a.particles), "--mu", str(a.mu), "--compression-speed", str(a.compression_speed),
          "--seed", str(a.seed), "--frames", "101"]
if a.particles != 2000:
    common += ["--box", repr(50 * (a.particles / 2000) ** 0.5)]
info = json.loads(subprocess.run([a.fnet_simd, *common, "--show-params"], capture_output=True, text=True, check=True).stdout)
p, d = info["params"], info["derived"]
data = os.path.join(work, "initial.data")
res = subprocess.run([a.fnet_simd, *common, "--no-dds", "--quiet", "--export-csv", os.path.join(work, "fnet"),
                      "--write-lammps-data", data], capture_output=True, text=True, check=True)
m = re.search(r"(\d+) steps in ([\d.]+) s", res.stderr)
f_steps, f_sec = int(m.group(1)), float(m.group(2))
with open(os.path.join(work, "fnet", "index.csv")) as f:
    steps = int(f.read().strip().splitlines()[-1].split(",")[1])
lvars = {"data": data, "mu": p["mu"], "kn": p["kn"], "kt": d["kt"], "gamma": d["gamma_n"], "dt": d["dt"],
         "vwall": d["wall_speed_internal"], "relax_ke": p["relax_energy"] / d["tau_c"] ** 2,
         "relax_max": int(p["relax_max_time"] * p["dt_divisor"]), "steps": steps, "every": max(1, steps // 100),
         "ngrains": a.particles, "out": os.path.join(work, "lammps_pairs.dump")}
cmd = [a.lmp, "-in", os.path.join(here, "..", "..", "sim", "lammps", "in.compress"), "-log", os.path.join(work, "log.lammps"),
       "-screen", "none"]
for k, v in lvars.items():
    cmd += ["-var", k, repr(v) if isinstance(v, float) else str(v)]
subprocess.run(cmd, check=True)
l_sec = l_steps = 0
with open(os.path.join(work, "log.lammps")) as f:
    for line in f:
        mm = re.match(r"Loop time of ([\d.eE+-]+) on 1 procs for (\d+) steps", line)
        if mm:
            l_sec += float(mm.group(1))
            l_steps += int(mm.group(2))
n = a.particles
fr, lr = f_steps / f_sec, l_steps / l_sec
print(f"same system and protocol: N = {n}, mu = {a.mu}, v_c = {a.compression_speed} d/tau_c, relaxation + {steps} compression steps")
print(f"{'':10} {'steps':>10} {'seconds':>9} {'steps/s':>9} {'particle-steps/s':>17}")
print(f"{'fnet-simd':10} {f_steps:10d} {f_sec:9.1f} {fr:9.0f} {fr * n:17.4g}")
print(f"{'LAMMPS':10} {l_steps:10d} {l_sec:9.1f} {lr:9.0f} {lr * n:17.4g}")
print(f"ratio fnet-simd / LAMMPS: {fr / lr:.2f}x")
full = steps * a.compression_speed / 2.5e-5
print(f"paper's protocol (v_c = 2.5e-5, {full / 1e6:.1f} M compression steps) at fnet-simd's rate: {full / fr / 60:.1f} min")
