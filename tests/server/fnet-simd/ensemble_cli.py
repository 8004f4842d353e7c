#!/usr/bin/env python3
"""fnet-simd --ensemble NAME --seeds S --jobs J as a user runs it, one case per CTest test:

  bad_seeds      bad --seeds specs and conflicting flags exit 2 naming the flag, nothing started
  equals_single  an ensemble of 3 seeds, --jobs 2, writes the same CSV files byte for byte as the
                 same seeds run one at a time as single runs (--seed S --ensemble NAME)
  jobs_limit     no more than --jobs realizations run at once (the parent's children, listed from
                 /proc while it runs), and --jobs of them do run together
  interrupt      SIGINT to the parent mid-ensemble: every running child stops, each leaving its
                 checkpoint, the parent exits 130; the same command resumes the stopped ones, skips
                 the finished ones (and stops on SIGTERM likewise); run to its end, the results
                 equal an uninterrupted ensemble byte for byte
  stop_at_start  SIGINT while the realizations start: each still stops at a checkpoint
  parent_killed  SIGKILL to the parent: its children stop at their checkpoints by themselves
  failure        a realization that fails is named with its exit code, the others finish, exit 1
  server         a real fnet-server receives every realization announced with the ensemble's name

usage: ensemble_cli.py CASE FNET_SIMD WORKDIR CYCLONEDDS_XML [FNET_SERVER]"""
import filecmp
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time

case, simd, work, dds_xml = sys.argv[1:5]
server_exe = sys.argv[5] if len(sys.argv) > 5 else None
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
env = dict(os.environ, CYCLONEDDS_URI="file://" + dds_xml)
failures = []

# Small and quick: 100-150 disks at 20-80x the paper's wall speed.
QUICK = ["--particles", "100", "--box", "11.2", "--compression-speed", "2e-3", "--relax-energy", "1e-5"]
# Long enough (a few seconds each) for a signal to land mid-run.
SLOW = ["--particles", "150", "--box", "13.7", "--compression-speed", "2.5e-4", "--relax-energy", "1e-5",
        "--frames", "10", "--checkpoint-interval", "0.2"]
LINE = re.compile(r"^fnet-simd: \[ *([0-9.]+)s\] (\S+): (.*?)\n?$")


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def finish():
    if failures:
        print(f"{len(failures)} failure(s)")
        sys.exit(1)
    print("all ok")
    sys.exit(0)


def run(*args, timeout=300):
    return subprocess.run([simd, *args], capture_output=True, text=True, timeout=timeout, env=env, cwd=work)


def csv_files(directory):
    return sorted(f for f in os.listdir(directory) if f.endswith(".csv")) if os.path.isdir(directory) else []


def same_csv(a, b):
    names = csv_files(a)
    if names != csv_files(b) or not names:
        return False
    _, mismatch, errors = filecmp.cmpfiles(a, b, names, shallow=False)
    return not mismatch and not errors


def children_of(pid):
    kids = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                stat = f.read()
        except OSError:
            continue
        if int(stat[stat.rindex(")") + 2:].split()[1]) == pid:  # field 4, after "pid (comm) state"
            kids.append(int(entry))
    return kids


def alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().split(")")[-1].split()[0] != "Z"
    except OSError:
        return False


class Ensemble:
    """The parent running in the background; a thread collects its progress lines as they come."""

    def __init__(self, *args):
        self.proc = subprocess.Popen([simd, *args], stderr=subprocess.PIPE, text=True, env=env, cwd=work)
        self.lines = []
        self._reader = threading.Thread(target=lambda: self.lines.extend(self.proc.stderr), daemon=True)
        self._reader.start()

    def wait(self, timeout=300):
        try:
            rc = self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            rc = self.proc.wait()
        self._reader.join(30)
        return rc

    def events(self):
        return [(float(m[1]), m[2], m[3]) for m in map(LINE.match, list(self.lines)) if m]


def started_pids(events):
    return {run: int(re.search(r"pid (\d+)", what)[1]) for _, run, what in events if what.startswith("started")}


if case == "bad_seeds":
    base = ["--no-dds", "--ensemble", "bad", "--export-csv", "never/{run}", *QUICK, "--frames", "6"]
    for args, flag, why in [
            (["--seeds", ""], "--seeds", "empty"), (["--seeds", "5-3"], "--seeds", "reversed"),
            (["--seeds", "1,1"], "--seeds", "seed 1 is listed twice"),
            (["--seeds", "1-3,2"], "--seeds", "seed 2 is listed twice"), (["--seeds", "x"], "--seeds", "'x'"),
            (["--seeds", "1,,2"], "--seeds", "empty item"), (["--seeds", "-3"], "--seeds", "'-3'"),
            (["--seeds", "2-"], "--seeds", "'2-'"), (["--seeds", "1-99999"], "--seeds", "more than"),
            (["--seeds", "1-3", "--seed", "4"], "--seed cannot", "its seed"),
            (["--seeds", "1-3", "--run-id", "x"], "--run-id cannot", "NAME-sSEED"),
            (["--seeds", "1-3", "--resume"], "--resume cannot", "by itself"),
            (["--seeds", "1-3", "--jobs", "0"], "--jobs", "between 1 and"), (["--jobs", "2"], "--jobs", "--seeds")]:
        res = run(*base, *args)
        check(res.returncode == 2 and flag in res.stderr and why in res.stderr and "started (pid" not in res.stderr,
              f"{' '.join(args)!r}: exit 2 naming {flag}, {why!r} ({res.returncode}: {res.stderr.strip()})")
    res = run("--no-dds", *QUICK, "--seeds", "1-3", "--export-csv", "never/{run}")
    check(res.returncode == 2 and "--ensemble" in res.stderr, f"--seeds without --ensemble: {res.stderr.strip()}")
    for flag in ["--out", "--export-csv", "--checkpoint"]:
        res = run("--no-dds", *QUICK, "--ensemble", "bad", "--seeds", "1-3", flag, "shared")
        check(res.returncode == 2 and flag in res.stderr and "{run}" in res.stderr,
              f"{flag} without {{run}} or {{seed}}: exit 2 naming it ({res.stderr.strip()})")
    check(not os.path.exists(os.path.join(work, "never")), "nothing written by a refused command")
    res = run(*QUICK, "--frames", "2", "--no-dds", "--ensemble", "ok", "--seeds", "3,1", "--export-csv", "ok/{seed}")
    check(res.returncode == 0 and sorted(os.listdir(os.path.join(work, "ok"))) == ["1", "3"],
          f"a good list, 3,1, runs those seeds ({res.returncode}: {res.stderr.strip()[-300:]})")
    help_text = run("--help").stdout
    check("--seeds" in help_text and "--jobs" in help_text and "{run}" in help_text, "--help explains ensembles")
    finish()

if case == "equals_single":
    ens = Ensemble(*QUICK, "--frames", "6", "--quiet", "--domain", "79", "--ensemble", "eq", "--seeds", "1-3", "--jobs", "2",
                   "--export-csv", "ens/{run}")
    rc = ens.wait()
    check(rc == 0, f"the ensemble exits 0 ({rc}): {ens.lines[-1:]}")
    for seed in (1, 2, 3):
        res = run(*QUICK, "--frames", "6", "--quiet", "--domain", "79", "--seed", str(seed), "--ensemble", "eq", "--export-csv", f"single/eq-s{seed}")
        check(res.returncode == 0, f"single run of seed {seed} ({res.stderr.strip()[-200:]})")
        a, b = os.path.join(work, "ens", f"eq-s{seed}"), os.path.join(work, "single", f"eq-s{seed}")
        check(len(csv_files(a)) == 1 + 3 * 6 and same_csv(a, b),
              f"realization eq-s{seed} equals the single run of seed {seed} byte for byte ({len(csv_files(a))} files)")
    check(not same_csv(os.path.join(work, "ens", "eq-s1"), os.path.join(work, "ens", "eq-s2")),
          "the realizations differ from each other (each has its own seed)")
    # Its checkpoints hold these parameters: another command over the same files is refused.
    res = run(*QUICK, "--frames", "6", "--mu", "0.3", "--no-dds", "--ensemble", "eq", "--seeds", "1-3",
              "--export-csv", "ens/{run}")
    check(res.returncode == 2 and "mu" in res.stderr and "started (pid" not in res.stderr,
          f"other parameters over its checkpoints: exit 2 naming mu ({res.returncode}: {res.stderr.strip()})")
    finish()

if case == "parent_killed":
    # SIGKILL gives the parent no chance to stop anything: its children stop themselves, cleanly.
    args = [*SLOW, "--no-dds", "--ensemble", "orph", "--seeds", "1-2", "--jobs", "2", "--export-csv", "k/{run}"]
    ens = Ensemble(*args)
    while ens.proc.poll() is None and sum(w.startswith("frame ") for _, _, w in ens.events()) < 2:
        time.sleep(0.01)
    pids = started_pids(ens.events())
    ens.proc.kill()
    ens.wait()
    deadline = time.monotonic() + 60
    while any(alive(p) for p in pids.values()) and time.monotonic() < deadline:
        time.sleep(0.05)
    check(len(pids) == 2 and not any(alive(p) for p in pids.values()), "the children of a killed parent exit")
    for run_id in pids:
        with open(os.path.join(work, "k", run_id, "checkpoint.log")) as f:
            log = f.read()
        check("stopped at step" in log and "frames 10/10" not in log, f"{run_id} stopped mid-run at a checkpoint")
    again = Ensemble(*args)
    check(again.wait() == 0, f"the same command finishes them: {again.lines[-1:]}")
    finish()

if case == "stop_at_start":
    # A stop that lands while the realizations are still starting (before their handlers are set)
    # is kept until they can take it: they stop at a checkpoint rather than die by the signal.
    args = [*SLOW, "--domain", "80", "--ensemble", "early", "--seeds", "1-2", "--jobs", "2", "--export-csv", "e/{run}",
            "--write-lammps-data", "lmp/{run}.data"]
    os.makedirs(os.path.join(work, "lmp"))
    ens = Ensemble(*args)
    while ens.proc.poll() is None and len(started_pids(ens.events())) < 2:
        time.sleep(0.001)
    ens.proc.send_signal(signal.SIGINT)
    rc = ens.wait(120)
    said = {run_id: what for _, run_id, what in ens.events()}
    check(rc == 130, f"exit 130 ({rc}): {ens.lines[-1:]}")
    for run_id in ("early-s1", "early-s2"):
        check(said.get(run_id, "").startswith("stopped (exit 130)"), f"{run_id} stopped cleanly: {said.get(run_id)}")
        check(os.path.exists(os.path.join(work, "e", run_id, "checkpoint.fnetsim")), f"{run_id} left its checkpoint")
    def initial_states():
        return [open(os.path.join(work, "lmp", f"early-s{k}.data"), "rb").read() for k in (1, 2)]

    written = initial_states()
    again = Ensemble(*args)
    check(again.wait() == 0, f"the same command finishes them: {again.lines[-1:]}")
    check(initial_states() == written, "the resumed realizations leave their initial states (--write-lammps-data) as written")
    finish()

if case == "failure":
    # Realization f-s2 cannot create its run file (a folder is in the way): it fails alone.
    os.makedirs(os.path.join(work, "fail", "f-s2.h5"))
    ens = Ensemble(*QUICK, "--frames", "4", "--no-dds", "--ensemble", "f", "--seeds", "1-3", "--jobs", "2",
                   "--out", "fail/{run}.h5")
    rc = ens.wait()
    said = {run_id: what for _, run_id, what in ens.events() if not what.startswith("frame ")}
    check(rc == 1, f"an ensemble with a failed realization exits 1 ({rc})")
    check(said.get("f-s2", "").startswith("failed (exit 1): ") and "f-s2.h5" in said.get("f-s2", ""),
          f"f-s2 failed with its exit code and its error: {said.get('f-s2')}")
    check(said.get("f-s1", "").startswith("finished") and said.get("f-s3", "").startswith("finished"),
          f"the others finished: {said.get('f-s1')}, {said.get('f-s3')}")
    check("failed: f-s2 (exit 1)" in ens.lines[-1], f"the summary names it: {ens.lines[-1].strip()}")
    finish()

if case == "jobs_limit":
    ens = Ensemble(*QUICK, "--frames", "8", "--no-dds", "--ensemble", "lim", "--seeds", "1-5", "--jobs", "2",
                   "--export-csv", "lim/{run}")
    most, seen = 0, set()
    while ens.proc.poll() is None:
        kids = children_of(ens.proc.pid)
        seen.update(kids)
        most = max(most, len(kids))
        time.sleep(0.005)
    rc = ens.wait()
    check(rc == 0, f"the ensemble exits 0 ({rc})")
    check(most == 2, f"at most --jobs 2 children at once, and 2 did run together (seen at most {most})")
    check(len(seen) >= 3, f"the parent's children were observed ({len(seen)} of 5)")
    # The parent's own record agrees: started and ended lines never leave more than 2 running.
    running, most_in_lines = 0, 0
    for _, _, what in ens.events():
        running += what.startswith("started") - what.startswith(("finished", "failed", "stopped"))
        most_in_lines = max(most_in_lines, running)
    check(most_in_lines == 2 and running == 0, f"progress lines show at most 2 running ({most_in_lines})")
    ends = [run for _, run, what in ens.events() if what.startswith("finished")]
    check(sorted(ends) == [f"lim-s{s}" for s in range(1, 6)], f"every realization finished once: {ends}")
    frames = [(run, what) for _, run, what in ens.events() if what.startswith("frame ")]
    check(len(frames) == 5 * 8 and ("lim-s3", "frame 8/8") in frames, f"one line per frame ({len(frames)})")
    finish()

if case == "interrupt":
    args = [*SLOW, "--domain", "78", "--ensemble", "cut", "--seeds", "1-4", "--jobs", "2"]
    # The reference: the same ensemble uninterrupted.
    ref = Ensemble(*args, "--export-csv", "ref/{run}", "--quiet")
    check(ref.wait() == 0, "the uninterrupted ensemble exits 0")
    ens = Ensemble(*args, "--export-csv", "cut/{run}")
    # Interrupt once a realization finished and every running one is mid-run.
    deadline = time.monotonic() + 300
    while ens.proc.poll() is None and time.monotonic() < deadline:
        done, frames = set(), {}
        for _, run_id, what in ens.events():
            if what.startswith("started"):
                frames[run_id] = 0
            elif what.startswith("frame "):
                frames[run_id] = int(what.split()[1].split("/")[0])
            elif what.startswith("finished"):
                done.add(run_id)
                frames.pop(run_id, None)
        if done and frames and all(0 < k < 9 for k in frames.values()):
            break
        time.sleep(0.01)
    ens.proc.send_signal(signal.SIGINT)  # to the parent only: it must stop its children
    rc = ens.wait(120)
    events = ens.events()
    stopped = [run_id for _, run_id, what in events if what.startswith("stopped")]
    finished = [run_id for _, run_id, what in events if what.startswith("finished")]
    check(rc == 130, f"the interrupted parent exits 130 ({rc}): {ens.lines[-1:]}")
    check(stopped and finished, f"the signal landed mid-ensemble: finished {finished}, stopped {stopped}")
    pids = started_pids(events)
    check(all(not alive(pids[r]) for r in pids), "every child has exited")
    for run_id in stopped:
        left = re.search(r"after (\d+) of 10 frames", next(w for _, r, w in events if r == run_id and w.startswith("stopped")))
        check(left and int(left[1]) < 10, f"{run_id} stopped mid-run ({left and left[1]} of 10 frames)")
        check(os.path.exists(os.path.join(work, "cut", run_id, "checkpoint.fnetsim")), f"{run_id} left its checkpoint")
    check(any("not started" in line for line in ens.lines), "the summary counts what was stopped and not started")

    # The same command again, itself stopped by SIGTERM once it made progress; then a third time.
    again = Ensemble(*args, "--export-csv", "cut/{run}")
    while again.proc.poll() is None and not any(w.startswith("frame ") for _, _, w in again.events()):
        time.sleep(0.01)
    again.proc.send_signal(signal.SIGTERM)
    rc = again.wait(120)
    check(rc == 130 and any(w.startswith("stopped") for _, _, w in again.events()),
          f"SIGTERM stops the rerun as SIGINT does: exit 130 ({rc}): {again.lines[-1:]}")
    last = Ensemble(*args, "--export-csv", "cut/{run}")
    rc = last.wait()
    check(rc == 0, f"the same command a third time exits 0 ({rc}): {last.lines[-1:]}")
    said = {run_id: what for _, run_id, what in again.events() if not what.startswith("frame ")}
    for run_id in finished:
        check(said.get(run_id, "").startswith("already finished"), f"{run_id} is not run again: {said.get(run_id)}")
    for run_id in stopped:
        check("resuming from its checkpoint" in " ".join(w for _, r, w in again.events() if r == run_id),
              f"{run_id} resumes from its checkpoint")
    for seed in range(1, 5):
        check(same_csv(os.path.join(work, "ref", f"cut-s{seed}"), os.path.join(work, "cut", f"cut-s{seed}")),
              f"cut-s{seed} equals the uninterrupted ensemble's byte for byte")
    finish()

if case == "server":
    data = os.path.join(work, "data")
    server = subprocess.Popen([server_exe, "--data-dir", data, "--port", "0", "--domain", "77"],
                              stdout=subprocess.PIPE, stderr=open(os.path.join(work, "server.err"), "w"), text=True,
                              env=env)
    try:
        first = server.stdout.readline()
        port = int(re.search(r":(\d+) ", first)[1])
        os.makedirs(os.path.join(work, "runs"))
        ens = Ensemble(*QUICK, "--frames", "4", "--domain", "77", "--ensemble", "srv", "--seeds", "2,5-6", "--jobs", "2",
                       "--out", "runs/{run}.h5")
        check(ens.wait() == 0, f"the ensemble exits 0: {ens.lines[-1:]}")
        with socket.create_connection(("127.0.0.1", port)) as sock:
            reader = sock.makefile("r")

            def call(method, params=None, _id=[0]):
                _id[0] += 1
                sock.sendall((json.dumps({"jsonrpc": "2.0", "id": _id[0], "method": method,
                                          **({"params": params} if params else {})}) + "\n").encode())
                return json.loads(reader.readline())["result"]

            want = {"srv-s2", "srv-s5", "srv-s6"}
            runs = {}
            deadline = time.monotonic() + 120
            while time.monotonic() < deadline:
                runs = {r["run"]: r for r in call("runs.list")["runs"]}
                if want <= runs.keys() and all(runs[r]["frames"] == 4 for r in want):
                    break
                time.sleep(0.1)
            check(set(runs) == want, f"the server lists the three realizations: {sorted(runs)}")
            for run_id in sorted(want & runs.keys()):
                check(runs[run_id]["frames"] == 4, f"{run_id}: every frame analyzed ({runs[run_id]['frames']})")
                got = call("run.get", {"run": run_id})
                check(got["parameters"]["ensemble"] == "srv", f"{run_id}: announced in ensemble srv ({got['parameters'].get('ensemble')})")
                check(got["parameters"]["seed"] == int(run_id.split("-s")[1]), f"{run_id}: announced with its seed")
    finally:
        server.send_signal(signal.SIGTERM)
        server.wait(30)
    finish()

print(f"unknown case {case}")
sys.exit(2)
