"""The paper's ensemble results (Kramar et al. 2014, Sec. IV) from a running fnet-server:
`curves.csv`, the figures, and `report.md`, whose every finding is measured here and said to hold
or not, with its numbers. `python3 -m fnet paper-report --ensemble 0.5=mu05 --ensemble 0=mu0`.

Where the paper speaks of packing fractions (rho < 0.75, rho_J) this report measures relative to
each ensemble's own jamming point rho_J (where Z first reaches 3, mean over the realizations):
the paper's density convention is shifted from fnet's (how the walls enter the area), so its
absolute rho values are not ours."""

import csv
import math
import os
import time

import numpy as np

from fnet import figures

METRICS = ("bottleneck", "wasserstein1", "wasserstein2")
RATIOS = {"ratio_w1": "wasserstein1", "ratio_w2": "wasserstein2"}
FORCES = ("normal", "tangential")
DIMS = (0, 1)
CSV_COLUMNS = ("mu", "force", "dim", "metric", "rho", "mean", "stderr", "n", "z")

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
    frames, mean/stderr/n the distances' (stderr empty where undefined), z the bin's mean Z."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(CSV_COLUMNS)
        for (mu, force, dim, metric), c in curves.items():
            for k in range(len(c["rho"])):
                w.writerow([mu, force, dim, metric, _number(c["rho"][k]), _number(c["mean"][k]),
                            _number(c["stderr"][k]), int(c["n"][k]), _number(c["z"][k])])


def read_csv(path):
    """curves.csv back as {(mu, force, dim, metric): {column: numpy array}}."""
    out = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            key = (row["mu"], row["force"], int(row["dim"]), row["metric"])
            c = out.setdefault(key, {k: [] for k in ("rho", "mean", "stderr", "n", "z")})
            for k in ("rho", "mean", "stderr", "z"):
                c[k].append(float(row[k]) if row[k] else math.nan)
            c["n"].append(int(row["n"]))
    return {key: {k: np.asarray(v) for k, v in c.items()} for key, c in out.items()}


# ---- the findings ------------------------------------------------------------------------------

def _region(c, lo=-math.inf, hi=math.inf):
    """The bins' means with lo <= rho < hi, finite only."""
    rho, mean = np.asarray(c["rho"], dtype=float), np.asarray(c["mean"], dtype=float)
    keep = (rho >= lo) & (rho < hi) & np.isfinite(mean)
    return rho[keep], mean[keep]


def _log10(values):
    """log10 of the positive values, NaN for the others (a distance of 0: no change at all)."""
    v = np.asarray(values, dtype=float)
    out = np.full(v.shape, np.nan)
    np.log10(v, out=out, where=v > 0)
    return out


def _ratio(a, b):
    """a / b; +inf for a > 0 over 0 (something from nothing), NaN for 0 / 0 or an undefined side."""
    if math.isnan(a) or math.isnan(b):
        return math.nan
    if b == 0:
        return math.inf if a > 0 else math.nan
    return a / b


def _median(values):
    return float(np.median(values)) if len(values) else math.nan


def _fmt(v, digits=3):
    return "n/a" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.{digits}g}"


class Finding:
    """A claim of the paper, what was measured, and its checks: (label, passed) pairs, or None when
    it could not be measured."""

    def __init__(self, claim, measured, checks, test):
        self.claim, self.measured, self.checks, self.test = claim, measured, checks, test

    @property
    def verdict(self):
        if self.checks is None:
            return "not measurable"
        passed = [label for label, ok in self.checks if ok]
        if len(passed) == len(self.checks):
            return "holds"
        if not passed:
            return "does not hold"
        return "holds in part: " + ", ".join(passed) + "; not " + ", ".join(l for l, ok in self.checks if not ok)


def findings(curves, rho_j, frictional="0.5", frictionless="0"):
    """The qualitative findings of the paper's Sec. IV, each measured on the curves. rho_j: {mu:
    the ensemble's mean rho_J}."""
    out = []
    mu = frictional
    jam = rho_j.get(mu)
    if jam is None:
        return [Finding(claim, f"not measurable: Z never reached 3 in the mu {mu} realizations, so rho_J is "
                        "unknown", None, "needs rho_J") for claim in CLAIMS]
    c = lambda force, dim, metric, m=mu: curves[(m, force, dim, metric)]
    pre_lo = min(float(np.min(c("normal", 0, "bottleneck")["rho"])), jam)
    early_hi = pre_lo + (jam - pre_lo) / 2  # the first half of the unjammed range

    # 1. Before jamming d_B is large: above 1 over most of the range.
    shares = []
    for dim in DIMS:
        _, m = _region(c("normal", dim, "bottleneck"), hi=jam)
        shares.append((dim, float(np.mean(m > 1)) if len(m) else math.nan, _median(m)))
    out.append(Finding(
        CLAIMS[0],
        "; ".join(f"PD{d}: d_B > 1 in {_fmt(100 * s, 3)} % of the bins below rho_J, median {_fmt(med)}"
                  for d, s, med in shares),
        [(f"PD{d}", s > 0.5) for d, s, _ in shares], "holds if d_B > 1 in more than half of the bins below rho_J, PD0 and PD1"))

    # 2. Early ratios: d_B/d_W2 ~ 0.75, d_B/d_W1 ~ 0.2, roughly constant.
    parts, ok = [], []
    for dim in DIMS:
        for label, target, lo, hi in (("ratio_w2", 0.75, 0.5, 1.0), ("ratio_w1", 0.2, 0.1, 0.4)):
            _, m = _region(c("normal", dim, label), hi=early_hi)
            med = _median(m)
            spread = float(np.percentile(m, 90) / np.percentile(m, 10)) if len(m) > 1 else math.nan
            parts.append(f"PD{dim} {label.replace('ratio_w', 'd_B/d_W')}: median {_fmt(med)} "
                         f"(paper ~{target}), p90/p10 {_fmt(spread)}")
            ok.append((f"PD{dim} {label.replace('ratio_w', 'd_B/d_W')}", lo <= med <= hi and spread < 2))
    out.append(Finding(
        CLAIMS[1],
        f"first half: rho < {early_hi:.4f}; " + "; ".join(parts), ok,
        "holds if the median d_B/d_W2 is in [0.5, 1], d_B/d_W1 in [0.1, 0.4], and the 90th/10th percentile "
        "ratio below 2, PD0 and PD1"))

    # 3. Approaching rho_J, d_B drops while d_W1 keeps rising.
    parts, ok = [], []
    for dim in DIMS:
        for metric, direction in (("bottleneck", "drops"), ("wasserstein1", "rises")):
            _, early = _region(c("normal", dim, metric), hi=early_hi)
            _, late = _region(c("normal", dim, metric), lo=early_hi + (jam - early_hi) / 2, hi=jam)
            change = _ratio(_median(late), _median(early))
            parts.append(f"PD{dim} {metric}: last quarter below rho_J / first half = {_fmt(change)}")
            ok.append((f"PD{dim} {metric} {direction}", change < 1 if direction == "drops" else change > 1))
    out.append(Finding(
        CLAIMS[2], "; ".join(parts), ok,
        "holds if the median d_B over the last quarter of the unjammed range is below its median over the "
        "first half, and d_W1's above, PD0 and PD1"))

    # 4. After rho_J every rate of change drops sharply; the ratios fall by ~1 (W2) and ~3 (W1) orders.
    parts, ok = [], []
    for dim in DIMS:
        for metric in METRICS:
            _, pre = _region(c("normal", dim, metric), hi=jam)
            _, post = _region(c("normal", dim, metric), lo=jam + JAMMED_FROM)
            drop = _ratio(_median(pre), _median(post))
            parts.append(f"PD{dim} {metric} drops {_fmt(drop)}x")
            ok.append((f"PD{dim} {metric} drops", drop >= 10))
    for dim in DIMS:
        for label, orders, lo, hi in (("ratio_w2", 1, 0.5, 1.5), ("ratio_w1", 3, 2, 4)):
            _, early = _region(c("normal", dim, label), hi=early_hi)
            _, post = _region(c("normal", dim, label), lo=jam + JAMMED_FROM)
            fall = _log10([_ratio(_median(early), _median(post))])[0]
            parts.append(f"PD{dim} {label.replace('ratio_w', 'd_B/d_W')} falls {_fmt(fall, 2)} orders "
                         f"(paper: {orders}), from {_fmt(_median(early))} to {_fmt(_median(post))}")
            ok.append((f"PD{dim} {label.replace('ratio_w', 'd_B/d_W')} falls", lo <= fall <= hi))
    out.append(Finding(
        CLAIMS[3], "; ".join(parts), ok,
        f"holds if each distance's median below rho_J is at least 10x its median from rho_J + {JAMMED_FROM} on, "
        "and the ratios fall by 0.5-1.5 (d_B/d_W2) and 2-4 (d_B/d_W1) orders, PD0 and PD1"))

    # 5. Tangential like normal, except near rho_J (smaller d_W1, d_W2 there).
    parts, ok = [], []
    for dim in DIMS:
        for metric in METRICS:
            rn, mn = _region(c("normal", dim, metric))
            rt, mt = _region(c("tangential", dim, metric))
            common = np.intersect1d(np.round(rn, 12), np.round(rt, 12))
            far = np.array([abs(r - jam) > 2 * NEAR_JAMMING for r in common])
            ln = _log10([mn[np.round(rn, 12) == r][0] for r in common])
            lt = _log10([mt[np.round(rt, 12) == r][0] for r in common])
            good = far & np.isfinite(ln) & np.isfinite(lt)
            corr = float(np.corrcoef(ln[good], lt[good])[0, 1]) if good.sum() > 2 else math.nan
            ok.append((f"PD{dim} {metric} alike", corr > 0.9))
            text = f"PD{dim} {metric}: correlation of log10 normal vs tangential away from rho_J {_fmt(corr)}"
            if metric != "bottleneck":
                _, near_n = _region(c("normal", dim, metric), lo=jam - NEAR_JAMMING, hi=jam + NEAR_JAMMING)
                _, near_t = _region(c("tangential", dim, metric), lo=jam - NEAR_JAMMING, hi=jam + NEAR_JAMMING)
                near = _ratio(_median(near_t), _median(near_n))
                text += f", tangential/normal within {NEAR_JAMMING} of rho_J {_fmt(near)}"
                ok.append((f"PD{dim} {metric} smaller near rho_J", near < 1))
            parts.append(text)
    out.append(Finding(
        CLAIMS[4],
        "; ".join(parts), ok,
        f"holds if log10 of the normal and tangential curves correlate above 0.9 farther than "
        f"{2 * NEAR_JAMMING} from rho_J, and the tangential d_W1, d_W2 are below the normal within "
        f"{NEAR_JAMMING} of rho_J"))

    # 6. Frictionless systems jam at larger rho; afterwards their loops change about twice as fast.
    if rho_j.get(frictionless) is not None:
        shift = rho_j[frictionless] - rho_j[frictional]
        parts = [f"rho_J = {_fmt(rho_j[frictional], 4)} (mu {frictional}), {_fmt(rho_j[frictionless], 4)} "
                 f"(mu {frictionless}): shift {_fmt(shift, 3)}"]
        ok = [("jams later", shift > 0)]
        for metric in METRICS:
            speeds = []
            for m in (frictional, frictionless):
                cm = curves[(m, "normal", 1, metric)]
                _, post = _region({"rho": np.asarray(cm["rho"]) - rho_j[m], "mean": cm["mean"]}, lo=JAMMED_FROM)
                speeds.append(_median(post))
            factor = _ratio(speeds[1], speeds[0])
            parts.append(f"PD1 {metric} after jamming, mu {frictionless} / mu {frictional}: {_fmt(factor)}")
            if metric == "wasserstein1":
                ok.append(("PD1 d_W1 about twice", 1.4 <= factor <= 2.8))
        out.append(Finding(
            CLAIMS[5], "; ".join(parts), ok,
            f"holds if rho_J(mu {frictionless}) > rho_J(mu {frictional}) and the median PD1 d_W1 from "
            f"rho - rho_J = {JAMMED_FROM} on is 1.4-2.8x the frictional one (compared at equal rho - rho_J)"))
    else:
        out.append(Finding(CLAIMS[5], f"not measurable: no rho_J for mu {frictionless} (Z never reached 3, or no "
                           "such ensemble)", None, "needs both ensembles' rho_J"))
    return out


# ---- figures -----------------------------------------------------------------------------------

def _log_y(fig):
    for ax in fig.axes[:1]:
        ax.set_yscale("log")
    return fig


def draw(curves, rho_j, out_dir, frictional="0.5", frictionless="0"):
    """The paper's Figs. 6-10 from the curves; returns {file name: what it shows}."""
    made = {}

    def save(fig, name, what):
        fig.savefig(os.path.join(out_dir, name), dpi=120)
        made[name] = what

    for dim in DIMS:
        mu = frictional
        save(_log_y(figures.ensemble([curves[(mu, "normal", dim, m)] for m in METRICS],
                                     labels=[f"{m} PD{dim}" for m in METRICS])),
             f"fig6-normal-pd{dim}.png", f"Fig. 6: mu {mu}, normal forces, PD{dim}: d_B, d_W1, d_W2, mean ± s.e., Z")
        save(_log_y(figures.ratio([curves[(mu, "normal", dim, r)] for r in RATIOS],
                                  labels=["d_B/d_W1", "d_B/d_W2"])),
             f"fig7-ratios-pd{dim}.png", f"Fig. 7: mu {mu}, normal forces, PD{dim}: d_B/d_W1, d_B/d_W2")
        save(_log_y(figures.ensemble([curves[(mu, "tangential", dim, m)] for m in METRICS],
                                     labels=[f"{m} PD{dim}" for m in METRICS])),
             f"fig8-tangential-pd{dim}.png", f"Fig. 8: mu {mu}, tangential forces, PD{dim}")
        if (frictionless, "normal", dim, "bottleneck") in curves and frictional in rho_j and frictionless in rho_j:
            shifted = []
            for m in (frictional, frictionless):
                for metric in ("bottleneck", "wasserstein2"):
                    cm = dict(curves[(m, "normal", dim, metric)])
                    cm["rho"] = np.asarray(cm["rho"]) - rho_j[m]
                    cm["axis"] = "rho_minus_rho_j"
                    shifted.append(cm)
            save(_log_y(figures.ensemble(shifted, labels=[f"mu {m} {metric}" for m in (frictional, frictionless)
                                                          for metric in ("bottleneck", "wasserstein2")], z=False)),
                 f"fig9-friction-pd{dim}.png", f"Fig. 9: mu {frictional} against mu {frictionless} against "
                 f"rho - rho_J, normal forces, PD{dim}")
            save(_log_y(figures.ratio([curves[(frictionless, "normal", dim, r)] for r in RATIOS],
                                      labels=["d_B/d_W1", "d_B/d_W2"])),
                 f"fig10-ratios-mu{frictionless}-pd{dim}.png", f"Fig. 10: mu {frictionless}, normal forces, PD{dim}")
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

def write_report(path, setup, rho_j, found, made, tables, timings):
    """report.md: the setting, each finding with its numbers and whether it holds, the figures."""
    lines = ["# The paper reproduced by fnet", "",
             "Kramar, Goullet, Kondic, Mischaikow (2014), Sec. IV: distances between consecutive frames of "
             "compressions through jamming, averaged over realizations, measured live by fnet-server.", "",
             "## Setting", ""]
    lines += [f"- {k}: {v}" for k, v in setup.items()]
    lines += ["", "Jamming points (rho where Z first reaches 3, interpolated; mean ± standard error over "
              "the realizations):", ""]
    lines += [f"- mu {mu}: rho_J = {_fmt(v['mean'], 5)} ± {_fmt(v['standard_error'])} (n = {v['n']})"
              for mu, v in rho_j.items()]
    lines += ["", "The paper's packing fractions are shifted from fnet's (its rho_J is lower: the density "
              "convention differs in how the walls enter the area), so every region below is taken "
              "relative to the ensemble's own rho_J. Curves: `curves.csv` (floor convention for classes "
              "that never die; ratio curves are the ratio of the bin means, as the paper plots).", "",
              "## Findings of the paper, measured here", ""]
    held = sum(1 for f in found if f.verdict == "holds")
    partly = sum(1 for f in found if f.verdict.startswith("holds in part"))
    lines += [f"{held} of {len(found)} hold here in full, {partly} in part.", ""]
    for n, f in enumerate(found, 1):
        lines += [f"### {n}. {f.claim}", "", f"- **{f.verdict}** ({f.test}).",
                  f"- measured: {f.measured}.", ""]
    if tables:
        lines += ["## Where the network changed (Tables II, III)", "",
                  "Block distances between consecutive frames of one realization, 2 x 2 cells over the grains' "
                  "bounding box (row 0 the bottom), normal forces:", ""]
        for t in tables:
            lines += [f"**{t['label']}** ({t['run']} frames {t['frame']} -> {t['other_frame']}, rho "
                      f"{t['rho']:.4f}), {t['metric']} PD{t['dim']}:", "", _block_markdown(t)]
    lines += ["## Figures", ""] + [f"- `{name}`: {what}" for name, what in made.items()]
    if timings:
        lines += ["", "## Timings", ""] + [f"- {k}: {v}" for k, v in timings.items()]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main(args):
    """python3 -m fnet paper-report: everything above, into args.out."""
    from fnet.rpc import Client

    os.makedirs(args.out, exist_ok=True)
    ensembles = dict(args.ensemble)
    frictional = next((mu for mu in ensembles if float(mu) > 0), next(iter(ensembles)))
    frictionless = next((mu for mu in ensembles if float(mu) == 0), None)
    setup = dict(s.split("=", 1) if "=" in s else (s, "") for s in args.setting)
    setup.update({f"ensemble mu {mu}": name for mu, name in ensembles.items()})
    with Client(args.host, args.port) as c:
        listed = {e["ensemble"]: e for e in c.ensembles()}
        missing = [name for name in ensembles.values() if name not in listed]
        if missing:
            raise KeyError(f"no ensemble {', '.join(missing)} on the server")
        jam = {mu: listed[name]["rho_j"] for mu, name in ensembles.items()}
        for mu, name in ensembles.items():
            setup[f"runs of mu {mu}"] = ", ".join(listed[name]["runs"])
        t0 = time.perf_counter()
        curves = collect(c, ensembles, args.bins)
        timings = {f"ensemble.series, {len(curves)} curves over {sum(len(listed[n]['runs']) for n in ensembles.values())}"
                   " runs": f"{1e3 * (time.perf_counter() - t0) / len(curves):.2f} ms per curve"}
        rho_j = {mu: v["mean"] for mu, v in jam.items() if v["mean"] is not None}
        tables = []
        if frictional in rho_j:
            t0 = time.perf_counter()
            tables = block_tables(c, ensembles[frictional], rho_j[frictional])
            timings[f"blocks.get, k = 2, {len(tables)} tables"] = \
                f"{1e3 * (time.perf_counter() - t0) / len(tables):.1f} ms per table"
    write_csv(os.path.join(args.out, "curves.csv"), curves)
    found = findings(curves, rho_j, frictional, frictionless or "0")
    made = draw(curves, rho_j, args.out, frictional, frictionless or "0")
    write_report(os.path.join(args.out, "report.md"), setup, jam, found, made, tables, timings)
    for f in found:
        print(f"{f.verdict.split(':')[0]:>15}: {f.claim}")
    print(os.path.join(args.out, "report.md"))
    return 0
