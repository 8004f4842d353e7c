#!/usr/bin/env python3
"""fnet-simd killed (SIGKILL, no chance to save) mid-run and resumed with --resume writes the same
CSV files, byte for byte, as an uninterrupted run; --help explains DDS publishing and the run file."""
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
args = ["--particles", "400", "--box", "22.36", "--compression-speed", "5e-4", "--relax-energy", "1e-5",
        "--frames", "12", "--seed", "9", "--no-dds", "--quiet", "--checkpoint-interval", "0.2"]
full, cut = os.path.join(work, "full"), os.path.join(work, "cut")

help_text = subprocess.run([simd, "--help"], capture_output=True, text=True, check=True).stdout
assert "--no-dds" in help_text and "--out" in help_text, "help must explain DDS publishing and the run file"

t0 = time.perf_counter()
subprocess.run([simd, *args, "--export-csv", full], check=True)
elapsed = time.perf_counter() - t0

def frames_written():
    return sum(1 for f in os.listdir(cut) if f.endswith("_particles.csv")) if os.path.isdir(cut) else 0


# Killed mid-compression: once 4 of the 12 frames are out (a frame every ~0.15 s).
proc = subprocess.Popen([simd, *args, "--export-csv", cut])
while frames_written() < 4 and proc.poll() is None:
    time.sleep(0.005)
proc.send_signal(signal.SIGKILL)
proc.wait()
done = frames_written()
print(f"uninterrupted run {elapsed:.1f} s; killed after {done} frames")
assert 0 < done < 12, f"the kill must land mid-run, it came after {done} of 12 frames"
subprocess.run([simd, "--resume", "--export-csv", cut, "--no-dds", "--quiet"], check=True)

names = sorted(f for f in os.listdir(full) if f.endswith(".csv"))
assert len(names) == 1 + 3 * 12, names
match, mismatch, errors = filecmp.cmpfiles(full, cut, names, shallow=False)
if mismatch or errors:
    print("differ:", mismatch, errors)
    sys.exit(1)
print(f"{len(match)} files identical after kill and resume")
