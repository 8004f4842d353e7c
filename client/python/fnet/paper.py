"""The paper's ensemble results (Kramar et al. 2014, Sec. IV) from a running fnet-server:
`curves.csv` (with its provenance in `curves.csv.json`), the figures, and `report.md`, whose every
finding is measured here and said to hold, not to hold, or to be undetermined, with its numbers
and their uncertainty. `python3 -m fnet paper-report --ensemble 0.5=mu05 --ensemble 0=mu0`.

Where the paper speaks of packing fractions (rho < 0.75, rho_J) this report measures relative to
each ensemble's own jamming point rho_J (where Z first reaches 3, mean over the realizations):
the paper's density convention is shifted from fnet's (how the walls enter the area), so its
absolute rho values are not ours.

Uncertainty: every finding's statistic is recomputed on bootstrap resamples of the realizations
(the runs, drawn with replacement; RESAMPLES of them from the fixed SEED), each run binned on its
own exactly as ensemble.series bins (aligned bins [k w, (k+1) w)) and a resample's curve the mean
over its runs of each run's bin mean. A check holds (or does not) only when the CONFIDENCE
percentile interval of its statistic lies inside (or outside) its accepted range; otherwise, or
with fewer than MIN_REALIZATIONS runs, it is undetermined."""

import csv
import json
import math
import os
import shutil
import signal
import tempfile
import time

import numpy as np

from fnet import figures, provenance

METRICS = ("bottleneck", "wasserstein1", "wasserstein2")
RATIOS = {"ratio_w1": "wasserstein1", "ratio_w2": "wasserstein2"}
FORCES = ("normal", "tangential")
DIMS = (0, 1)
CSV_COLUMNS = ("mu", "force", "dim", "metric", "rho", "mean", "stderr", "n", "n_runs", "z")
SYMBOLS = {"bottleneck": "$d_B$", "wasserstein1": "$d_{W1}$", "wasserstein2": "$d_{W2}$",
           "ratio_w1": "$d_B/d_{W1}$", "ratio_w2": "$d_B/d_{W2}$"}
TEXT_SYMBOLS = {"bottleneck": "d_B", "wasserstein1": "d_W1", "wasserstein2": "d_W2", "ratio_w1": "d_B/d_W1",
                "ratio_w2": "d_B/d_W2"}

RESAMPLES = 1000  # bootstrap resamples of the realizations
CONFIDENCE = 0.95  # the percentile interval reported and judged
SEED = 2014  # the bootstrap's random seed: the same data give the same intervals
MIN_REALIZATIONS = 3  # fewer: every verdict on that ensemble is undetermined
FEW_REALIZATIONS = 5  # fewer: the report warns that the intervals rest on few runs
# A ratio d_B / d_Wq this close to 1 is a single feature's change (d_B = d_Wq exactly when one
# point moved, or each frame pair of the bin moved one): degenerate, excluded from the statistics.
SINGLE_FEATURE = 1e-9
# The share of resamples whose statistic may be undefined before the interval's ends are unknown.
UNDEFINED_ALLOWED = (1 - CONFIDENCE) / 2
UNTESTED = (-math.inf, math.inf)  # the accepted range of a statistic only reported, not judged

CLAIMS = (
    "Before jamming, d_B is large (above 1 over most of the range): big localized events.",
    "Well before jamming (the paper's rho < 0.75; here the first half of the range below rho_J) d_B/d_W2 ~ 0.75 "
    "and d_B/d_W1 ~ 0.2, roughly constant.",
    "Approaching rho_J (the paper's rho ~ 0.75) d_B drops while d_W1 keeps rising: many small rearrangements.",
    "Through jamming the network changes globally; after rho_J every rate of change drops sharply, and the "
    "ratios settle one (d_B/d_W2) and three (d_B/d_W1) orders of magnitude below their pre-jamming values.",
    "Tangential forces evolve like the normal ones, except near rho_J where their d_W1, d_W2 are smaller.",
    "Frictionless systems jam at larger rho; after jamming their loop structure (PD1) changes about twice as "
    "fast as the frictional one.",
)

# How far past rho_J the jammed regime is taken to start, and the half-width of "near rho_J".
JAMMED_FROM = 0.01
NEAR_JAMMING = 0.01
# The start comparison looks at frames this far below their run's rho_J and lower.
BEFORE_JAMMING = 0.01


def collect(client, ensembles, bin_width):
    """Every curve of the report: {(mu, force, dim, metric): ensemble.series answer} for the
    metrics and the ratio curves (metric names of RATIOS), floor convention, against rho."""
    curves = {}
    for mu, name in ensembles.items():
        for force in FORCES:
            for dim in DIMS:
                for metric in METRICS:
                    curves[(mu, force, dim, metric)] = client.ensemble_series(
                        ensemble=name, metric=metric, dim=dim, force=force, bin_width=bin_width)
                for label, denominator in RATIOS.items():
                    curves[(mu, force, dim, label)] = client.ensemble_series(
                        ensemble=name, ratio=denominator, dim=dim, force=force, bin_width=bin_width)
    return curves


def _number(v):
    """Exact (shortest round-trip) text; empty for an undefined value."""
    v = float(v)
    if math.isnan(v):
        return ""
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    return repr(v)


def write_csv(path, curves):
    """curves.csv: one row per (mu, force, dim, metric, rho bin); rho is the mean rho of the bin's
    frames, mean/stderr/n/n_runs as ensemble.series serves them (stderr empty where undefined,
    n_runs empty where the server does not give it), z the bin's mean Z."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(CSV_COLUMNS)
        for (mu, force, dim, metric), c in curves.items():
            runs = c.get("n_runs")
            for k in range(len(c["rho"])):
                w.writerow([mu, force, dim, metric, _number(c["rho"][k]), _number(c["mean"][k]),
                            _number(c["stderr"][k]), int(c["n"][k]), "" if runs is None else int(runs[k]),
                            _number(c["z"][k])])


def read_csv(path):
    """curves.csv back as {(mu, force, dim, metric): {column: numpy array}}; n_runs -1 where empty."""
    out = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            key = (row["mu"], row["force"], int(row["dim"]), row["metric"])
            c = out.setdefault(key, {k: [] for k in ("rho", "mean", "stderr", "n", "n_runs", "z")})
            for k in ("rho", "mean", "stderr", "z"):
                c[k].append(float(row[k]) if row[k] else math.nan)
            c["n"].append(int(row["n"]))
            c["n_runs"].append(int(row["n_runs"]) if row.get("n_runs") else -1)
    return {key: {k: np.asarray(v) for k, v in c.items()} for key, c in out.items()}


def write_provenance(path, info):
    """A file's provenance sidecar (curves.csv.json): the fnet.provenance.describe dict as JSON."""
    with open(path, "w") as f:
        json.dump(info, f, indent=1, sort_keys=True)
        f.write("\n")


# ---- the realizations, one by one --------------------------------------------------------------

class Realizations:
    """One ensemble's runs, each binned on its own as ensemble.series bins the ensemble: a frame
    with a previous frame is a sample (its rho, Z and distance; rho, Z finite, the distance not
    NaN) in bin floor(rho / w), bins [k w, (k+1) w). For each curve key (force, dim, metric),
    `means[key]` is a (runs x bins) array of each run's mean distance in each bin (NaN where the run
    has no sample there) over the bins `index` (sorted, the union over runs and keys); `rho_j` each
    run's rho_J (NaN for none); `frames[run][key]` the run's samples (frame, rho, value)."""

    def __init__(self, name, runs, bin_width, series, rho_j):
        """series: {run: {key: {"frame", "rho", "z", "value"} arrays}} (what Client.series gives);
        rho_j: {run: rho_J or None}."""
        self.name, self.runs, self.width = name, list(runs), float(bin_width)
        if not self.width > 0 or not math.isfinite(self.width):
            raise ValueError(f"bin width must be a positive number, got {bin_width!r}")
        self.rho_j = np.array([math.nan if rho_j.get(r) is None else float(rho_j[r]) for r in self.runs])
        self.frames = {}
        binned = {}
        for r in self.runs:
            self.frames[r] = {}
            for key, s in series[r].items():
                rho, z, value = (np.asarray(s[k], dtype=np.float64) for k in ("rho", "z", "value"))
                use = np.isfinite(rho) & np.isfinite(z) & ~np.isnan(value)
                frame = np.asarray(s["frame"])[use] if "frame" in s else np.flatnonzero(use)
                self.frames[r][key] = {"frame": frame, "rho": rho[use], "value": value[use]}
                binned[(r, key)] = (np.floor(rho[use] / self.width).astype(np.int64), value[use])
        self.keys = sorted({key for r in self.runs for key in series[r]})
        self.index = np.unique(np.concatenate([k for k, _ in binned.values()] + [np.zeros(0, np.int64)]))
        column = {k: j for j, k in enumerate(self.index.tolist())}
        self.means = {}
        for key in self.keys:
            m = np.full((len(self.runs), len(self.index)), np.nan)
            for i, r in enumerate(self.runs):
                if (r, key) not in binned:
                    continue
                k, v = binned[(r, key)]
                for b in np.unique(k):
                    m[i, column[int(b)]] = np.mean(v[k == b])
            self.means[key] = m

    @property
    def centers(self):
        """Each bin's centre, (k + 1/2) w: where a bin sits when regions of rho are cut."""
        return (self.index + 0.5) * self.width

    def __len__(self):
        return len(self.runs)


def bootstrap_weights(n_runs, rng, resamples=RESAMPLES):
    """(1 + resamples, n_runs) multiplicities: row 0 every run once (the estimate), then each row a
    resample of the runs with replacement (how often each run was drawn)."""
    w = np.zeros((1 + resamples, n_runs))
    w[0] = 1
    if n_runs:
        draws = rng.integers(0, n_runs, size=(resamples, n_runs))
        np.add.at(w, (np.arange(1, resamples + 1)[:, None], draws), 1)
    return w


class Resampled:
    """An ensemble's curves for every row of a weight matrix (bootstrap_weights): a row's curve in
    a bin is the mean over its runs (with their multiplicity) of each run's bin mean, over the runs
    with a sample there (ensemble.series' mean with n_runs); its rho_J the mean of its runs' rho_J."""

    def __init__(self, data, weights):
        self.data, self.w = data, weights
        self.centers = data.centers
        has = np.isfinite(data.rho_j)
        self.rho_j = _divide(weights @ np.where(has, data.rho_j, 0.0), weights @ has)
        self._cache = {}

    def mean(self, force, dim, metric):
        key = (force, dim, metric)
        if key not in self._cache:
            m = self.data.means[key]
            has = ~np.isnan(m)
            self._cache[key] = _divide(self.w @ np.where(has, m, 0.0), self.w @ has)
        return self._cache[key]

    def ratio(self, force, dim, denominator):
        """d_B / d_Wq of the bin means, and {reason: mask} of the degenerate bins, which are NaN in
        the ratio: 0/0 (nothing changed), infinite, and single-feature ratios (within SINGLE_FEATURE
        of 1)."""
        num, den = self.mean(force, dim, "bottleneck"), self.mean(force, dim, denominator)
        present = ~np.isnan(num) & ~np.isnan(den)
        zero = present & (num == 0) & (den == 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            r = num / den
        infinite = present & ~zero & ~np.isfinite(r)
        single = present & np.isfinite(r) & (np.abs(r - 1) <= SINGLE_FEATURE)
        bad = {"single-feature (exactly 1)": single, "0/0": zero, "infinite": infinite}
        return np.where(present & ~zero & ~infinite & ~single, r, np.nan), bad


def _divide(a, b):
    """a / b elementwise, NaN where b is 0."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(b != 0, a / np.where(b != 0, b, 1), np.nan)


def _masked(values, mask):
    """values where mask and finite, NaN elsewhere."""
    return np.where(mask & np.isfinite(values), values, np.nan)


def _row_percentile(values, mask, q, at_least=1):
    """The q-th percentile (linear interpolation, as numpy's default) of each row over its masked
    finite entries; NaN for rows with fewer than `at_least` of them."""
    v = np.sort(_masked(values, mask), axis=1)  # NaN sorts last
    n = np.sum(~np.isnan(v), axis=1)
    out = np.full(v.shape[0], np.nan)
    rows = np.flatnonzero(n >= max(at_least, 1))
    if len(rows):
        pos = q / 100 * (n[rows] - 1)
        lo = np.floor(pos).astype(np.int64)
        hi = np.minimum(lo + 1, n[rows] - 1)
        a, b = v[rows, lo], v[rows, hi]
        out[rows] = a + (b - a) * (pos - lo)
    return out


def _row_median(values, mask):
    """The median of each row over its masked finite entries (NaN for none)."""
    return _row_percentile(values, mask, 50)


def _row_corr(x, y, mask):
    """Pearson's correlation of each row's masked pairs (NaN with fewer than 3 or no spread)."""
    m = mask & np.isfinite(x) & np.isfinite(y)
    n = m.sum(axis=1)
    x0, y0 = np.where(m, x, 0.0), np.where(m, y, 0.0)
    mx, my = _divide(x0.sum(axis=1), n), _divide(y0.sum(axis=1), n)
    dx, dy = np.where(m, x - mx[:, None], 0.0), np.where(m, y - my[:, None], 0.0)
    with np.errstate(invalid="ignore"):
        r = _divide((dx * dy).sum(axis=1), np.sqrt((dx * dx).sum(axis=1) * (dy * dy).sum(axis=1)))
    return np.where(n > 2, r, np.nan)


def _ratio_of(a, b):
    """a / b per row, NaN where either is 0 (a degenerate ratio of zero medians: nothing changed on
    one side, so no factor of change exists) or not finite."""
    ok = np.isfinite(a) & np.isfinite(b) & (b != 0) & (a != 0)
    out = np.full(np.shape(a), np.nan)
    np.divide(a, b, out=out, where=ok)
    return np.where(np.isfinite(out), out, np.nan)


def _log10(values):
    """log10 of the positive values, NaN for the others."""
    v = np.asarray(values, dtype=float)
    out = np.full(v.shape, np.nan)
    np.log10(v, out=out, where=v > 0)
    return out


def _median(values):
    return float(np.median(values)) if len(values) else math.nan


def _fmt(v, digits=3):
    return "n/a" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.{digits}g}"


def _range_text(lo, hi):
    if math.isinf(hi):
        return f">= {_fmt(lo)}"
    if math.isinf(lo):
        return f"<= {_fmt(hi)}"
    return f"{_fmt(lo)} to {_fmt(hi)}"


class Check:
    """One statistic of a finding: its estimate (on every realization once), its bootstrap
    interval, the range where the claim holds, and the verdict.

    values: (1 + resamples,) the statistic, row 0 the estimate; accept: (lo, hi), the claim holds
    for a value in [lo, hi]; runs: the number of realizations it rests on (the smaller ensemble's);
    excluded: {reason: count} of degenerate values left out of the estimate."""

    def __init__(self, label, values, accept, runs, excluded=None, note=""):
        values = np.asarray(values, dtype=np.float64)
        self.label, self.accept, self.runs, self.note = label, accept, runs, note
        self.excluded = {k: int(v) for k, v in (excluded or {}).items() if v}
        self.estimate = float(values[0])
        boot = values[1:]
        self.resamples = len(boot)
        self.undefined = int(np.sum(~np.isfinite(boot)))
        defined = boot[np.isfinite(boot)]
        tail = 100 * (1 - CONFIDENCE) / 2
        self.interval = (tuple(float(x) for x in np.percentile(defined, [tail, 100 - tail])) if len(defined)
                         else (math.nan, math.nan))

    @property
    def verdict(self):
        """"holds", "does not hold" or "undetermined"."""
        lo, hi = self.interval
        a, b = self.accept
        if self.runs < MIN_REALIZATIONS or not math.isfinite(self.estimate) or not math.isfinite(lo):
            return "undetermined"
        if self.undefined > UNDEFINED_ALLOWED * self.resamples:
            return "undetermined"
        if a <= lo and hi <= b:
            return "holds"
        if hi < a or lo > b:
            return "does not hold"
        return "undetermined"

    @property
    def why(self):
        """Why an undetermined check is undetermined ("" otherwise)."""
        if self.verdict != "undetermined":
            return ""
        if self.runs < MIN_REALIZATIONS:
            return f"{self.runs} realizations, fewer than {MIN_REALIZATIONS}"
        if not math.isfinite(self.estimate):
            return "the estimate is undefined"
        if not math.isfinite(self.interval[0]) or self.undefined > UNDEFINED_ALLOWED * self.resamples:
            return f"undefined in {self.undefined} of {self.resamples} resamples"
        return "the interval straddles the threshold"

    def text(self, digits=3):
        """"label estimate [interval] (holds for range: verdict, why) — notes, exclusions"; a
        statistic with the UNTESTED range has no verdict."""
        lo, hi = self.interval
        out = f"{self.label} {_fmt(self.estimate, digits)} [{_fmt(lo, digits)}, {_fmt(hi, digits)}]"
        if self.accept != UNTESTED:
            why = f", {self.why}" if self.why else ""
            out += f" (holds for {_range_text(*self.accept)}: {self.verdict}{why})"
        extra = [f"{n} {reason}" for reason, n in self.excluded.items()]
        if self.undefined and "undefined in" not in self.why:
            extra.append(f"undefined in {self.undefined} of {self.resamples} resamples")
        if self.note:
            extra.insert(0, self.note)
        return out + (" — " + ", ".join(extra) if extra else "")


class Finding:
    """A claim of the paper, what was measured, and its checks (None when it could not be
    measured)."""

    def __init__(self, claim, measured, checks, test):
        self.claim, self.measured, self.checks, self.test = claim, measured, checks, test

    @property
    def verdict(self):
        """"holds" / "does not hold" / "undetermined" when every check says so; "mixed: ..." naming
        the checks of each verdict otherwise; "not measurable" without checks."""
        if self.checks is None:
            return "not measurable"
        kinds = {}
        for c in self.checks:
            kinds.setdefault(c.verdict, []).append(c.label)
        if len(kinds) == 1:
            return next(iter(kinds))
        return "mixed: " + "; ".join(f"{kind} for {', '.join(kinds[kind])}"
                                     for kind in ("holds", "does not hold", "undetermined") if kind in kinds)


# ---- the findings ------------------------------------------------------------------------------

def _bins(k):
    return f"{int(k)} bin" + ("" if int(k) == 1 else "s")


def _count(mask, region):
    """How many of the estimate's (row 0's) bins in region the mask marks."""
    return int(np.sum(mask[0] & region[0]))


def _distances_excluded(values, region):
    return {"infinite": _count(np.isinf(values), region)}


def _ratio_excluded(bad, region):
    return {reason: _count(mask, region) for reason, mask in bad.items()}


def _zero_median(*medians):
    """The estimate's ratio of medians is degenerate when one of its medians is 0."""
    return {"ratio of zero medians": int(any(m[0] == 0 for m in medians))}


def findings(data, frictional="0.5", frictionless="0", seed=SEED, resamples=RESAMPLES):
    """The qualitative findings of the paper's Sec. IV, each measured on the realizations `data`
    ({mu: Realizations} holding the keys (force, dim, metric) of FORCES x DIMS x METRICS) with
    bootstrap intervals over them (Check). Regions of rho are cut at each bin's centre, relative to
    the mean rho_J of the runs (of each resample)."""
    rng = np.random.default_rng(seed)
    order = [m for m in (frictional, frictionless) if m in data] + [m for m in data if m not in (frictional,
                                                                                                   frictionless)]
    res = {m: Resampled(data[m], bootstrap_weights(len(data[m]), rng, resamples)) for m in order}
    mu = frictional
    e = res.get(mu)
    if e is None or not len(e.centers) or not math.isfinite(e.rho_j[0]):
        return [Finding(claim, f"not measurable: Z never reached 3 in the mu {mu} realizations, so rho_J is "
                        "unknown", None, "needs rho_J") for claim in CLAIMS]
    n = len(data[mu])
    jam = e.rho_j[:, None]
    x = e.centers[None, :]
    pre_lo = np.minimum(e.centers[0], jam)
    early_hi = pre_lo + (jam - pre_lo) / 2  # the first half of the unjammed range
    below = x < jam
    early = x < early_hi
    late = (x >= early_hi + (jam - early_hi) / 2) & below  # the last quarter of the unjammed range
    post = x >= jam + JAMMED_FROM
    out = []

    # 1. Before jamming d_B is large: above 1 over most of the range.
    checks = []
    for dim in DIMS:
        v = e.mean("normal", dim, "bottleneck")
        valid = below & np.isfinite(v)
        share = _divide(np.sum(valid & (v > 1), axis=1), np.sum(valid, axis=1))
        checks.append(Check(f"PD{dim} share of bins below rho_J with d_B > 1", share, (0.5, 1.0), n,
                            _distances_excluded(v, below),
                            note=f"median d_B {_fmt(_row_median(v, below)[0])} over {_bins(valid[0].sum())}"))
    out.append(Finding(CLAIMS[0], "; ".join(c.text() for c in checks), checks,
                       "holds if d_B > 1 in at least half of the bins below rho_J, PD0 and PD1"))

    # 2. Early ratios: d_B/d_W2 ~ 0.75, d_B/d_W1 ~ 0.2, roughly constant.
    checks = []
    for dim in DIMS:
        for label, target, lo, hi in (("ratio_w2", 0.75, 0.5, 1.0), ("ratio_w1", 0.2, 0.1, 0.4)):
            r, bad = e.ratio("normal", dim, RATIOS[label])
            name = f"PD{dim} {TEXT_SYMBOLS[label]}"
            checks.append(Check(f"{name} median", _row_median(r, early), (lo, hi), n, _ratio_excluded(bad, early),
                                note=f"paper ~{target}, {_bins(np.sum(early[0] & np.isfinite(r[0])))}"))
            spread = _ratio_of(_row_percentile(r, early, 90, 2), _row_percentile(r, early, 10, 2))
            checks.append(Check(f"{name} p90/p10", spread, (1.0, 2.0), n))
    out.append(Finding(
        CLAIMS[1], f"first half: rho < {early_hi[0, 0]:.4f}; " + "; ".join(c.text() for c in checks), checks,
        "holds if the median d_B/d_W2 is in [0.5, 1], d_B/d_W1 in [0.1, 0.4], and each one's 90th/10th "
        "percentile ratio at most 2, PD0 and PD1"))

    # 3. Approaching rho_J, d_B drops while d_W1 keeps rising.
    checks = []
    for dim in DIMS:
        for metric, accept in (("bottleneck", (0.0, 1.0)), ("wasserstein1", (1.0, math.inf))):
            v = e.mean("normal", dim, metric)
            m_early, m_late = _row_median(v, early), _row_median(v, late)
            checks.append(Check(f"PD{dim} {TEXT_SYMBOLS[metric]} last quarter / first half", _ratio_of(m_late, m_early),
                                accept, n, {**_distances_excluded(v, early | late), **_zero_median(m_early, m_late)}))
    out.append(Finding(
        CLAIMS[2], "; ".join(c.text() for c in checks), checks,
        "holds if the median d_B over the last quarter of the unjammed range is at most its median over the "
        "first half, and d_W1's at least, PD0 and PD1"))

    # 4. After rho_J every rate of change drops sharply; the ratios fall by ~1 (W2) and ~3 (W1) orders.
    checks = []
    for dim in DIMS:
        for metric in METRICS:
            v = e.mean("normal", dim, metric)
            m_pre, m_post = _row_median(v, below), _row_median(v, post)
            checks.append(Check(f"PD{dim} {TEXT_SYMBOLS[metric]} below / after rho_J", _ratio_of(m_pre, m_post),
                                (10.0, math.inf), n, {**_distances_excluded(v, below | post),
                                                       **_zero_median(m_pre, m_post)}))
    for dim in DIMS:
        for label, orders, lo, hi in (("ratio_w2", 1, 0.5, 1.5), ("ratio_w1", 3, 2.0, 4.0)):
            r, bad = e.ratio("normal", dim, RATIOS[label])
            m_early, m_post = _row_median(r, early), _row_median(r, post)
            checks.append(Check(f"PD{dim} {TEXT_SYMBOLS[label]} orders of magnitude fallen",
                                _log10(_ratio_of(m_early, m_post)), (lo, hi), n,
                                {**_ratio_excluded(bad, early | post), **_zero_median(m_early, m_post)},
                                note=f"paper {orders}; from {_fmt(m_early[0])} to {_fmt(m_post[0])}"))
    out.append(Finding(
        CLAIMS[3], "; ".join(c.text() for c in checks), checks,
        f"holds if each distance's median below rho_J is at least 10x its median from rho_J + {JAMMED_FROM} on, "
        "and the ratios fall by 0.5-1.5 (d_B/d_W2) and 2-4 (d_B/d_W1) orders, PD0 and PD1"))

    # 5. Tangential like normal, except near rho_J (smaller d_W1, d_W2 there).
    checks = []
    far = np.abs(x - jam) > 2 * NEAR_JAMMING
    near = np.abs(x - jam) <= NEAR_JAMMING
    for dim in DIMS:
        for metric in METRICS:
            vn, vt = e.mean("normal", dim, metric), e.mean("tangential", dim, metric)
            checks.append(Check(f"PD{dim} {TEXT_SYMBOLS[metric]} correlation of log10 normal and tangential "
                                f"away from rho_J", _row_corr(_log10(vn), _log10(vt), far), (0.9, 1.0), n,
                                {"zero or infinite": _count(~(vn > 0) | ~(vt > 0) | np.isinf(vn) | np.isinf(vt),
                                                            far & ~np.isnan(vn) & ~np.isnan(vt))}))
            if metric != "bottleneck":
                m_n, m_t = _row_median(vn, near), _row_median(vt, near)
                checks.append(Check(f"PD{dim} {TEXT_SYMBOLS[metric]} tangential / normal within {NEAR_JAMMING} of "
                                    "rho_J", _ratio_of(m_t, m_n), (0.0, 1.0), n, _zero_median(m_n, m_t)))
    out.append(Finding(
        CLAIMS[4], "; ".join(c.text() for c in checks), checks,
        f"holds if log10 of the normal and tangential curves correlate at 0.9 or more farther than "
        f"{2 * NEAR_JAMMING} from rho_J, and the tangential d_W1, d_W2 are at most the normal within "
        f"{NEAR_JAMMING} of rho_J"))

    # 6. Frictionless systems jam at larger rho; afterwards their loops change about twice as fast.
    f = res.get(frictionless)
    if f is not None and len(f.centers) and math.isfinite(f.rho_j[0]):
        both = min(n, len(data[frictionless]))
        checks = [Check(f"rho_J(mu {frictionless}) - rho_J(mu {frictional})", f.rho_j - e.rho_j, (0.0, math.inf), both,
                        note=f"rho_J {_fmt(e.rho_j[0], 4)} (mu {frictional}), {_fmt(f.rho_j[0], 4)} "
                             f"(mu {frictionless})")]
        texts = [checks[0].text(4)]
        for metric in METRICS:
            medians = []
            for g in (e, f):
                after = g.centers[None, :] - g.rho_j[:, None] >= JAMMED_FROM
                medians.append(_row_median(g.mean("normal", 1, metric), after))
            tested = metric == "wasserstein1"  # the paper's "about twice", judged on d_W1
            c = Check(f"PD1 {TEXT_SYMBOLS[metric]} after jamming, mu {frictionless} / mu {frictional}",
                      _ratio_of(medians[1], medians[0]), (1.4, 2.8) if tested else UNTESTED, both,
                      _zero_median(*medians))
            texts.append(c.text())
            if tested:
                checks.append(c)
        out.append(Finding(
            CLAIMS[5], "; ".join(texts), checks,
            f"holds if rho_J(mu {frictionless}) > rho_J(mu {frictional}) and the median PD1 d_W1 from "
            f"rho - rho_J = {JAMMED_FROM} on is 1.4-2.8x the frictional one (compared at equal rho - rho_J)"))
    else:
        out.append(Finding(CLAIMS[5], f"not measurable: no rho_J for mu {frictionless} (Z never reached 3, or no "
                           "such ensemble)", None, "needs both ensembles' rho_J"))
    return out


def compare_starts(a, b, empty, seed=SEED, resamples=RESAMPLES):
    """Two ensembles of the same system from different starts, before jamming: per ensemble the
    median PD1 d_B (normal forces) over the frames more than BEFORE_JAMMING below their run's rho_J
    (the ensemble's mean rho_J for a run without one; without any, the first half of the run's
    range), and the fraction of those frames whose PD1 is empty; bootstrap intervals over each
    ensemble's realizations, and of the differences b - a. `empty[(run, frame)]`: whether that
    frame's PD1 is empty. Returns {"rows": [(name, runs, median Check, fraction Check)], "differences":
    [Check, Check]}."""
    rng = np.random.default_rng(seed)
    key = ("normal", 1, "bottleneck")
    rows, stats = [], []
    for data in (a, b):
        w = bootstrap_weights(len(data), rng, resamples)
        fallback = float(np.nanmean(data.rho_j)) if np.isfinite(data.rho_j).any() else math.nan
        values, owner, empties, counts = [], [], [], []
        for i, r in enumerate(data.runs):
            s = data.frames[r][key]
            limit = data.rho_j[i] if math.isfinite(data.rho_j[i]) else fallback
            if math.isfinite(limit):
                pick = s["rho"] < limit - BEFORE_JAMMING
            else:
                pick = s["rho"] < (s["rho"].min() + s["rho"].max()) / 2 if len(s["rho"]) else s["rho"] > 0
            values.append(s["value"][pick])
            owner.append(np.full(int(pick.sum()), i))
            empties.append(sum(bool(empty[(r, int(f))]) for f in s["frame"][pick]))
            counts.append(int(pick.sum()))
        values, owner = np.concatenate(values + [np.zeros(0)]), np.concatenate(owner + [np.zeros(0, np.int64)])
        order = np.argsort(values, kind="stable")
        values, owner = values[order], owner[order]
        median = np.array([_weighted_median(values, row[owner]) for row in w])
        fraction = _divide(w @ np.array(empties, dtype=float), w @ np.array(counts, dtype=float))
        stats.append((median, fraction))
        rows.append((data.name, len(data), int(sum(counts)),
                     Check("median PD1 d_B", median, UNTESTED, len(data)),
                     Check("fraction of frames with an empty PD1", fraction, UNTESTED, len(data))))
    runs = min(len(a), len(b))
    differences = [Check(f"median PD1 d_B, {b.name} - {a.name}", stats[1][0] - stats[0][0], UNTESTED, runs),
                   Check(f"empty PD1 fraction, {b.name} - {a.name}", stats[1][1] - stats[0][1],
                         UNTESTED, runs)]
    return {"rows": rows, "differences": differences}


def _weighted_median(sorted_values, weights):
    """The median of sorted_values each repeated weights[k] (integer) times, as np.median of that
    repetition; NaN for no values."""
    cum = np.cumsum(weights)
    total = int(round(cum[-1])) if len(cum) else 0
    if total == 0:
        return math.nan
    lo = sorted_values[np.searchsorted(cum, (total - 1) // 2, side="right")]
    hi = sorted_values[np.searchsorted(cum, total // 2, side="right")]
    return float((lo + hi) / 2)


# ---- collecting the realizations ---------------------------------------------------------------

def collect_realizations(client, name, runs, rho_j, bin_width, keys=None):
    """Realizations of ensemble `name` from each member run's series.get (floor convention):
    keys (force, dim, metric), by default every one of FORCES x DIMS x METRICS; rho_j: {run: its
    rho_J or None} (runs.list)."""
    keys = keys or [(f, d, m) for f in FORCES for d in DIMS for m in METRICS]
    series = {r: {key: client.series(key[2], run=r, dim=key[1], force=key[0]) for key in keys} for r in runs}
    return Realizations(name, runs, bin_width, series, rho_j)


def _before_jamming(data, i, key=("normal", 1, "bottleneck")):
    """Which of run i's samples compare_starts takes: rho below the run's rho_J - BEFORE_JAMMING
    (the ensemble's mean rho_J for a run without one), else the first half of its range."""
    s = data.frames[data.runs[i]][key]
    limit = data.rho_j[i]
    if not math.isfinite(limit) and np.isfinite(data.rho_j).any():
        limit = float(np.nanmean(data.rho_j))
    if math.isfinite(limit):
        return s["rho"] < limit - BEFORE_JAMMING
    if not len(s["rho"]):
        return np.zeros(0, dtype=bool)
    return s["rho"] < (s["rho"].min() + s["rho"].max()) / 2


def empty_pd1(client, data, key=("normal", 1, "bottleneck")):
    """{(run, frame): PD1 (normal forces) is empty} for the frames compare_starts takes."""
    out = {}
    for i, r in enumerate(data.runs):
        s = data.frames[r][key]
        for f in s["frame"][_before_jamming(data, i, key)]:
            out[(r, int(f))] = len(client.diagram(int(f), run=r, dim=1, force="normal")) == 0
    return out


# ---- figures -----------------------------------------------------------------------------------

def system_text(mu, listed, realizations, plain=False):
    """The simulated system of an ensemble as ensembles.list describes it."""
    n, speed = listed.get("particles"), listed.get("compression_speed")
    speed = "n/a" if speed is None else f"{speed:g}"
    if plain:
        return f"mu = {mu}, N = {n}, v_c = {speed} d/tau_c, {realizations} realizations"
    return rf"$\mu$ = {mu}, N = {n}, $v_c$ = {speed} $d/\tau_c$, {realizations} realizations"


def _shifted(c, by):
    """A curve against rho - rho_J (its rho and bin edges shifted by -by)."""
    out = dict(c)
    for key in ("rho", "rho_lo", "rho_hi"):
        if key in out:
            out[key] = np.asarray(out[key], dtype=np.float64) - by
    out["axis"] = "rho_minus_rho_j"
    return out


def draw(curves, jam, systems, out_dir, info, bin_width, frictional="0.5", frictionless="0"):
    """The paper's Figs. 6-10 from the curves, on log axes, each with rho_J marked and the system in
    its title, saved with the provenance `info` (fnet.provenance.png_metadata) and its caption;
    jam: {mu: ensembles.list's rho_j}; systems: {mu: (title text, caption text)}. Returns {file
    name: caption}."""
    made = {}
    convention = "floor convention"

    def save(fig, name, caption):
        fig.savefig(os.path.join(out_dir, name), dpi=120,
                    metadata=provenance.png_metadata({**info, "figure": name, "caption": caption}))
        made[name] = caption

    def title(mu, what):
        return f"{systems[mu][0]}\n{what}, {convention}"

    bins = f"bins of rho {bin_width:g} wide; open triangles on the bottom edge: bins whose mean is 0"
    for dim in DIMS:
        mu = frictional
        rho_j = jam.get(mu)
        for fig_no, force in ((6, "normal"), (8, "tangential")):
            save(figures.ensemble([curves[(mu, force, dim, m)] for m in METRICS], labels=[SYMBOLS[m] for m in METRICS],
                                  log=True, rho_j=rho_j, title=title(mu, f"{force} forces, PD{dim}")),
                 f"fig{6 if force == 'normal' else 8}-{force}-pd{dim}.png",
                 f"Fig. {fig_no}, PD{dim}: d_B, d_W1, d_W2 between consecutive frames, {force} forces, "
                 f"{systems[mu][1]}; mean over the realizations ± standard error per bin ({bins}), mean Z "
                 f"on the right axis, rho_J ± its standard error as a vertical line; {convention}.")
        save(figures.ratio([curves[(mu, "normal", dim, r)] for r in RATIOS], labels=[SYMBOLS[r] for r in RATIOS],
                           log=True, rho_j=rho_j, title=title(mu, f"normal forces, PD{dim}")),
             f"fig7-ratios-pd{dim}.png",
             f"Fig. 7, PD{dim}: d_B/d_W1 and d_B/d_W2 (ratio of the bin means), normal forces, {systems[mu][1]}; "
             f"{bins}, rho_J as a vertical line; {convention}.")
        if (frictionless, "normal", dim, "bottleneck") in curves and frictional in jam and frictionless in jam \
                and jam[frictional].get("mean") is not None and jam[frictionless].get("mean") is not None:
            shifted, labels = [], []
            for m in (frictional, frictionless):
                for metric in ("bottleneck", "wasserstein2"):
                    shifted.append(_shifted(curves[(m, "normal", dim, metric)], jam[m]["mean"]))
                    labels.append(rf"{SYMBOLS[metric]}, $\mu$ = {m}")
            marks = [{**jam[m], "label": rf"$\mu$ = {m}"} for m in (frictional, frictionless)]
            save(figures.ensemble(shifted, labels=labels, z=False, log=True, rho_j=marks,
                                  title=f"{systems[frictional][0]}\n{systems[frictionless][0]}\nnormal forces, "
                                        f"PD{dim}, {convention}"),
                 f"fig9-friction-pd{dim}.png",
                 f"Fig. 9, PD{dim}: d_B and d_W2 of mu {frictional} against mu {frictionless} against rho - rho_J "
                 f"(each ensemble's mean rho_J, at 0), normal forces; {systems[frictional][1]}; "
                 f"{systems[frictionless][1]}; mean ± standard error per bin ({bins}); {convention}.")
            save(figures.ratio([curves[(frictionless, "normal", dim, r)] for r in RATIOS],
                               labels=[SYMBOLS[r] for r in RATIOS], log=True, rho_j=jam[frictionless],
                               title=title(frictionless, f"normal forces, PD{dim}")),
                 f"fig10-ratios-mu{frictionless}-pd{dim}.png",
                 f"Fig. 10, PD{dim}: d_B/d_W1 and d_B/d_W2, normal forces, {systems[frictionless][1]}; {bins}, "
                 f"rho_J as a vertical line; {convention}.")
    return made


# ---- blocks: where the network changed (Tables II, III) --------------------------------------

def block_tables(client, ensemble_name, rho_j, k=2):
    """For the ensemble's first realization: the k x k block distances (d_B and d_W2 of PD0 and
    PD1, normal forces) between consecutive frames just below, at, and after rho_J."""
    members = [e for e in client.ensembles() if e["ensemble"] == ensemble_name][0]["runs"]
    run = sorted(members)[0]
    s = client.series("bottleneck", run=run)
    frames, rho = np.asarray(s["frame"]), np.asarray(s["rho"])
    picks = []
    for label, target in (("below rho_J", rho_j - 0.02), ("at rho_J", rho_j), ("jammed", rho_j + 0.03)):
        k_at = int(np.argmin(np.abs(rho - target)))
        if k_at == 0:
            k_at = 1
        picks.append((label, int(frames[k_at - 1]), int(frames[k_at]), float(rho[k_at])))
    tables = []
    for label, a, b, r in picks:
        for dim in DIMS:
            for metric in ("bottleneck", "wasserstein2"):
                t = client.blocks(a, b, run=run, k=k, metric=metric, dim=dim)
                tables.append({"label": label, "run": run, "frame": a, "other_frame": b, "rho": r, "dim": dim,
                               "metric": metric, "table": t})
    return tables


def _block_markdown(t):
    value = np.asarray(t["table"]["value"], dtype=float)
    k = value.shape[0]
    head = "| row \\ col | " + " | ".join(str(c) for c in range(k)) + " |\n|---|" + "---|" * k + "\n"
    rows = "".join(f"| {r} | " + " | ".join(figures.block_text(float(value[r, c])) for c in range(k)) + " |\n"
                   for r in reversed(range(k)))
    return head + rows


# ---- the report --------------------------------------------------------------------------------

PROVENANCE_LINES = (("fnet_version", "fnet (the package that wrote this report)"), ("fnet_commit", "fnet commit"),
                    ("server_version", "fnet-server version"), ("server_commit", "fnet-server commit"),
                    ("date", "date (UTC)"), ("convention", "convention for classes that never die"),
                    ("method", "method"))


def write_report(path, info, setup, realizations, rho_j, found, made, tables, timings, compared=()):
    """report.md: its provenance, the setting, each finding with its numbers, their bootstrap
    intervals and whether it holds, the start comparison, the block tables, the figures with their
    captions, the timings. realizations: {mu: (ensemble name, number of runs)}."""
    lines = ["# The paper reproduced by fnet", "", "## Provenance", ""]
    lines += [f"- {label}: {info.get(key, 'unknown')}" for key, label in PROVENANCE_LINES]
    lines += [f"- uncertainty: {100 * CONFIDENCE:g} % percentile interval of a bootstrap over the realizations "
              f"({RESAMPLES} resamples of the runs with replacement, seed {SEED}); a check holds or does not only "
              f"when its interval lies inside or outside the range it is judged on, and is undetermined otherwise "
              f"or with fewer than {MIN_REALIZATIONS} realizations", "",
              "Kramar, Goulet, Kondic, Mischaikow (2014), Sec. IV: distances between consecutive frames of "
              "compressions through jamming, averaged over realizations, measured live by fnet-server.", "",
              "## Setting", ""]
    lines += [f"- {k}: {v}" for k, v in setup.items()]
    lines += [f"- realizations of mu {mu}: {n} (ensemble `{name}`)" for mu, (name, n) in realizations.items()]
    few = [(mu, n) for mu, (_, n) in realizations.items() if n < FEW_REALIZATIONS]
    if few:
        lines += ["", "> **Warning: few realizations** — " + ", ".join(f"mu {mu}: {n}" for mu, n in few) +
                  f" (fewer than {FEW_REALIZATIONS}). The intervals below rest on so few runs that they are "
                  f"rough; below {MIN_REALIZATIONS} every verdict is undetermined."]
    lines += ["", "Jamming points (rho where Z first reaches 3, interpolated; mean ± standard error over "
              "the realizations):", ""]
    lines += [f"- mu {mu}: rho_J = {_fmt(v['mean'], 5)} ± {_fmt(v['standard_error'])} (n = {v['n']})"
              for mu, v in rho_j.items()]
    lines += ["", "The paper's packing fractions are shifted from fnet's (its rho_J is lower: the density "
              "convention differs in how the walls enter the area), so every region below is taken "
              "relative to the ensemble's own rho_J, at each bin's centre. Curves: `curves.csv` (floor convention "
              "for classes that never die; ratio curves are the ratio of the bin means, as the paper plots). "
              "Degenerate values are left out of each statistic and counted beside it: ratios of exactly 1 "
              "(a single feature changed), 0/0, infinite values, ratios of zero medians.", "",
              "## Findings of the paper, measured here", ""]
    verdicts = [f.verdict.split(":")[0] for f in found]
    lines += [", ".join(f"{verdicts.count(v)} {v}" for v in ("holds", "does not hold", "undetermined", "mixed",
                                                               "not measurable") if v in verdicts)
              + f" (of {len(found)}).", ""]
    for n, f in enumerate(found, 1):
        lines += [f"### {n}. {f.claim}", "", f"- **{f.verdict}** ({f.test}).",
                  f"- measured (estimate [{100 * CONFIDENCE:g} % interval]): {f.measured}.", ""]
    for comparison in compared:
        lines += _comparison_markdown(comparison)
    if tables:
        lines += ["## Where the network changed (Tables II, III)", "",
                  "Block distances between consecutive frames of one realization, 2 x 2 cells over the grains' "
                  "bounding box (row 0 the bottom), normal forces:", ""]
        for t in tables:
            lines += [f"**{t['label']}** ({t['run']} frames {t['frame']} -> {t['other_frame']}, rho "
                      f"{t['rho']:.4f}), {t['metric']} PD{t['dim']}:", "", _block_markdown(t)]
    lines += ["## Figures", ""]
    for name, caption in made.items():
        lines += [f"![{caption}]({name})", "", f"*{caption}*", ""]
    if timings:
        lines += ["## Timings", ""] + [f"- {k}: {v}" for k, v in timings.items()]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def _comparison_markdown(c):
    lines = [f"## Two starts compared before jamming: `{c['rows'][0][0]}` and `{c['rows'][1][0]}`", "",
             f"Frames more than {BEFORE_JAMMING} below their run's rho_J (normal forces): the median PD1 d_B and "
             f"the fraction of frames whose PD1 is empty, with {100 * CONFIDENCE:g} % bootstrap intervals over "
             "each ensemble's realizations.", "",
             "| ensemble | realizations | frames | median PD1 d_B | empty PD1 |", "|---|---|---|---|---|"]
    for name, runs, frames, median, fraction in c["rows"]:
        lines.append(f"| `{name}` | {runs} | {frames} | {_interval_text(median)} | {_interval_text(fraction)} |")
    lines.append("")
    for d in c["differences"]:
        lo, hi = d.interval
        if d.runs < MIN_REALIZATIONS or not (math.isfinite(lo) and math.isfinite(hi)):
            said = f"undetermined ({d.runs} realizations, or undefined)"
        else:
            said = "differs from 0" if lo > 0 or hi < 0 else "no difference resolved (the interval holds 0)"
        lines.append(f"- {d.label}: {_interval_text(d)}: {said}.")
    return lines + [""]


def _interval_text(check):
    lo, hi = check.interval
    return f"{_fmt(check.estimate)} [{_fmt(lo)}, {_fmt(hi)}]"


def _publish(staging, out, names):
    """Moves the staged files into `out` (each os.replace: atomic), report.md last; a Ctrl-C during
    the moves is held until they are done (the report is then whole). When `out` does not exist
    yet, the staging folder itself becomes it."""
    held = []
    try:
        previous = signal.signal(signal.SIGINT, lambda *_: held.append(True))
    except ValueError:  # not the main thread: nothing to hold
        previous = None
    try:
        if not os.path.isdir(out):
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(staging, 0o777 & ~umask)  # mkdtemp's folder is private; the report's is not
            os.rename(staging, out)
            return
        for name in names:
            os.replace(os.path.join(staging, name), os.path.join(out, name))
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)


def _staging(out):
    """A temporary folder for the report's files: inside `out` when it exists (the same file
    system, so each file moves into place atomically), else beside it."""
    if os.path.isdir(out):
        return tempfile.mkdtemp(prefix=".paper-report-", dir=out)
    parent = os.path.dirname(os.path.abspath(out))
    os.makedirs(parent, exist_ok=True)
    return tempfile.mkdtemp(prefix=f".{os.path.basename(os.path.abspath(out))}-", dir=parent)


def main(args):
    """python3 -m fnet paper-report: everything above, into args.out (written into a temporary
    folder and moved into place at the end: interrupted, it leaves args.out as it was)."""
    from fnet.rpc import Client

    started = time.perf_counter()
    ensembles = dict(args.ensemble)
    frictional = next((mu for mu in ensembles if float(mu) > 0), next(iter(ensembles)))
    frictionless = next((mu for mu in ensembles if float(mu) == 0), None)
    setup = dict(s.split("=", 1) if "=" in s else (s, "") for s in args.setting)
    setup.update({f"ensemble mu {mu}": name for mu, name in ensembles.items()})
    comparisons = list(getattr(args, "compare_start", None) or [])
    timings = {}
    with Client(args.host, args.port) as c:
        status = c.status()
        listed = {e["ensemble"]: e for e in c.ensembles()}
        wanted = list(ensembles.values()) + [n for pair in comparisons for n in pair]
        missing = sorted({name for name in wanted if name not in listed})
        if missing:
            raise KeyError(f"no ensemble {', '.join(missing)} on the server")
        jam = {mu: listed[name]["rho_j"] for mu, name in ensembles.items()}
        run_rho_j = {r["run"]: r["rho_j"] for r in c.runs()}
        for mu, name in ensembles.items():
            setup[f"runs of mu {mu}"] = ", ".join(listed[name]["runs"])
        t0 = time.perf_counter()
        curves = collect(c, ensembles, args.bins)
        n_runs = sum(len(listed[n]['runs']) for n in ensembles.values())
        timings[f"ensemble.series, {len(curves)} curves over {n_runs} runs"] = \
            f"{1e3 * (time.perf_counter() - t0) / len(curves):.2f} ms per curve"
        t0 = time.perf_counter()
        data = {mu: collect_realizations(c, name, listed[name]["runs"], run_rho_j, args.bins)
                for mu, name in ensembles.items()}
        timings[f"series.get, {len(FORCES) * len(DIMS) * len(METRICS)} series of each of {n_runs} runs"] = \
            f"{time.perf_counter() - t0:.2f} s"
        by_name = {d.name: d for d in data.values()}
        compared = []
        for a, b in comparisons:
            pair = []
            for name in (a, b):
                d = by_name.get(name) or collect_realizations(c, name, listed[name]["runs"], run_rho_j, args.bins,
                                                              [("normal", 1, "bottleneck")])
                pair.append((d, empty_pd1(c, d)))
            compared.append(compare_starts(pair[0][0], pair[1][0], {**pair[0][1], **pair[1][1]}))
            setup[f"start comparison {a} against {b}"] = "see the section below"
        rho_j = {mu: v["mean"] for mu, v in jam.items() if v["mean"] is not None}
        tables = []
        if frictional in rho_j:
            t0 = time.perf_counter()
            tables = block_tables(c, ensembles[frictional], rho_j[frictional])
            timings[f"blocks.get, k = 2, {len(tables)} tables"] = \
                f"{1e3 * (time.perf_counter() - t0) / len(tables):.1f} ms per table"
    info = provenance.describe(
        server_status=status, bin_width=args.bins,
        ensembles="; ".join(f"mu {mu}: {name} ({len(listed[name]['runs'])} realizations)"
                            for mu, name in ensembles.items()),
        settings="; ".join(f"{k}={v}" for k, v in setup.items() if not k.startswith(("runs of", "start comparison"))))
    systems = {mu: (system_text(mu, listed[name], len(listed[name]["runs"])),
                    system_text(mu, listed[name], len(listed[name]["runs"]), plain=True))
               for mu, name in ensembles.items()}
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    staging = _staging(args.out)
    try:
        write_csv(os.path.join(staging, "curves.csv"), curves)
        write_provenance(os.path.join(staging, "curves.csv.json"), info)
        t0 = time.perf_counter()
        found = findings(data, frictional, frictionless or "0")
        timings[f"findings, {RESAMPLES} bootstrap resamples"] = f"{time.perf_counter() - t0:.2f} s"
        t0 = time.perf_counter()
        made = draw(curves, jam, systems, staging, info, args.bins, frictional, frictionless or "0")
        timings[f"figures, {len(made)}"] = f"{time.perf_counter() - t0:.2f} s"
        timings["the whole report"] = f"{time.perf_counter() - started:.2f} s"
        realizations = {mu: (name, len(listed[name]["runs"])) for mu, name in ensembles.items()}
        write_report(os.path.join(staging, "report.md"), info, setup, realizations, jam, found, made, tables,
                     timings, compared)
        _publish(staging, args.out, ["curves.csv", "curves.csv.json", *made, "report.md"])
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    for f in found:
        print(f"{f.verdict.split(':')[0]:>15}: {f.claim}")
    print(os.path.join(args.out, "report.md"))
    return 0
