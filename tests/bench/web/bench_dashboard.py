"""How responsive the dashboard is, in Debian's headless Chromium against a real fnet-server (DDS
domain 47): time to first paint and to a 100-frame 2 000-disk run's curve and network; the time
from a frame's commit (the server's notification to a TCP subscriber) to its point on the curve;
the page's JS heap before and after 1 000 live updates; an ensemble of 20 runs; a frame of 20 000
grains drawn, with the longest task that held the page's main thread (Long Tasks API: > 50 ms).

usage: python3 tests/bench/web/bench_dashboard.py BUILD_DIR [WORK_DIR]
"""

import math
import os
import random
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
sys.path.insert(0, os.path.join(SOURCE_DIR, "tests", "e2e"))
from dashboard_fixture import Api, CommitWatch, Server, browser, close_browser, latencies, wait_until  # noqa: E402

DOMAIN = 47
LAMMPS = os.path.join(SOURCE_DIR, "tests", "data", "lammps-mu0.5-seed777")


def cycled_run(folder, frames):
    """`frames` frames of 2 000 disks: the LAMMPS reference frames in turn, ρ rising from 0.63 to 0.86."""
    os.makedirs(folder)
    rows = open(os.path.join(LAMMPS, "index.csv")).read().split("\n")[1:]
    rows = [r.split(",") for r in rows if r]
    with open(os.path.join(folder, "index.csv"), "w") as index:
        index.write("frame,step,rho,Z\n")
        for k in range(frames):
            src = k % len(rows)
            index.write(f"{k},{k * 1000},{0.63 + 0.23 * k / (frames - 1):.6f},{rows[src][-1]}\n")
            for kind in ("particles", "contacts"):
                shutil.copy(os.path.join(LAMMPS, f"frame_{src:04d}_{kind}.csv"),
                            os.path.join(folder, f"frame_{k:04d}_{kind}.csv"))


def lattice_run(folder, n_rows=125, n_cols=160, frames=2, seed=5):
    """A triangular lattice of n_rows x n_cols grains (20 000), each contact with its right and two
    upper neighbours, forces drawn at random per frame."""
    os.makedirs(folder)
    rng = random.Random(seed)
    h = math.sqrt(3) / 2
    with open(os.path.join(folder, "index.csv"), "w") as index:
        index.write("frame,step,rho,Z\n")
        for f in range(frames):
            index.write(f"{f},{f * 1000},{0.85 + 0.01 * f},5.9\n")
    grain = lambda r, c: r * n_cols + c
    for f in range(frames):
        with open(os.path.join(folder, f"frame_{f:04d}_particles.csv"), "w") as p:
            p.write("id,x,y,r\n")
            for r in range(n_rows):
                for c in range(n_cols):
                    p.write(f"{grain(r, c)},{c + 0.5 * (r % 2):.6f},{r * h:.6f},0.5\n")
        with open(os.path.join(folder, f"frame_{f:04d}_contacts.csv"), "w") as out:
            out.write("i,j,fn,ft\n")
            for r in range(n_rows):
                for c in range(n_cols):
                    near = [(r, c + 1), (r + 1, c - 1 + r % 2), (r + 1, c + r % 2)]
                    for rr, cc in near:
                        if rr < n_rows and 0 <= cc < n_cols:
                            out.write(f"{grain(r, c)},{grain(rr, cc)},{rng.expovariate(1):.6f},"
                                      f"{0.3 * rng.expovariate(1):.6f}\n")


def publish(server, folder, run, log, rate=None, ensemble=None):
    args = [os.path.join(server.build_dir, "bin", "fnet-analyze"), "publish", "--csv-dir", folder, "--run-id", run,
            "--domain", str(DOMAIN), "--wait-for-reader", "30"]
    if rate:
        args += ["--rate", str(rate)]
    if ensemble:
        args += ["--ensemble", ensemble]
    return subprocess.Popen(args, env=server.env, stdout=subprocess.DEVNULL, stderr=open(log, "w"))


def js(driver, expression):
    return driver.execute_script("return " + expression)


def heap(driver):
    driver.execute_script("window.gc && window.gc()")
    return js(driver, "performance.memory.usedJSHeapSize") / 2 ** 20


def open_page(server, fragment):
    driver = browser(1400, 1000)
    driver.get(server.url + fragment)
    return driver


def curve_at(driver, frames, limit=300):
    wait_until(lambda: js(driver, "fnetDashboard.curve().length") >= frames, limit, f"{frames} points")
    drawn = js(driver, "fnetDashboard.runView.drawnAt")
    return (max(drawn.values()) - js(driver, "performance.timeOrigin")) / 1000


def live_latency(server, driver, run, frames, start):
    """Starts the feed with `start()`, then the seconds from each frame's notification on TCP to its
    point on the page's curve."""
    watch = CommitWatch(server.port)
    feed = start()
    wait_until(lambda: js(driver, "fnetDashboard.curve().length") >= frames, 1200, f"{frames} live points", 0.2)
    feed.wait()
    watch.stop()
    return list(latencies(driver, watch.times(run)).values())


def main():
    build = os.path.abspath(sys.argv[1])
    work = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else os.path.join(build, "bench-dashboard"))
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.environ["FNET_CHROMIUM_EXTRA"] = "--enable-precise-memory-info --js-flags=--expose-gc"
    cycled_run(os.path.join(work, "big"), 100)
    lattice_run(os.path.join(work, "huge"))
    server = Server(build, SOURCE_DIR, work, DOMAIN, ["--threads", "2"])
    api = Api(server.port)
    rows = Rows()
    print(f"the dashboard in headless Chromium {chromium_version()}, fnet-server with 2 analysis threads, "
          f"{os.cpu_count()} cores", flush=True)
    try:
        # A 100-frame 2 000-disk run, stored: a fresh page opened on it.
        assert publish(server, os.path.join(work, "big"), "big", os.path.join(work, "big.log")).wait() == 0
        api.wait_for_frames("big", 100)
        d = open_page(server, "#run=big")
        curve_s = curve_at(d, 100)
        fcp = js(d, "performance.getEntriesByType('paint').find(e => e.name === 'first-contentful-paint').startTime")
        wait_until(lambda: js(d, "fnetDashboard.runView.latest.drawnAt"), 60, "the latest network")
        network_s = (js(d, "fnetDashboard.runView.latest.drawnAt") - js(d, "performance.timeOrigin")) / 1000
        draw_ms, fetch_ms = js(d, "fnetDashboard.runView.latest.drawMs"), js(d, "fnetDashboard.runView.latest.fetchMs")
        click_ms = d.execute_async_script(
            "const done = arguments[0], t = performance.now();"
            "fnetDashboard.runView.select(60).then(() => done(performance.now() - t));")
        rows += [("first contentful paint (ms)", f"{fcp:.0f}"),
                 ("100-frame 2000-disk run: curve of 100 points drawn, from navigation (s)", f"{curve_s:.2f}"),
                 ("  its latest network and diagrams drawn, from navigation (s)", f"{network_s:.2f}"),
                 ("  network.get + 2 diagram.get of a 2000-disk frame (ms) / drawing it (ms)",
                  f"{fetch_ms:.0f} / {draw_ms:.1f}"),
                 ("  a point clicked: 2 networks, blocks.get, distance.get explain, drawn (ms)", f"{click_ms:.0f}"),
                 ("  longest main-thread task (ms)", f"{max(js(d, 'fnetDashboard.longTasks') or [0]):.0f}")]

        # The same frames live at 4 per second, the page open on the run before it starts.
        close_browser(d)
        d = open_page(server, "#run=big-live")
        wait_until(lambda: js(d, "fnetDashboard.rpc.open"), 20, "the WebSocket")
        lat = live_latency(server, d, "big-live", 100, lambda: publish(
            server, os.path.join(work, "big"), "big-live", os.path.join(work, "live.log"), rate=4))
        lat.sort()
        rows.append(("live, 2000 disks at 4 frames/s: commit to its point, median / p95 / max (ms), frames",
                     f"{1000 * statistics.median(lat):.1f} / {1000 * lat[int(0.95 * (len(lat) - 1))]:.1f} / "
                     f"{1000 * max(lat):.1f} ({len(lat)} frames)"))
        close_browser(d)

        # 1 000 live updates: the page's heap before and after.
        d = open_page(server, "#run=updates")
        wait_until(lambda: js(d, "fnetDashboard.rpc.open"), 20, "the WebSocket")
        time.sleep(1)
        before = heap(d)
        simd = lambda: server.simd(["--particles", "100", "--frames", "1000", "--compression-speed", "2e-3",
                                    "--rho-final", "0.88", "--run-id", "updates"], os.path.join(work, "updates.log"))
        lat = live_latency(server, d, "updates", 1000, simd)
        time.sleep(2)
        after = heap(d)
        lat.sort()
        rows += [("1000 live updates (100 disks): JS heap before / after (MiB)", f"{before:.1f} / {after:.1f}"),
                 ("  commit to its point, median / p95 / max (ms), frames",
                  f"{1000 * statistics.median(lat):.1f} / {1000 * lat[int(0.95 * (len(lat) - 1))]:.1f} / "
                  f"{1000 * max(lat):.1f} ({len(lat)} frames)"),
                 ("  longest main-thread task (ms)", f"{max(js(d, 'fnetDashboard.longTasks') or [0]):.0f}")]
        close_browser(d)

        # An ensemble of 20 runs of 11 frames of 2 000 disks.
        lammps = os.path.join(work, "lammps11")
        cycled_run(lammps, 11)
        feeds = [publish(server, lammps, f"e20-r{k:02d}", os.path.join(work, f"e20-{k}.log"), ensemble="e20")
                 for k in range(20)]
        for f in feeds:
            assert f.wait() == 0
        for k in range(20):
            api.wait_for_frames(f"e20-r{k:02d}", 11)
        d = open_page(server, "#ensemble=e20")
        wait_until(lambda: js(d, "fnetDashboard.band().length") > 0, 60, "the band")
        shown_s = (time.time() * 1000 - js(d, "performance.timeOrigin")) / 1000
        redraw = sorted(js(d, "fnetDashboard.ensembleView.redrawMs"))
        curve = api.call("ensemble.series", {"ensemble": "e20", "metric": "bottleneck"})
        rows += [(f"ensemble of 20 runs ({len(curve['rho_lo'])} bins): band shown, from navigation (s)",
                  f"{shown_s:.2f}"),
                 ("  a redraw of its two charts, median / max (ms)",
                  f"{statistics.median(redraw):.1f} / {max(redraw):.1f}")]
        close_browser(d)

        # A frame of 20 000 grains.
        assert publish(server, os.path.join(work, "huge"), "huge", os.path.join(work, "huge.log")).wait() == 0
        api.wait_for_frames("huge", 2)
        d = open_page(server, "#run=huge")
        wait_until(lambda: js(d, "fnetDashboard.runView.latest.drawnAt"), 120, "the 20 000-grain network")
        draw_ms, fetch_ms = js(d, "fnetDashboard.runView.latest.drawMs"), js(d, "fnetDashboard.runView.latest.fetchMs")
        contacts = js(d, "fnetDashboard.runView.latest.drawn.net.contacts.length")
        click_ms = d.execute_async_script(
            "const done = arguments[0], t = performance.now();"
            "fnetDashboard.runView.select(1).then(() => done(performance.now() - t));")
        rows += [(f"a frame of 20000 grains, {contacts} contacts: network.get + diagrams (ms) / drawing (ms)",
                  f"{fetch_ms:.0f} / {draw_ms:.0f}"),
                 ("  its change from the previous frame, clicked (ms)", f"{click_ms:.0f}"),
                 ("  longest main-thread task (ms)", f"{max(js(d, 'fnetDashboard.longTasks') or [0]):.0f}")]
        close_browser(d)
    finally:
        server.stop()


class Rows(list):
    """Each figure printed as it is measured, the first column 88 wide."""

    def append(self, row):
        super().append(row)
        print(f"{row[0]:<88}  {row[1]}", flush=True)

    def __iadd__(self, rows):
        for row in rows:
            self.append(row)
        return self


def chromium_version():
    out = subprocess.run(["chromium", "--version"], capture_output=True, text=True).stdout.split()
    return out[1] if len(out) > 1 else "?"


if __name__ == "__main__":
    main()
