"""The paper's figures with matplotlib, drawn headless (Agg) on Figure objects of their own (no
pyplot state: safe in scripts, servers and notebooks, where a returned Figure displays itself).

Each function takes the data it plots — what fnet.Client or fnet.store return — and returns the
Figure. The artists that carry the data have a gid (`artist.get_gid()`), so that what was drawn can
be checked against what was served: "contacts", "grains", "finite", "never_dies", "distance",
"z", "mean", "ratio", "blocks".
"""

import math

import numpy as np

try:
    import matplotlib  # noqa: F401
except ImportError as e:  # a python3 other than Debian's (a pyenv one, say) may lack it
    raise ImportError(f"fnet.figures needs matplotlib: Debian's python3 (/usr/bin/python3) with "
                      f"python3-matplotlib ({e})") from e
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection, PatchCollection
from matplotlib.colors import Normalize, TwoSlopeNorm
from matplotlib.figure import Figure
from matplotlib.patches import Circle, Rectangle

METRIC_SYMBOLS = {"bottleneck": "d_B", "wasserstein1": "d_{W1}", "wasserstein2": "d_{W2}"}
AXIS_LABELS = {"rho": r"$\rho$", "rho_minus_rho_j": r"$\rho - \rho_J$"}


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
    return f"${symbol}$ PD{r.get('dim', 0)}, {r.get('force', 'normal')} forces"


def normalized_network(frame, force="normal"):
    """The contacts of a frame's force network as fnet builds it: those whose force magnitude is
    > 0, each as (i, j, force / mean force over exactly those contacts). Returns (pairs, values)."""
    forces = frame.forces(force)
    keep = forces > 0
    pairs = frame.contact_pairs[keep]
    values = forces[keep]
    return pairs, (values / values.mean() if len(values) else values)


def _grains(ax, particles):
    grains = PatchCollection([Circle((x, y), r) for x, y, r in particles], facecolor="none", edgecolor="0.6",
                             linewidth=0.3, gid="grains")
    ax.add_collection(grains)
    return grains


def _frame_axes(ax, particles):
    if len(particles):
        lo = (particles[:, :2] - particles[:, 2:3]).min(axis=0)
        hi = (particles[:, :2] + particles[:, 2:3]).max(axis=0)
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")


def network(frame, force="normal", cmap="viridis", grains=True):
    """Fig. 1: a frame's force network. Contacts are segments between grain centres coloured by
    force / mean force (the "contacts" LineCollection: get_segments(), get_array()), grains are
    circles (the "grains" collection), in `frame`'s positions (a fnet.store.Frame)."""
    pairs, values = normalized_network(frame, force)
    xy = frame.particles[:, :2]
    fig = _figure(6.4, 6.4)
    ax = fig.add_subplot()
    if grains:
        _grains(ax, frame.particles)
    top = values.max() if len(values) else 1.0
    lines = LineCollection(np.stack([xy[pairs[:, 0]], xy[pairs[:, 1]]], axis=1).reshape(-1, 2, 2), array=values,
                           cmap=cmap, norm=Normalize(0, top), linewidths=0.4 + 1.6 * values / top, gid="contacts")
    ax.add_collection(lines)
    fig.colorbar(lines, ax=ax, shrink=0.8, label=f"{force} force / mean")
    _frame_axes(ax, frame.particles)
    ax.set_title(f"{frame.get('run', '')} frame {frame.index}, " + r"$\rho$" + f" = {frame.rho:.4f}, Z = {frame.z:.3f}")
    return fig


def network_change(before, after, force="normal", cmap="RdBu_r", grains=True):
    """The difference between two frames' force networks: every contact of either frame, drawn in
    `after`'s positions, coloured by its normalized force in `after` minus that in `before` (0 where
    the contact is absent). The "contacts" LineCollection's get_array() holds the differences, in
    the order of `contact_change(before, after, force)`."""
    pairs, change = contact_change(before, after, force)
    xy = after.particles[:, :2]
    fig = _figure(6.4, 6.4)
    ax = fig.add_subplot()
    if grains:
        _grains(ax, after.particles)
    span = float(np.abs(change).max()) if len(change) and np.abs(change).max() > 0 else 1.0
    lines = LineCollection(np.stack([xy[pairs[:, 0]], xy[pairs[:, 1]]], axis=1).reshape(-1, 2, 2), array=change,
                           cmap=cmap, norm=TwoSlopeNorm(0, -span, span), linewidths=0.4 + 1.6 * np.abs(change) / span,
                           gid="contacts")
    ax.add_collection(lines)
    fig.colorbar(lines, ax=ax, shrink=0.8, label=f"change of {force} force / mean")
    _frame_axes(ax, after.particles)
    ax.set_title(f"{after.get('run', '')} frame {before.index} → {after.index}")
    return fig


def contact_change(before, after, force="normal"):
    """(pairs, change): the contacts of either frame's network, sorted by (i, j), and for each its
    normalized force in `after` minus that in `before` (0 where absent)."""
    forces = {}
    for sign, frame in ((-1.0, before), (1.0, after)):
        pairs, values = normalized_network(frame, force)
        for (i, j), v in zip(pairs.tolist(), values.tolist()):
            key = (min(i, j), max(i, j))
            forces[key] = forces.get(key, 0.0) + sign * v
    keys = sorted(forces)
    return np.array(keys, dtype=np.int64).reshape(-1, 2), np.array([forces[k] for k in keys], dtype=np.float64)


def never_dies_level(points):
    """Where a diagram's never-dying classes are drawn: a line below every finite death."""
    finite = points[points[:, 1] != -1] if len(points) else points
    values = np.concatenate([points[:, 0], finite[:, 1]]) if len(points) else np.array([0.0, 1.0])
    lo, hi = float(min(values.min(), 0.0)), float(values.max())
    return lo - 0.1 * max(hi - lo, 1e-12)


def diagrams(pd0, pd1, title=None):
    """Fig. 3: persistence diagrams PD0 and PD1 (each an (n, 2) array of birth, death; death -1:
    never dies), birth on x, death on y. Finite points are the "finite" scatter of each axes;
    classes that never die are drawn on a separate line below, the "never_dies" scatter, at
    y = never_dies_level(points)."""
    fig = _figure(10, 4.8)
    for k, points in enumerate((pd0, pd1)):
        ax = fig.add_subplot(1, 2, k + 1)
        points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        essential = points[:, 1] == -1
        finite, forever = points[~essential], points[essential]
        level = never_dies_level(points)
        top = float(points[:, 0].max()) if len(points) else 1.0
        ax.plot([level, top], [level, top], color="0.7", linewidth=0.8)
        ax.scatter(finite[:, 0], finite[:, 1], s=10, color="C0", label="finite", gid="finite")
        ax.axhline(level, color="0.7", linestyle="--", linewidth=0.8)
        ax.scatter(forever[:, 0], np.full(len(forever), level), s=12, marker="^", color="C3",
                   label=f"never dies ({len(forever)})", gid="never_dies")
        ax.set_xlabel("birth (force / mean)")
        ax.set_ylabel("death (force / mean)")
        ax.set_title(f"PD{k}: {len(points)} points")
        ax.legend(loc="upper left", fontsize="small")
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


def distances(series, labels=None, z=True, log=False, rho_j=None, title=None):
    """Distances between consecutive frames against rho (each `series` as Client.series or
    Store.series returns it, one or a list): one "distance" line per series through its drawable
    values (finite; > 0 on a log axis, `log`), broken (a NaN row) where a value between was left
    out; values <= 0 on a log axis are marked on its bottom edge ("nonpositive"). Z against rho on
    a second axis (the "z" line, of the first series); rho_j: vertical lines (see ensemble)."""
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
    ax.set_xlabel(AXIS_LABELS["rho"])
    ax.set_ylabel("distance to the previous frame")
    twin = _z_line(ax, series[0], "Z") if z and series else None
    _legend(ax, twin)
    if title:
        ax.set_title(title, fontsize="medium")
    return fig


def ensemble(curves, labels=None, z=True, log=False, rho_j=None, title=None):
    """Figs. 6, 8, 9: ensemble mean ± standard error per bin of rho (each curve as
    Client.ensemble_series returns it, one or a list). Per curve, the "mean" line holds (rho, mean)
    of its drawable bins (finite mean; > 0 on a log axis, `log`) in order, with a NaN row wherever
    the next drawn bin is not the next bin of the grid (an empty bin, or one left out), so no line
    spans a gap; its error bars (the curve's ErrorbarContainer in ax.containers) span mean ±
    stderr, none where the standard error is undefined, and on a log axis their lower ends are
    clipped at the axis' bottom (never <= 0). Bins with a mean <= 0 on a log axis are marked on
    its bottom edge ("nonpositive"). The mean Z of the first curve's bins on a second axis ("z",
    in the legend). rho_j: the jamming point(s) as vertical lines ("rho_j") whose legend entries
    give the value ± standard error (_rho_j_marks)."""
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
    ax.set_xlabel(AXIS_LABELS.get(axis, AXIS_LABELS["rho"]))
    ax.set_ylabel("distance to the previous frame: mean ± s.e.")
    twin = _z_line(ax, curves[0], "mean Z") if z and curves else None
    _legend(ax, twin)
    if title:
        ax.set_title(title, fontsize="medium")
    return fig


def ratio(curves, labels=None, log=False, rho_j=None, title=None):
    """Figs. 7, 10: ratio curves d_B / d_Wq against rho (each as Client.ensemble_series(ratio=...)
    or Client.series(ratio=...) returns it): one "ratio" line per curve through its drawable values
    (finite; > 0 on a log axis), broken at gaps as ensemble's "mean" lines; rho_j as in ensemble."""
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
                                          f"PD{c.get('dim', 0)}, {c.get('force', 'normal')}")
        ax.plot(gx, gy, marker=".", color=f"C{k}", label=label, gid="ratio")
        if log:
            _mark_nonpositive(ax, x, y, f"C{k}")
    _rho_j_marks(ax, rho_j, axis)
    ax.set_xlabel(AXIS_LABELS.get(axis, AXIS_LABELS["rho"]))
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


def blocks(table):
    """Tables II, III: the k x k block distances of blocks.get (as Client.blocks returns it) as a
    heat map (the "blocks" image, row 0 = lowest y at the bottom), each cell's value written in it
    (block_text), the largest framed."""
    value = np.asarray(table["value"], dtype=np.float64)
    k = value.shape[0]
    fig = _figure(5.6, 4.8)
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
    fig.colorbar(image, ax=ax, label=_metric_label(table))
    ax.set_title(f"{table.get('run', '')} frames {table.get('frame')} → {table.get('other_frame')}, k = {k}")
    return fig
