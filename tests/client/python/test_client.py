"""fnet.Client against a real fnet-server holding the LAMMPS frames of tests/data (published on DDS
by fnet-analyze): every array it returns is what the server answered (raw JSON through call()) and
what the server stored (its HDF5 store, read with fnet.store)."""

import json
import math
import socket
import threading
import time

import numpy as np
import pytest

import fnet
from conftest import LAMMPS_FRAMES, publish_lammps, start_server, wait_for

DOMAIN = 90
RUN = "lammps"
METRICS = ("bottleneck", "wasserstein1", "wasserstein2")


def same(a, b):
    """Equal arrays, NaN equal to NaN."""
    np.testing.assert_array_equal(np.asarray(a), np.asarray(b))


def test_runs_run_and_status(client):
    runs = client.runs()
    assert [r["run"] for r in runs] == [RUN]
    assert runs[0]["frames"] == LAMMPS_FRAMES
    r = client.run(RUN)
    assert r["run"] == RUN and r["parameters"]["run"] == RUN
    assert client.run()["run"] == RUN  # the newest run
    status = client.status()
    assert status["frames"]["analyzed"] == LAMMPS_FRAMES and status["ingest"] == "running"


@pytest.mark.parametrize("metric", METRICS)
@pytest.mark.parametrize("dim", (0, 1))
@pytest.mark.parametrize("force", ("normal", "tangential"))
def test_series_are_the_served_arrays_and_the_stored_ones(client, server, metric, dim, force):
    s = client.series(metric, run=RUN, dim=dim, force=force)
    raw = client.call("series.get", {"run": RUN, "metric": metric, "dim": dim, "force": force})
    assert s.frame.dtype == np.int64 and s.value.dtype == np.float64
    same(s.frame, raw["frame"])
    same(s.step, raw["step"])
    same(s.rho, raw["rho"])
    same(s.z, raw["z"])
    same(s.time, raw["time"])
    assert raw["value"][0] is None and math.isnan(s.value[0]) and s.previous[0] == -1
    same(s.value[1:], raw["value"][1:])
    same(s.previous[1:], raw["previous"][1:])
    assert not s.infinite.any()
    assert (s.metric, s.dim, s.force, s.essential) == (metric, dim, force, "floor")
    with fnet.store.open_store(server.store_path(RUN)) as st:  # the server holds it open: SWMR
        stored = st.series(metric, dim=dim, force=force)
    for key in ("frame", "step", "time", "rho", "z", "previous", "value"):
        same(s[key], stored[key])


def test_infinite_distances_are_inf(client):
    # PD1 of these frames has classes that never die, in different numbers from frame to frame.
    s = client.series("wasserstein", q=3, run=RUN, dim=1, essential="separate", from_=1)
    raw = client.call("series.get", {"run": RUN, "metric": "wasserstein", "q": 3, "dim": 1, "essential": "separate",
                                     "from": 1})
    assert "infinite" in raw and any(raw["infinite"])
    same(s.infinite, raw["infinite"])
    assert np.all(np.isposinf(s.value[s.infinite]))
    assert s.frame[0] == 1 and s.q == 3


def test_from_and_to_select_frames(client):
    s = client.series("bottleneck", run=RUN, from_=3, to=5)
    same(s.frame, [3, 4, 5])


def test_diagrams_are_the_served_and_stored_points(client, server):
    with fnet.store.open_store(server.store_path(RUN)) as st:
        for frame in (0, 5, 10):
            for dim in (0, 1):
                for force in ("normal", "tangential"):
                    d = client.diagram(frame, run=RUN, dim=dim, force=force)
                    raw = client.call("diagram.get", {"run": RUN, "frame": frame, "dim": dim, "force": force})
                    assert d.shape == (len(raw["points"]), 2)
                    same(d, np.array(raw["points"]).reshape(-1, 2))
                    same(d, st.diagram(frame, dim=dim, force=force))


def test_distance_between_consecutive_frames_is_the_series_value(client):
    s = client.series("wasserstein2", run=RUN, dim=1)
    for k in (1, 6, 10):
        d = client.distance(int(s.previous[k]), int(s.frame[k]), "wasserstein2", run=RUN, dim=1)
        assert d.value == s.value[k] and d.exact
    inf = client.distance(0, 2, "bottleneck", run=RUN, essential="separate")
    assert inf.infinite and inf.value == math.inf and inf.lower == math.inf


def test_server_errors_are_rpc_errors(client):
    with pytest.raises(fnet.RpcError) as e:
        client.series("bottleneck", run="nope")
    assert e.value.code == -32001 and e.value.data == {"run": "nope", "close": []}
    with pytest.raises(fnet.RpcError) as e:
        client.series("bottleneck", run=RUN, dim=2)
    assert e.value.code == -32602 and e.value.data["parameter"] == "dim"
    with pytest.raises(fnet.RpcError) as e:
        client.diagram(99, run=RUN)
    assert e.value.code == -32002 and e.value.data["frame"] == 99
    with pytest.raises(fnet.RpcError) as e:
        client.call("series.get", {"run": RUN, "metric": "bottleneck", "dimension": 1})
    assert e.value.data["parameter"] == "dimension"
    assert client.runs()[0]["run"] == RUN  # the connection survives an error answer


def test_client_reads_host_and_port_from_the_environment(server, monkeypatch):
    monkeypatch.setenv("FNET_PORT", str(server.port))
    monkeypatch.setenv("FNET_HOST", "127.0.0.1")
    with fnet.Client() as c:
        assert c.port == server.port and c.runs()[0]["run"] == RUN
    assert fnet.Client(port=1).port == 1


def test_unreachable_server_raises_connection_error():
    with pytest.raises(ConnectionError):
        fnet.Client("127.0.0.1", 1).runs()


def test_subscription_is_an_iterator_that_unsubscribes_on_exit(client):
    stored = client.series("bottleneck", run=RUN, dim=1)
    with client.subscribe(run=RUN, since=7) as sub:
        assert sub.reply == {"subscription": sub.id, "run": RUN}
        points = [next(sub) for _ in range(3)]
        assert client.status()["subscriptions"] == 1
    assert sub.unsubscribed == sub.id
    assert [p.frame for p in points] == [8, 9, 10]
    for p in points:
        k = int(np.flatnonzero(stored.frame == p.frame)[0])
        assert p.rho == stored.rho[k] and p.previous == stored.previous[k]
        assert p.distances["bottleneck/pd1/normal"] == stored.value[k]
    wait_for(lambda: client.status()["subscriptions"] == 0, "the subscription to end")
    with pytest.raises(StopIteration):
        next(sub)


def test_subscription_of_every_run_sends_every_frame_in_order(client):
    with client.subscribe() as sub:
        assert sub.reply["run"] is None
        frames = [next(sub).frame for _ in range(LAMMPS_FRAMES)]
        assert sub.next(timeout=0.5) is None  # nothing more until a new frame
    assert frames == list(range(LAMMPS_FRAMES)) and sub.unsubscribed == sub.id


def test_subscribe_waits_for_a_run_not_yet_announced(client, server, processes):
    assert "late" not in [r["run"] for r in client.runs()]
    got = {}

    def subscriber():  # waits for the run on a connection of its own
        try:
            with fnet.Client("127.0.0.1", server.port) as c, c.subscribe(run="late", wait=240) as sub:
                got["points"] = [next(sub) for _ in range(3)]
        except BaseException as e:  # noqa: BLE001 -- handed to the test's thread
            got["error"] = e

    waiting = threading.Thread(target=subscriber)
    waiting.start()
    time.sleep(2.0)
    assert waiting.is_alive() and not got  # the run is not there: the subscription waits
    publish_lammps(processes, "late", DOMAIN)  # from this thread: the publisher dies with its starter
    waiting.join(300)
    assert "error" not in got, got.get("error")
    points = got["points"]
    assert [p.frame for p in points] == [0, 1, 2] and all(p.run == "late" for p in points)
    stored = client.series("bottleneck", run="late", dim=1)
    assert [p.rho for p in points] == list(stored.rho[:3])


def test_unknown_run_of_a_subscription_names_the_close_runs(client):
    with pytest.raises(fnet.RpcError) as e:
        client.subscribe(run="lamps")
    assert e.value.code == -32001 and e.value.data == {"run": "lamps", "close": [RUN]}
    assert e.value.message == "unknown run 'lamps'; close: lammps"
    began = time.monotonic()
    with pytest.raises(fnet.RpcError) as e:
        client.subscribe(run="zzz", wait=1.5)
    assert 1.5 <= time.monotonic() - began < 30
    assert e.value.code == -32001 and e.value.data == {"run": "zzz", "close": []}  # nothing close: the server's error
    assert client.status()["subscriptions"] == 0


def test_a_client_goes_on_after_the_server_closed_its_idle_connection(processes):
    idle = start_server(processes, DOMAIN, name="idle", options=["--idle-timeout", "0.5"])
    # The server closes an idle connection, saying why in its last line.
    with socket.create_connection(("127.0.0.1", idle.port), timeout=10) as raw:
        raw.sendall(b'{"jsonrpc":"2.0","id":1,"method":"runs.list"}\n')
        received = b""
        while chunk := raw.recv(65536):
            received += chunk
    last = json.loads(received.splitlines()[-1])
    assert last["id"] is None and last["error"]["code"] == fnet.rpc.LIMIT_EXCEEDED
    assert last["error"]["data"]["limit"] == "idle_timeout"
    # A Client left idle as long reconnects on its next call.
    with idle.client() as c:
        first = c.status()["uptime_seconds"]
        time.sleep(1.5)
        assert c.status()["uptime_seconds"] > first
