// One run, live: the distance between consecutive frames against ρ (the metric, diagram, force
// and convention chosen; log scale; Z on a second axis; ρ_J marked), kept up to date by a
// series.subscribe subscription; the latest frame's force network and its PD0 and PD1; and, for a
// point clicked on the curve, that frame against the previous one: the change in force per
// contact, the block table over the packing and the explained terms of the distance.

import { changeColor, forceColor, SERIES_COLORS } from "./colors.js";
import { drawDiagram } from "./diagram_view.js";
import { drawChange, drawNetwork, legend } from "./network_view.js";
import { formatNumber, plot } from "./plot.js";

const $ = (id) => document.getElementById(id);
const STORED = ["bottleneck", "wasserstein1", "wasserstein2"];  // served from series.point as they come
const METRIC_LABEL = { bottleneck: "d_B", wasserstein1: "d_W1", wasserstein2: "d_W2" };
const BLOCKS_K = 4;
const UNKNOWN_RUN = -32001;
const EXPLAIN_TERMS = 5;

export class RunView {
  constructor(rpc, options) {
    this.rpc = rpc;
    this.options = options;
    this.run = null;
    this.points = [];  // {frame, rho, z, previous, value, infinite}, in frame order
    this.drawnAt = {};  // frame -> Date.now() when its point was first drawn
    this.latest = { frame: null, busy: false, drawn: null };
    this.change = null;
    rpc.on("series.point", (p) => this.onPoint(p));
    rpc.onOpen(() => this.run && this.show(this.run, true));
    $("curve").addEventListener("click", (e) => this.onClick(e));
  }

  hide() {
    this.unsubscribe();
    this.run = null;
  }

  async show(run, again = false) {
    if (this.run === run && !again) return;
    this.unsubscribe();
    this.run = run;
    this.points = [];
    this.live = [];
    this.rhoJ = null;
    this.latest = { frame: null, busy: false, drawn: null };
    this.change = null;
    this.selected = null;
    $("change").hidden = true;
    $("run-title").textContent = run;
    this.draw();
    await this.loadCurve();
    if (this.run !== run) return;
    try {
      const last = this.points.length ? this.points[this.points.length - 1].frame : null;
      const answer = await this.rpc.call("series.subscribe", last === null ? { run } : { run, since: last });
      if (this.run === run) {
        this.subscription = answer.subscription;
        this.subscribedAt = Date.now();
      }
      else this.rpc.call("series.unsubscribe", { subscription: answer.subscription }).catch(() => {});
    } catch (e) {
      $("run-state").textContent = e.message;
    }
  }

  unsubscribe() {
    if (this.subscription !== undefined && this.rpc.open)
      this.rpc.call("series.unsubscribe", { subscription: this.subscription }).catch(() => {});
    this.subscription = undefined;
  }

  measure() {
    const o = this.options();
    return { metric: o.metric, dim: o.dim, force: o.force, essential: o.essential };
  }

  // The whole curve, then the points notified meanwhile.
  async loadCurve() {
    const run = this.run, m = this.measure();
    let s;
    try {
      s = await this.rpc.call("series.get", { run, ...m });
    } catch (e) {
      $("run-state").textContent = e.message;
      // A run linked to before it starts: asked for again until it appears.
      if (e.code === UNKNOWN_RUN && this.run === run) {
        $("run-state").textContent = `waiting for run ${run} to appear on the server…`;
        await new Promise((resolve) => setTimeout(resolve, 500));
        if (this.run === run) return this.loadCurve();
      }
      return;
    }
    if (this.run !== run || JSON.stringify(m) !== JSON.stringify(this.measure())) return;
    this.points = s.frame.map((frame, k) => ({
      frame, rho: s.rho[k], z: s.z[k], previous: s.previous[k], value: s.value[k],
      infinite: s.infinite ? s.infinite[k] : false,
    }));
    const last = this.points.length ? this.points[this.points.length - 1].frame : -1;
    for (const p of this.live) if (p.frame > last) this.addPoint(p);
    this.draw();
    this.refreshLatest();
  }

  onPoint(p) {
    if (p.run !== this.run) return;
    this.live.push(p);
    if (this.live.length > 4096) this.live.splice(0, this.live.length - 4096);
    if (this.points.length && p.frame <= this.points[this.points.length - 1].frame) return;
    this.addPoint(p);
    this.draw();
    this.refreshLatest();
  }

  // A notified frame on the curve: its distance is in the notification for the metrics stored as
  // frames arrive (floor convention); otherwise series.get computes it.
  addPoint(p) {
    const m = this.measure();
    const point = { frame: p.frame, rho: p.rho, z: p.z, previous: p.previous, value: null, infinite: false };
    if (m.essential === "floor" && STORED.includes(m.metric)) {
      point.value = p.distances[`${m.metric}/pd${m.dim}/${m.force}`];
    } else if (p.previous !== null) {
      this.rpc.call("series.get", { run: this.run, ...m, from: p.frame, to: p.frame }).then((s) => {
        if (JSON.stringify(m) !== JSON.stringify(this.measure())) return;
        point.value = s.value[0];
        point.infinite = s.infinite ? s.infinite[0] : false;
        this.draw();
      }).catch(() => {});
    }
    this.points.push(point);
  }

  optionsChanged(onlyScale) {
    if (!this.run) return;
    if (onlyScale) return this.draw();
    this.loadCurve();
    this.latest.frame = null;
    this.refreshLatest();
    if (this.selected !== null && this.selected !== undefined) this.select(this.selected);
  }

  summary(run, complete) {
    if (run.rho_j !== this.rhoJ) {
      this.rhoJ = run.rho_j;
      this.draw();
    }
    const parts = [
      `${run.frames}${run.planned_frames !== undefined ? " of " + run.planned_frames : ""} frames analyzed and stored`,
      complete ? "complete" : run.seconds_since_last_frame < 30 ? "running" : "idle",
      `ρ ${formatNumber(run.rho, 4)}`, `Z ${formatNumber(run.z, 3)}`,
      run.rho_j === null ? "ρ_J not reached (Z < 3)" : `ρ_J ${formatNumber(run.rho_j, 4)}`,
    ];
    if (run.rejected) parts.push(`${run.rejected} rejected`);
    if (run.skipped) parts.push(`${run.skipped} skipped`);
    if (run.dimension === 3) parts.push("3D frames, drawn as their xy projection");
    if (run.store_fault) parts.unshift(`store fault: ${run.unstored} settled frame(s) wait for the store (${run.store_fault})`);
    $("run-state").textContent = parts.join(" · ");
    $("run-state").classList.toggle("fault", Boolean(run.store_fault));
  }

  curve() {
    return this.points.map((p) => ({ ...p }));
  }

  // Where frame `frame`'s point is drawn, in CSS pixels from the curve canvas's top left.
  pointPosition(frame) {
    const hit = this.layout && this.layout.points.find((p) => p.point.key === frame && p.series.clickable);
    return hit ? { x: hit.px, y: hit.py } : null;
  }

  draw() {
    if (this.pending) return;
    this.pending = requestAnimationFrame(() => {
      this.pending = null;
      this.redraw();
    });
  }

  redraw() {
    if (!this.run) return;
    const o = this.options();
    const name = `${METRIC_LABEL[o.metric]}(PD${o.dim}), ${o.force} forces, ${o.essential} convention`;
    const infinite = this.points.filter((p) => p.infinite).length;
    this.layout = plot($("curve"), {
      x: { label: "packing fraction ρ" },
      y: { label: `${METRIC_LABEL[o.metric]} to the previous frame`, log: o.log },
      y2: { label: "mean contact number Z", color: "#6b6b70" },
      series: [
        { name, color: SERIES_COLORS[0], markers: true, clickable: true,
          points: this.points.map((p) => ({ x: p.rho, y: p.value, key: p.frame })) },
        { name: "Z", color: "#9a9aa0", axis: "y2", dash: [3, 3], width: 1.2,
          points: this.points.map((p) => ({ x: p.rho, y: p.z })) },
      ],
      vlines: this.rhoJ === null || this.rhoJ === undefined ? [] : [{ x: this.rhoJ, label: `ρ_J = ${formatNumber(this.rhoJ, 4)}`, color: "#b0302a" }],
      selected: this.selected,
      empty: "waiting for the run's first analyzed frames…" + (infinite ? "" : ""),
    });
    const now = Date.now();
    for (const p of this.points) if (!(p.frame in this.drawnAt)) this.drawnAt[p.frame] = now;
  }

  // After a change of the window's size: everything drawn again at the new size.
  resize() {
    this.redraw();
    if (this.latest.drawn) this.drawLatest();
    if (this.change && this.change.drawn) this.drawChangeView();
  }

  // The newest frame's network and diagrams, fetched again when a newer frame has come.
  async refreshLatest() {
    if (this.latest.busy || !this.points.length) return;
    const newest = this.points[this.points.length - 1].frame;
    const force = this.options().force;
    if (newest === this.latest.frame && force === this.latest.force) return;
    this.latest.busy = true;
    const run = this.run;
    const asked = performance.now();
    try {
      const [net, pd0, pd1] = await Promise.all([
        this.rpc.call("network.get", { run, frame: newest }),
        this.rpc.call("diagram.get", { run, frame: newest, dim: 0, force }),
        this.rpc.call("diagram.get", { run, frame: newest, dim: 1, force }),
      ]);
      if (run !== this.run) return;
      this.latest.frame = newest;
      this.latest.force = force;
      this.latest.drawn = { net, pd0, pd1, force };
      this.latest.fetchMs = performance.now() - asked;
      await this.drawLatest();
    } catch (e) {
      $("network-caption").textContent = `frame ${newest}: ${e.message}`;
      this.latest.frame = newest;
    } finally {
      this.latest.busy = false;
      if (run === this.run) setTimeout(() => this.refreshLatest(), 300);
    }
  }

  async drawLatest() {
    const { net, pd0, pd1, force } = this.latest.drawn;
    const start = performance.now();
    const drawn = await drawNetwork($("network"), net, force);
    if (!drawn && net.particles.length) return;  // a newer drawing took the canvas
    this.latest.drawMs = performance.now() - start;
    this.latest.drawnAt = Date.now();
    $("network-caption").textContent = `latest frame ${net.frame}: ρ ${formatNumber(net.rho, 4)}, Z ${formatNumber(net.z, 3)}, ` +
      `${net.particles.length} grains, ${net.contacts.length} contacts; ${force} force / mean force` +
      (net.dimension === 3 ? " (xy projection of a 3D frame)" : "");
    if (drawn)
      legend($("network-legend"), forceColor, "0", `${drawn.top} or more`,
        `${force} force / mean ${force} force (the mean: ${formatNumber(net.mean_force[force], 3)} in the simulation's units)`);
    $("diagram-caption").textContent = `persistence diagrams of frame ${net.frame}, ${force} forces: ` +
      `PD0 (chains) above, PD1 (loops) below`;
    drawDiagram($("pd0"), pd0, SERIES_COLORS[1]);
    drawDiagram($("pd1"), pd1, SERIES_COLORS[0]);
  }

  onClick(event) {
    if (!this.layout) return;
    const r = event.target.getBoundingClientRect();
    const hit = this.layout.hit(event.clientX - r.left, event.clientY - r.top);
    if (hit && hit.series.clickable) this.select(hit.point.key);
  }

  // Frame `frame` against the frame its distance is measured from.
  async select(frame) {
    const point = this.points.find((p) => p.frame === frame);
    if (!point) return;
    this.selected = frame;
    this.redraw();
    $("change").hidden = false;
    const m = this.measure();
    const run = this.run;
    if (point.previous === null) {
      $("change-title").textContent = `frame ${frame} is the run's first: no previous frame to compare with`;
      this.change = { frame, previous: null };
      return;
    }
    const previous = point.previous;
    $("change-title").textContent = `frame ${frame} against frame ${previous}: loading…`;
    this.change = null;
    try {
      const [before, after, blocks, distance] = await Promise.all([
        this.rpc.call("network.get", { run, frame: previous }),
        this.rpc.call("network.get", { run, frame }),
        this.rpc.call("blocks.get", { run, frame: previous, other_frame: frame, k: BLOCKS_K, ...m }),
        this.rpc.call("distance.get", { run, frame: previous, other_frame: frame, ...m, explain: EXPLAIN_TERMS }),
      ]);
      if (run !== this.run || this.selected !== frame) return;
      this.changeNetworks = { before, after, force: m.force };
      this.change = { frame, previous, blocks, distance, drawn: null };
      const drawn = await this.drawChangeView();
      const superseded = !drawn && before.particles.length > 0 && after.particles.length > 0;
      if (!this.change || this.change.frame !== frame || superseded) return;
      const value = distance.infinite ? "∞" : formatNumber(distance.value, 4);
      $("change-title").textContent = `frame ${frame} (ρ ${formatNumber(point.rho, 4)}) against frame ${previous}: ` +
        `${METRIC_LABEL[m.metric]}(PD${m.dim}) = ${value}`;
      $("change-caption").textContent = `change in ${m.force} force / mean force per contact, on frame ${frame}'s grains ` +
        `(${drawn ? drawn.changed : 0} contacts changed); cells: the ${BLOCKS_K} × ${BLOCKS_K} block table; rings: the explained terms`;
      if (drawn)
        legend($("change-legend"), changeColor, `${formatNumber(-drawn.clip, 2)} or less`,
          `${formatNumber(drawn.clip, 2)} or more`,
          `change in ${m.force} force / mean force (blue: weaker, red: stronger)`);
      const largest = blocks.largest;
      $("blocks-caption").textContent = `Block table (${BLOCKS_K} × ${BLOCKS_K}, shaded by ${METRIC_LABEL[m.metric]} cell by cell, ` +
        `each cell normalized by its own mean force; pale: 0, dark red: the largest): largest in row ${largest.row}, column ${largest.col}, ` +
        `${largest.value === null ? "∞" : formatNumber(largest.value, 4)}.`;
      this.renderTerms(distance.explain || []);
    } catch (e) {
      $("change-title").textContent = `frame ${frame} against frame ${previous}: ${e.message}`;
    }
  }

  // The selected change drawn (again): the networks kept apart from this.change, which tests read.
  async drawChangeView() {
    const { before, after, force } = this.changeNetworks;
    const change = this.change;
    const drawn = await drawChange($("change-network"), before, after, force, change.blocks, change.distance.explain);
    if (drawn) change.drawn = drawn;
    return drawn;
  }

  renderTerms(terms) {
    const body = $("terms").tBodies[0];
    body.replaceChildren();
    const point = (p) => (p ? `(${formatNumber(p.birth, 3)}, ${formatNumber(p.death, 3)})` : "diagonal");
    const grains = (t) => [t.a, t.b].filter(Boolean).map((p) => p.birth_simplex ? p.birth_simplex.grains.join("–") : "").join(" → ");
    for (const t of terms) {
      const row = body.insertRow();
      for (const text of [t.rank, formatNumber(t.cost, 4), point(t.a), point(t.b), grains(t)]) row.insertCell().textContent = text;
    }
    if (!terms.length) body.insertRow().insertCell().textContent = "no term: the diagrams are equal";
  }
}
