"""`python3 -m fnet plot KIND ... --out FILE`: the paper's figures from a running fnet-server
(or from files). Options are named as fnetctl's; exit codes are fnetctl's: 0 ok, 1 failure (an
input file or answer it cannot read, output it cannot write), 2 usage (naming the bad option),
3 server unreachable, 4 unknown run, frame or ensemble, 5 other server error; each failure is one
line on stderr. A PNG carries where it came from as text chunks (fnet.provenance)."""

import argparse
import os
import shlex
import socket
import sys

from fnet import figures, provenance, store
from fnet.rpc import DEFAULT_DIM, DEFAULT_HOST, DEFAULT_PORT, UNKNOWN_RUN, Client, RpcError

EXIT_OK, EXIT_FAILURE, EXIT_USAGE, EXIT_UNREACHABLE, EXIT_UNKNOWN, EXIT_SERVER = 0, 1, 2, 3, 4, 5
EXIT_INTERRUPTED = 130
UNKNOWN_CODES = (UNKNOWN_RUN, -32002, -32006)  # proto/api.md: unknown run, frame, ensemble
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
DPI = _bounded(float, 10, 1200, "dots per inch 10 ... 1200")
DEFAULT_DPI = 150


def _size(text):
    """--size W,H: the figure's width and height in inches, each in (0, 100]."""
    parts = text.split(",")
    try:
        w, h = (float(v) for v in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected W,H in inches (e.g. 6.4,4.8), got {text!r}") from None
    if not all(0 < v <= 100 for v in (w, h)):
        raise argparse.ArgumentTypeError(f"expected W,H each above 0 and at most 100 inches, got {text!r}")
    return w, h


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
    parser.add_argument("--dim", type=int, choices=(0, 1), default=DEFAULT_DIM,
                        help=f"0 (components) or 1 (loops) (default {DEFAULT_DIM})")
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


def _out(parser, y_scale=False):
    parser.add_argument("--out", required=True, help="the image file (its extension names the format: png, pdf, svg)")
    g = parser.add_argument_group("figure")
    g.add_argument("--title", help="the figure's title instead of its own ('' for none)")
    g.add_argument("--size", type=_size, metavar="W,H", help="width and height in inches (default: the figure's)")
    g.add_argument("--dpi", type=DPI, default=DEFAULT_DPI, help=f"dots per inch (default {DEFAULT_DPI})")
    if y_scale:
        scale = g.add_mutually_exclusive_group()
        scale.add_argument("--log", dest="y_scale", action="store_const", const="log",
                           help="logarithmic y axis (values <= 0 are left out)")
        scale.add_argument("--linear", dest="y_scale", action="store_const", const="linear",
                           help="linear y axis (the default)")
        parser.set_defaults(y_scale="linear")


def build_parser():
    parser = argparse.ArgumentParser(prog="python3 -m fnet", description=__doc__.split("\n\n")[0])
    from fnet import provenance
    parser.add_argument("--version", action="version",
                        version=f"fnet {provenance.__version__} (commit {provenance.package_commit()})",
                        help="print the version and the commit of the checkout, then exit")
    commands = parser.add_subparsers(dest="command", required=True, metavar="plot|paper-report")
    plot = commands.add_parser("plot", help="draw one of the paper's figures")
    kinds = plot.add_subparsers(dest="kind", required=True, metavar="KIND")

    p = kinds.add_parser("network", help="Fig. 1: a frame's force network (or the change between two frames)")
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--run-file", help="the run file fnet-simd wrote (--out)")
    source.add_argument("--store", help="an analysis store that keeps the frames' networks (fnet-store-2 or later)")
    p.add_argument("--frame", type=FRAME, required=True, help="the frame")
    p.add_argument("--other-frame", type=FRAME, help="draw the change from --frame to this frame")
    p.add_argument("--force", choices=("normal", "tangential"), default="normal", help="force network")
    p.add_argument("--slab", type=_positive_float,
                   help=f"3D frames: the contacts within this many d of the middle z (default {figures.SLAB_HALF_WIDTH:g})")
    p.add_argument("--projection", action="store_true", help="3D frames: every contact projected on xy, not a slab")
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
    _out(p, y_scale=True)

    p = kinds.add_parser("ensemble", help="Figs. 6, 8, 9: ensembles' mean ± standard error, one curve per "
                                          "--ensemble and --force")
    _endpoint(p)
    p.add_argument("--ensemble", action="append", required=True, help="an ensemble (repeat to compare)")
    _distance_options(p, forces=True)
    _bin_options(p)
    _out(p, y_scale=True)

    p = kinds.add_parser("ratio", help="Figs. 7, 10: d_B / d_W1 and d_B / d_W2 against rho")
    _endpoint(p)
    who = p.add_mutually_exclusive_group()
    who.add_argument("--run", help="one run's ratio per frame (default: the newest run); binned with --bins")
    who.add_argument("--ensemble", help="an ensemble's ratio of bin means")
    p.add_argument("--ratio", choices=RATIOS, action="append", help="d_B / d_Wq (repeatable; default: both)")
    p.add_argument("--dim", type=int, choices=(0, 1), default=DEFAULT_DIM,
                   help=f"0 (components) or 1 (loops) (default {DEFAULT_DIM})")
    p.add_argument("--force", choices=("normal", "tangential"), default="normal", help="force network")
    p.add_argument("--essential", choices=("floor", "sentinel", "separate"), default="floor",
                   help="how classes that never die are matched")
    _bin_options(p)
    _out(p, y_scale=True)

    p = kinds.add_parser("blocks", help="Tables II, III: distances cell by cell of a k x k grid")
    _endpoint(p)
    p.add_argument("--run", help="run id (default: the newest run)")
    p.add_argument("--frame", type=FRAME, required=True, help="the first frame")
    p.add_argument("--other-frame", type=FRAME, required=True, help="the second frame")
    p.add_argument("--k", type=_bounded(int, 1, 16, "an integer 1 ... 16"), default=2, help="grid of k x k cells")
    _distance_options(p, metric_required=False)
    packing = p.add_mutually_exclusive_group()
    packing.add_argument("--store", help="draw the grid over --frame's packing, read from this analysis store (the "
                                         "server's DATA_DIR/RUN.h5)")
    packing.add_argument("--run-file", help="likewise, from the run file fnet-simd wrote (--out)")
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


def _read_file(path, run_file, read):
    """`read(f)` on the run file or analysis store at `path`; an unknown frame is a LookupError."""
    try:
        f = store.open_run_file(path) if run_file else store.open_store(path)
    except OSError as e:  # h5py's message does not name the file
        raise ValueError(f"{path}: not an HDF5 file that can be read ({_one_line(e)})") from e
    with f:
        return read(f)


def _draw_network(args, record):
    path = args.run_file or args.store
    record.update(source=path)

    def read(f):
        read_frame = f.frame if args.run_file else f.network
        frames = [read_frame(k) for k in (args.frame, args.other_frame) if k is not None]
        if any(frame is None for frame in frames):
            raise ValueError(f"the store {path} does not keep the networks of its frames (schema {f.schema})")
        record.update(run=f.run_id)
        return frames, figures.run_walls(f)

    frames, walls = _read_file(path, args.run_file, read)
    if figures.dimension_of(frames[0]) == 3:
        view = {"slab": figures.SLAB_HALF_WIDTH if args.slab is None else args.slab, "projection": args.projection}
    elif args.slab is not None or args.projection:
        raise ValueError(f"--slab and --projection draw 3D frames; frame {args.frame} of {path} is 2D")
    else:
        view = {"walls": walls}
    if len(frames) == 1:
        return figures.network(frames[0], force=args.force, **view)
    return figures.network_change(*frames, force=args.force, **view)


def _draw_served(args, c, record):
    """The figures drawn from the server's answers; `record` gets what provenance names."""
    record["server_status"] = c.status()
    if getattr(args, "ensemble", None):
        record["ensemble"] = ",".join(args.ensemble) if isinstance(args.ensemble, list) else args.ensemble
        run = None
    else:
        run = c.run(args.run)["run"]  # the newest run when none is named: every call then asks for that one
        record["run"] = run
    if args.kind == "diagram":
        d = [c.diagram(args.frame, run=run, dim=k, force=args.force) for k in (0, 1)]
        title = args.title if args.title is not None else f"{run} frame {args.frame}, {args.force} forces"
        return figures.diagrams(*d, title=title)
    if args.kind == "distances" and not _binned(args):
        return figures.distances(c.series(run=run, force=args.force, from_=args.from_, to=args.to, **_distance(args)))
    if args.kind == "distances":
        who = {"ensemble": args.ensemble} if args.ensemble else {"run": run}
        return figures.ensemble(c.ensemble_series(**who, force=args.force, **_distance(args), **_binning(args)))
    if args.kind == "ensemble":
        curves = [c.ensemble_series(ensemble=e, force=force, **_distance(args), **_binning(args))
                  for e in args.ensemble for force in (args.force or ["normal"])]
        return figures.ensemble(curves)
    if args.kind == "ratio" and not _binned(args):
        curves = [c.series(None, run=run, ratio=r, dim=args.dim, force=args.force, essential=args.essential)
                  for r in (args.ratio or list(RATIOS))]
        return figures.ratio(curves)
    if args.kind == "ratio":
        who = {"ensemble": args.ensemble} if args.ensemble else {"run": run}
        curves = [c.ensemble_series(**who, ratio=r, dim=args.dim, force=args.force, essential=args.essential,
                                    **_binning(args))
                  for r in (args.ratio or list(RATIOS))]
        return figures.ratio(curves)
    if args.kind == "blocks":
        table = c.blocks(args.frame, args.other_frame, run=run, k=args.k, force=args.force, **_distance(args))
        whole = c.distance(args.frame, args.other_frame, run=run, force=args.force, **_distance(args))["value"]
        network, walls = None, None
        if args.store or args.run_file:
            path = args.store or args.run_file
            record["source"] = path
            network, walls = _read_file(path, args.run_file, lambda f: (
                f.frame(args.frame) if args.run_file else f.network(args.frame), figures.run_walls(f)))
            if network is None:
                raise ValueError(f"the store {path} does not keep the networks of its frames")
        return figures.blocks(table, network=network, whole=whole, walls=walls)
    raise AssertionError(args.kind)


def _draw(args, record):
    if args.kind == "network":
        return _draw_network(args, record)
    if args.kind == "diagram" and args.store:
        record.update(source=args.store)

        def read(s):
            record.update(run=s.run_id)
            d = [s.diagram(args.frame, k, args.force) for k in (0, 1)]
            return d, f"{s.run_id} frame {args.frame}, {args.force} forces"
        d, title = _read_file(args.store, False, read)
        return figures.diagrams(*d, title=args.title if args.title is not None else title)
    try:
        with Client(args.host, args.port) as c:
            return _draw_served(args, c, record)
    except OSError as e:
        # Before the server answered, any OSError is the connection's; after, a file's (h5py's) unless
        # it is a socket's.
        if "server_status" not in record or isinstance(e, (ConnectionError, TimeoutError, socket.gaierror)):
            raise ServerUnreachable(f"cannot reach fnet-server at {args.host}:{args.port}: {_one_line(e)} (see "
                                    "--host/--port, FNET_HOST/FNET_PORT)") from e
        raise


class ServerUnreachable(Exception):
    """The server could not be reached, or the connection to it broke."""


def _finish(fig, args):
    """The figure options: --title (the figure's own title replaced; diagrams take it when drawn),
    --log/--linear, --size."""
    if args.title is not None and args.kind != "diagram":
        fig.axes[0].set_title(args.title)
    if getattr(args, "y_scale", None):
        fig.axes[0].set_yscale(args.y_scale)
    if args.size:
        fig.set_size_inches(*args.size)


def figure(args, record=None):
    """The figure `args` (as build_parser() parsed them) asks for, its options applied; `record`
    (a dict) gets what its provenance names."""
    record = {} if record is None else record
    fig = _draw(args, record)
    _finish(fig, args)
    return fig


def _provenance(args, argv, record):
    """fnet.provenance.describe() of a figure: the command, the server's build, run, frames, the
    distance asked for."""
    extra = {"command": shlex.join(["python3", "-m", "fnet", *argv]), "figure": args.kind}
    for key in ("run", "ensemble", "source"):
        if record.get(key):
            extra[key] = record[key]
    for key in ("frame", "other_frame", "metric", "q", "dim", "force", "k", "ratio", "y_scale"):
        value = getattr(args, key, None)
        if value is not None:
            extra[key] = ",".join(map(str, value)) if isinstance(value, list) else value
    convention = getattr(args, "essential", None) or "none (no distance drawn)"
    return provenance.describe(server_status=record.get("server_status"), convention=convention, **extra)


def _save(fig, args, argv, record):
    if os.path.splitext(args.out)[1].lower() == ".png":
        fig.savefig(args.out, dpi=args.dpi, metadata=provenance.png_metadata(_provenance(args, argv, record)))
    else:
        fig.savefig(args.out, dpi=args.dpi)


def _one_line(e):
    """An exception as one line: a KeyError's text without its quotes."""
    text = e.args[0] if isinstance(e, KeyError) and e.args else str(e)
    return " ".join(str(text).split()) or type(e).__name__


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command == "paper-report":
        try:
            from fnet import paper
            return paper.main(args)
        except RpcError as e:
            print(f"python3 -m fnet paper-report: {e.message}", file=sys.stderr)
            return EXIT_UNKNOWN if e.code in UNKNOWN_CODES else EXIT_SERVER
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
    prefix = f"python3 -m fnet plot {args.kind}"
    record = {}
    try:
        fig = figure(args, record)
    except KeyboardInterrupt:
        return EXIT_INTERRUPTED
    except RpcError as e:
        print(f"{prefix}: {' '.join(str(e.message).split())}", file=sys.stderr)
        if e.code in UNKNOWN_CODES:
            return EXIT_UNKNOWN
        return EXIT_USAGE if e.code == -32602 else EXIT_SERVER
    except ServerUnreachable as e:
        print(f"python3 -m fnet: {e}", file=sys.stderr)
        return EXIT_UNREACHABLE
    except LookupError as e:  # a frame the file does not hold
        print(f"{prefix}: {_one_line(e)}", file=sys.stderr)
        return EXIT_UNKNOWN
    except Exception as e:  # noqa: BLE001 -- a file that is not what it should be, say: one line, no traceback
        print(f"{prefix}: {_one_line(e)}", file=sys.stderr)
        return EXIT_FAILURE
    try:
        _save(fig, args, argv, record)
    except Exception as e:  # noqa: BLE001
        print(f"{prefix}: cannot write --out {args.out}: {_one_line(e)}", file=sys.stderr)
        return EXIT_FAILURE
    print(args.out)
    return EXIT_OK
