"""fnet-analyze diagram and distance against the same work done with GUDHI through Python, whole
process: start-up, reading the files, the maths, writing the answer.

usage: bench_analyze.py FNET_ANALYZE WRITE_SYNTHETIC_FRAME [--sizes N ...] [--runs R] [--gudhi-runs G]
                        [--lammps DIR]

For each size N, two synthetic packings (seeds 1 and 2, written as CSV by WRITE_SYNTHETIC_FRAME):
  diagram   `fnet-analyze diagram --contacts C --particles P > out.json` against
            `python3 gudhi_diagram.py C P out.json` (numpy.loadtxt, SimplexTree, persistence, json.dump);
  distance  `fnet-analyze distance A B --metric bottleneck --dim D` on the two frames' diagram
            documents against `python3 gudhi_distance.py A B D` (json.load, gudhi.bottleneck_distance,
            exact), both with never-dying classes dying at 0.
With --lammps DIR, the same for the frames 0008 and 0009 of that folder (2 000 disks).
Each command runs once untimed (page cache, lazy binding), then R times (G for GUDHI); the table
gives the median wall time. Both sides' answers are checked to agree ("same"). "points": in the
frame's two diagrams (diagram) or in the two diagrams compared (distance). "fnet math ms" is the
distance's own "seconds" (the computation alone, in-process); whole minus math is start-up and I/O.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PYTHON = "/usr/bin/python3"


def wall(cmd, runs, out_path=None):
    """Median wall time of `cmd` (stdout to out_path, truncated each run, or discarded)."""
    def run():
        if out_path is None:
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        else:
            with open(out_path, "w") as out:
                subprocess.run(cmd, check=True, stdout=out)
    run()
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        run()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def output(cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout


def same_diagrams(a_json, b_json):
    with open(a_json) as f:
        a = json.load(f)
    with open(b_json) as f:
        b = json.load(f)
    for key in ("vertices", "edges", "triangles"):
        if a[key] != b[key]:
            return False
    # The forces' mean is summed in another order (fnet: sorted, extended precision): ulps apart.
    for key in ("pd0", "pd1"):
        if len(a[key]) != len(b[key]):
            return False
        for p, q in zip(a[key], b[key]):
            if max(abs(p[0] - q[0]), abs(p[1] - q[1])) > 1e-12 * max(1.0, abs(p[0])):
                return False
    return True


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("fnet_analyze")
    ap.add_argument("write_frame")
    ap.add_argument("--sizes", type=int, nargs="+", default=[2000, 40000])
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--gudhi-runs", type=int, default=3)
    ap.add_argument("--lammps")
    args = ap.parse_args()
    exe = args.fnet_analyze

    with tempfile.TemporaryDirectory(prefix="fnet-bench-analyze-") as tmp:
        inputs = []
        for n in args.sizes:
            frames = []
            for seed in (1, 2):
                c, p = (os.path.join(tmp, "n%d_s%d_%s.csv" % (n, seed, what)) for what in ("contacts", "particles"))
                subprocess.run([args.write_frame, str(n), str(seed), c, p], check=True)
                frames.append((c, p))
            inputs.append(("synthetic %d" % n, frames))
        if args.lammps:
            inputs.append(("LAMMPS 2000 (0008, 0009)", [
                tuple(os.path.join(args.lammps, "frame_%s_%s.csv" % (k, what)) for what in ("contacts", "particles"))
                for k in ("0008", "0009")]))

        start = wall([exe, "--help"], args.runs)
        print("load average %s; fnet-analyze --help (start-up alone): %.1f ms" % (
            " ".join("%.2f" % x for x in os.getloadavg()), start * 1e3))
        print()
        print("%-26s %-9s %4s %7s %12s %12s %12s %8s  %s" % (
            "input", "command", "dim", "points", "fnet ms", "fnet math ms", "GUDHI ms", "ratio", "same"))
        for label, frames in inputs:
            docs = []
            for k, (c, p) in enumerate(frames):
                ours, theirs = os.path.join(tmp, "fnet%d.json" % k), os.path.join(tmp, "gudhi%d.json" % k)
                t_fnet = wall([exe, "diagram", "--contacts", c, "--particles", p], args.runs, out_path=ours)
                t_gudhi = wall([PYTHON, os.path.join(HERE, "gudhi_diagram.py"), c, p, theirs], args.gudhi_runs)
                docs.append(ours)
                if k == 0:
                    with open(ours) as f:
                        d = json.load(f)
                    print("%-26s %-9s %4s %7d %12.1f %12s %12.1f %7.1fx  %s" % (
                        label, "diagram", "0+1", len(d["pd0"]) + len(d["pd1"]), t_fnet * 1e3, "", t_gudhi * 1e3,
                        t_gudhi / t_fnet, "same" if same_diagrams(ours, theirs) else "DIFFERENT"))
            for dim in (0, 1):
                cmd = [exe, "distance", docs[0], docs[1], "--metric", "bottleneck", "--dim", str(dim)]
                ours = json.loads(output(cmd))
                t_fnet = wall(cmd, args.runs)
                gcmd = [PYTHON, os.path.join(HERE, "gudhi_distance.py"), docs[0], docs[1], str(dim)]
                theirs = json.loads(output(gcmd))
                t_gudhi = wall(gcmd, args.gudhi_runs)
                points = sum(len(json.load(open(doc))["pd%d" % dim]) for doc in docs)
                agree = abs(ours["value"] - theirs["value"]) <= 1e-12 * max(1.0, abs(ours["value"]))
                print("%-26s %-9s %4d %7d %12.1f %12.1f %12.1f %7.1fx  %s" % (
                    label, "distance", dim, points, t_fnet * 1e3, ours["seconds"] * 1e3, t_gudhi * 1e3,
                    t_gudhi / t_fnet, "same" if agree else "DIFFERENT %r %r" % (ours["value"], theirs["value"])))
                sys.stdout.flush()


if __name__ == "__main__":
    main()
