#!/usr/bin/env python3
"""Z(rho) of fnet-simd against LAMMPS on the same system, start and protocol.

fnet-simd runs the paper's protocol and writes its initial state (lattice, diameters, masses,
velocities, walls) as a LAMMPS data file; LAMMPS (in.compress beside this script) runs the same
relaxation (grain velocities damped at the same rate until the same translational-energy target)
and compression with gran/hooke/history from that file. Both give Z (2 x grain-grain contacts
with F_n > 0 / N) at the same compression steps; the packing fraction where Z first reaches 3
(linear interpolation between frames) must agree within --tolerance.
Exit status 0 when it does, 1 when not, 2 on a failed run. Prints both series and the timings.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time


def relax_damp(p, d):
    """LAMMPS's damping time (fix langevin) for fnet-simd's relax_damping rate (1/tau_c); none for 0."""
    return d["tau_c"] / p["relax_damping"] if p["relax_damping"] > 0 else 1e300


def crossing(rho, z, level=3.0):
    for k in range(1, len(z)):
        if z[k - 1] < level <= z[k]:
            return rho[k - 1] + (level - z[k - 1]) * (rho[k] - rho[k - 1]) / (z[k] - z[k - 1])
    return math.nan


def run(cmd, **kw):
    t = time.perf_counter()
    res = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if res.returncode != 0:
        sys.stderr.write(f"command failed ({res.returncode}): {' '.join(cmd)}\n{res.stdout[-3000:]}\n{res.stderr[-3000:]}\n")
        sys.exit(2)
    return res, time.perf_counter() - t


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fnet-simd", required=True)
    ap.add_argument("--lmp", default="lmp")
    ap.add_argument("--input", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "in.compress"))
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--particles", type=int, default=2000)
    ap.add_argument("--mu", type=float, default=0.5)
    ap.add_argument("--compression-speed", type=float, default=1e-3)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--frames", type=int, default=101)
    ap.add_argument("--tolerance", type=float, default=0.01)
    a = ap.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    common = ["--particles", str(a.particles), "--mu", str(a.mu), "--compression-speed", str(a.compression_speed),
              "--seed", str(a.seed), "--frames", str(a.frames)]
    res, _ = run([a.fnet_simd, *common, "--show-params"])
    info = json.loads(res.stdout)
    p, d = info["params"], info["derived"]
    fdir = os.path.join(a.workdir, "fnet")
    data = os.path.join(a.workdir, "initial.data")
    _, t_fnet = run([a.fnet_simd, *common, "--no-dds", "--quiet", "--export-csv", fdir, "--write-lammps-data", data])

    with open(os.path.join(fdir, "index.csv")) as f:
        rows = [line.strip().split(",") for line in f][1:]
    f_step = [int(r[1]) for r in rows]
    f_rho = [float(r[3]) for r in rows]
    f_z = [float(r[4]) for r in rows]
    steps = f_step[-1]
    every = max(1, round(steps / (a.frames - 1)))

    dump = os.path.join(a.workdir, "lammps_pairs.dump")
    tau2 = d["tau_c"] ** 2
    lvars = {"data": data, "mu": p["mu"], "kn": p["kn"], "kt": d["kt"], "gamma": d["gamma_n"], "dt": d["dt"],
             "vwall": d["wall_speed_internal"], "relax_ke": p["relax_energy"] / tau2,
             "relax_damp": relax_damp(p, d),
             "relax_max": int(p["relax_max_time"] * p["dt_divisor"]), "steps": steps, "every": every,
             "ngrains": a.particles, "out": dump}
    cmd = [a.lmp, "-in", a.input, "-log", os.path.join(a.workdir, "log.lammps"), "-screen", "none"]
    for k, v in lvars.items():
        cmd += ["-var", k, repr(v) if isinstance(v, float) else str(v)]
    _, t_lmp = run(cmd)

    # Grain area and box from the data file (types 1 are grains).
    area = 0.0
    with open(data) as f:
        lines = f.read().split("Atoms # sphere")[1].split("Velocities")[0].strip().splitlines()
    for line in lines:
        t = line.split()
        if t[1] == "1":
            area += math.pi * (float(t[2]) / 2) ** 2
    box = p["box"]
    l_rho, l_z = [], []
    with open(dump) as f:
        lines = f.read().splitlines()
    k = 0
    while k < len(lines):
        if lines[k].startswith("ITEM: TIMESTEP"):
            step = int(lines[k + 1])
            n = int(lines[k + 3])
            body = lines[k + 5 + 4: k + 9 + n] if False else None
            # header: TIMESTEP, step, NUMBER OF ENTRIES, n, BOX BOUNDS + 3 lines, ENTRIES line
            start = k + 9
            contacts = 0
            for line in lines[start:start + n]:
                i, j, fn = line.split()
                if int(float(i)) <= a.particles and int(float(j)) <= a.particles and float(fn) > 0:
                    contacts += 1
            side = box - 2 * d["wall_speed_internal"] * d["dt"] * step
            l_rho.append(area / side ** 2)
            l_z.append(2 * contacts / a.particles)
            k = start + n
        else:
            k += 1

    rho_f, rho_l = crossing(f_rho, f_z), crossing(l_rho, l_z)
    print(f"N = {a.particles}, mu = {a.mu}, v_c = {a.compression_speed} d/tau_c, seed {a.seed}, {steps} compression steps")
    print(f"{'rho':>8} {'Z fnet':>8} {'rho':>8} {'Z lammps':>8}")
    for q in range(0, min(len(f_rho), len(l_rho)), max(1, len(f_rho) // 25)):
        print(f"{f_rho[q]:8.4f} {f_z[q]:8.3f} {l_rho[q]:8.4f} {l_z[q]:8.3f}")
    print(f"Z = 3 crossing: fnet-simd rho = {rho_f:.4f}, LAMMPS rho = {rho_l:.4f}, difference {rho_f - rho_l:+.4f} "
          f"(tolerance {a.tolerance})")
    print(f"wall time incl. relaxation: fnet-simd {t_fnet:.1f} s, LAMMPS {t_lmp:.1f} s")
    ok = math.isfinite(rho_f) and math.isfinite(rho_l) and abs(rho_f - rho_l) <= a.tolerance
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
