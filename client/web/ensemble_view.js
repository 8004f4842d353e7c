// One ensemble, live: its runs' distances binned in ρ (or ρ − ρ_J) and averaged over the runs,
// mean ± standard error as a band, Z on a second axis, ρ_J marked (Figs. 6, 8, 9); and the ratio
// curves d_B / d_W1 and d_B / d_W2 of the bin means (Figs. 7, 10). Each curve is an
// ensemble.subscribe subscription: its answer, then the bins each ensemble.bins notification
// changes, applied in order (by rho_lo; removed ones dropped).

import { SERIES_COLORS } from "./colors.js";
import { formatNumber, plot } from "./plot.js";

const $ = (id) => document.getElementById(id);
const KEYS = ["rho_lo", "rho_hi", "rho", "mean", "stderr", "n_runs", "n", "z"];
const METRIC_LABEL = { bottleneck: "d_B", wasserstein1: "d_W1", wasserstein2: "d_W2" };

// A curve as ensemble.series answers it, as a list of bins.
function binsOf(answer) {
  return answer.rho_lo.map((_, k) => {
    const bin = {};
    for (const key of KEYS) bin[key] = answer[key][k];
    bin.infinite = answer.infinite ? answer.infinite[k] : false;
    return bin;
  });
}

// ensemble.bins applied to a curve's bins.
function applyBins(bins, update) {
  const byLo = new Map(bins.map((b) => [b.rho_lo, b]));
  for (const lo of update.removed || []) byLo.delete(lo);
  for (const b of binsOf(update)) byLo.set(b.rho_lo, b);
  return [...byLo.values()].sort((a, b) => a.rho_lo - b.rho_lo);
}

export class EnsembleView {
  constructor(rpc, options) {
    this.rpc = rpc;
    this.options = options;
    this.ensemble = null;
    this.curves = {};  // "value" | "ratio_w1" | "ratio_w2" -> {id, bins, answer}
    this.early = [];  // notifications that came before their subscription's answer
    rpc.on("ensemble.bins", (p) => this.onBins(p));
    rpc.onOpen(() => this.ensemble && this.show(this.ensemble, true));
  }

  hide() {
    this.unsubscribe();
    this.ensemble = null;
  }

  unsubscribe() {
    for (const c of Object.values(this.curves))
      if (c.id !== undefined && this.rpc.open) this.rpc.call("ensemble.unsubscribe", { subscription: c.id }).catch(() => {});
    this.curves = {};
    this.early = [];
  }

  async show(ensemble, again = false) {
    if (this.ensemble === ensemble && !again) return;
    this.unsubscribe();
    this.ensemble = ensemble;
    $("ensemble-title").textContent = `ensemble ${ensemble}`;
    await this.subscribe();
  }

  async subscribe() {
    const o = this.options(), ensemble = this.ensemble;
    const base = { ensemble, dim: o.dim, force: o.force, essential: o.essential, axis: o.axis };
    const asked = {
      value: { ...base, metric: o.metric },
      ratio_w1: { ...base, ratio: "wasserstein1" },
      ratio_w2: { ...base, ratio: "wasserstein2" },
    };
    this.asked = JSON.stringify(asked);
    const answers = await Promise.all(Object.entries(asked).map(async ([name, params]) => {
      try {
        return [name, await this.rpc.call("ensemble.subscribe", params)];
      } catch (e) {
        return [name, e];
      }
    }));
    if (this.ensemble !== ensemble || this.asked !== JSON.stringify(asked)) {
      for (const [, a] of answers) if (a.subscription !== undefined) this.rpc.call("ensemble.unsubscribe", { subscription: a.subscription }).catch(() => {});
      return;
    }
    for (const [name, a] of answers) {
      if (a instanceof Error) {
        $("ensemble-state").textContent = a.message;
        continue;
      }
      const curve = { id: a.subscription, bins: binsOf(a), answer: a };
      for (const n of this.early.filter((n) => n.subscription === a.subscription)) curve.bins = applyBins(curve.bins, n);
      this.curves[name] = curve;
    }
    this.early = [];
    this.redraw();
  }

  onBins(p) {
    const curve = Object.values(this.curves).find((c) => c.id === p.subscription);
    if (!curve) {
      this.early.push(p);
      return;
    }
    curve.bins = applyBins(curve.bins, p);
    curve.answer.runs = p.runs;
    this.redraw();
  }

  optionsChanged(onlyScale) {
    if (!this.ensemble) return;
    if (onlyScale) return this.redraw();
    this.unsubscribe();
    this.subscribe();
  }

  summary(e) {
    const changed = JSON.stringify(e.rho_j) !== JSON.stringify(this.info && this.info.rho_j);
    this.info = e;
    if (changed) this.redraw();
    const j = e.rho_j;
    $("ensemble-state").textContent = [
      `${e.runs.length} runs, ${e.frames} frames analyzed`,
      `μ ${e.friction === null ? "differs" : formatNumber(e.friction, 3)}`,
      `N ${e.particles === null ? "differs" : e.particles}`,
      j.mean === null ? "ρ_J not reached" : `ρ_J ${formatNumber(j.mean, 4)} ± ${j.standard_error === null ? "–" : formatNumber(j.standard_error, 2)} over ${j.n} runs`,
    ].join(" · ");
  }

  // The band as drawn: the bins of the chosen metric's curve.
  bins() {
    return this.curves.value ? this.curves.value.bins.map((b) => ({ ...b })) : [];
  }

  redraw() {
    if (!this.ensemble) return;
    const start = performance.now();
    this.redrawMs = this.redrawMs || [];
    const o = this.options();
    const axis = o.axis === "rho" ? "packing fraction ρ" : "ρ − ρ_J (each run's own ρ_J)";
    const rhoJ = this.info && this.info.rho_j.mean !== null ? this.info.rho_j.mean : null;
    const vlines = o.axis === "rho" ? (rhoJ === null ? [] : [{ x: rhoJ, label: `ρ_J = ${formatNumber(rhoJ, 4)}`, color: "#b0302a" }])
      : [{ x: 0, label: "ρ_J", color: "#b0302a" }];
    const value = this.curves.value;
    const runs = value ? value.answer.runs.length : 0;
    plot($("band"), {
      x: { label: axis },
      y: { label: `${METRIC_LABEL[o.metric]}(PD${o.dim}), mean ± s.e. over runs`, log: o.log },
      y2: { label: "mean contact number Z", color: "#6b6b70" },
      series: value ? [
        { name: `${METRIC_LABEL[o.metric]}, ${o.force} forces, ${o.essential} convention, ${runs} runs`, color: SERIES_COLORS[0],
          band: true, markers: true,
          points: value.bins.map((b) => ({ x: b.rho, y: b.mean, lo: b.stderr === null ? null : b.mean - b.stderr,
            hi: b.stderr === null ? null : b.mean + b.stderr, key: b.rho_lo })) },
        { name: "Z", color: "#9a9aa0", axis: "y2", dash: [3, 3], width: 1.2, points: value.bins.map((b) => ({ x: b.rho, y: b.z })) },
      ] : [],
      vlines,
      empty: "no binned frames yet",
    });
    const ratios = [["ratio_w1", "d_B / d_W1", SERIES_COLORS[1]], ["ratio_w2", "d_B / d_W2", SERIES_COLORS[2]]]
      .filter(([name]) => this.curves[name])
      .map(([name, label, color]) => ({ name: label + " (ratio of the bin means)", color, markers: true,
        points: this.curves[name].bins.map((b) => ({ x: b.rho, y: b.mean })) }));
    plot($("ratios"), {
      x: { label: axis },
      y: { label: `ratios, PD${o.dim}, ${o.force} forces`, log: o.log },
      series: ratios,
      vlines,
      empty: "no binned frames yet",
    });
    this.redrawMs.push(performance.now() - start);
    if (this.redrawMs.length > 1000) this.redrawMs.shift();
  }
}
