// fnet's dashboard: the runs and ensembles fnet-server holds, with their state, and the view of
// the one selected (run_view.js, ensemble_view.js), all through the JSON-RPC API over the page's
// WebSocket. The selection and the options live in the address (#run=NAME, #ensemble=NAME), so a
// view can be linked to. window.fnetDashboard exposes what is drawn, for tests and benchmarks.

import { dashboardSocketUrl, Rpc } from "./rpc.js";
import { EnsembleView } from "./ensemble_view.js";
import { formatNumber } from "./plot.js";
import { RunView } from "./run_view.js";

const $ = (id) => document.getElementById(id);
const rpc = new Rpc(dashboardSocketUrl());
const options = () => ({
  metric: $("metric").value,
  dim: Number($("dim").value),
  force: $("force").value,
  essential: $("essential").value,
  log: $("log").checked,
  axis: $("axis").value,
});
const runView = new RunView(rpc, options);
const ensembleView = new EnsembleView(rpc, options);
const state = { runs: [], ensembles: [], selected: null, history: new Map() };

// The main thread's tasks longer than 50 ms (Chromium's Long Tasks API), for the benchmark.
const longTasks = [];
try {
  new PerformanceObserver((list) => list.getEntries().forEach((e) => longTasks.push(e.duration)))
    .observe({ type: "longtask", buffered: true });
} catch (e) {
  // a browser without the Long Tasks API: none recorded
}

window.fnetDashboard = {
  rpc,
  longTasks,
  runView,
  ensembleView,
  state,
  curve: () => runView.curve(),
  pointPosition: (frame) => runView.pointPosition(frame),
  band: () => ensembleView.bins(),
  select: (kind, id) => select(kind, id),
};

rpc.onState((s) => {
  const el = $("connection");
  el.className = "state " + (s === "live" ? "live" : s === "lost" ? "lost" : "");
  el.textContent = s === "live" ? "live" : s === "lost" ? "connection lost: reconnecting…" : "connecting…";
});

rpc.onOpen(async () => {
  try {
    const status = await rpc.call("server.status");
    $("server").textContent = `fnet-server ${status.build.version} (${status.build.commit.slice(0, 10)}), ` +
      `convention of stored distances: ${status.build.convention}`;
  } catch (e) {
    console.warn(e);
  }
  await refreshLists();
  if (state.selected) select(state.selected.kind, state.selected.id, true);
});

// frames per minute over the last minute, from the frame counts seen.
function rate(run) {
  const samples = state.history.get(run.run) || [];
  const now = performance.now();
  samples.push([now, run.frames]);
  while (samples.length > 2 && now - samples[0][0] > 60000) samples.shift();
  state.history.set(run.run, samples);
  const [t0, f0] = samples[0];
  return now - t0 > 1500 ? ((run.frames - f0) / (now - t0)) * 60000 : null;
}

export function complete(run) {
  if (run.planned_frames === undefined) return false;
  return run.frames + run.rejected + run.skipped >= run.planned_frames && run.pending === 0;
}

function renderRuns() {
  const body = $("runs").tBodies[0];
  body.replaceChildren();
  for (const r of state.runs) {
    const row = body.insertRow();
    row.dataset.run = r.run;
    if (state.selected && state.selected.kind === "run" && state.selected.id === r.run) row.className = "selected";
    const cells = [
      r.run + (r.dimension === 3 ? " (3D)" : ""),
      `${r.frames}${r.planned_frames !== undefined ? " / " + r.planned_frames : ""}`,
      formatNumber(r.rho, 4),
      formatNumber(r.z, 3),
      formatNumber(r.rho_j, 4),
      r.rate === null ? "–" : formatNumber(r.rate, 2),
      String(r.rejected),
    ];
    cells.forEach((text, k) => {
      const td = row.insertCell();
      td.textContent = text;
      if (k === 1 && complete(r)) {
        td.className = "done";
        td.title = "complete: every planned frame is accounted for";
      }
    });
    // A store fault fails the run until the store takes writes again: its name says so.
    if (r.store_fault) {
      row.cells[0].textContent += " · store fault";
      row.cells[0].className = "fault";
      row.cells[0].title = `not stored: ${r.store_fault}`;
    }
    row.onclick = () => select("run", r.run);
  }
}

function renderEnsembles() {
  const body = $("ensembles").tBodies[0];
  body.replaceChildren();
  for (const e of state.ensembles) {
    const row = body.insertRow();
    row.dataset.ensemble = e.ensemble;
    if (state.selected && state.selected.kind === "ensemble" && state.selected.id === e.ensemble) row.className = "selected";
    const j = e.rho_j;
    const cells = [e.ensemble, String(e.runs.length), String(e.frames),
      j.mean === null ? "–" : `${formatNumber(j.mean, 4)} ± ${j.standard_error === null ? "–" : formatNumber(j.standard_error, 2)} (${j.n})`];
    for (const text of cells) row.insertCell().textContent = text;
    row.onclick = () => select("ensemble", e.ensemble);
  }
}

async function refreshLists() {
  if (!rpc.open) return;
  try {
    const [runs, ensembles] = await Promise.all([rpc.call("runs.list"), rpc.call("ensembles.list")]);
    state.runs = runs.runs.map((r) => ({ ...r, rate: rate(r) }));
    state.ensembles = ensembles.ensembles;
    renderRuns();
    renderEnsembles();
    $("empty").hidden = state.runs.length > 0 || state.selected !== null;
    if (!state.selected && !location.hash && state.runs.length) {
      const newest = state.runs.reduce((a, b) => ((b.last_activity || 0) > (a.last_activity || 0) ? b : a));
      select("run", newest.run);
    }
    if (state.selected && state.selected.kind === "run") {
      const summary = state.runs.find((r) => r.run === state.selected.id);
      if (summary) runView.summary(summary, complete(summary));
    }
    if (state.selected && state.selected.kind === "ensemble") {
      const summary = state.ensembles.find((e) => e.ensemble === state.selected.id);
      if (summary) ensembleView.summary(summary);
    }
  } catch (e) {
    console.warn(e);
  }
}

function select(kind, id, again = false) {
  if (!again && state.selected && state.selected.kind === kind && state.selected.id === id) return;
  state.selected = { kind, id };
  history.replaceState(null, "", `#${kind}=${encodeURIComponent(id)}`);
  $("empty").hidden = true;
  $("run-view").hidden = kind !== "run";
  $("ensemble-view").hidden = kind !== "ensemble";
  $("axis-control").hidden = kind !== "ensemble";
  if (kind === "run") {
    ensembleView.hide();
    runView.show(id);
    const summary = state.runs.find((r) => r.run === id);
    if (summary) runView.summary(summary, complete(summary));
  } else {
    runView.hide();
    ensembleView.show(id);
    const summary = state.ensembles.find((e) => e.ensemble === id);
    if (summary) ensembleView.summary(summary);
  }
  renderRuns();
  renderEnsembles();
}

for (const id of ["metric", "dim", "force", "essential", "log", "axis"])
  $(id).addEventListener("change", () => {
    if (!state.selected) return;
    if (state.selected.kind === "run") runView.optionsChanged(id === "log");
    else ensembleView.optionsChanged(id === "log");
  });
window.addEventListener("resize", () => {
  runView.resize();
  ensembleView.redraw();
});

const hash = /^#(run|ensemble)=(.+)$/.exec(location.hash);
if (hash) select(hash[1], decodeURIComponent(hash[2]));
else $("axis-control").hidden = true;
setInterval(refreshLists, 2000);
