"""What the Python client's tests share: real fnet-server, fnet-analyze, fnet-simd and fnetctl
processes (their paths come from CMake in FNET_SERVER, FNET_ANALYZE, FNET_SIMD, FNETCTL), on the
DDS loopback configuration and a DDS domain of each test file's own (its module-level DOMAIN,
90-99), each stopped when its test file is done. The `server` fixture serves the LAMMPS frames of
tests/data on that domain as the file's RUN (a file may define its own `server`)."""

import ctypes
import os
import re
import signal
import struct
import subprocess
import sys
import time
import zlib
from pathlib import Path

import numpy as np
import pytest

SOURCE_DIR = Path(os.environ.get("FNET_SOURCE_DIR", Path(__file__).resolve().parents[3]))
sys.path.insert(0, str(SOURCE_DIR / "client" / "python"))

import fnet  # noqa: E402

LAMMPS = SOURCE_DIR / "tests" / "data" / "lammps-mu0.5-seed777"
LAMMPS_FRAMES = 11


def binary(name):
    path = os.environ.get(name)
    if not path or not os.access(path, os.X_OK):
        pytest.fail(f"{name} must name the built binary (CTest sets it), got {path!r}")
    return path


def dds_environment():
    env = dict(os.environ)
    env["CYCLONEDDS_URI"] = "file://" + str(SOURCE_DIR / "deploy" / "cyclonedds-loopback.xml")
    return env


def _die_with_parent():
    """In the child: SIGTERM when the test process dies, so that a killed pytest (a CTest timeout)
    leaves no server behind."""
    ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


class Process:
    """A child process with stdout readable line by line and stderr in a log file; stop() sends
    SIGTERM, waits, then SIGKILL."""

    def __init__(self, args, log, env=None):
        self.log = Path(log)
        self._err = open(self.log, "ab")
        self.popen = subprocess.Popen([str(a) for a in args], stdout=subprocess.PIPE, stderr=self._err,
                                      env=env or dds_environment(), preexec_fn=_die_with_parent)

    def read_line(self):
        return self.popen.stdout.readline().decode()

    def wait(self, timeout):
        return self.popen.wait(timeout)

    def stop(self, grace=10):
        if self.popen.poll() is None:
            self.popen.send_signal(signal.SIGTERM)
            try:
                self.popen.wait(grace)
            except subprocess.TimeoutExpired:
                self.popen.kill()
                self.popen.wait(30)
        self.popen.stdout.close()
        self._err.close()
        return self.popen.returncode


class Processes:
    """Every process a test file started, stopped at its end (newest first)."""

    def __init__(self, tmp):
        self.tmp = Path(tmp)
        self.started = []

    def start(self, args, log_name, env=None):
        p = Process(args, self.tmp / log_name, env)
        self.started.append(p)
        return p

    def stop_all(self):
        for p in reversed(self.started):
            p.stop()


@pytest.fixture(scope="module")
def processes(tmp_path_factory):
    procs = Processes(tmp_path_factory.mktemp("processes"))
    yield procs
    procs.stop_all()


class Server:
    def __init__(self, process, port, data_dir, domain):
        self.process, self.port, self.data_dir, self.domain = process, port, Path(data_dir), domain

    def client(self):
        return fnet.Client("127.0.0.1", self.port)

    def store_path(self, run):
        return self.data_dir / f"{run}.h5"


def start_server(processes, domain, name="server", data=None, options=()):
    """fnet-server on `domain`, its stores in `data` (default a folder of its own), with `options`."""
    data = data or processes.tmp / f"{name}-data"
    p = processes.start([binary("FNET_SERVER"), "--data-dir", data, "--port", "0", "--domain", domain, "--threads",
                         "2", *options], f"{name}.log")
    line = p.read_line()
    m = re.search(r":(\d+) ", line)
    if not m:
        pytest.fail(f"fnet-server did not start ({line!r}); see {p.log}")
    return Server(p, int(m.group(1)), data, domain)


def publish_lammps(processes, run_id, domain, rate=0):
    """The LAMMPS frames of tests/data, published on DDS by fnet-analyze publish (`rate` frames per
    second; 0: at once)."""
    return processes.start([binary("FNET_ANALYZE"), "publish", "--csv-dir", LAMMPS, "--run-id", run_id, "--domain",
                            domain, "--rate", rate, "--linger", "60", "--wait-for-reader", "60"],
                           f"publish-{run_id}.log")


def simd_args(domain, out=None, frames=8, seed=11, run_id=None, ensemble=None, particles=150, box=13.7):
    """A short, fast compression of fnet-simd: 150 disks at 80x the paper's wall speed."""
    args = [binary("FNET_SIMD"), "--particles", particles, "--box", box, "--compression-speed", "2e-3", "--frames",
            frames, "--seed", seed, "--domain", domain, "--linger", "60", "--quiet"]
    if run_id:
        args += ["--run-id", run_id]
    if ensemble:
        args += ["--ensemble", ensemble]
    if out:
        args += ["--out", out]
    return args


def wait_for(predicate, what, limit=300):
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        if predicate():
            return
        time.sleep(0.1)
    pytest.fail(f"timed out waiting for {what}")


def wait_for_frames(server, run, frames, limit=300):
    """Until `run` has `frames` settled frames and nothing pending; returns its summary."""
    with server.client() as c:
        found = {}

        def settled():
            for r in c.runs():
                if r["run"] == run:
                    found["run"] = r
                    return r["frames"] + r["rejected"] >= frames and r["pending"] == 0
            return False

        wait_for(settled, f"run {run} to reach {frames} frames (see {server.process.log})", limit)
        return found["run"]


def serve_lammps(processes, domain, run):
    """fnet-server on `domain`, the LAMMPS frames of tests/data published to it as run `run` and
    every one of them settled."""
    s = start_server(processes, domain)
    publish_lammps(processes, run, domain)
    wait_for_frames(s, run, LAMMPS_FRAMES)
    return s


@pytest.fixture(scope="module")
def server(request, processes):
    """The test file's server: serve_lammps on its DOMAIN as its RUN (a file may define its own)."""
    return serve_lammps(processes, request.module.DOMAIN, request.module.RUN)


@pytest.fixture()
def client(server):
    with server.client() as c:
        yield c


def wait_for_run_file(path, frames):
    """Until the run file fnet-simd writes holds `frames` frames: the daemon closes it after the
    last one, and until then HDF5 may refuse a reader."""
    def readable():
        try:
            with fnet.store.open_run_file(path) as f:
                return len(f.frames) == frames
        except OSError:
            return False
    wait_for(readable, "the run file")


def simd_run_file(processes, domain, frames):
    """A run file of `frames` frames written by fnet-simd without DDS, as run "net"."""
    out = processes.tmp / "run.h5"
    processes.start(simd_args(domain, out=out, frames=frames, run_id="net") + ["--no-dds"], "simd.log")
    wait_for_run_file(out, frames)
    return out


PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def render(fig, path):
    """Saves the figure as a PNG file at `path` and checks that it is one."""
    fig.savefig(path)
    with open(path, "rb") as f:
        assert f.read(8) == PNG_SIGNATURE


def artists(fig, gid):
    """The artists of the figure's axes whose gid is `gid`."""
    return [a for ax in fig.axes for a in ax.get_children() if a.get_gid() == gid]


def canonical(segments, values):
    """Rows (x0, y0, x1, y1, value) sorted: what was drawn, whatever its order."""
    rows = np.column_stack([np.asarray(segments, dtype=np.float64).reshape(-1, 4), values])
    return rows[np.lexsort(rows.T[::-1])]


def plot(*args, port=None):
    """python3 -m fnet plot with `args`, run to its end; FNET_PORT is `port` (unset by default)."""
    env = dict(os.environ, PYTHONPATH=str(SOURCE_DIR / "client" / "python"))
    env.pop("FNET_PORT", None)
    if port is not None:
        env["FNET_PORT"] = str(port)
    return subprocess.run([sys.executable, "-m", "fnet", "plot", *map(str, args)], capture_output=True, text=True,
                          env=env, timeout=300)


def expect_png(r, path):
    """The command `r` succeeded and `path` is a PNG file."""
    assert r.returncode == 0, r.stderr
    with open(path, "rb") as f:
        assert f.read(8) == PNG_SIGNATURE


def png_text(path):
    """The text chunks (tEXt, iTXt) of a PNG file as a dict, read chunk by chunk."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == PNG_SIGNATURE
    out, at = {}, 8
    while at < len(data):
        (length,), kind = struct.unpack(">I", data[at:at + 4]), data[at + 4:at + 8]
        body = data[at + 8:at + 8 + length]
        assert zlib.crc32(kind + body) == struct.unpack(">I", data[at + 8 + length:at + 12 + length])[0]
        if kind == b"tEXt":
            key, value = body.split(b"\0", 1)
            out[key.decode("latin-1")] = value.decode("latin-1")
        elif kind == b"iTXt":
            key, rest = body.split(b"\0", 1)
            compressed, rest = rest[0], rest[2:]
            _, _, value = rest.split(b"\0", 2)
            out[key.decode("latin-1")] = (zlib.decompress(value) if compressed else value).decode()
        at += 12 + length
    return out
