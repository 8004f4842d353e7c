"""What `fnet-analyze diagram` does, done with GUDHI through Python: the anchor of bench_analyze.py.

usage: gudhi_diagram.py CONTACTS.csv PARTICLES.csv OUT.json

Reads the two CSVs (numpy.loadtxt, columns found by the header) and writes the diagram document
of the normal forces that tests/support/gudhi_flag.py computes with GUDHI (the flag complex of the
contact graph in a SimplexTree, insert_batch for vertices and edges, expansion(2), persistence over
Z/2).
"""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
from gudhi_flag import flag_diagrams  # noqa: E402


def columns(path, names):
    with open(path) as f:
        header = [h.strip() for h in f.readline().split(",")]
    return np.loadtxt(path, delimiter=",", skiprows=1, usecols=[header.index(n) for n in names], ndmin=2)


def main(contacts_csv, particles_csv, out_json):
    contacts = columns(contacts_csv, ["i", "j", "fn"])
    n = len(columns(particles_csv, ["id"]))
    document = flag_diagrams(n, contacts[:, 0], contacts[:, 1], contacts[:, 2])
    with open(out_json, "w") as f:
        json.dump(document, f, separators=(",", ":"))


if __name__ == "__main__":
    main(*sys.argv[1:])
