"""`python3 -m fnet plot KIND ... --out FILE`: the paper's figures from a running fnet-server
(or from files). Options are named as fnetctl's; exit codes are fnetctl's: 0 ok, 1 failure,
2 usage (naming the bad option), 3 server unreachable, 4 unknown run or frame, 5 server error."""

import argparse
import os
import socket
import sys

from fnet import figures, store
from fnet.rpc import DEFAULT_HOST, DEFAULT_PORT, Client, RpcError

EXIT_OK, EXIT_FAILURE, EXIT_USAGE, EXIT_UNREACHABLE, EXIT_UNKNOWN, EXIT_SERVER = 0, 1, 2, 3, 4, 5
METRICS = ("bottleneck", "wasserstein1", "wasserstein2", "wasserstein")
RATIOS = ("wasserstein1", "wasserstein2")


def _bounded(kind, lo=None, hi=None, what=""):
    def parse(text):
        try:
            v = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}") from None
        if (lo is not None and not v >= lo) or (hi is not None and not v <= hi) or v != v:
            raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}")
        return v
    return parse


FRAME = _bounded(int, 0, 2**32 - 1, "a frame index 0 ... 4294967295")
PORT = _bounded(int, 1, 65535, "a port 1 ... 65535")


def _positive_float(text):
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number > 0, got {text!r}") from None
    if not (v > 0 and v != float("inf")):
        raise argparse.ArgumentTypeError(f"expected a finite number > 0, got {text!r}")
    return v


def _endpoint(parser):
    env_port = os.environ.get("FNET_PORT")
    g = parser.add_argument_group("server")
    g.add_argument("--host", default=os.environ.get("FNET_HOST") or DEFAULT_HOST,
                   help="fnet-server's host (default $FNET_HOST, else 127.0.0.1)")
    g.add_argument("--port", type=PORT, default=PORT(env_port) if env_port else DEFAULT_PORT,
                   help="its port (default $FNET_PORT, else 7707)")


def _distance_options(parser, metric_required=True, forces=False):
    parser.add_argument("--metric", choices=METRICS, required=metric_required, default=None if metric_required
                        else "bottleneck", help="the distance")
    parser.add_argument("--q", type=_bounded(float, 1, None, "a real number >= 1"),
                        help="the exponent of --metric wasserstein")
    parser.add_argument("--dim", type=int, choices=(0, 1), default=0, help="0 (components) or 1 (loops)")
    if forces:
        parser.add_argument("--force", choices=("normal", "tangential"), action="append",
                            help="force network (repeatable: one curve each; default normal)")
    else:
        parser.add_argument("--force", choices=("normal", "tangential"), default="normal", help="force network")
    parser.add_argument("--essential", choices=("floor", "sentinel", "separate"), default="floor",
                        help="how classes that never die are matched")


def _axis(text):
    if text in ("rho", "rho-minus-rho-j", "rho_minus_rho_j"):
        return text.replace("-", "_")
    raise argparse.ArgumentTypeError(f"expected rho or rho-minus-rho-j, got {text!r}")


def _bin_options(parser):
    """As fnetctl's: --bins is a bin width, --bin-count a number of bins."""
    g = parser.add_mutually_exclusive_group()
    g.add_argument("--bins", type=_positive_float, metavar="W",
                   help="bin width in rho of a binned curve (default 0.002 with --ensemble)")
    g.add_argument("--bin-count", type=_bounded(int, 1, None, "an integer >= 1"), metavar="N",
                   help="instead of --bins: this many bins over the samples' range")
    parser.add_argument("--axis", type=_axis, default="rho",
                        help="x of a binned curve: rho, or rho-minus-rho-j (each run's rho - rho_J)")


def _binned(args):
    return bool(getattr(args, "ensemble", None) or args.bins or args.bin_count or args.axis != "rho")


def _out(parser):
    parser.add_argument("--out", required=True, help="the image file (its extension names the format: png, pdf, svg)")


def build_parser():
    parser = argparse.ArgumentParser(prog="python3 -m fnet", description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True, metavar="plot|paper-report")
    plot = commands.add_parser("plot", help="draw one of the paper's figures")
    kinds = plot.add_subparsers(dest="kind", required=True, metavar="KIND")

    p = kinds.add_parser("network", help="Fig. 1: a frame's force network (or the change between two frames)")
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--run-file", help="the run file fnet-simd wrote (--out)")
    source.add_argument("--store", help="an analysis store that keeps the frames' networks (fnet-store-2)")
    p.add_argument("--frame", type=FRAME, required=True, help="the frame")
    p.add_argument("--other-frame", type=FRAME, help="draw the change from --frame to this frame")
    p.add_argument("--force", choices=("normal", "tangential"), default="normal", help="force network")
    _out(p)

    p = kinds.add_parser("diagram", help="Fig. 3: a frame's persistence diagrams PD0 and PD1")
    _endpoint(p)
    p.add_argument("--run", help="run id (default: the newest run)")
    p.add_argument("--store", help="read the diagrams from this analysis store instead of the server")
    p.add_argument("--frame", type=FRAME, required=True, help="the frame")
    p.add_argument("--force", choices=("normal", "tangential"), default="normal", help="force network")
    _out(p)

    p = kinds.add_parser("distances", help="distances against rho with Z; with --ensemble, Figs. 6, 8, 9")
    _endpoint(p)
    who = p.add_mutually_exclusive_group()
    who.add_argument("--run", help="one run's series (default: the newest run); binned with --bins/--bin-count")
    who.add_argument("--ensemble", help="the ensemble's mean ± standard error per bin of rho")
    _distance_options(p)
    _bin_options(p)
    p.add_argument("--from", dest="from_", metavar="FRAME", type=FRAME, help="first frame (a run's series)")
    p.add_argument("--to", metavar="FRAME", type=FRAME, help="last frame (a run's series)")
    _out(p)

    p = kinds.add_parser("ensemble", help="Figs. 6, 8, 9: ensembles' mean ± standard error, one curve per "
                                          "--ensemble and --force")
    _endpoint(p)
    p.add_argument("--ensemble", action="append", required=True, help="an ensemble (repeat to compare)")
    _distance_options(p, forces=True)
    _bin_options(p)
    _out(p)

    p = kinds.add_parser("ratio", help="Figs. 7, 10: d_B / d_W1 and d_B / d_W2 against rho")
    _endpoint(p)
    who = p.add_mutually_exclusive_group()
    who.add_argument("--run", help="one run's ratio per frame (default: the newest run); binned with --bins")
    who.add_argument("--ensemble", help="an ensemble's ratio of bin means")
    p.add_argument("--ratio", choices=RATIOS, action="append", help="d_B / d_Wq (repeatable; default: both)")
    p.add_argument("--dim", type=int, choices=(0, 1), default=0, help="0 (components) or 1 (loops)")
    p.add_argument("--force", choices=("normal", "tangential"), default="normal", help="force network")
    p.add_argument("--essential", choices=("floor", "sentinel", "separate"), default="floor",
                   help="how classes that never die are matched")
    _bin_options(p)
    _out(p)

    p = kinds.add_parser("blocks", help="Tables II, III: distances cell by cell of a k x k grid")
    _endpoint(p)
    p.add_argument("--run", help="run id (default: the newest run)")
    p.add_argument("--frame", type=FRAME, required=True, help="the first frame")
    p.add_argument("--other-frame", type=FRAME, required=True, help="the second frame")
    p.add_argument("--k", type=_bounded(int, 1, 16, "an integer 1 ... 16"), default=2, help="grid of k x k cells")
    _distance_options(p, metric_required=False)
    _out(p)
    parser.kind_parsers = kinds.choices  # for the checks argparse cannot make alone

    p = commands.add_parser("paper-report", help="the paper's Sec. IV from two ensembles: curves.csv, figures, "
                                                 "report.md (what deploy/reproduce-paper.sh writes)")
    _endpoint(p)
    p.add_argument("--ensemble", action="append", required=True, metavar="MU=NAME", type=_mu_ensemble,
                   help="an ensemble and its friction coefficient, e.g. 0.5=mu05 (repeat: 0.5 and 0)")
    p.add_argument("--bins", type=_positive_float, default=0.005, help="rho bin width (default 0.005)")
    p.add_argument("--out", required=True, help="the report folder")
    p.add_argument("--setting", action="append", default=[], metavar="KEY=VALUE",
                   help="a line of the report's Setting section (repeatable)")
    p.add_argument("--compare-start", action="append", default=[], metavar="A=B", type=_ensemble_pair,
                   help="compare two ensembles of the same system from different starts before jamming: "
                        "median PD1 d_B and the share of empty PD1s, with bootstrap intervals (repeatable)")
    parser.report_parser = p
    return parser


def _mu_ensemble(text):
    mu, sep, name = text.partition("=")
    try:
        float(mu)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected MU=NAME with MU a number, got {text!r}") from None
    if not sep or not name:
        raise argparse.ArgumentTypeError(f"expected MU=NAME, got {text!r}")
    return mu, name


def _ensemble_pair(text):
    a, sep, b = text.partition("=")
    if not sep or not a or not b:
        raise argparse.ArgumentTypeError(f"expected ENSEMBLE_A=ENSEMBLE_B, got {text!r}")
    return a, b


def _check(parser, args):
    """What argparse cannot see alone: usage errors exit 2 before any work, naming the option."""
    sub = parser.kind_parsers[args.kind]
    ext = os.path.splitext(args.out)[1].lstrip(".").lower()
    supported = sorted(figures._figure().canvas.get_supported_filetypes())
    if ext not in supported:
        sub.error(f"--out: unknown image format {ext!r} of {args.out!r} (expected one of {', '.join(supported)})")
    metric = getattr(args, "metric", None)
    if getattr(args, "q", None) is not None and metric not in ("wasserstein", "wasserstein1", "wasserstein2"):
        sub.error(f"--q: only with --metric wasserstein, not with --metric {metric}")
    if metric == "wasserstein" and getattr(args, "q", None) is None:
        sub.error("--metric wasserstein needs --q")
    if args.kind == "distances" and _binned(args) and (args.from_ is not None or args.to is not None):
        sub.error("--from/--to select frames of a run's series, not bins (--ensemble, --bins, --bin-count, --axis)")
    if args.kind == "diagram" and args.store and args.run:
        sub.error("--run: not with --store (a store holds one run)")
    for option in ("run_file", "store"):
        path = getattr(args, option, None)
        if path and not os.path.exists(path):
            sub.error(f"--{option.replace('_', '-')}: no such file {path!r}")


def _binning(args):
    return {"bin_width": args.bins, "bins": args.bin_count, "axis": args.axis}


def _distance(args):
    return {"metric": args.metric, "q": args.q, "dim": args.dim, "essential": args.essential}


def _draw(args):
    if args.kind == "network":
        with (store.open_run_file(args.run_file) if args.run_file else store.open_store(args.store)) as f:
            read = f.frame if args.run_file else f.network
            frames = [read(k) for k in (args.frame, args.other_frame) if k is not None]
        if any(frame is None for frame in frames):
            raise KeyError(f"the store {args.store} does not keep the networks of its frames (schema {f.schema})")
        if len(frames) == 1:
            return figures.network(frames[0], force=args.force)
        return figures.network_change(*frames, force=args.force)
    if args.kind == "diagram" and args.store:
        with store.open_store(args.store) as s:
            return figures.diagrams(s.diagram(args.frame, 0, args.force), s.diagram(args.frame, 1, args.force),
                                    title=f"{s.run_id} frame {args.frame}, {args.force} forces")
    with Client(args.host, args.port) as c:
        if args.kind == "diagram":
            d = [c.diagram(args.frame, run=args.run, dim=k, force=args.force) for k in (0, 1)]
            return figures.diagrams(*d, title=f"{args.run or 'newest run'} frame {args.frame}, {args.force} forces")
        if args.kind == "distances" and not _binned(args):
            return figures.distances(c.series(run=args.run, force=args.force, from_=args.from_, to=args.to,
                                              **_distance(args)))
        if args.kind == "distances":
            who = {"ensemble": args.ensemble} if args.ensemble else {"run": args.run or c.run()["run"]}
            return figures.ensemble(c.ensemble_series(**who, force=args.force, **_distance(args), **_binning(args)))
        if args.kind == "ensemble":
            curves = [c.ensemble_series(ensemble=e, force=force, **_distance(args), **_binning(args))
                      for e in args.ensemble for force in (args.force or ["normal"])]
            return figures.ensemble(curves)
        if args.kind == "ratio" and not _binned(args):
            curves = [c.series(None, run=args.run, ratio=r, dim=args.dim, force=args.force, essential=args.essential)
                      for r in (args.ratio or list(RATIOS))]
            return figures.ratio(curves)
        if args.kind == "ratio":
            who = {"ensemble": args.ensemble} if args.ensemble else {"run": args.run or c.run()["run"]}
            curves = [c.ensemble_series(**who, ratio=r, dim=args.dim, force=args.force, essential=args.essential,
                                        **_binning(args))
                      for r in (args.ratio or list(RATIOS))]
            return figures.ratio(curves)
        if args.kind == "blocks":
            return figures.blocks(c.blocks(args.frame, args.other_frame, run=args.run, k=args.k, force=args.force,
                                           **_distance(args)))
    raise AssertionError(args.kind)


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command == "paper-report":
        try:
            from fnet import paper
            return paper.main(args)
        except RpcError as e:
            print(f"python3 -m fnet paper-report: {e.message}", file=sys.stderr)
            return EXIT_UNKNOWN if e.code in (-32001, -32002, -32006) else EXIT_SERVER
        except (ConnectionError, socket.timeout, socket.gaierror) as e:
            print(f"python3 -m fnet: cannot reach fnet-server at {args.host}:{args.port}: {e}", file=sys.stderr)
            return EXIT_UNREACHABLE
        except OSError as e:
            print(f"python3 -m fnet paper-report: {e}", file=sys.stderr)
            return EXIT_FAILURE
        except KeyError as e:
            print(f"python3 -m fnet paper-report: {e.args[0] if e.args else e}", file=sys.stderr)
            return EXIT_UNKNOWN
        except KeyboardInterrupt:
            print(f"python3 -m fnet paper-report: interrupted; {args.out} left as it was", file=sys.stderr)
            return 130
    _check(parser, args)
    try:
        fig = _draw(args)
        fig.savefig(args.out, dpi=150)
    except RpcError as e:
        print(f"python3 -m fnet plot {args.kind}: {e.message}", file=sys.stderr)
        if e.code in (-32001, -32002, -32006):
            return EXIT_UNKNOWN  # an unknown run, frame or ensemble
        return EXIT_USAGE if e.code == -32602 else EXIT_SERVER
    except (ConnectionError, OSError) as e:
        if isinstance(e, FileNotFoundError) or not hasattr(args, "host"):
            print(f"python3 -m fnet plot {args.kind}: {e}", file=sys.stderr)
            return EXIT_FAILURE
        print(f"python3 -m fnet: cannot reach fnet-server at {args.host}:{args.port}: {e} (see --host/--port, "
              "FNET_HOST/FNET_PORT)", file=sys.stderr)
        return EXIT_UNREACHABLE
    except (KeyError, ValueError) as e:
        print(f"python3 -m fnet plot {args.kind}: {e}", file=sys.stderr)
        return EXIT_FAILURE
    print(args.out)
    return EXIT_OK
