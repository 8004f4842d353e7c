"""fnet's diagrams in the sublevel form GUDHI, Hera and persim read (as `fnet-analyze diagram
--format gudhi` writes them): fnet's filtration is superlevel, (b, d) with b >= d and d = -1 for a
class that never dies; negating both coordinates gives birth <= death and keeps every L-infinity
distance, so bottleneck and Wasserstein distances (internal_p = inf) are the same in both forms."""

import numpy as np

NEVER_DIES = -1.0
ESSENTIAL = ("inf", "floor")


def to_gudhi(diagram, essential="inf"):
    """An (n, 2) float64 array of (-b, -d) for the points (b, d) of `diagram` (an (n, 2) array or a
    list of [birth, death] pairs as fnet gives them: Client.diagram, a store's diagram, a diagram
    document's "pd0" or "pd1"), as gudhi.bottleneck_distance and gudhi.hera.wasserstein_distance take
    it. A class that never dies (d = -1) dies at +inf with essential="inf" (GUDHI's own form, which
    matches such points only among themselves, as fnet's `separate` convention), or at 0 with
    essential="floor" (fnet's default convention; a rattler's (0, -1) then lies on the diagonal and
    is left out)."""
    if essential not in ESSENTIAL:
        raise ValueError(f"essential must be one of {', '.join(ESSENTIAL)}, not {essential!r}")
    points = np.asarray(diagram, dtype=np.float64).reshape(-1, 2)
    never = points[:, 1] == NEVER_DIES
    # 0.0 - x rather than -x: a coordinate of 0 stays +0.
    out = 0.0 - points
    out[never, 1] = np.inf if essential == "inf" else 0.0
    if essential == "floor":
        out = out[~(never & (out[:, 0] == 0.0))]
    return np.ascontiguousarray(out)
