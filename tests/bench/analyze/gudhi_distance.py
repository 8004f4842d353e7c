"""What `fnet-analyze distance A B --metric bottleneck --dim D` does, done with GUDHI through
Python: the anchor of bench_analyze.py.

usage: gudhi_distance.py A.json B.json DIM

Reads the two diagram documents (json.load), takes the never-dying classes to die at 0 (fnet's
`floor` convention), drops points on the diagonal, and prints GUDHI's exact bottleneck distance
(gudhi.bottleneck_distance without e). The points go to GUDHI as (death, birth): superlevel
diagrams lie below the diagonal, which GUDHI would ignore; swapping keeps every L-infinity distance.
"""
import json
import sys

import numpy as np
import gudhi


def finite(points):
    swapped = [[0.0 if d == -1 else d, b] for b, d in points]
    return np.array([p for p in swapped if p[0] != p[1]], dtype=float).reshape(-1, 2)


def main(a_json, b_json, dim):
    key = "pd%d" % int(dim)
    with open(a_json) as f:
        a = finite(json.load(f)[key])
    with open(b_json) as f:
        b = finite(json.load(f)[key])
    print(json.dumps({"value": gudhi.bottleneck_distance(a, b)}))


if __name__ == "__main__":
    main(*sys.argv[1:])
