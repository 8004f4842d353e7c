"""What `fnet-analyze diagram` does, done with GUDHI through Python: the anchor of bench_analyze.py.

usage: gudhi_diagram.py CONTACTS.csv PARTICLES.csv OUT.json

Reads the two CSVs (numpy.loadtxt, columns found by the header) and writes the diagram document
of the normal forces (diagram_document with column "ft": the tangential network) that
tests/support/gudhi_flag.py computes with GUDHI (the flag complex of the contact graph in a
SimplexTree, insert_batch for vertices and edges, expansion(2), persistence over Z/2).
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


def diagram_document(contacts_csv, particles_csv, column="fn"):
    """The diagram document of the network of one force column, as fnet-analyze diagram writes it."""
    contacts = columns(contacts_csv, ["i", "j", column])
    n = len(columns(particles_csv, ["id"]))
    return flag_diagrams(n, contacts[:, 0], contacts[:, 1], contacts[:, 2])


def main(contacts_csv, particles_csv, out_json):
    with open(out_json, "w") as f:
        json.dump(diagram_document(contacts_csv, particles_csv), f, separators=(",", ":"))


if __name__ == "__main__":
    main(*sys.argv[1:])
