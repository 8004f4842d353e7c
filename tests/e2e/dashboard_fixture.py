"""What the dashboard's browser tests and benchmark share: fnet-server with its dashboard on ports
it picks, fnet-simd runs and ensembles feeding it over DDS, a JSON-RPC connection to it, and
Debian's headless Chromium driven by Selenium (chromium, chromium-driver, python3-selenium)."""

import json
import os
import shutil
import socket
import subprocess
import tempfile
import threading
import time

# --remote-debugging-pipe: ChromeDriver talks to Chromium over a pipe, not over TCP to "localhost".
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  "--disable-dev-shm-usage", "--remote-debugging-pipe"]


class Server:
    """fnet-server on DDS `domain` with the dashboard on; stopped by stop()."""

    def __init__(self, build_dir, source_dir, work, domain, extra=()):
        self.env = dict(os.environ, CYCLONEDDS_URI=f"file://{source_dir}/deploy/cyclonedds-loopback.xml")
        self.build_dir = build_dir
        self.domain = domain
        self.work = work
        os.makedirs(work, exist_ok=True)
        self.out_path = os.path.join(work, "server.out")
        self.err_path = os.path.join(work, "server.err")
        self.process = subprocess.Popen(
            [os.path.join(build_dir, "bin", "fnet-server"), "--data-dir", os.path.join(work, "data"), "--port", "0",
             "--http-port", "0", "--domain", str(domain), *extra],
            env=self.env, stdout=open(self.out_path, "w"), stderr=open(self.err_path, "w"))
        deadline = time.monotonic() + 60
        while True:
            text = open(self.out_path).read()
            if "dashboard on" in text:
                break
            if self.process.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError("fnet-server did not start: " + open(self.err_path).read())
            time.sleep(0.05)
        self.port = int(text.split("listening on 127.0.0.1:")[1].split()[0])
        self.url = text.split("dashboard on ")[1].split()[0]

    def simd(self, args, log):
        """fnet-simd with `args` on the server's domain, started in the work folder (which holds
        its checkpoints)."""
        return subprocess.Popen([os.path.join(self.build_dir, "bin", "fnet-simd"), "--domain", str(self.domain),
                                 "--quiet", *args], env=self.env, cwd=self.work, stdout=subprocess.DEVNULL,
                                stderr=open(log, "w"))

    def stop(self):
        self.process.terminate()
        try:
            self.process.wait(20)
        except subprocess.TimeoutExpired:
            self.process.kill()


class Api:
    """One TCP connection to the JSON-RPC API; notifications kept with the time they came."""

    def __init__(self, port):
        self.port = port
        self.sock = self.file = None  # connected at the first call: the server closes a silent connection
        self.next_id = 1
        self.notifications = []  # (time.time() when read, message)

    def read(self):
        message = json.loads(self.file.readline())
        if "id" not in message:
            self.notifications.append((time.time(), message))
        return message

    def call(self, method, params=None):
        if self.sock is None:
            self.sock = socket.create_connection(("127.0.0.1", self.port), timeout=120)
            self.file = self.sock.makefile("r")
        request_id = self.next_id
        self.next_id += 1
        self.sock.sendall((json.dumps({"jsonrpc": "2.0", "id": request_id, "method": method,
                                       "params": params or {}}) + "\n").encode())
        while True:
            message = self.read()
            if message.get("id") == request_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message["result"]

    def wait_for_frames(self, run, frames, limit=600):
        deadline = time.monotonic() + limit
        while time.monotonic() < deadline:
            for r in self.call("runs.list")["runs"]:
                if r["run"] == run and r["frames"] + r["rejected"] + r["skipped"] >= frames and r["pending"] == 0:
                    return r
            time.sleep(0.2)
        raise RuntimeError(f"run {run} did not reach {frames} frames")


class CommitWatch:
    """A series.subscribe subscription of every run on a connection of its own, read by a thread:
    when each frame's commit was notified."""

    def __init__(self, port):
        self.api = Api(port)
        self.api.call("series.subscribe", {})
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self):
        while True:
            try:
                self.api.read()
            except (OSError, ValueError):
                return

    def stop(self):
        self.api.sock.close()

    def times(self, run):
        """frame -> time.time() when its series.point notification was read."""
        return {m["params"]["frame"]: t for t, m in list(self.api.notifications)
                if m.get("method") == "series.point" and m["params"]["run"] == run}


def latencies(driver, times):
    """Seconds from each frame's notification (`times`) to the page's drawing of its point, for the
    frames committed once the page had subscribed (those before came with series.get)."""
    drawn = driver.execute_script("return fnetDashboard.runView.drawnAt")
    subscribed = driver.execute_script("return fnetDashboard.runView.subscribedAt") / 1000
    return {f: drawn[str(f)] / 1000 - t for f, t in times.items() if str(f) in drawn and t > subscribed}


def browser(width=1400, height=1000):
    """Headless Chromium with a fresh profile, its console kept (goog:loggingPrefs). ChromeDriver is
    started here and reached at 127.0.0.1: Selenium's own service reaches it by the name localhost,
    which a minimal system without /etc/hosts does not resolve (nor does Chromium's DevTools client,
    hence the pipe)."""
    from selenium import webdriver

    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium") or "/usr/bin/chromium"
    profile = tempfile.mkdtemp(prefix="fnet-chromium-")
    extra = os.environ.get("FNET_CHROMIUM_EXTRA", "").split()  # a benchmark's flags (heap figures)
    for flag in CHROMIUM_FLAGS + extra + [f"--user-data-dir={profile}", f"--window-size={width},{height}"]:
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    port = free_port()
    chromedriver = subprocess.Popen([shutil.which("chromedriver") or "/usr/bin/chromedriver", f"--port={port}"],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_until(lambda: chromedriver.poll() is not None or _connectable(port), 30, "chromedriver to listen")
        if chromedriver.poll() is not None:
            raise RuntimeError(f"chromedriver exited with status {chromedriver.returncode}")
        driver = webdriver.Remote(command_executor=f"http://127.0.0.1:{port}", options=options)
    except BaseException:
        chromedriver.kill()
        chromedriver.wait()
        shutil.rmtree(profile, ignore_errors=True)
        raise
    driver.fnet_profile = profile
    driver.fnet_chromedriver = chromedriver
    return driver


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _connectable(port):
    try:
        socket.create_connection(("127.0.0.1", port), timeout=1).close()
        return True
    except OSError:
        return False


def close_browser(driver):
    try:
        driver.quit()
    finally:
        driver.fnet_chromedriver.terminate()
        try:
            driver.fnet_chromedriver.wait(10)
        except subprocess.TimeoutExpired:
            driver.fnet_chromedriver.kill()
            driver.fnet_chromedriver.wait()
        shutil.rmtree(driver.fnet_profile, ignore_errors=True)


def wait_until(condition, limit, what, step=0.05):
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(step)
    raise AssertionError(f"timed out after {limit} s waiting for {what}")


def console_errors(driver):
    return [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]
