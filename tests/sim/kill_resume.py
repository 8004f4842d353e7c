#!/usr/bin/env python3
"""fnet-simd killed (SIGKILL, no chance to save) mid-run and resumed with --resume writes the same
CSV files, byte for byte, as an uninterrupted run; --help mentions that DDS is not implemented."""
import filecmp
import os
import shutil
import signal
import subprocess
import sys
import time

simd, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
args = ["--particles", "400", "--box", "22.36", "--compression-speed", "5e-3", "--relax-energy", "1e-5",
        "--frames", "12", "--seed", "9", "--no-dds", "--quiet", "--checkpoint-interval", "0.2"]
full, cut = os.path.join(work, "full"), os.path.join(work, "cut")

help_text = subprocess.run([simd, "--help"], capture_output=True, text=True, check=True).stdout
assert "--no-dds" in help_text and "--out" in help_text, "help must explain DDS publishing and the run file"

t0 = time.perf_counter()
subprocess.run([simd, *args, "--export-csv", full], check=True)
elapsed = time.perf_counter() - t0

proc = subprocess.Popen([simd, *args, "--export-csv", cut])
time.sleep(max(0.6, elapsed / 2))
proc.send_signal(signal.SIGKILL)
proc.wait()
done = sum(1 for f in os.listdir(cut) if f.endswith("_particles.csv"))
print(f"uninterrupted run {elapsed:.1f} s; killed after {done} frames")
subprocess.run([simd, "--resume", "--export-csv", cut, "--no-dds", "--quiet"], check=True)

names = sorted(f for f in os.listdir(full) if f.endswith(".csv"))
assert len(names) == 1 + 3 * 12, names
match, mismatch, errors = filecmp.cmpfiles(full, cut, names, shallow=False)
if mismatch or errors:
    print("differ:", mismatch, errors)
    sys.exit(1)
print(f"{len(match)} files identical after kill and resume")
