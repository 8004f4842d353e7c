#!/usr/bin/env python3
"""fnet-simd's command line as a user meets it: bad values are usage errors (exit 2) naming the
flag before any work is done; --rho-initial sizes the box (--box overrides it); --rho-final must
be above the start; the help shows the code's defaults for every parameter; --show-params output
and the parameters of earlier versions load back with --config; the relaxation is reported (and
a capped one warned about); frames that only DDS carries, with no subscriber, are an error (exit 3,
naming the domain); --version prints the version and commit; a CSV export names its provenance;
the --out run file is readable with h5py while it is written.

usage: cli_params.py FNET_SIMD WORKDIR CYCLONEDDS_XML"""
import json
import os
import random
import re
import shutil
import subprocess
import sys
import time

simd, work, dds_xml = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
failures = []


def run(*args, env=None, timeout=120):
    try:
        return subprocess.run([simd, *args], capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:  # a value that was not rejected starts a long run
        return subprocess.CompletedProcess(args, -9, "", f"still running after {timeout} s")


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def show(*args):
    res = run(*args, "--show-params")
    if res.returncode != 0:
        check(False, f"--show-params {' '.join(args)}: rc {res.returncode}: {res.stderr.strip()}")
        return None
    shown = json.loads(res.stdout)
    if "rho_initial" not in shown["derived"]:
        check(False, f"--show-params {' '.join(args)} gives the start's packing fraction")
        return None
    return shown


# Bad values: exit 2, the flag named, nothing written.
out_dir = os.path.join(work, "never")
for args, flag in [(["--particles", "-5"], "--particles"), (["--particles", "abc"], "--particles"),
                   (["--particles", "12x"], "--particles"), (["--frames", "-1"], "--frames"),
                   (["--seed", "-3"], "--seed"), (["--mu", "abc"], "--mu"), (["--mu", "-0.5"], "--mu"),
                   (["--compression-speed", "0"], "--compression-speed"), (["--box", "nan"], "--box"),
                   (["--rho-initial", "1.5"], "--rho-initial"), (["--integrator", "euler"], "--integrator"),
                   (["--run-id", "bad id/x"], "--run-id"), (["--run-id", "x" * 65], "--run-id"),
                   (["--run-id", ""], "--run-id"), (["--threads", "-1"], "--threads"),
                   (["--ensemble", "bad name"], "--ensemble"), (["--ensemble", "e" * 63], "--ensemble"),
                   (["--rho-initial", "0.7", "--rho-final", "0.7"], "--rho-final"),
                   (["--rho-final", "0.5"], "--rho-final"),
                   (["--particles", "300", "--box", "19", "--rho-final", "0.6"], "--rho-final"),
                   (["--particles", "300", "--rho-initial", "0.85"], "--rho-initial"),
                   (["--particles", "300", "stray"], "unexpected argument 'stray'")]:
    res = run(*args, "--no-dds", "--quiet", "--export-csv", out_dir, timeout=20)
    wrote = os.path.exists(out_dir)
    shutil.rmtree(out_dir, ignore_errors=True)
    check(res.returncode == 2 and flag in res.stderr and not wrote,
          f"{' '.join(args)}: exit 2 naming {flag} before any work (rc {res.returncode}: {res.stderr.strip()})")

# --rho-initial sizes the box; --box overrides it.
p = show("--particles", "300")
if p:
    check(abs(p["derived"]["rho_initial"] - 0.63) < 1e-9 and p["params"]["rho_initial"] == 0.63,
          f"--particles 300 starts at rho 0.63 by default (rho {p['derived']['rho_initial']}, box {p['params']['box']})")
p = show("--particles", "300", "--rho-initial", "0.55")
if p:
    check(abs(p["derived"]["rho_initial"] - 0.55) < 1e-9, f"--rho-initial 0.55 gives rho {p['derived']['rho_initial']}")
p = show("--particles", "300", "--box", "30")
if p:
    check(p["params"]["box"] == 30 and abs(p["params"]["rho_initial"] - p["derived"]["rho_initial"]) < 1e-12,
          f"--box 30 overrides the start's density (box {p['params']['box']}, rho {p['derived']['rho_initial']})")

# The help shows every parameter as a flag, with the code's default.
help_text = run("--help").stdout
p = show()
if p:
    for key, value in p["params"].items():
        if key == "box":
            continue  # its default is 'sized by rho_initial'
        flag = "--" + key.replace("_", "-")
        shown = f"{value:g}" if isinstance(value, float) else str(value)
        m = re.search(re.escape(flag) + r" arg\s+[^(]*(?:\([^d][^)]*\)[^(]*)*\(default ([^)]*)\)", help_text)
        got = m.group(1) if m else None
        same = got is not None and (got == value if isinstance(value, str) else float(got) == float(value))
        check(same, f"--help lists {flag} with the default {value} (shows {got})")
    check("sized by rho_initial" in " ".join(help_text.split()), "--help says the box is sized by rho_initial by default")

# --show-params output loads back with --config, and gives the same parameters.
p = show("--particles", "500", "--mu", "0", "--seed", "4")
if p:
    config = os.path.join(work, "shown.json")
    with open(config, "w") as f:
        json.dump(p["params"], f)
    q = show("--config", config)
    check(q == p, "--show-params output, given back as --config, gives the same parameters")

# Parameters as an earlier fnet-simd wrote them (checkpoints carry them): every key it knew,
# the box always given.
old = {"particles": 2000, "polydispersity": 0.4, "mu": 0.5, "kn": 4000.0, "en": 0.5, "kt_ratio": 0.8,
       "compression_speed": 2.5e-05, "dt_divisor": 50.0, "rho_final": 0.9, "frames": 100, "seed": 1, "box": 50.0,
       "wall_diameter": 1.0, "initial_speed": 0.1, "relax_energy": 1e-07, "relax_max_time": 200000.0, "skin": 0.15,
       "integrator": "gear"}
config = os.path.join(work, "old.json")
with open(config, "w") as f:
    json.dump(old, f)
q = show("--config", config)
if q:
    check(all(q["params"][k] == v for k, v in old.items()), "an earlier version's parameters load unchanged")
bad = os.path.join(work, "bad.json")
with open(bad, "w") as f:
    json.dump({"particles": -5}, f)
res = run("--config", bad, "--show-params")
check(res.returncode == 2 and "particles" in res.stderr, f"a config with particles -5: exit 2 ({res.stderr.strip()})")

# The relaxation is reported; one ended by the cap is warned about, also with --quiet.
small = ["--particles", "100", "--compression-speed", "1e-2", "--frames", "2", "--rho-final", "0.66", "--no-dds"]
res = run(*small, "--quiet")
m = re.search(r"relaxed in (\d+) steps: translational kinetic energy per grain (\S+) < (\S+)", res.stderr)
check(res.returncode == 0 and m is not None and float(m.group(2)) < float(m.group(3)) == 1e-12,
      f"the relaxation is reported ({m.group(0) if m else res.stderr.strip()})")
# The demo's 400 disks (it relaxed for its whole cap of 10 000 000 steps before): at rest well within.
res = run("--particles", "400", "--compression-speed", "5e-4", "--frames", "2", "--rho-final", "0.64", "--no-dds",
          timeout=60)
m = re.search(r"relaxed in (\d+) steps", res.stderr)
check(res.returncode == 0 and m is not None and int(m.group(1)) < 200000,
      f"the demo's 400 disks relax in under 200 000 steps ({m.group(0) if m else res.stderr.strip()})")
res = run(*small, "--quiet", "--relax-max-time", "2")
check(res.returncode == 0 and "warning: relaxation stopped by --relax-max-time after 100 steps" in res.stderr,
      f"a relaxation ended by --relax-max-time is warned about ({res.stderr.strip()})")

# Frames only DDS carries, with no subscriber: lost, exit 3 naming the domain. With --out: no warning.
env = dict(os.environ, CYCLONEDDS_URI="file://" + os.path.abspath(dds_xml))
domain = str(random.Random(os.getpid()).randrange(100, 200))  # a domain no other test uses
dds_run = ["--particles", "100", "--compression-speed", "1e-2", "--frames", "3", "--rho-final", "0.66", "--quiet",
           "--domain", domain, "--ack-timeout", "1"]
res = run(*dds_run, env=env)
check(res.returncode == 3 and "warning: no DDS subscriber matched on domain " + domain in res.stderr
      and "error: no DDS subscriber matched on domain " + domain in res.stderr and "frames were lost" in res.stderr,
      f"frames published to no subscriber: exit 3 naming domain {domain} (rc {res.returncode}: {res.stderr.strip()})")
res = run(*dds_run, "--out", os.path.join(work, "run.h5"), env=env)
check(res.returncode == 0 and "no DDS subscriber" not in res.stderr,
      f"no such warning with --out (rc {res.returncode}: {res.stderr.strip()})")

# --version: the version of CMake's project and a commit; a CSV export's provenance.json names the
# same build, the date and the run's parameters.
res = run("--version")
m = re.fullmatch(r"fnet-simd (\d+\.\d+\.\d+) \(commit ([0-9a-f]{40}(-dirty)?|unknown)\)\n", res.stdout)
check(res.returncode == 0 and m is not None, f"--version prints the version and commit ({res.stdout!r})")
csv_dir = os.path.join(work, "csv-provenance")
res = run("--particles", "50", "--compression-speed", "1e-2", "--frames", "2", "--rho-final", "0.66", "--quiet",
          "--no-dds", "--seed", "5", "--export-csv", csv_dir)
try:
    prov = json.load(open(os.path.join(csv_dir, "provenance.json")))
    ok = (m is not None and prov["fnet_version"] == m.group(1) and prov["fnet_commit"] == m.group(2)
          and re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", prov["created"]) is not None
          and prov["run"]["seed"] == 5 and prov["run"]["particles"] == 50)
except (OSError, ValueError, KeyError) as e:
    ok, prov = False, e
check(res.returncode == 0 and ok, f"--export-csv writes provenance.json with the build and the run ({prov})")

# The run file is readable while fnet-simd writes it (SWMR, as proto/run_file.md says).
try:
    import h5py
except ImportError:
    h5py = None
    check(False, "h5py is installed (python3-h5py)")
if h5py:
    run_file = os.path.join(work, "live.h5")
    proc = subprocess.Popen([simd, "--particles", "200", "--compression-speed", "1e-4", "--frames", "40", "--no-dds",
                             "--quiet", "--out", run_file], stderr=subprocess.PIPE, text=True)
    seen, error = 0, None
    while proc.poll() is None and seen < 3:
        try:
            with h5py.File(run_file, "r", libver="latest", swmr=True) as f:
                frames = list(f["frame"][:])
                if frames:
                    p0, p1 = f["offsets"][len(frames) - 1][:2]
                    assert frames == list(range(len(frames))) and p1 - p0 == 200, (frames, p0, p1)
                seen = len(frames)
        except (OSError, KeyError) as e:  # not created yet, or not readable while written
            error = str(e)
        time.sleep(0.05)
    live = proc.poll() is None
    proc.terminate()  # stops at the next 1024 steps and closes the file
    _, err = proc.communicate(timeout=300)
    check(live and seen >= 3, f"h5py reads the run file while fnet-simd writes it ({seen} frames seen live; {error})")
    with h5py.File(run_file, "r", libver="latest", swmr=True) as f:
        frames = list(f["frame"][:])
        check(len(frames) >= seen and frames == list(range(len(frames))),
              f"the stopped run's file holds every frame written ({len(frames)}; {err.strip()})")

print(f"{len(failures)} failed" if failures else "all passed")
sys.exit(1 if failures else 0)
