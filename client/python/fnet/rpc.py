"""A JSON-RPC 2.0 client for fnet-server (proto/api.md): newline-delimited JSON over TCP.

Every method returns what the server answered, with the equal-length arrays of a series turned into
numpy arrays: a missing distance (`null`) is NaN, an infinite one (`infinite[k]` true) is +inf.
"""

import collections
import json
import math
import os
import socket
import ssl
import time

import numpy as np

from fnet.arrays import Result, float_array, index_array

DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 7707
DEFAULT_DIM = 1  # the diagram a request means when it names none: proto/api.md's `dim` default
UNKNOWN_RUN = -32001  # proto/api.md's error code of an unknown run
UNAUTHORIZED = -32007  # proto/api.md's error code of a connection that did not present the token
LIMIT_EXCEEDED = -32008  # proto/api.md's error code of a limit passed (data.limit names it)


class RpcError(Exception):
    """An error answer of the server: `code` (proto/api.md's table), `message`, `data`."""

    def __init__(self, code, message, data=None):
        super().__init__(f"{message} (code {code})")
        self.code = code
        self.message = message
        self.data = data


def _params(**given):
    """The named parameters that were given (None: left to the server's default)."""
    return {k: v for k, v in given.items() if v is not None}


_DEFAULT = object()  # a connection's own timeout


def _tls_context(tls):
    """None (plain TCP), or the SSLContext of `tls`: True for the system's trusted authorities."""
    if not tls:
        return None
    return tls if isinstance(tls, ssl.SSLContext) else ssl.create_default_context()


class _Connection:
    """One TCP connection: requests out, lines in; notifications kept until asked for. With a
    `token`, it is presented first (proto/api.md, "Access"); with `tls` (an SSLContext), the
    connection speaks TLS, the server's certificate checked against the host name."""

    def __init__(self, host, port, timeout, token=None, tls=None):
        self._sock = socket.create_connection((host, port), timeout=timeout)
        if tls is not None:
            try:
                self._sock = tls.wrap_socket(self._sock, server_hostname=host)
            except BaseException:
                self._sock.close()
                raise
        self._timeout = timeout
        self._buffer = bytearray()  # kept across a timeout: a line is never lost half read
        self._next_id = 1
        self.notifications = collections.deque()
        if token:
            try:
                self.call("auth", {"token": token})
            except BaseException:
                self.close()
                raise

    def close(self):
        self._sock.close()

    def read_message(self, timeout=_DEFAULT):
        """The next line as JSON; socket.timeout after `timeout` seconds (default: the connection's;
        None: no limit)."""
        self._sock.settimeout(self._timeout if timeout is _DEFAULT else timeout)
        while True:
            end = self._buffer.find(b"\n")
            if end >= 0:
                line = bytes(self._buffer[:end])
                del self._buffer[:end + 1]
                if line.strip():
                    return json.loads(line)
                continue
            chunk = self._sock.recv(1 << 16)
            if not chunk:
                raise ConnectionError("fnet-server closed the connection")
            self._buffer += chunk

    def call(self, method, params=None):
        request_id = self._next_id
        self._next_id += 1
        request = {"jsonrpc": "2.0", "id": request_id, "method": method}
        if params:
            request["params"] = params
        # allow_nan=False: NaN is not JSON; the server would answer a parse error.
        self._sock.settimeout(self._timeout)
        self._sock.sendall(json.dumps(request, allow_nan=False).encode() + b"\n")
        while True:
            message = self.read_message()
            if "id" not in message:  # a notification: a subscription's backlog may come first
                self.notifications.append(message)
                continue
            if message["id"] is None and message.get("error", {}).get("code") == LIMIT_EXCEEDED:
                # The server's last words before it closes the connection (an idle one, say).
                raise ConnectionError(message["error"].get("message", "closed by fnet-server"))
            if message["id"] != request_id:
                raise RpcError(-32603, f"answer to request {message['id']} while waiting for {request_id}", message)
            if "error" in message:
                e = message["error"]
                raise RpcError(e.get("code"), e.get("message"), e.get("data"))
            return message["result"]

    def next_notification(self, timeout=_DEFAULT):
        if self.notifications:
            return self.notifications.popleft()
        message = self.read_message(timeout)
        if "id" in message:
            raise RpcError(-32603, "an answer with no request waiting", message)
        return message


def _series(result):
    """series.get's answer with its arrays as numpy arrays."""
    out = Result(result)
    n = len(result["frame"])
    out["frame"] = index_array(result["frame"])
    out["step"] = np.array(result.get("step", [0] * n), dtype=np.int64)
    out["time"] = float_array(result.get("time", [0.0] * n))
    out["rho"] = float_array(result["rho"])
    out["z"] = float_array(result["z"])
    out["previous"] = index_array(result["previous"])
    out["value"] = float_array(result["value"], result.get("infinite"))
    out["infinite"] = np.isinf(out["value"])
    return out


def _ensemble_series(result):
    """ensemble.series' (or an ensemble.bins notification's) arrays as numpy arrays."""
    out = Result(result)
    for key in ("rho_lo", "rho_hi", "rho", "z"):
        if key in result:
            out[key] = float_array(result[key])
    if "mean" in result:
        out["mean"] = float_array(result["mean"], result.get("infinite"))
        out["infinite"] = np.isinf(out["mean"])
    if "stderr" in result:
        out["stderr"] = float_array(result["stderr"])
    for key in ("n_runs", "n"):
        if key in result:
            out[key] = np.array(result[key], dtype=np.int64)
    return out


_BIN_ARRAYS = ("rho_lo", "rho_hi", "rho", "mean", "stderr", "n_runs", "n", "z", "infinite")


def apply_bins(curve, change):
    """The curve after an ensemble.bins notification: its bins (named by rho_lo) replace or join
    those of `curve`, its `removed` ones are dropped, and its head (runs, ...) is the new one."""
    bins = {lo: {key: curve[key][k] for key in _BIN_ARRAYS} for k, lo in enumerate(curve["rho_lo"])}
    for lo in change.get("removed", []):
        bins.pop(lo, None)
    for k, lo in enumerate(change["rho_lo"]):
        bins[lo] = {key: change[key][k] for key in _BIN_ARRAYS}
    out = Result({k: v for k, v in change.items() if k not in _BIN_ARRAYS + ("removed", "subscription")})
    order = sorted(bins)
    for key, dtype in zip(_BIN_ARRAYS, (float, float, float, float, float, np.int64, np.int64, float, bool)):
        out[key] = np.array([bins[lo][key] for lo in order], dtype=dtype)
    return out


def _blocks(result):
    """blocks.get's cells as k x k arrays indexed [row, col] (row 0: lowest y); for a 3D run
    (dimension 3) k x k x k arrays indexed [layer, row, col] (layer 0: lowest z)."""
    out = Result(result)
    k = result["k"]
    three_d = result.get("dimension", 2) == 3
    shape = (k, k, k) if three_d else (k, k)
    value = np.full(shape, np.nan)
    contacts = np.zeros(shape + (2,), dtype=np.int64)
    points = np.zeros(shape + (2,), dtype=np.int64)
    bounds = np.full(shape + (2, 6 if three_d else 4), np.nan)
    for cell in result["cells"]:
        at = (cell["layer"], cell["row"], cell["col"]) if three_d else (cell["row"], cell["col"])
        value[at] = math.inf if cell.get("infinite") else (np.nan if cell["value"] is None else cell["value"])
        contacts[at] = cell["contacts"]
        points[at] = cell["points"]
        bounds[at] = cell["bounds"]
    out["value"] = value
    out["contacts"] = contacts
    out["points"] = points
    out["bounds"] = bounds
    return out


class Subscription:
    """An iterator over a subscription's notifications, on a connection of its own.

    Iterating waits for the next notification as long as it takes (a live run may be quiet for
    long); next(timeout) waits at most `timeout` seconds and returns None when none came. Leaving a
    with-block, or close(), unsubscribes and closes the connection."""

    def __init__(self, host, port, timeout, method, params, notification, unsubscribe, convert, track=None,
                 token=None, tls=None):
        self._conn = _Connection(host, port, timeout, token, tls)
        self._notification = notification
        self._unsubscribe = unsubscribe
        self._convert = convert
        self._track = track
        try:
            self.reply = self._conn.call(method, params)
        except BaseException:
            self._conn.close()
            raise
        self.id = self.reply["subscription"]
        if track:
            self.reply = convert(self.reply)
            self.curve = self.reply  # the subscribed curve as of the last notification taken
        self.unsubscribed = None  # the server's word that the subscription ended, once closed

    def __iter__(self):
        return self

    def __next__(self):
        if self._conn is None:
            raise StopIteration
        return self.next(None)

    def next(self, timeout=None):
        """The next notification, waiting at most `timeout` seconds (None: no limit); None when
        none came in time."""
        if self._conn is None:
            raise StopIteration
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            left = None if deadline is None else max(deadline - time.monotonic(), 0.001)
            try:
                message = self._conn.next_notification(left)
            except socket.timeout:
                return None
            params = message.get("params", {})
            if message.get("method") == self._notification and params.get("subscription") == self.id:
                point = self._convert(params)
                if self._track:
                    self.curve = self._track(self.curve, point)
                return point

    def close(self):
        if self._conn is None:
            return
        conn, self._conn = self._conn, None
        try:
            self.unsubscribed = conn.call(self._unsubscribe, {"subscription": self.id})["unsubscribed"]
        except (OSError, ConnectionError):
            pass  # the server is gone: the subscription ended with the connection
        finally:
            conn.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class Client:
    """A connection to fnet-server, opened on the first call. Where the server is: `host` and
    `port`, else FNET_HOST and FNET_PORT from the environment (as fnetctl), else 127.0.0.1:7707.
    `token`, else FNET_TOKEN: the token a server started with --token-file asks for, presented
    on each connection before any call. `tls`: True to speak TLS to a server given --tls-cert (its
    certificate verified against the system's authorities), or an ssl.SSLContext (e.g.
    ssl.create_default_context(cafile=...)). Usable as a context manager (closes the connection)."""

    def __init__(self, host=None, port=None, timeout=60.0, token=None, tls=None):
        self.host = host or os.environ.get("FNET_HOST") or DEFAULT_HOST
        self.port = int(port if port is not None else (os.environ.get("FNET_PORT") or DEFAULT_PORT))
        self.timeout = timeout
        self.token = token or os.environ.get("FNET_TOKEN") or None
        self.tls = _tls_context(tls)
        self._conn = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        if self._conn is not None:
            self._conn.close()
            self._conn = None

    def call(self, method, params=None):
        """Any method by name, with its params as a dict; the raw result."""
        reused = self._conn is not None
        if not reused:
            self._conn = _Connection(self.host, self.port, self.timeout, self.token, self.tls)
        try:
            return self._conn.call(method, params)
        except (OSError, ConnectionError):
            self.close()
            if not reused:
                raise
        # The server closes a connection left idle (proto/api.md, Limits): once more, on a new one.
        # Every method a Client calls only reads, so asking twice is safe.
        self._conn = _Connection(self.host, self.port, self.timeout, self.token, self.tls)
        try:
            return self._conn.call(method, params)
        except (OSError, ConnectionError):
            self.close()
            raise

    # -- runs and the server ------------------------------------------------------------------
    def runs(self):
        """runs.list: a list of RunSummary dicts, in name order."""
        return self.call("runs.list")["runs"]

    def run(self, run=None):
        """run.get: the run's summary, parameters and rejected frames."""
        return self.call("run.get", _params(run=run))

    def status(self):
        """server.status."""
        return self.call("server.status")

    # -- series, diagrams, distances ------------------------------------------------------------
    def series(self, metric, run=None, dim=DEFAULT_DIM, force="normal", q=None, essential="floor", ratio=None,
               from_=None, to=None):
        """series.get as numpy arrays: frame, step, time, rho, z, previous (-1: none), value (NaN for
        the first frame, +inf where infinite), infinite (booleans)."""
        return _series(self.call("series.get", _params(metric=metric, run=run, dim=dim, force=force, q=q,
                                                       essential=essential, ratio=ratio, **{"from": from_},
                                                       to=to)))

    def diagram(self, frame, run=None, dim=DEFAULT_DIM, force="normal"):
        """diagram.get's points as an (n, 2) array of birth, death (death -1: never dies)."""
        r = self.call("diagram.get", _params(frame=frame, run=run, dim=dim, force=force))
        return np.array(r["points"], dtype=np.float64).reshape(-1, 2)

    def distance(self, frame, other_frame, metric, run=None, other_run=None, dim=DEFAULT_DIM, force="normal", q=None,
                 essential="floor", delta=None, explain=None):
        """distance.get; `value`, `lower`, `upper` are +inf for an infinite distance."""
        r = Result(self.call("distance.get", _params(frame=frame, other_frame=other_frame, metric=metric, run=run,
                                                     other_run=other_run, dim=dim, force=force, q=q,
                                                     essential=essential, delta=delta, explain=explain)))
        if r.get("infinite"):
            for key in ("value", "lower", "upper"):
                r[key] = math.inf
        return r

    # -- ensembles and blocks -------------------------------------------------------------------
    def ensembles(self):
        """ensembles.list: a list of ensemble dicts, in name order."""
        return self.call("ensembles.list")["ensembles"]

    def ensemble_series(self, ensemble=None, run=None, metric=None, dim=DEFAULT_DIM, force="normal", q=None,
                        essential="floor", bin_width=None, bins=None, axis=None, ratio=None):
        """ensemble.series as numpy arrays per bin: rho_lo, rho_hi, rho, mean (+inf where infinite),
        stderr (NaN where undefined), n_runs, n, z."""
        return _ensemble_series(self.call("ensemble.series", _ensemble_params(**locals())))

    def blocks(self, frame, other_frame, run=None, k=None, metric="bottleneck", dim=DEFAULT_DIM, force="normal", q=None,
               essential="floor"):
        """blocks.get; adds k x k arrays value, contacts, points, bounds indexed [row, col] (k x k x k
        indexed [layer, row, col] for a 3D run)."""
        return _blocks(self.call("blocks.get", _params(run=run, frame=frame, other_frame=other_frame, k=k,
                                                       metric=metric, q=q, dim=dim, force=force,
                                                       essential=essential)))

    # -- subscriptions --------------------------------------------------------------------------
    def subscribe(self, run=None, since=None, wait=None):
        """series.subscribe: an iterator of series.point params (dicts), on its own connection.

        A named `run` that the server does not know yet (fnet-simd may still be relaxing) is waited
        for up to `wait` seconds (math.inf: as long as it takes), asking every half second, as
        `fnetctl watch --run` does; without `wait`, or once it is over, an unknown run raises the
        server's RpcError -32001, whose message and data ("close") name the runs with a close name."""
        deadline = None if wait is None else time.monotonic() + wait
        while run is not None and deadline is not None:
            try:
                self.call("run.get", {"run": run})
                break
            except RpcError as e:
                if e.code != UNKNOWN_RUN or time.monotonic() >= deadline:
                    raise
                time.sleep(max(min(0.5, deadline - time.monotonic()), 0.0))
        return Subscription(self.host, self.port, self.timeout, "series.subscribe", _params(run=run, since=since),
                            "series.point", "series.unsubscribe", Result, token=self.token, tls=self.tls)

    def subscribe_ensemble(self, ensemble=None, run=None, metric=None, dim=DEFAULT_DIM, force="normal", q=None,
                           essential="floor", bin_width=None, bins=None, axis=None, ratio=None):
        """ensemble.subscribe: an iterator of ensemble.bins notifications (the bins that changed)
        with numpy arrays; `reply` is the curve when subscribing and `curve` the curve with every
        notification taken so far applied (apply_bins)."""
        return Subscription(self.host, self.port, self.timeout, "ensemble.subscribe", _ensemble_params(**locals()),
                            "ensemble.bins", "ensemble.unsubscribe", _ensemble_series, apply_bins, token=self.token,
                            tls=self.tls)


def _ensemble_params(self=None, **given):
    return _params(**given)
