"""What `fnet-analyze diagram` does, done with GUDHI through Python: the anchor of bench_analyze.py.

usage: gudhi_diagram.py CONTACTS.csv PARTICLES.csv OUT.json

Reads the two CSVs (numpy.loadtxt, columns found by the header), normalizes |fn| (diagram_document
with column "ft": the tangential network) by its mean over
contacts with force > 0, builds the flag complex of the contact graph in a SimplexTree (values
negated: GUDHI filters by sublevel sets; insert_batch for vertices and edges, expansion(2)),
computes persistence over Z/2 and writes the diagram document {"pd0", "pd1", "vertices", "edges",
"triangles"} with the points mapped back (birth = -b, death = -d, never dying -> -1) and sorted as
fnet sorts them (birth, then death, both descending).
"""
import json
import sys

import numpy as np
import gudhi


def columns(path, names):
    with open(path) as f:
        header = [h.strip() for h in f.readline().split(",")]
    return np.loadtxt(path, delimiter=",", skiprows=1, usecols=[header.index(n) for n in names], ndmin=2)


def superlevel(intervals):
    out = [(-b, -1.0 if np.isinf(d) else -d) for b, d in intervals]
    out = [p for p in out if p[0] != p[1]]
    out.sort(reverse=True)
    return [list(p) for p in out]


def diagram_document(contacts_csv, particles_csv, column="fn"):
    """The diagram document of the network of one force column, as fnet-analyze diagram writes it."""
    contacts = columns(contacts_csv, ["i", "j", column])
    n = len(columns(particles_csv, ["id"]))
    force = np.abs(contacts[:, 2])
    keep = force > 0
    i, j = contacts[keep, 0].astype(np.int64), contacts[keep, 1].astype(np.int64)
    value = force[keep] / force[keep].mean()
    vertex = np.zeros(n)
    np.maximum.at(vertex, i, value)
    np.maximum.at(vertex, j, value)

    tree = gudhi.SimplexTree()
    tree.insert_batch(np.arange(n).reshape(1, -1), -vertex)
    tree.insert_batch(np.vstack([i, j]), -value)
    tree.expansion(2)
    # As in tests/support/gudhi_persistence.cpp: the top dimension only when there are no triangles.
    tree.compute_persistence(homology_coeff_field=2, min_persistence=0,
                             persistence_dim_max=tree.dimension() < 2)
    edges = len(value)
    document = {
        "pd0": superlevel(tree.persistence_intervals_in_dimension(0)),
        "pd1": superlevel(tree.persistence_intervals_in_dimension(1)),
        "vertices": n,
        "edges": edges,
        "triangles": tree.num_simplices() - n - edges,
    }
    return document


def main(contacts_csv, particles_csv, out_json):
    document = diagram_document(contacts_csv, particles_csv)
    with open(out_json, "w") as f:
        json.dump(document, f, separators=(",", ":"))


if __name__ == "__main__":
    main(*sys.argv[1:])
