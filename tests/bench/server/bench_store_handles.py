"""What finished runs cost fnet-server: its open file descriptors and resident memory after each
of RUNS runs of FRAMES LAMMPS frames (tests/data), published one after another by fnet-analyze
publish and waited for, then once more after IDLE seconds without frames.

    python3 tests/bench/server/bench_store_handles.py BUILD_DIR [RUNS] [FRAMES] [IDLE]

Prints one line per tenth of the runs: runs, open fds, fds on stores (*.h5), VmRSS MiB."""
import os, shutil, subprocess, sys, tempfile, time

from fnet_service import DDS_ENV, SOURCE_DIR, Binaries, start_server, stop

DOMAIN = 210  # one of the store-fault domains (CONTRIBUTING.md)


def csv_run(dest, frames):
    src = os.path.join(SOURCE_DIR, "tests", "data", "lammps-mu0.5-seed777")
    os.makedirs(dest)
    for name in os.listdir(src):
        if name.endswith(".csv") and (name == "index.csv" or int(name[6:10]) < frames):
            shutil.copy(os.path.join(src, name), dest)
    rows = open(os.path.join(src, "index.csv")).read().splitlines()
    with open(os.path.join(dest, "index.csv"), "w") as out:
        out.write("\n".join(rows[: frames + 1]) + "\n")
    return dest


def handles(pid):
    fds = os.listdir(f"/proc/{pid}/fd")
    stores = 0
    for fd in fds:
        try:
            stores += os.readlink(f"/proc/{pid}/fd/{fd}").endswith(".h5")
        except OSError:
            pass
    rss = next(int(l.split()[1]) for l in open(f"/proc/{pid}/status") if l.startswith("VmRSS"))
    return len(fds), stores, rss / 1024


def main():
    build = sys.argv[1]
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 40
    frames = int(sys.argv[3]) if len(sys.argv) > 3 else 11
    idle = float(sys.argv[4]) if len(sys.argv) > 4 else 0
    b = Binaries(build)
    tmp = tempfile.mkdtemp()
    try:
        run_dir = csv_run(os.path.join(tmp, "csv"), frames)
        proc, rpc = start_server(b, os.path.join(tmp, "data"), os.path.join(tmp, "server.log"), DOMAIN)
        print(f"{'runs':>5} {'fds':>5} {'on stores':>9} {'RSS MiB':>8}")
        print(f"{0:5d} {handles(proc.pid)[0]:5d} {handles(proc.pid)[1]:9d} {handles(proc.pid)[2]:8.1f}")
        for k in range(1, runs + 1):
            run = f"handles-{k:03d}"
            subprocess.run([b.analyze, "publish", "--csv-dir", run_dir, "--run-id", run, "--domain", str(DOMAIN)],
                           env=DDS_ENV, check=False, stderr=subprocess.DEVNULL)
            while True:
                s = next((r for r in rpc.call("runs.list")["runs"] if r["run"] == run), None)
                if s and s["frames"] + s["rejected"] >= frames and s["pending"] == 0:
                    break
                time.sleep(0.05)
            if k % max(1, runs // 10) == 0:
                fds, stores, rss = handles(proc.pid)
                print(f"{k:5d} {fds:5d} {stores:9d} {rss:8.1f}", flush=True)
        if idle > 0:
            time.sleep(idle)
            fds, stores, rss = handles(proc.pid)
            print(f"idle {idle:g} s: {fds} fds, {stores} on stores, {rss:.1f} MiB")
        stop(proc)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
