"""One default diagram dimension: every front end, asked without a dim, answers for the one that
proto/api.md documents — fnet-server's JSON-RPC methods, fnetctl's commands, fnet-analyze's
distance and explain, and the Python package (its client, store reader and command line). Against
a real fnet-server holding the LAMMPS frames of tests/data."""

import inspect
import json
import re
import subprocess

import fnet
import fnet.store
from conftest import LAMMPS, SOURCE_DIR, Processes, binary, expect_png, plot, png_text
from fnet import cli

DOMAIN = 99
RUN = "lammps"


def documented_default():
    text = (SOURCE_DIR / "proto" / "api.md").read_text()
    m = re.search(r"^- `dim`: 0 \(components, PD0\) or 1 \(loops, PD1\); default ([01])\.", text, re.M)
    assert m, "proto/api.md states dim's default in its conventions"
    return int(m.group(1))


def run(*args):
    r = subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, f"{args}: {r.stderr}"
    return r.stdout


def server_answers(server):
    asked = {
        "series.get": {"run": RUN, "metric": "bottleneck"},
        "diagram.get": {"run": RUN, "frame": 9},
        "distance.get": {"run": RUN, "frame": 9, "other_frame": 10, "metric": "bottleneck"},
        "blocks.get": {"run": RUN, "frame": 9, "other_frame": 10, "metric": "bottleneck"},
        "ensemble.series": {"run": RUN, "metric": "bottleneck"},
    }
    with server.client() as c:
        return {f"fnet-server {method}": c.call(method, params)["dim"] for method, params in asked.items()}


def fnetctl_answers(server, processes):
    ctl = [binary("FNETCTL"), "--port", server.port]
    out = {}
    for name, args in {"query": ["query", "--run", RUN, "--metric", "bottleneck"],
                       "distance": ["distance", "--run", RUN, "--frame", 9, "--other-frame", 10, "--metric",
                                    "bottleneck"],
                       "blocks": ["blocks", "--run", RUN, "--frame", 9, "--other-frame", 10, "--metric",
                                  "bottleneck"]}.items():
        out[f"fnetctl {name}"] = json.loads(run(*ctl, *args, "--format", "json"))["dim"]
    table = run(*ctl, "diagram", "--run", RUN, "--frame", 9)
    out["fnetctl diagram"] = int(re.search(r"\), PD([01]) of the ", table).group(1))
    watch = processes.start([*ctl, "watch", "--run", RUN, "--plain"], "watch.log")
    try:
        for line in iter(watch.read_line, ""):
            m = re.search(r" wasserstein2/pd([01])/normal ", line)
            if m:
                out["fnetctl watch"] = int(m.group(1))
                break
    finally:
        watch.stop()
    return out


def fnet_analyze_answers(tmp_path):
    analyze = binary("FNET_ANALYZE")
    frames = [(LAMMPS / f"frame_{k:04d}_contacts.csv", LAMMPS / f"frame_{k:04d}_particles.csv") for k in (9, 10)]
    documents = []
    for k, (contacts, particles) in enumerate(frames):
        documents.append(tmp_path / f"frame{k}.json")
        documents[-1].write_text(run(analyze, "diagram", "--contacts", contacts, "--particles", particles))
    distance = json.loads(run(analyze, "distance", *documents, "--metric", "bottleneck"))
    explain = json.loads(run(analyze, "explain", frames[0][0], frames[1][0], "--metric", "bottleneck", "--format",
                             "json"))
    return {"fnet-analyze distance": distance["dim"], "fnet-analyze explain": explain["dim"]}


def python_answers(server, tmp_path):
    out = {"fnet.DEFAULT_DIM": fnet.DEFAULT_DIM}
    for owner in (fnet.Client, fnet.store.Store):
        for name, method in inspect.getmembers(owner, inspect.isfunction):
            if "dim" in inspect.signature(method).parameters:
                out[f"{owner.__name__}.{name} default"] = inspect.signature(method).parameters["dim"].default
    with server.client() as c:
        out["Client.series"] = c.series("bottleneck", run=RUN).dim
        out["Client.distance"] = c.distance(9, 10, "bottleneck", run=RUN).dim
        out["Client.blocks"] = c.blocks(9, 10, run=RUN).dim
        out["Client.ensemble_series"] = c.ensemble_series(run=RUN, metric="bottleneck").dim
    with fnet.store.open_store(server.store_path(RUN)) as st:
        out["store series"] = st.series("bottleneck").dim
    for kind, required in (("distances", ["--metric", "bottleneck"]),
                           ("ensemble", ["--ensemble", "E", "--metric", "bottleneck"]), ("ratio", []),
                           ("blocks", ["--frame", "9", "--other-frame", "10"])):
        args = cli.build_parser().parse_args(["plot", kind, *required, "--out", "x.png"])
        out[f"python3 -m fnet plot {kind}"] = args.dim
    png = tmp_path / "distances.png"
    expect_png(plot("distances", "--run", RUN, "--metric", "bottleneck", "--out", png, port=server.port), png)
    out["python3 -m fnet plot distances (PNG)"] = int(png_text(png)["fnet:dim"])
    return out


def test_every_front_end_defaults_to_the_documented_dim(server, processes: Processes, tmp_path):
    answers = {**server_answers(server), **fnetctl_answers(server, processes), **fnet_analyze_answers(tmp_path),
               **python_answers(server, tmp_path)}
    expected = documented_default()
    assert "fnetctl watch" in answers, "fnetctl watch printed no line of its trend series"
    differ = {who: dim for who, dim in answers.items() if dim != expected}
    assert not differ, f"proto/api.md documents dim {expected}; these answer otherwise: {differ}"
