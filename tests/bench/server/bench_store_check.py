"""What checking the stores of its data directory costs fnet-server at start: STORES stores of
FRAMES frames of the 2 000-disk LAMMPS run (its 11 frames repeated), one written by fnet-analyze
store and copied under other run ids; the seconds from the server's start to its first line
(it listens once every store is loaded) and the CPU seconds it and its checks took, REPEAT
times, for this build's fnet-server and, when given, another (BEFORE: one without the check).

    /usr/bin/python3 tests/bench/server/bench_store_check.py BUILD_DIR [STORES] [FRAMES] [REPEAT] [BEFORE]

Needs h5py (Debian's python3-h5py) to rename the copies."""
import json, os, resource, shutil, subprocess, sys, tempfile, time

import h5py

from fnet_service import DDS_ENV, SOURCE_DIR, Binaries

DOMAIN = 221  # one of the damaged-store domains (CONTRIBUTING.md); nothing is published on it


def csv_run(dest, frames):
    src = os.path.join(SOURCE_DIR, "tests", "data", "lammps-mu0.5-seed777")
    rows = open(os.path.join(src, "index.csv")).read().splitlines()[1:]
    os.makedirs(dest)
    with open(os.path.join(dest, "index.csv"), "w") as index:
        index.write("frame,step,rho,Z\n")
        for k in range(frames):
            s = k % len(rows)
            for kind in ("particles", "contacts"):
                shutil.copy(os.path.join(src, f"frame_{s:04d}_{kind}.csv"), os.path.join(dest, f"frame_{k:04d}_{kind}.csv"))
            _, _, rho, z = rows[s].split(",")
            index.write(f"{k},{20000 * k},{rho},{z}\n")
    return dest


def copy_as(store, dest, run):
    shutil.copy(store, dest)
    with h5py.File(dest, "r+") as f:
        f.attrs["run_id"] = run
        announcements = f["announcements"]
        for k in range(announcements.shape[0]):
            info = json.loads(announcements[k].rstrip(b"\0").decode())
            info["run"] = run
            announcements[k] = json.dumps(info, separators=(",", ":")).encode()


def start_to_listen(server, data_dir):
    """Seconds to the server's first line, and CPU seconds of the server and its checks."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    begin = time.monotonic()
    proc = subprocess.Popen([server, "--data-dir", data_dir, "--port", "0", "--domain", str(DOMAIN)],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, env=DDS_ENV, text=True)
    proc.stdout.readline()
    seconds = time.monotonic() - begin
    proc.terminate()
    proc.wait()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return seconds, after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime


def main():
    b = Binaries(sys.argv[1])
    stores = int(sys.argv[2]) if len(sys.argv) > 2 else 100
    frames = int(sys.argv[3]) if len(sys.argv) > 3 else 100
    repeat = int(sys.argv[4]) if len(sys.argv) > 4 else 3
    servers = [("this build", b.server)] + ([("before", os.path.abspath(sys.argv[5]))] if len(sys.argv) > 5 else [])
    tmp = tempfile.mkdtemp()
    try:
        data = os.path.join(tmp, "data")
        subprocess.run([b.analyze, "store", "--csv-dir", csv_run(os.path.join(tmp, "csv"), frames), "--run-id",
                        "check-000", "--data-dir", data], check=True, stdout=subprocess.DEVNULL)
        first = os.path.join(data, "check-000.h5")
        for k in range(1, stores):
            copy_as(first, os.path.join(data, f"check-{k:03d}.h5"), f"check-{k:03d}")
        size = sum(os.path.getsize(os.path.join(data, f)) for f in os.listdir(data)) / 2**20
        print(f"{stores} stores of {frames} frames, {size:.0f} MiB; load average {os.getloadavg()[0]:.1f}")
        print(f"{'server':>12} {'to listen s':>12} {'CPU s':>7}")
        for _ in range(repeat):
            for name, server in servers:
                seconds, cpu = start_to_listen(server, data)
                print(f"{name:>12} {seconds:12.2f} {cpu:7.2f}")
    finally:
        shutil.rmtree(tmp)


if __name__ == "__main__":
    main()
