"""The paper's figures with matplotlib, drawn headless (Agg) on Figure objects of their own (no
pyplot state: safe in scripts, servers and notebooks, where a returned Figure displays itself).

Each function takes the data it plots — what fnet.Client or fnet.store return — and returns the
Figure. The artists that carry the data have a gid (`artist.get_gid()`), so that what was drawn can
be checked against what was served: "contacts", "created", "broken", "grains", "walls", "finite",
"never_dies", "count", "diagonal", "distance", "z", "mean", "ratio", "blocks", "cells".

Lengths are in d, the mean grain diameter (fnet-simd's unit of length, and that of the LAMMPS
runs fnet reads); forces in units of the mean force of the network they belong to.

A 3D frame (`frame.dimension` 3, each grain's z in `frame.particle_z`) is drawn as a slab seen from +z: the
contacts whose contact point lies within `slab` d of the middle z, projected on xy, and each
sphere's part inside the slab as a disc ("slab" gid: the slab's bounds); or, with
`projection=True`, every contact projected on xy. Against rho, a 3D run's axis says that rho is
its volume fraction (a 2D run's is the area fraction).
"""

import json
import math

import numpy as np

try:
    import matplotlib  # noqa: F401
except ImportError as e:  # a python3 other than Debian's (a pyenv one, say) may lack it
    raise ImportError(f"fnet.figures needs matplotlib: Debian's python3 (/usr/bin/python3) with "
                      f"python3-matplotlib ({e})") from e
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection, PatchCollection
from matplotlib.colors import LinearSegmentedColormap, Normalize, TwoSlopeNorm
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, Rectangle

from fnet.rpc import DEFAULT_DIM

METRIC_SYMBOLS = {"bottleneck": "d_B", "wasserstein1": "d_{W1}", "wasserstein2": "d_{W2}"}
AXIS_LABELS = {"rho": r"$\rho$", "rho_minus_rho_j": r"$\rho - \rho_J$"}
VOLUME_FRACTION = " (volume fraction)"  # added to a rho axis of a 3D run
SLAB_HALF_WIDTH = 1.0  # d: a 3D frame's default slab is two diameters thick
FORCE_UNIT = r"$f / \langle f \rangle$"  # a force over the mean force of its network
COLOUR_PERCENTILE = 99.0  # the top of a force colour scale: a few strong contacts do not wash out the rest
# A diverging scale whose middle, no change, is a grey that shows on white.
CHANGE_CMAP = LinearSegmentedColormap.from_list("fnet_change", ["#2166ac", "0.62", "#b2182b"])
CELL_NORMALIZATION = "each cell normalized by its own mean force:\na cell's distance can exceed the whole frame's"
def _figure(width=6.4, height=4.8):
    fig = Figure(figsize=(width, height), layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def _metric_label(r):
    metric = r.get("metric") or "bottleneck"
    if metric == "wasserstein":
        symbol = "d_{W%g}" % r.get("q", 1)
    else:
        symbol = METRIC_SYMBOLS.get(metric, metric)
    return f"${symbol}$ PD{r.get('dim', DEFAULT_DIM)}, {r.get('force', 'normal')} forces"


def normalized_network(frame, force="normal"):
    """The contacts of a frame's force network as fnet builds it: those whose force magnitude is
    > 0, each as (i, j, force / mean force over exactly those contacts). Returns (pairs, values)."""
    forces = frame.forces(force)
    keep = forces > 0
    pairs = frame.contact_pairs[keep]
    values = forces[keep]
    return pairs, (values / values.mean() if len(values) else values)


def colour_top(values, percentile=COLOUR_PERCENTILE):
    """The top of a colour scale for `values` (>= 0): their `percentile`-th percentile, or their
    maximum when that is 0; 1 when there are none or all are 0."""
    values = np.asarray(values, dtype=np.float64)
    values = values[np.isfinite(values)]
    if not len(values):
        return 1.0
    top = float(np.percentile(values, percentile))
    if top <= 0:
        top = float(values.max())
    return top if top > 0 else 1.0


def run_walls(source):
    """The walls of an fnet-simd run as its parameters set them, {"box": the side of the free
    interior at the start, "wall_diameter"} in d, from a run file (fnet.store.RunFile: its config),
    an analysis store (fnet.store.Store: its announcement's config_json) or a dict of the run's
    parameters (run.get's parameters["config"]); None when the run does not record them (a
    recorded LAMMPS run, say)."""
    if isinstance(source, dict):
        config = source
    elif hasattr(source, "config"):
        config = source.config
    else:
        text = (source.announcement() or {}).get("config_json") or "{}"
        try:
            config = json.loads(text)
        except ValueError:
            config = {}
    if not isinstance(config, dict) or config.get("box") is None:
        return None
    return {"box": float(config["box"]), "wall_diameter": float(config.get("wall_diameter", 1.0))}


def free_interior(frame, walls):
    """(lo, hi): the square [lo, hi]² between the walls at `frame`, in d. fnet-simd's walls start
    around [0, box]² and move inward symmetrically, and a frame's ρ is its grains' area over the
    interior's, so the side is sqrt(Σ π r² / ρ) and the centre box / 2."""
    box = walls["box"]
    r = frame.particles[:, 2]
    if not len(r) or not frame.rho > 0:
        raise ValueError(f"frame {frame.index}: the free interior needs grains and a packing fraction > 0")
    side = math.sqrt(math.pi * float(np.sum(r * r)) / frame.rho)
    if not 0 < box or side > box * (1 + 1e-9):
        raise ValueError(f"box {box!r}: smaller than the free interior of frame {frame.index} ({side:.6g} d, from "
                         f"its grains and rho {frame.rho:.6g}); is it this run's box?")
    return 0.5 * (box - side), 0.5 * (box + side)


def wall_disks(frame, walls):
    """The wall particles at `frame`, an (n, 3) array of x, y, r in d, placed as fnet-simd places
    them (server/dem/walls.cpp): four rows of touching disks of the wall diameter whose centres
    form a square ring half a diameter outside the free interior, bottom, right, top, left, each
    row moved inward by the walls' offset (free_interior)."""
    box, dw = walls["box"], walls["wall_diameter"]
    lo_interior, _ = free_interior(frame, walls)
    ring = box + dw
    per_side = math.ceil(ring / dw - 1e-9)
    t = np.arange(per_side) * (ring / per_side)
    lo, hi = -0.5 * dw + lo_interior, box + 0.5 * dw - lo_interior
    x = np.concatenate([-0.5 * dw + t, np.full(per_side, hi), box + 0.5 * dw - t, np.full(per_side, lo)])
    y = np.concatenate([np.full(per_side, lo), -0.5 * dw + t, np.full(per_side, hi), box + 0.5 * dw - t])
    return np.column_stack([x, y, np.full(4 * per_side, 0.5 * dw)])


def _segments(xy, pairs):
    return np.stack([xy[pairs[:, 0]], xy[pairs[:, 1]]], axis=1).reshape(-1, 2, 2)


def _grains(ax, particles):
    grains = PatchCollection([Circle((x, y), r) for x, y, r in particles], facecolor="none", edgecolor="0.6",
                             linewidth=0.3, gid="grains")
    ax.add_collection(grains)
    return grains


def _packing_axes(ax, frame, walls):
    """The walls (the "walls" collection of wall disks, or a rectangle), limits and length labels of
    a frame's axes; returns what the walls drawn are, for the caption."""
    particles = frame.particles
    lo = (particles[:, :2] - particles[:, 2:3]).min(axis=0) if len(particles) else np.zeros(2)
    hi = (particles[:, :2] + particles[:, 2:3]).max(axis=0) if len(particles) else np.ones(2)
    if walls is not None:
        disks = wall_disks(frame, walls)
        ax.add_collection(PatchCollection([Circle((x, y), r) for x, y, r in disks], facecolor="0.75",
                                          edgecolor="0.35", linewidth=0.4, gid="walls"))
        lo = np.minimum(lo, (disks[:, :2] - disks[:, 2:3]).min(axis=0))
        hi = np.maximum(hi, (disks[:, :2] + disks[:, 2:3]).max(axis=0))
        note = "grey disks: the walls, placed from the run's box and this frame's ρ"
    else:
        ax.add_patch(Rectangle(tuple(lo), *(hi - lo), fill=False, edgecolor="0.3", linestyle="--", linewidth=1.0,
                               gid="walls"))
        note = "dashed: the grains' bounding box (the run records no walls)"
    pad = 0.01 * float(max(hi - lo))
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel(r"$x / d$")
    ax.set_ylabel(r"$y / d$")
    return note


def dimension_of(frame_or_series, dimension=None):
    """2 or 3: `dimension` when given, else the `dimension` the frame or series carries (2 when it
    carries none)."""
    d = dimension if dimension is not None else frame_or_series.get("dimension", 2)
    if d not in (2, 3):
        raise ValueError(f"dimension: 2 or 3, not {d!r}")
    return int(d)


def _zs(frame):
    """The grains' z: a 3D frame's particle_z (fnet.store.Frame)."""
    z = frame.get("particle_z")
    if z is None or len(z) != len(frame.particles):
        raise ValueError(f"frame {frame.get('index')}: a 3D frame needs particle_z, the z of each of its "
                         f"{len(frame.particles)} particles")
    return np.asarray(z, dtype=np.float64)


def contact_points(frame, pairs):
    """(m, 3): the contact point of each pair (i, j) in 3D: on the line of centres at distance r_i
    from grain i's centre, as fnet's blocks place a contact (i's centre when the centres coincide)."""
    p = frame.particles
    centres = np.column_stack([p[:, 0], p[:, 1], _zs(frame)])
    a, b = centres[pairs[:, 0]], centres[pairs[:, 1]]
    length = np.linalg.norm(b - a, axis=1)
    step = np.divide(p[pairs[:, 0], 2], length, out=np.zeros(len(length)), where=length > 0)
    return a + (b - a) * step[:, None]


def slab_of(frame, half_width=SLAB_HALF_WIDTH, centre=None):
    """(lo, hi): the slab |z - centre| <= half_width of a 3D frame, centre the middle of its
    spheres' z extent (min z - r to max z + r) when not given."""
    if not half_width > 0:
        raise ValueError(f"slab: a half-width > 0 in d, not {half_width!r}")
    z, r = _zs(frame), frame.particles[:, 2]
    if centre is None:
        centre = 0.5 * (float((z - r).min()) + float((z + r).max())) if len(z) else 0.0
    return centre - half_width, centre + half_width


def in_slab(frame, pairs, slab):
    """Which pairs have their contact point in the slab (lo, hi), bounds included."""
    z = contact_points(frame, pairs)[:, 2]
    return (z >= slab[0]) & (z <= slab[1])


def slab_discs(frame, slab):
    """(indices, radii): the spheres that reach into the slab (lo, hi), and the radius of the disc
    each one's part inside the slab covers seen from +z: r for a centre inside, sqrt(r² - g²) for a
    centre at distance g < r outside."""
    z, r = _zs(frame), frame.particles[:, 2]
    gap = np.maximum(np.maximum(slab[0] - z, z - slab[1]), 0.0)
    keep = gap < r
    return np.flatnonzero(keep), np.sqrt(r[keep] ** 2 - gap[keep] ** 2)


def _frame_title(frame):
    # Two lines: a run's name is long, and one line would run under the colour bar or off the figure.
    return f"{frame.get('run', '')}\nframe {frame.index}, " + r"$\rho$" + f" = {frame.rho:.4f}, Z = {frame.z:.3f}"


def _frame_title_3d(frame):
    rho, z = frame.get("rho"), frame.get("z")
    numbers = [r"$\rho$" + f" = {rho:.4f} (volume fraction)" if rho is not None else None,
               f"Z = {z:.3f}" if z is not None else None]
    return f"{frame.get('run', '')}\nframe {frame.get('index')}, 3D" + "".join(f", {n}" for n in numbers if n)


def _contact_lines(ax, segments, values, cmap, top, gid="contacts"):
    lines = LineCollection(segments, array=values, cmap=cmap, norm=Normalize(0, top),
                           linewidths=0.4 + 1.6 * np.minimum(values / top, 1.0), gid=gid)
    ax.add_collection(lines)
    return lines


def network(frame, force="normal", cmap="viridis", grains=True, walls=None, slab=SLAB_HALF_WIDTH, z_centre=None,
            projection=False):
    """Fig. 1: a frame's force network. Contacts are segments between grain centres coloured by
    force / mean force (the "contacts" LineCollection: get_segments(), get_array()), the colour
    scale topped at the 99th percentile (colour_top; the maximum is in its label); grains are
    circles (the "grains" collection), in `frame`'s positions (a fnet.store.Frame). The "walls"
    are the wall disks when the run's `walls` are given (run_walls, wall_disks), else the grains'
    bounding box, dashed; the caption says which.

    A 3D frame (dimension_of(frame) 3) is seen from +z: the contacts whose contact point lies in
    the slab |z - z_centre| <= `slab` (d; z_centre the middle of the spheres' extent by default),
    their segments projected on xy and drawn weakest first so that strong chains stay on top, and
    the "grains" discs of slab_discs; with `projection`, every contact and no grains. Forces are
    normalized over the whole network either way; the caption states the slab and how many
    contacts it holds."""
    if dimension_of(frame) == 3:
        return _network_3d(frame, force, cmap, grains, walls, slab, z_centre, projection)
    pairs, values = normalized_network(frame, force)
    xy = frame.particles[:, :2]
    fig = _figure(6.4, 6.6)
    ax = fig.add_subplot()
    if grains:
        _grains(ax, frame.particles)
    top = colour_top(values)
    biggest = float(values.max()) if len(values) else 0.0
    lines = _contact_lines(ax, _segments(xy, pairs), values, cmap, top)
    fig.colorbar(lines, ax=ax, shrink=0.8, extend="max" if biggest > top else "neither",
                 label=f"{force} force, {FORCE_UNIT}\n(scale to the {COLOUR_PERCENTILE:g}th percentile; "
                       f"max {biggest:.3g})")
    fig.supxlabel(_packing_axes(ax, frame, walls), fontsize="small")
    ax.set_title(_frame_title(frame))
    return fig


def _no_walls(walls):
    if walls is not None:
        raise ValueError("walls: fnet-simd's walls are those of a 2D run; a 3D frame is drawn in its spheres' "
                         "bounding box")


def _view_3d(frame, pairs, slab, z_centre, projection, of_what):
    """(keep, bounds, where): which `pairs` a 3D figure of `frame` draws (those whose contact point
    lies in the slab, or all with `projection`), the slab's (lo, hi) (None for the projection) and
    the caption saying so; `of_what` names the pairs ("of the network")."""
    if projection:
        return (np.ones(len(pairs), dtype=bool), None,
                f"every contact {of_what} ({len(pairs)}), projected on xy")
    bounds = slab_of(frame, slab, z_centre)
    keep = in_slab(frame, pairs, bounds)
    return keep, bounds, (f"the {int(keep.sum())} of {len(pairs)} contacts {of_what} whose contact point lies in "
                          f"the slab\n{bounds[0]:.2f} ≤ z ≤ {bounds[1]:.2f} ({2 * slab:g} d thick), seen from +z; "
                          "circles: each sphere's part inside the slab")


def _slab_grains(ax, frame, bounds):
    """The "grains" discs of slab_discs: each sphere's part inside the slab, seen from +z."""
    indices, radii = slab_discs(frame, bounds)
    p = frame.particles
    ax.add_collection(PatchCollection([Circle((p[g, 0], p[g, 1]), rad) for g, rad in zip(indices, radii)],
                                      facecolor="none", edgecolor="0.6", linewidth=0.3, gid="grains"))


def _network_3d(frame, force, cmap, grains, walls, slab, z_centre, projection):
    _no_walls(walls)
    pairs, values = normalized_network(frame, force)
    top = colour_top(values)
    keep, bounds, where = _view_3d(frame, pairs, slab, z_centre, projection, "of the network")
    order = np.argsort(values[keep], kind="stable")  # weakest first: strong chains drawn on top
    shown, shown_values = pairs[keep][order], values[keep][order]
    fig = _figure(6.4, 6.9)
    ax = fig.add_subplot()
    if grains and not projection:
        _slab_grains(ax, frame, bounds)
    biggest = float(values.max()) if len(values) else 0.0
    lines = _contact_lines(ax, _segments(frame.particles[:, :2], shown), shown_values, cmap, top)
    fig.colorbar(lines, ax=ax, shrink=0.8, extend="max" if biggest > top else "neither",
                 label=f"{force} force, {FORCE_UNIT} (over the whole network)\n(scale to the "
                       f"{COLOUR_PERCENTILE:g}th percentile; max {biggest:.3g})")
    box = _packing_axes(ax, frame, None)
    fig.supxlabel(f"{where}\n{box}", fontsize="small")
    ax.set_title(_frame_title_3d(frame))
    return fig


def contact_states(before, after, force="normal"):
    """(pairs, f_before, f_after): the contacts of either frame's network, as (i, j) with i < j
    sorted, and each one's normalized force in `before` and in `after`, NaN where it is not in that
    frame's network (created: NaN before; broken: NaN after)."""
    forces = {}
    for k, frame in enumerate((before, after)):
        pairs, values = normalized_network(frame, force)
        for (i, j), v in zip(pairs.tolist(), values.tolist()):
            forces.setdefault((min(i, j), max(i, j)), [math.nan, math.nan])[k] = v
    keys = sorted(forces)
    states = np.array([forces[key] for key in keys], dtype=np.float64).reshape(-1, 2)
    return np.array(keys, dtype=np.int64).reshape(-1, 2), states[:, 0], states[:, 1]


def contact_change(before, after, force="normal"):
    """(pairs, change): the contacts of either frame's network, sorted by (i, j), and for each its
    normalized force in `after` minus that in `before` (0 where absent)."""
    pairs, f_before, f_after = contact_states(before, after, force)
    return pairs, np.nan_to_num(f_after, nan=0.0) - np.nan_to_num(f_before, nan=0.0)


def network_change(before, after, force="normal", cmap=CHANGE_CMAP, grains=True, walls=None, slab=SLAB_HALF_WIDTH,
                   z_centre=None, projection=False):
    """The difference between two frames' force networks, drawn in `after`'s positions: the
    contacts of both networks (the "contacts" LineCollection) coloured by their normalized force in
    `after` minus that in `before` (the scale topped at the 99th percentile of |change|), the
    contacts created (in `after` only: "created", green, solid) and broken (in `before` only:
    "broken", grey, dashed); each collection's contacts in the order of contact_states. `walls`
    as in network().

    Two 3D frames are seen from +z as network() sees one, in `after`'s positions: the contacts of
    either network whose contact point lies in `after`'s slab (`slab`, `z_centre`), or every one
    with `projection`, and the "grains" discs of the slab; the "contacts" are drawn smallest
    |change| first, so that the largest changes stay on top. The changes and their colour scale are
    those of the whole networks either way."""
    dimension = dimension_of(after)
    if dimension_of(before) != dimension:
        raise ValueError(f"before and after: two frames of one dimension, not {dimension_of(before)}D and "
                         f"{dimension}D")
    pairs, f_before, f_after = contact_states(before, after, force)
    created, broken = np.isnan(f_before), np.isnan(f_after)
    kept = ~created & ~broken
    change = f_after - f_before  # NaN but where kept
    span = colour_top(np.abs(change[kept]))
    biggest = float(np.abs(change[kept]).max()) if kept.any() else 0.0
    order = np.arange(len(pairs))
    if dimension == 3:
        _no_walls(walls)
        shown, bounds, where = _view_3d(after, pairs, slab, z_centre, projection, "of either network")
        order = order[shown]
        order = order[np.argsort(np.abs(np.nan_to_num(change[order])), kind="stable")]
    pairs, created, broken, kept, change = pairs[order], created[order], broken[order], kept[order], change[order]
    segments = _segments(after.particles[:, :2], pairs)
    fig = _figure(6.4, 6.6 if dimension == 2 else 7.2)
    ax = fig.add_subplot()
    if grains and dimension == 2:
        _grains(ax, after.particles)
    elif grains and not projection:
        _slab_grains(ax, after, bounds)
    lines = LineCollection(segments[kept], array=change[kept], cmap=cmap, norm=TwoSlopeNorm(0, -span, span),
                           linewidths=0.4 + 1.6 * np.minimum(np.abs(change[kept]) / span, 1.0), gid="contacts",
                           zorder=2)
    ax.add_collection(lines)
    ax.add_collection(LineCollection(segments[broken], colors="black", linewidths=0.9, linestyles=(0, (3, 2)),
                                     gid="broken", zorder=3))
    ax.add_collection(LineCollection(segments[created], colors="tab:green", linewidths=1.2, gid="created", zorder=3))
    whole = " (over the whole networks)" if dimension == 3 else ""
    fig.colorbar(lines, ax=ax, shrink=0.7, extend="both" if biggest > span else "neither",
                 label=f"change of {force} force, {FORCE_UNIT}{whole}\n(scale to the {COLOUR_PERCENTILE:g}th "
                       f"percentile of |change|; max {biggest:.3g})")
    handles = [Line2D([], [], color="tab:green", linewidth=1.2, label=f"created ({int(created.sum())})"),
               Line2D([], [], color="black", linewidth=0.9, linestyle=(0, (3, 2)),
                      label=f"broken ({int(broken.sum())})"),
               Line2D([], [], color=lines.cmap(0.5), linewidth=1.2,
                      label=f"in both ({int(kept.sum())}): colour = change")]
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=3, fontsize="small",
              frameon=False)
    if dimension == 2:
        fig.supxlabel(_packing_axes(ax, after, walls), fontsize="small")
    else:
        fig.supxlabel(f"{where}\n{_packing_axes(ax, after, None)}", fontsize="small")
    ax.set_title(f"{after.get('run', '')}\nframe {before.index} → {after.index}" + (", 3D" if dimension == 3 else "")
                 + ", " + r"$\rho$" + f" = {before.rho:.4f} → {after.rho:.4f}"
                 + (VOLUME_FRACTION if dimension == 3 else ""))
    return fig


def multiplicity(points):
    """(distinct, counts): the distinct rows of an (n, 2) array of points, sorted, and how many
    times each occurs."""
    points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if not len(points):
        return points, np.zeros(0, dtype=np.int64)
    distinct, counts = np.unique(points, axis=0, return_counts=True)
    return distinct, counts.astype(np.int64)


def marker_area(counts, base=14.0):
    """The marker area (points²) of a diagram point standing for `counts` coinciding points: it
    grows as the count's square root (a count above 1 is also written beside it)."""
    return base * np.sqrt(np.asarray(counts, dtype=np.float64))


def _counted_scatter(ax, xy, counts, gid, **style):
    ax.scatter(xy[:, 0], xy[:, 1], s=marker_area(counts), gid=gid, **style)
    for (x, y), n in zip(xy.tolist(), counts.tolist()):
        if n > 1:
            ax.annotate(f"×{n}", (x, y), xytext=(4, 3), textcoords="offset points", fontsize=7, color="0.2",
                        gid="count")


def diagrams(pd0, pd1, title=None):
    """Fig. 3: persistence diagrams PD0 and PD1 (each an (n, 2) array of birth, death; death -1:
    never dies), birth on x, death on y, in units of the mean force, with the diagonal (the
    "diagonal" line). Coinciding points are drawn once (multiplicity): the "finite" scatter's
    offsets are the distinct finite points, each with a marker area by its count (marker_area) and
    the count written beside it (a "count" annotation) when above 1. Classes that never die are the
    "never_dies" scatter on a strip of their own above (the axes labelled "PDk never dies"), at
    their birth, y 0, counted likewise. The legend gives the number of points of each kind."""
    fig = _figure(10, 5.4)
    grid = fig.add_gridspec(2, 2, height_ratios=(1, 7))
    for k, points in enumerate((pd0, pd1)):
        points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        essential = points[:, 1] == -1
        finite, finite_counts = multiplicity(points[~essential])
        forever, forever_counts = multiplicity(np.column_stack([points[essential, 0], np.zeros(essential.sum())]))
        ax = fig.add_subplot(grid[1, k], label=f"PD{k}")
        strip = fig.add_subplot(grid[0, k], sharex=ax, label=f"PD{k} never dies")
        top = 1.05 * max(float(points[:, 0].max()) if len(points) else 0.0,
                         float(finite[:, 1].max()) if len(finite) else 0.0, 1e-12)
        ax.plot([0, top], [0, top], color="0.6", linewidth=0.8, gid="diagonal")
        _counted_scatter(ax, finite, finite_counts, "finite", color="C0", edgecolor="none", alpha=0.8)
        _counted_scatter(strip, forever, forever_counts, "never_dies", color="C3", marker="^", edgecolor="none")
        ax.set_xlim(-0.02 * top, top)  # a margin, so that a marker at 0 shows whole
        ax.set_ylim(-0.02 * top, top)
        ax.set_xlabel(f"birth, {FORCE_UNIT}")
        ax.set_ylabel(f"death, {FORCE_UNIT}")
        strip.set_ylim(-1, 1)
        strip.set_yticks([])
        strip.set_ylabel("never\ndies", rotation=0, ha="right", va="center", fontsize="small")
        strip.tick_params(labelbottom=False)
        strip.set_title(f"PD{k}: {len(points)} points")
        ax.legend(handles=[
            Line2D([], [], color="C0", marker="o", linestyle="none",
                   label=f"finite: {len(points) - int(essential.sum())} ({len(finite)} distinct)"),
            Line2D([], [], color="C3", marker="^", linestyle="none",
                   label=f"never die (death −1): {int(essential.sum())} ({len(forever)} distinct)"),
            Line2D([], [], color="0.6", linewidth=0.8, label="birth = death"),
            Line2D([], [], color="none", label="×n: n coinciding points")], loc="upper left", fontsize="small")
    if title:
        fig.suptitle(title)
    return fig


def _drawable(x, y, log):
    """Which points can be drawn: finite x and y, and on a log axis y > 0."""
    keep = np.isfinite(x) & np.isfinite(y)
    if log:
        keep &= y > 0
    return keep


def _neighbours(c, x):
    """neighbours[i]: whether point i and point i + 1 of a curve are next to each other, so that a
    line may join them. Binned curves: bin i's rho_hi is bin i + 1's rho_lo (else a bin of the grid
    holds no sample: a gap); without edges, with a bin_width w: floor(x / w) differ by one; else
    (a run's frames) every point is next to the following one."""
    n = len(x)
    if n < 2:
        return np.zeros(0, dtype=bool)
    if "rho_lo" in c and "rho_hi" in c and len(c["rho_lo"]) == n:
        lo, hi = np.asarray(c["rho_lo"], dtype=np.float64), np.asarray(c["rho_hi"], dtype=np.float64)
        return np.isclose(hi[:-1], lo[1:], rtol=1e-9, atol=1e-12)
    width = c.get("bin_width")
    if width:
        k = np.floor(np.asarray(x, dtype=np.float64) / float(width))
        return np.diff(k) == 1
    return np.ones(n - 1, dtype=bool)


def _gapped(x, y, keep, neighbours):
    """The kept points of (x, y) in order, with a NaN row between two consecutive kept points that
    are not neighbours (a point left out between them, or an empty bin): matplotlib breaks a line at
    NaN, so no line spans a gap."""
    xs, ys, prev = [], [], None
    for i in np.flatnonzero(keep):
        if prev is not None and not (i == prev + 1 and neighbours[prev]):
            xs.append(math.nan)
            ys.append(math.nan)
        xs.append(x[i])
        ys.append(y[i])
        prev = i
    return np.array(xs, dtype=np.float64), np.array(ys, dtype=np.float64)


def _mark_nonpositive(ax, x, y, color):
    """On a log axis: values <= 0 as open triangles on the bottom edge (the "nonpositive" line; its
    y data are 0 in axes coordinates), never as data."""
    at = np.isfinite(x) & np.isfinite(y) & (y <= 0)
    if at.any():
        ax.plot(x[at], np.zeros(at.sum()), linestyle="none", marker="v", markerfacecolor="none", color=color,
                transform=ax.get_xaxis_transform(), clip_on=False, gid="nonpositive")
    return int(at.sum())


def _rho_j_marks(ax, rho_j, axis):
    """Vertical lines at each rho_J ("rho_j", with its value ± standard error in the legend) and a
    band of ± one standard error. rho_j: a number, a dict {"mean", "standard_error"?, "label"?} (as
    ensembles.list has it), or a list of them; against rho - rho_J the line is at 0."""
    if rho_j is None:
        return
    items = rho_j if isinstance(rho_j, (list, tuple)) else [rho_j]
    for k, item in enumerate(items):
        item = {"mean": item} if not isinstance(item, dict) else item
        mean, se = item.get("mean"), item.get("standard_error")
        if mean is None or not math.isfinite(mean):
            continue
        x = 0.0 if axis == "rho_minus_rho_j" else float(mean)
        value = f"{mean:.4f}" + (f" ± {se:.4f}" if se is not None and math.isfinite(se) else "")
        who = f" ({item['label']})" if item.get("label") else ""
        ax.axvline(x, color="0.25", linestyle=("--", "-.", ":")[k % 3], linewidth=1.0, gid="rho_j",
                   label=r"$\rho_J$" + f" = {value}{who}")
        if se is not None and math.isfinite(se) and se > 0:
            ax.axvspan(x - se, x + se, color="0.25", alpha=0.12, linewidth=0)


def _log_limits(ax, means, lows, highs):
    """y limits of a log axis that hold every drawn mean and bar top, from a decade below the
    smallest mean at most (bars reaching lower, or to <= 0, are clipped there); the bottom."""
    bottom = float(np.min(means)) / 10.0
    lows = lows[lows > 0]
    if len(lows):
        bottom = max(bottom, min(float(np.min(lows)), float(np.min(means))) / 1.25)
    top = float(np.max(highs)) * 1.25
    ax.set_ylim(bottom, top)
    return bottom


def _z_line(ax, c, label):
    """Z against rho of curve c on a second axis ("z" line), broken at gaps like the curves."""
    twin = ax.twinx()
    x, z = np.asarray(c["rho"], dtype=np.float64), np.asarray(c["z"], dtype=np.float64)
    zx, zy = _gapped(x, z, np.isfinite(x) & np.isfinite(z), _neighbours(c, x))
    twin.plot(zx, zy, color="0.4", linestyle=":", marker=".", markersize=3, label="Z", gid="z")
    twin.set_ylabel(label)
    return twin


def _legend(ax, twin):
    """One legend holding the entries of both axes (the curves, rho_J, Z), below the axes so that it
    hides no data."""
    handles, labels = ax.get_legend_handles_labels()
    if twin is not None:
        h, l = twin.get_legend_handles_labels()
        handles, labels = handles + h, labels + l
    (twin or ax).legend(handles, labels, fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.13),
                        ncol=min(len(labels), 3) or 1, frameon=False)


def _rho_label(axis, curves, dimension):
    """The x label against rho: for a 3D run (`dimension`, else the first curve's) it says that rho
    is the volume fraction."""
    label = AXIS_LABELS.get(axis, AXIS_LABELS["rho"])
    three_d = dimension_of(curves[0] if curves else {}, dimension) == 3
    return label + VOLUME_FRACTION if three_d else label


def distances(series, labels=None, z=True, log=False, rho_j=None, title=None, dimension=None):
    """Distances between consecutive frames against rho (each `series` as Client.series or
    Store.series returns it, one or a list): one "distance" line per series through its drawable
    values (finite; > 0 on a log axis, `log`), broken (a NaN row) where a value between was left
    out; values <= 0 on a log axis are marked on its bottom edge ("nonpositive"). Z against rho on
    a second axis (the "z" line, of the first series); rho_j: vertical lines (see ensemble).
    `dimension` 3 (or a first series that carries it) labels rho as the volume fraction."""
    series = [series] if isinstance(series, dict) else list(series)
    fig = _figure()
    ax = fig.add_subplot()
    if log:
        ax.set_yscale("log")
    for k, s in enumerate(series):
        x, y = np.asarray(s["rho"], dtype=np.float64), np.asarray(s["value"], dtype=np.float64)
        gx, gy = _gapped(x, y, _drawable(x, y, log), _neighbours(s, x))
        label = labels[k] if labels else f"{s.get('run', '')} {_metric_label(s)}"
        ax.plot(gx, gy, marker=".", color=f"C{k}", label=label, gid="distance")
        if log:
            _mark_nonpositive(ax, x, y, f"C{k}")
    _rho_j_marks(ax, rho_j, "rho")
    ax.set_xlabel(_rho_label("rho", series, dimension))
    ax.set_ylabel("distance to the previous frame")
    twin = _z_line(ax, series[0], "Z") if z and series else None
    _legend(ax, twin)
    if title:
        ax.set_title(title, fontsize="medium")
    return fig


def ensemble(curves, labels=None, z=True, log=False, rho_j=None, title=None, dimension=None):
    """Figs. 6, 8, 9: ensemble mean ± standard error per bin of rho (each curve as
    Client.ensemble_series returns it, one or a list). Per curve, the "mean" line holds (rho, mean)
    of its drawable bins (finite mean; > 0 on a log axis, `log`) in order, with a NaN row wherever
    the next drawn bin is not the next bin of the grid (an empty bin, or one left out), so no line
    spans a gap; its error bars (the curve's ErrorbarContainer in ax.containers) span mean ±
    stderr, none where the standard error is undefined, and on a log axis their lower ends are
    clipped at the axis' bottom (never <= 0). Bins with a mean <= 0 on a log axis are marked on
    its bottom edge ("nonpositive"). The mean Z of the first curve's bins on a second axis ("z",
    in the legend). rho_j: the jamming point(s) as vertical lines ("rho_j") whose legend entries
    give the value ± standard error (_rho_j_marks). `dimension` as in distances."""
    curves = [curves] if isinstance(curves, dict) else list(curves)
    fig = _figure()
    ax = fig.add_subplot()
    axis = curves[0].get("axis", "rho") if curves else "rho"
    if log:
        ax.set_yscale("log")
    drawn = []
    for k, c in enumerate(curves):
        rho, mean, stderr = (np.asarray(c[key], dtype=np.float64) for key in ("rho", "mean", "stderr"))
        keep = _drawable(rho, mean, log)
        se = np.where(np.isfinite(stderr), stderr, 0.0)
        drawn.append((rho[keep], mean[keep], se[keep]))
        label = labels[k] if labels else f"{c.get('ensemble') or c.get('run')} {_metric_label(c)}"
        gx, gy = _gapped(rho, mean, keep, _neighbours(c, rho))
        ax.plot(gx, gy, marker=".", color=f"C{k}", label=label, gid="mean")
        if log:
            _mark_nonpositive(ax, rho, mean, f"C{k}")
    bottom = None
    if log and any(len(m) for _, m, _ in drawn):
        means = np.concatenate([m for _, m, _ in drawn])
        bottom = _log_limits(ax, means, np.concatenate([m - s for _, m, s in drawn]),
                             np.concatenate([m + s for _, m, s in drawn]))
    for k, (x, m, s) in enumerate(drawn):
        low = m - s if bottom is None else np.maximum(m - s, bottom)
        ax.errorbar(x, m, yerr=np.vstack([m - low, s]), fmt="none", capsize=2, color=f"C{k}")
    _rho_j_marks(ax, rho_j, axis)
    ax.set_xlabel(_rho_label(axis, curves, dimension))
    ax.set_ylabel("distance to the previous frame: mean ± s.e.")
    twin = _z_line(ax, curves[0], "mean Z") if z and curves else None
    _legend(ax, twin)
    if title:
        ax.set_title(title, fontsize="medium")
    return fig


def ratio(curves, labels=None, log=False, rho_j=None, title=None, dimension=None):
    """Figs. 7, 10: ratio curves d_B / d_Wq against rho (each as Client.ensemble_series(ratio=...)
    or Client.series(ratio=...) returns it): one "ratio" line per curve through its drawable values
    (finite; > 0 on a log axis), broken at gaps as ensemble's "mean" lines; rho_j and `dimension`
    as in ensemble."""
    curves = [curves] if isinstance(curves, dict) else list(curves)
    fig = _figure()
    ax = fig.add_subplot()
    axis = curves[0].get("axis", "rho") if curves else "rho"
    if log:
        ax.set_yscale("log")
    for k, c in enumerate(curves):
        y = np.asarray(c["mean"] if "mean" in c else c["value"], dtype=np.float64)
        x = np.asarray(c["rho"], dtype=np.float64)
        gx, gy = _gapped(x, y, _drawable(x, y, log), _neighbours(c, x))
        q = {"wasserstein1": "W1", "wasserstein2": "W2"}.get(c.get("ratio"), str(c.get("ratio")))
        label = labels[k] if labels else (f"{c.get('ensemble') or c.get('run')} $d_B / d_{{{q}}}$ "
                                          f"PD{c.get('dim', DEFAULT_DIM)}, {c.get('force', 'normal')}")
        ax.plot(gx, gy, marker=".", color=f"C{k}", label=label, gid="ratio")
        if log:
            _mark_nonpositive(ax, x, y, f"C{k}")
    _rho_j_marks(ax, rho_j, axis)
    ax.set_xlabel(_rho_label(axis, curves, dimension))
    ax.set_ylabel("ratio of distances")
    _legend(ax, None)
    if title:
        ax.set_title(title, fontsize="medium")
    return fig


def block_text(value):
    """How a block's distance is written in its cell."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    return "∞" if math.isinf(value) else f"{value:.3g}"


def _normalization_note(table, whole):
    note = CELL_NORMALIZATION
    if whole is not None:
        note += f" ({_metric_label(table).split(' PD')[0]} of the whole frame: {block_text(float(whole))})"
    return note


def blocks(table, network=None, whole=None, walls=None):
    """Tables II, III: the k x k block distances of blocks.get (as Client.blocks returns it).

    Without `network`, a heat map (the "blocks" image, row 0 = lowest y at the bottom), each cell's
    value written in it (block_text), the largest framed. With `network` (the fnet.store.Frame of
    the table's `frame` or `other_frame`), the grid is drawn over that frame's packing at the cells'
    bounds for it: the "cells" rectangles (their get_array() the values, row by row) over the
    network's "contacts", each value written in its cell. Either way the figure states that each
    cell is normalized by its own mean force, with the distance of the whole frame when `whole` is
    given (a cell's distance can exceed it); `walls` as in network().

    A 3D table (k x k x k, indexed [layer, row, col]) is drawn as k heat maps side by side, one per
    layer from the lowest z, on one colour scale: each layer's "blocks" image, its cells' texts
    "block_{layer}_{row}_{col}", the largest framed in its layer."""
    value = np.asarray(table["value"], dtype=np.float64)
    if value.ndim == 3:
        if network is not None:
            raise ValueError("network: a 3D table (k x k x k) is drawn as its layers, not over a packing")
        return _blocks_layers(table, value, whole)
    if network is not None:
        return _blocks_over(table, network, whole, walls)
    k = value.shape[0]
    fig = _figure(5.6, 5.0)
    ax = fig.add_subplot()
    finite = value[np.isfinite(value)]
    image = ax.imshow(np.where(np.isfinite(value), value, np.nan), origin="lower", cmap="magma_r",
                      vmin=0, vmax=float(finite.max()) if len(finite) and finite.max() > 0 else 1.0, gid="blocks")
    for r in range(k):
        for c in range(k):
            ax.text(c, r, block_text(float(value[r, c])), ha="center", va="center", fontsize=9,
                    color="black", gid=f"block_{r}_{c}",
                    bbox={"facecolor": "white", "alpha": 0.6, "edgecolor": "none", "pad": 1})
    largest = table.get("largest")
    if largest:
        ax.add_patch(Rectangle((largest["col"] - 0.5, largest["row"] - 0.5), 1, 1, fill=False, edgecolor="C0",
                               linewidth=2.5, gid="largest"))
    ax.set_xticks(range(k))
    ax.set_yticks(range(k))
    ax.set_xlabel("column (x)")
    ax.set_ylabel("row (y)")
    fig.colorbar(image, ax=ax, label=_metric_label(table) + ", per cell")
    ax.set_title(f"{table.get('run', '')} frames {table.get('frame')} → {table.get('other_frame')}, k = {k}")
    fig.supxlabel(_normalization_note(table, whole), fontsize="small")
    return fig


def _blocks_layers(table, value, whole):
    k = value.shape[0]
    finite = value[np.isfinite(value)]
    top = float(finite.max()) if len(finite) and finite.max() > 0 else 1.0
    fig = _figure(2.4 + 2.6 * k, 3.9)
    axes = fig.subplots(1, k, squeeze=False)[0]
    largest = table.get("largest")
    for layer, ax in enumerate(axes):
        image = ax.imshow(np.where(np.isfinite(value[layer]), value[layer], np.nan), origin="lower", cmap="magma_r",
                          vmin=0, vmax=top, gid="blocks")
        for r in range(k):
            for c in range(k):
                ax.text(c, r, block_text(float(value[layer, r, c])), ha="center", va="center",
                        fontsize=9 if k <= 4 else 6, color="black", gid=f"block_{layer}_{r}_{c}",
                        bbox={"facecolor": "white", "alpha": 0.6, "edgecolor": "none", "pad": 1})
        if largest and largest.get("layer") == layer:
            ax.add_patch(Rectangle((largest["col"] - 0.5, largest["row"] - 0.5), 1, 1, fill=False, edgecolor="C0",
                                   linewidth=2.5, gid="largest"))
        ax.set_xticks(range(k))
        ax.set_yticks(range(k))
        ax.set_xlabel("column (x)")
        ax.set_ylabel("row (y)" if layer == 0 else "")
        end = " (lowest z)" if layer == 0 else " (highest z)" if layer == k - 1 else ""
        ax.set_title(f"layer {layer}{end}", fontsize="medium")
    fig.colorbar(image, ax=list(axes), shrink=0.9, label=_metric_label(table) + ", per cell")
    fig.suptitle(f"{table.get('run', '')} frames {table.get('frame')} → {table.get('other_frame')}, "
                 f"k = {k}: {k} × {k} × {k} cells")
    fig.supxlabel(_normalization_note(table, whole), fontsize="small")
    return fig


def _blocks_over(table, network, whole, walls):
    if network.index not in (table.get("frame"), table.get("other_frame")):
        raise ValueError(f"network: frame {network.index} is neither frame of the table ({table.get('frame')}, "
                         f"{table.get('other_frame')})")
    which = 0 if network.index == table.get("frame") else 1
    value = np.asarray(table["value"], dtype=np.float64)
    bounds = np.asarray(table["bounds"], dtype=np.float64)[:, :, which]  # [row, col] -> x_lo, x_hi, y_lo, y_hi
    k = value.shape[0]
    fig = _figure(6.6, 6.8)
    ax = fig.add_subplot()
    _grains(ax, network.particles)
    pairs, forces = normalized_network(network, table.get("force", "normal"))
    top = colour_top(forces)
    ax.add_collection(LineCollection(_segments(network.particles[:, :2], pairs), colors="0.15",
                                     linewidths=0.2 + 1.2 * np.minimum(forces / top, 1.0), gid="contacts", zorder=3))
    finite = value[np.isfinite(value)]
    cells = PatchCollection([Rectangle((b[0], b[2]), b[1] - b[0], b[3] - b[2]) for b in bounds.reshape(-1, 4)],
                            array=value.reshape(-1), cmap="YlOrRd", alpha=0.5, edgecolor="black", linewidth=1.2,
                            norm=Normalize(0, float(finite.max()) if len(finite) and finite.max() > 0 else 1.0),
                            gid="cells", zorder=2)
    ax.add_collection(cells)
    for r in range(k):
        for c in range(k):
            x_lo, x_hi, y_lo, y_hi = bounds[r, c]
            ax.text(0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi), block_text(float(value[r, c])), ha="center",
                    va="center", fontsize=11, color="black", gid=f"block_{r}_{c}", zorder=5,
                    bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none", "pad": 1.5})
    largest = table.get("largest")
    if largest:
        x_lo, x_hi, y_lo, y_hi = bounds[largest["row"], largest["col"]]
        ax.add_patch(Rectangle((x_lo, y_lo), x_hi - x_lo, y_hi - y_lo, fill=False, edgecolor="C0", linewidth=3,
                               gid="largest", zorder=4))
    _packing_axes(ax, network, walls)
    fig.colorbar(cells, ax=ax, shrink=0.8, label=_metric_label(table) + ", per cell")
    ax.set_title(f"{table.get('run', '')}\nframes {table.get('frame')} → {table.get('other_frame')}, k = {k}, "
                 f"drawn over frame {network.index}")
    fig.supxlabel(_normalization_note(table, whole), fontsize="small")
    return fig
