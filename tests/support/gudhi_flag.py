"""fnet's diagrams computed by GUDHI (python3-gudhi), the anchor of the tests and benchmarks that
compare: the 2-skeleton of the flag complex of a contact graph, filtered by superlevel sets.

flag_diagrams(n, i, j, force): the grains 0..n-1 and the contacts (i[k], j[k]) with their forces;
the contacts with |force| > 0 are the edges, valued |force| over their mean; a vertex is valued the
max of its edges (0 for none); expansion(2) gives each triangle the min of its edges. Values enter
GUDHI negated (it filters by sublevel sets); persistence over Z/2, the top dimension only when there
are no triangles (as tests/support/gudhi_persistence.cpp); points mapped back (birth = -b,
death = -d, never dying -> -1), those with birth == death left out, sorted as fnet sorts them
(birth, then death, both descending). Returns the diagram document {"pd0", "pd1", "vertices",
"edges", "triangles"}.
"""
import gudhi
import numpy as np


def superlevel(intervals):
    out = [(-b, -1.0 if np.isinf(d) else -d) for b, d in intervals]
    out = [p for p in out if p[0] != p[1]]
    out.sort(reverse=True)
    return [list(p) for p in out]


def flag_diagrams(n, i, j, force):
    force = np.abs(np.asarray(force, dtype=float))
    keep = force > 0
    i, j = np.asarray(i, dtype=np.int64)[keep], np.asarray(j, dtype=np.int64)[keep]
    value = force[keep] / force[keep].mean()
    vertex = np.zeros(n)
    np.maximum.at(vertex, i, value)
    np.maximum.at(vertex, j, value)
    tree = gudhi.SimplexTree()
    tree.insert_batch(np.arange(n).reshape(1, -1), -vertex)
    tree.insert_batch(np.vstack([i, j]), -value)
    tree.expansion(2)
    tree.compute_persistence(homology_coeff_field=2, min_persistence=0, persistence_dim_max=tree.dimension() < 2)
    edges = len(value)
    return {"pd0": superlevel(tree.persistence_intervals_in_dimension(0)),
            "pd1": superlevel(tree.persistence_intervals_in_dimension(1)),
            "vertices": n, "edges": edges, "triangles": tree.num_simplices() - n - edges}
