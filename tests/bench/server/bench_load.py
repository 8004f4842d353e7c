#!/usr/bin/env python3
"""fnet-server under load: many clients mixing the methods and subscriptions while runs stream.

usage: bench_load.py BUILD_DIR [--clients 500] [--subscribers 100] [--runs 4] [--frames 40]
                     [--particles 2000] [--rate 2] [--domain 217] [--check]

fnet-simd records one compression of PARTICLES disks (--no-dds, CSV export); RUNS publishers
(fnet-analyze publish --rate RATE) replay it onto DDS as RUNS runs streaming at once to a fresh
fnet-server. Meanwhile CLIENTS connections are open: SUBSCRIBERS of them subscribe (half to one
run, half to every run) and read every point; the others loop over runs.list, run.get, series.get,
diagram.get, distance.get and server.status until the runs end. Printed: per method, calls, p50,
p99 and max round trip (ms) and errors, as those clients measured them (one asyncio loop holding
every connection: its own backlog counts in its round trips), and as one more client in a process
of its own measured them (the probe: the cheap methods in turn, one at a time, every 20 ms); the
server's peak RSS; whether every subscriber got every frame of its runs once, in order. --check:
exit 1 unless every subscriber did and no call failed.
"""
import argparse, asyncio, json, os, re, shutil, statistics, subprocess, sys, tempfile, time

from fnet_service import DDS_ENV as env, Binaries, record_compression

p = argparse.ArgumentParser()
p.add_argument("build")
p.add_argument("--clients", type=int, default=500)
p.add_argument("--subscribers", type=int, default=100)
p.add_argument("--runs", type=int, default=4)
p.add_argument("--frames", type=int, default=40)
p.add_argument("--particles", type=int, default=2000)
p.add_argument("--rate", type=float, default=2)
p.add_argument("--domain", type=int, default=217)
p.add_argument("--check", action="store_true")
p.add_argument("--probe-port", type=int, help=argparse.SUPPRESS)  # the probe's own process
a = p.parse_args()
CHEAP = ("runs.list", "run.get", "series.get", "diagram.get", "server.status")
RUNS = [f"load-{k}" for k in range(a.runs)]


def params_of(method, run):
    return {"runs.list": {}, "server.status": {}, "run.get": {"run": run},
            "series.get": {"run": run, "metric": "wasserstein2"},
            "diagram.get": {"run": run, "frame": 0},
            "distance.get": {"run": run, "frame": 1, "other_frame": 0, "metric": "wasserstein2"}}[method]


def probe(port):
    """Calls the cheap methods in turn on one blocking connection until stdin closes; prints the
    round trips (ms) per method as one JSON line."""
    import selectors, socket
    latencies = {m: [] for m in CHEAP}
    with socket.create_connection(("127.0.0.1", port)) as sock:
        stream = sock.makefile("rwb")
        stdin = selectors.DefaultSelector()
        stdin.register(sys.stdin, selectors.EVENT_READ)
        k = 0
        while not stdin.select(timeout=0.02):
            method = CHEAP[k % len(CHEAP)]
            request = {"jsonrpc": "2.0", "id": k, "method": method, "params": params_of(method, RUNS[k % len(RUNS)])}
            t = time.perf_counter()
            stream.write((json.dumps(request) + "\n").encode())
            stream.flush()
            answer = json.loads(stream.readline())
            if "result" in answer:
                latencies[method].append(1e3 * (time.perf_counter() - t))
            k += 1
    print(json.dumps(latencies))


if a.probe_port:
    probe(a.probe_port)
    sys.exit(0)

bins = Binaries(a.build)
work = tempfile.mkdtemp(prefix="fnet-bench-load-")


class Connection:
    """One JSON-RPC connection: calls matched by id, notifications handed to `on_point`."""

    def __init__(self, reader, writer, on_point=None):
        self.reader, self.writer, self.on_point = reader, writer, on_point
        self.next_id, self.waiting = 1, {}
        self.task = asyncio.ensure_future(self.read())

    @classmethod
    async def open(cls, port, on_point=None):
        reader, writer = await asyncio.open_connection("127.0.0.1", port, limit=1 << 24)
        return cls(reader, writer, on_point)

    async def read(self):
        while line := await self.reader.readline():
            m = json.loads(line)
            if "id" not in m:
                if self.on_point:
                    self.on_point(m)
            elif m["id"] in self.waiting:
                self.waiting.pop(m["id"]).set_result(m)
        for f in self.waiting.values():
            f.set_exception(ConnectionError("closed"))

    async def call(self, method, params=None):
        request_id, self.next_id = self.next_id, self.next_id + 1
        future = asyncio.get_running_loop().create_future()
        self.waiting[request_id] = future
        self.writer.write((json.dumps({"jsonrpc": "2.0", "id": request_id, "method": method,
                                       "params": params or {}}) + "\n").encode())
        await self.writer.drain()
        return await future


def peak_rss_mb(pid):
    with open(f"/proc/{pid}/status") as f:
        return int(re.search(r"VmHWM:\s+(\d+)", f.read()).group(1)) / 1024


async def main(port, server_pid):
    latencies = {m: [] for m in (*CHEAP, "distance.get")}
    errors = {m: 0 for m in latencies}
    points = [dict() for _ in range(a.subscribers)]  # per subscriber: run -> frames in arrival order
    done = asyncio.Event()

    def recorder(k):
        def on_point(m):
            if m.get("method") == "series.point":
                points[k].setdefault(m["params"]["run"], []).append(m["params"]["frame"])
        return on_point

    subscribers = []
    for k in range(a.subscribers):
        c = await Connection.open(port, recorder(k))
        params = {"run": RUNS[k % len(RUNS)]} if k % 2 == 0 else {}
        while "error" in await c.call("series.subscribe", params):  # the run exists at its first frame
            await asyncio.sleep(0.2)
        subscribers.append(c)

    async def caller(k):
        c = await Connection.open(port)
        step = 0
        while not done.is_set():
            run = RUNS[(k + step) % len(RUNS)]
            method = (*CHEAP, "distance.get")[step % 6]
            params = params_of(method, run)
            t = time.perf_counter()
            r = await c.call(method, params)
            if "error" in r and r["error"]["code"] not in (-32001, -32002):  # runs and frames not there yet
                errors[method] += 1
            else:
                latencies[method].append(1e3 * (time.perf_counter() - t))
            step += 1
            await asyncio.sleep(0.05)
        c.writer.close()

    callers = [asyncio.ensure_future(caller(k)) for k in range(a.clients - a.subscribers)]
    prober = await asyncio.create_subprocess_exec(sys.executable, __file__, a.build, "--runs", str(a.runs),
                                                  "--probe-port", str(port), stdin=subprocess.PIPE,
                                                  stdout=subprocess.PIPE)
    watcher = await Connection.open(port)
    while True:
        runs = {r["run"]: r for r in (await watcher.call("runs.list"))["result"]["runs"]}
        if all(r in runs and runs[r]["frames"] + runs[r]["rejected"] >= a.frames and runs[r]["pending"] == 0
               for r in RUNS):
            break
        await asyncio.sleep(0.5)
    await asyncio.sleep(2)  # the last points reach every subscriber
    done.set()
    await asyncio.gather(*callers)
    probed = json.loads((await prober.communicate(b""))[0])
    rss = peak_rss_mb(server_pid)

    expected = list(range(a.frames))
    complete = 0
    for k, got in enumerate(points):
        want = [RUNS[k % len(RUNS)]] if k % 2 == 0 else RUNS
        if all(got.get(r) == expected for r in want) and set(got) == set(want):
            complete += 1
    print(f"fnet-server under load: {a.clients} connections ({a.subscribers} subscribers), {a.runs} runs of "
          f"{a.frames} frames of {a.particles} disks streaming at {a.rate} frames/s each; {os.cpu_count()} cores "
          "shared with the clients and the publishers")
    def table(title, latencies, errors):
        print(title)
        print(f"{'method':14s} {'calls':>7s} {'p50 ms':>8s} {'p99 ms':>8s} {'max ms':>8s} {'errors':>7s}")
        for m, lat in latencies.items():
            lat.sort()
            if lat:
                print(f"{m:14s} {len(lat):7d} {statistics.median(lat):8.2f} {lat[int(0.99 * (len(lat) - 1))]:8.2f} "
                      f"{lat[-1]:8.2f} {errors.get(m, 0):7d}")

    table(f"the {a.clients - a.subscribers} calling connections (one asyncio loop):", latencies, errors)
    table("the probe (one more client, a process of its own, one call at a time):", probed, {})
    print(f"server peak RSS: {rss:.1f} MB")
    print(f"subscribers with every frame of their runs, once, in order: {complete} / {a.subscribers}")
    return complete == a.subscribers and not any(errors.values())


ok = False
procs = []
try:
    csv = os.path.join(work, "csv")
    record_compression(bins, csv, a.particles, a.frames)
    server = subprocess.Popen([bins.server, "--data-dir", os.path.join(work, "data"), "--port", "0", "--domain",
                               str(a.domain), "--threads", "2", "--max-connections", str(a.clients + 16)],
                              stdout=subprocess.PIPE, stderr=open(os.path.join(work, "server.log"), "w"), env=env,
                              text=True)
    procs.append(server)
    port = int(re.search(r":(\d+) ", server.stdout.readline()).group(1))
    for run in RUNS:
        procs.append(subprocess.Popen([bins.analyze, "publish", "--csv-dir", csv, "--run-id", run, "--domain",
                                       str(a.domain), "--rate", str(a.rate), "--wait-for-reader", "60"], env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    ok = asyncio.run(main(port, server.pid))
finally:
    for proc in reversed(procs):
        proc.terminate()
        proc.wait()
    shutil.rmtree(work, ignore_errors=True)
sys.exit(0 if ok or not a.check else 1)
