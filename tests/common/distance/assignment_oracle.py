"""Independent oracle for fnet's diagram distances: a plain assignment solver on the
diagonal-augmented cost matrix (scipy.optimize.linear_sum_assignment, exact), and the bottleneck by
binary search over the sorted candidate distances with scipy's maximum bipartite matching.

usage: assignment_oracle.py A.json B.json KEY CONVENTION METRIC...
  KEY: pd0 or pd1; CONVENTION: floor, sentinel, separate; METRIC: bottleneck or a real q >= 1.
Prints one JSON object {"metric": value, ...}; value null when infinite.
Optional: "--scale C" multiplies every coordinate first (exact arithmetic is scipy's business).
"""
import json
import sys

import numpy as np
from scipy.optimize import linear_sum_assignment
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import maximum_bipartite_matching


def convention(points, name):
    finite, essential = [], []
    for b, d in points:
        if d == -1:
            if name == "separate":
                essential.append(b)
                continue
            if name == "floor":
                d = 0.0
        if b != d:
            finite.append((b, d))
    return np.array(finite, dtype=float).reshape(-1, 2), sorted(essential)


def augmented(a, b):
    """Square (n+m) matrix of L-inf distances: a_i vs b_j, a_i vs its own diagonal copy,
    b_j's diagonal copy vs b_j, diagonal copies vs each other at 0; inf elsewhere."""
    n, m = len(a), len(b)
    big = np.inf
    c = np.full((n + m, m + n), big)
    if n and m:
        c[:n, :m] = np.maximum(np.abs(a[:, None, 0] - b[None, :, 0]), np.abs(a[:, None, 1] - b[None, :, 1]))
    for i in range(n):
        c[i, m + i] = abs(a[i, 0] - a[i, 1]) / 2
    for j in range(m):
        c[n + j, j] = abs(b[j, 0] - b[j, 1]) / 2
    c[n:, m:] = 0.0
    return c


def wasserstein(a, b, q):
    if len(a) + len(b) == 0:
        return 0.0
    c = augmented(a, b)
    finite = np.isfinite(c)
    # Normalize before the q-th power so tiny scales keep their precision.
    s = np.max(c[finite]) if np.any(c[finite] > 0) else 1.0
    cq = np.where(finite, (c / s) ** q, 1e300)
    rows, cols = linear_sum_assignment(cq)
    return float(np.sum(cq[rows, cols]) ** (1.0 / q) * s)


def bottleneck(a, b):
    if len(a) + len(b) == 0:
        return 0.0
    c = augmented(a, b)
    values = np.unique(c[np.isfinite(c)])
    lo, hi = 0, len(values) - 1
    while lo < hi:
        mid = (lo + hi) // 2
        graph = csr_matrix((c <= values[mid]).astype(np.int8))
        matching = maximum_bipartite_matching(graph, perm_type="column")
        if np.all(matching >= 0):
            hi = mid
        else:
            lo = mid + 1
    return float(values[lo])


def main(argv):
    scale = 1.0
    if "--scale" in argv:
        k = argv.index("--scale")
        scale = float(argv[k + 1])
        argv = argv[:k] + argv[k + 2:]
    fa, fb, key, conv = argv[1:5]
    metrics = argv[5:]
    pa = [(p[0] * scale, p[1] if p[1] == -1 else p[1] * scale) for p in json.load(open(fa))[key]]
    pb = [(p[0] * scale, p[1] if p[1] == -1 else p[1] * scale) for p in json.load(open(fb))[key]]
    a, ea = convention(pa, conv)
    b, eb = convention(pb, conv)
    out = {}
    for metric in metrics:
        if conv == "separate" and len(ea) != len(eb):
            out[metric] = None
            continue
        ess = np.abs(np.array(ea) - np.array(eb))
        if metric == "bottleneck":
            v = bottleneck(a, b)
            out[metric] = float(max(v, ess.max() if len(ess) else 0.0))
        else:
            q = float(metric)
            v = wasserstein(a, b, q)
            out[metric] = float((v ** q + np.sum(ess ** q)) ** (1.0 / q))
    print(json.dumps(out))


if __name__ == "__main__":
    main(sys.argv)
