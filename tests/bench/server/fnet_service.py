"""What the fnet-server benchmarks share: the built binaries, the loopback DDS environment, a
recorded compression, a JSON-RPC client on one connection, and fnet-server started on a port it
picks."""
import json, os, re, socket, subprocess

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
DDS_ENV = dict(os.environ, CYCLONEDDS_URI="file://" + os.path.join(SOURCE_DIR, "deploy", "cyclonedds-loopback.xml"))


class Binaries:
    """fnet-simd, fnet-server and fnet-analyze of the build directory `build`."""

    def __init__(self, build):
        build = os.path.abspath(build)
        self.simd = os.path.join(build, "bin/fnet-simd")
        self.server = os.path.join(build, "bin/fnet-server")
        self.analyze = os.path.join(build, "bin/fnet-analyze")


class Rpc:
    def __init__(self, port):
        self.sock = socket.create_connection(("127.0.0.1", port))
        self.file = self.sock.makefile("rwb")
        self.id = 0

    def call(self, method, params=None):
        self.id += 1
        self.file.write((json.dumps({"jsonrpc": "2.0", "id": self.id, "method": method, "params": params or {}}) + "\n").encode())
        self.file.flush()
        while True:
            msg = json.loads(self.file.readline())
            if msg.get("id") == self.id:
                if "error" in msg:
                    raise RuntimeError(msg["error"])
                return msg["result"]


def record_compression(binaries, csv_dir, particles, frames, speed="1e-3"):
    """One fnet-simd compression of `particles` disks (the box scaled to keep the paper's packing
    fraction), `frames` frames exported as a CSV run folder, no DDS."""
    box = 50 * (particles / 2000) ** 0.5
    subprocess.run([binaries.simd, "--particles", str(particles), "--box", f"{box:.4f}", "--compression-speed",
                    str(speed), "--frames", str(frames), "--seed", "5", "--quiet", "--no-dds", "--export-csv",
                    csv_dir], check=True, env=DDS_ENV)


def start_server(binaries, data_dir, log_path, domain, threads=None):
    """fnet-server on `data_dir` and DDS `domain` (with --threads when given), its stderr in
    `log_path`: the process and a client on the port it picked (its first line names it)."""
    args = [binaries.server, "--data-dir", data_dir, "--port", "0", "--domain", str(domain)]
    if threads is not None:
        args += ["--threads", str(threads)]
    log = open(log_path, "w")
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=log, env=DDS_ENV, text=True)
    return proc, Rpc(int(re.search(r":(\d+) ", proc.stdout.readline()).group(1)))


def stop(proc):
    proc.terminate()
    proc.wait()
