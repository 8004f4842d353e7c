"""The analysis of one frame done with GUDHI and Hera through Python: the anchor of
bench_frame_analysis.

usage: anchor_frame_analysis.py A_CONTACTS A_PARTICLES B_CONTACTS B_PARTICLES OUT_DIR [--exact-bottleneck-max P]

Frame B follows frame A. The diagrams of both networks (normal "fn", tangential "ft") of both frames
come from gudhi_diagram.py's SimplexTree pipeline (frame B's are timed: A's were made when A
arrived); B's are written to OUT_DIR/anchor_{normal,tangential}.json for the caller to compare.
Then the twelve distances from A to B, as fnet's run pipeline takes them (bottleneck, W1, W2 x PD0,
PD1 x normal, tangential; never-dying classes die at 0): W1 and W2 by Hera at relative error 0.01,
the bottleneck by GUDHI's exact algorithm up to P points a diagram (default 5 000: ~30 s there),
above that by Hera at 0.01. Prints one JSON object: the diagram time, and per distance its key,
value, CPU time and tool.
"""
import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "distance"))

from compare_anchors import finite, gudhi_bottleneck, hera  # noqa: E402
from gudhi_diagram import diagram_document  # noqa: E402

FORCES = (("normal", "fn"), ("tangential", "ft"))
METRICS = (("bottleneck", None), ("wasserstein1", 1), ("wasserstein2", 2))  # fnet's stored series order
HERA_DELTA = 0.01


def timed(f):
    """(f(), CPU seconds of this process): the figures fnet's side reports are CPU time too."""
    t = time.process_time()
    v = f()
    return v, time.process_time() - t


def main(argv):
    a_contacts, a_particles, b_contacts, b_particles, out_dir = argv[1:6]
    exact_max = 5000
    if "--exact-bottleneck-max" in argv:
        exact_max = int(argv[argv.index("--exact-bottleneck-max") + 1])
    before, after = {}, {}
    diagram_seconds = 0.0
    for force, column in FORCES:
        before[force] = diagram_document(a_contacts, a_particles, column)
        after[force], seconds = timed(lambda: diagram_document(b_contacts, b_particles, column))
        diagram_seconds += seconds
        with open(os.path.join(out_dir, "anchor_%s.json" % force), "w") as f:
            json.dump(after[force], f)
    distances = []
    for metric, q in METRICS:
        for dim in (0, 1):
            for force, _ in FORCES:
                key = "pd%d" % dim
                a, b = finite(before[force][key]), finite(after[force][key])
                if q is None and max(len(a), len(b)) <= exact_max:
                    value, seconds = timed(lambda: gudhi_bottleneck(a, b))
                    tool = "gudhi exact"
                else:
                    value, seconds = timed(lambda: hera(a, b, q, HERA_DELTA))
                    tool = "hera %g" % HERA_DELTA
                distances.append({"key": "%s/%s/%s" % (metric, key, force), "value": float(value),
                                  "seconds": seconds, "tool": tool})
    print(json.dumps({"diagram_seconds": diagram_seconds, "distances": distances}))

if __name__ == "__main__":
    main(sys.argv)
