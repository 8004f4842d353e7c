// A frame's force network on a canvas, as the paper's Fig. 1 draws it: the grains as discs, each
// contact as a segment between the centres of its grains, coloured and thickened by its force
// over the frame's mean force, inside the walls' box (the bounding box of the grains' discs, which
// the walls enclose). A 3D frame is drawn as its projection on the xy plane.
//
// In change mode the segments show the change in force per contact from a previous frame (each
// force over its own frame's mean force; a contact present in one frame only changes from or to
// 0), the cells of a block table are shaded by their distance, and the explained terms of the
// distance are ringed where they sit, numbered by rank. Segments are drawn in one path per colour
// bin, and a large network in several tasks (the page answers input in between), so that a frame of
// 20 000 grains never holds the page for long.

import { changeColor, forceColor, heatColor } from "./colors.js";
import { fitCanvas } from "./plot.js";

const BINS = 24;
const FORCE_TOP = 3;  // force / mean force at the top of the scale
const SEGMENTS_PER_TASK = 15000;

// Lets the page run its other tasks; false when a newer drawing has taken the canvas meanwhile.
async function stillMine(canvas, token) {
  await new Promise((resolve) => setTimeout(resolve, 0));
  return canvas.fnetDrawing === token;
}

function contactKey(i, j) {
  return i < j ? i * 4294967296 + j : j * 4294967296 + i;
}

// f / mean f of each contact, for one force kind (0 where the mean is 0).
function normalized(net, force) {
  const mean = net.mean_force[force];
  const column = force === "normal" ? 2 : 3;
  return net.contacts.map((c) => (mean > 0 ? Math.abs(c[column]) / mean : 0));
}

function domainOf(net) {
  if (net.domain) return net.domain;
  let [xl, xh, yl, yh] = [Infinity, -Infinity, Infinity, -Infinity];
  for (const p of net.particles) {
    xl = Math.min(xl, p[0] - p[2]);
    xh = Math.max(xh, p[0] + p[2]);
    yl = Math.min(yl, p[1] - p[2]);
    yh = Math.max(yh, p[1] + p[2]);
  }
  return [xl, xh, yl, yh];
}

// The map from the frame's coordinates to the canvas's pixels (y up), the box with a margin.
function transformFor(domain, w, h) {
  const [xl, xh, yl, yh] = domain;
  const pad = 0.02 * Math.max(xh - xl, yh - yl, 1e-9);
  const s = Math.min(w / (xh - xl + 2 * pad), h / (yh - yl + 2 * pad));
  const ox = (w - s * (xh - xl)) / 2, oy = (h - s * (yh - yl)) / 2;
  return { s, x: (x) => ox + (x - xl) * s, y: (y) => h - oy - (y - yl) * s };
}

function drawGrains(ctx, net, t) {
  ctx.beginPath();
  for (const p of net.particles) {
    const x = t.x(p[0]), y = t.y(p[1]), r = p[2] * t.s;
    ctx.moveTo(x + r, y);
    ctx.arc(x, y, r, 0, 2 * Math.PI);
  }
  ctx.fillStyle = "#f1f1f3";
  ctx.fill();
  if (net.particles.length <= 5000) {
    ctx.strokeStyle = "#c9c9cf";
    ctx.lineWidth = 0.6;
    ctx.stroke();
  }
}

// Segments by bin: `binOf(k)` gives contact k's bin (or -1: not drawn), `colorOf(b)` and
// `widthOf(b)` the bin's colour and width in pixels. False when the drawing was given up.
async function drawSegments(canvas, token, ctx, t, count, ends, binOf, colorOf, widthOf) {
  const paths = Array.from({ length: BINS }, () => []);
  for (let k = 0; k < count; ++k) {
    const b = binOf(k);
    if (b >= 0) paths[b].push(k);
  }
  let drawn = 0;
  for (let b = 0; b < BINS; ++b) {
    if (!paths[b].length) continue;
    if (drawn >= SEGMENTS_PER_TASK) {
      if (!(await stillMine(canvas, token))) return false;
      drawn = 0;
    }
    ctx.lineCap = "round";
    ctx.beginPath();
    for (const k of paths[b]) {
      const [pi, pj] = ends(k);
      ctx.moveTo(t.x(pi[0]), t.y(pi[1]));
      ctx.lineTo(t.x(pj[0]), t.y(pj[1]));
    }
    ctx.strokeStyle = colorOf(b);
    ctx.lineWidth = widthOf(b);
    ctx.stroke();
    drawn += paths[b].length;
  }
  return true;
}

function drawBox(ctx, domain, t) {
  const [xl, xh, yl, yh] = domain;
  ctx.strokeStyle = "#444";
  ctx.lineWidth = 2;
  ctx.strokeRect(t.x(xl), t.y(yh), (xh - xl) * t.s, (yh - yl) * t.s);
  ctx.lineWidth = 1;
}

function meanRadius(net) {
  if (!net.particles.length) return 1;
  let sum = 0;
  for (const p of net.particles) sum += p[2];
  return sum / net.particles.length;
}

// The network of one frame, its contacts coloured by force / mean force; null when it has no
// positions or a newer drawing took the canvas.
export async function drawNetwork(canvas, net, force) {
  const token = (canvas.fnetDrawing = (canvas.fnetDrawing || 0) + 1);
  if (!(await stillMine(canvas, token))) return null;  // the answer's parsing apart from the drawing
  const { ctx, w, h } = fitCanvas(canvas);
  if (!net.particles.length) {
    ctx.fillStyle = "#6b6b70";
    ctx.fillText("this frame was stored without its grains' positions", 10, 20);
    return null;
  }
  const domain = domainOf(net);
  const t = transformFor(domain, w, h);
  drawGrains(ctx, net, t);
  drawBox(ctx, domain, t);
  const f = normalized(net, force);
  const rpx = meanRadius(net) * t.s;
  const P = net.particles;
  if (net.particles.length > SEGMENTS_PER_TASK && !(await stillMine(canvas, token))) return null;
  const complete = await drawSegments(
    canvas, token, ctx, t, net.contacts.length, (k) => [P[net.contacts[k][0]], P[net.contacts[k][1]]],
    (k) => (f[k] > 0 ? Math.min(BINS - 1, Math.floor((f[k] / FORCE_TOP) * BINS)) : -1),
    (b) => forceColor((b + 0.5) / BINS),
    (b) => Math.max(0.6, rpx * (0.15 + (0.75 * (b + 0.5)) / BINS)));
  return complete ? { transform: t, domain, top: FORCE_TOP } : null;
}

// The change from `before` to `after` (two frames of a run) drawn on `after`'s grains, with the
// block table and the explained terms of the distance over it; null when there are no positions
// or a newer drawing took the canvas.
export async function drawChange(canvas, before, after, force, blocks, terms) {
  const token = (canvas.fnetDrawing = (canvas.fnetDrawing || 0) + 1);
  if (!(await stillMine(canvas, token))) return null;
  const { ctx, w, h } = fitCanvas(canvas);
  if (!after.particles.length || !before.particles.length) {
    ctx.fillStyle = "#6b6b70";
    ctx.fillText("these frames were stored without their grains' positions", 10, 20);
    return null;
  }
  const domain = domainOf(after);
  const t = transformFor(domain, w, h);

  drawGrains(ctx, after, t);
  // The block table as a heat map over the grains, under the contacts: each cell of `after`'s grid.
  // A 3D grid is drawn as its projection: each (row, col) column of cells shaded by its largest.
  if (blocks) {
    const columns = new Map();
    for (const c of blocks.cells) {
      const key = `${c.row},${c.col}`, held = columns.get(key);
      const larger = !held || (c.infinite && !held.infinite) || (!held.infinite && c.value > held.value);
      if (larger) columns.set(key, c);
    }
    const cells = [...columns.values()];
    const finite = cells.filter((c) => !c.infinite).map((c) => c.value);
    const top = Math.max(...finite, 1e-12);
    for (const c of cells) {
      const [xl, xh, yl, yh] = c.bounds[1];
      ctx.fillStyle = c.infinite ? "#7a0020" : heatColor(c.value / top);
      ctx.globalAlpha = 0.4;
      ctx.fillRect(t.x(xl), t.y(yh), (xh - xl) * t.s, (yh - yl) * t.s);
      ctx.globalAlpha = 1;
      ctx.strokeStyle = "#fff";
      ctx.strokeRect(t.x(xl), t.y(yh), (xh - xl) * t.s, (yh - yl) * t.s);
    }
  }

  // Δ(f / mean f) per contact.
  const fa = normalized(after, force), fb = normalized(before, force);
  const was = new Map();
  before.contacts.forEach((c, k) => was.set(contactKey(c[0], c[1]), fb[k]));
  const rows = [];  // [i, j, delta], on after's grains
  after.contacts.forEach((c, k) => {
    const key = contactKey(c[0], c[1]);
    rows.push([c[0], c[1], fa[k] - (was.get(key) || 0)]);
    was.delete(key);
  });
  const gone = [];
  before.contacts.forEach((c, k) => {
    if (was.has(contactKey(c[0], c[1])) && fb[k] > 0) gone.push([c[0], c[1], -fb[k]]);
  });
  const changes = rows.concat(gone).filter((r) => r[2] !== 0);
  const magnitudes = Float64Array.from(changes, (r) => Math.abs(r[2])).sort();
  const clip = Math.max(0.25, magnitudes.length ? magnitudes[Math.floor(0.95 * (magnitudes.length - 1))] : 0);
  const P = after.particles;
  const rpx = meanRadius(after) * t.s;
  const half = BINS / 2;
  drawBox(ctx, domain, t);
  if (after.particles.length > SEGMENTS_PER_TASK && !(await stillMine(canvas, token))) return null;
  const complete = await drawSegments(
    canvas, token, ctx, t, changes.length,
    (k) => [P[changes[k][0]] || before.particles[changes[k][0]], P[changes[k][1]] || before.particles[changes[k][1]]],
    (k) => Math.max(0, Math.min(BINS - 1, Math.floor(half + (changes[k][2] / clip) * half))),
    (b) => changeColor((b + 0.5) / BINS),
    (b) => Math.max(0.7, rpx * (0.15 + (0.8 * Math.abs(b + 0.5 - half)) / half)));
  if (!complete) return null;

  // The explained terms: a ring where each sits (the centre of the grains that create its
  // feature in the later frame, else in the earlier one), numbered by rank.
  const marks = [];
  for (const term of terms || []) {
    const point = term.b || term.a;
    const simplex = point && point.birth_simplex;
    if (!simplex || !simplex.positions || !simplex.positions.length) continue;
    const cx = simplex.positions.reduce((s, p) => s + p[0], 0) / simplex.positions.length;
    const cy = simplex.positions.reduce((s, p) => s + p[1], 0) / simplex.positions.length;
    const x = t.x(cx), y = t.y(cy);
    const radius = Math.max(9, 2.5 * rpx);
    ctx.lineWidth = 2.5;
    ctx.strokeStyle = "#111";
    ctx.beginPath();
    ctx.arc(x, y, radius, 0, 2 * Math.PI);
    ctx.stroke();
    ctx.font = "bold 13px system-ui, 'DejaVu Sans', sans-serif";
    ctx.fillStyle = "#111";
    ctx.textAlign = "left";
    ctx.textBaseline = "bottom";
    // The number beside its ring, kept on the canvas by a ring at its edge.
    const lx = Math.min(Math.max(x + radius * 0.75, 2), w - 12), ly = Math.min(Math.max(y - radius * 0.75, 16), h - 2);
    ctx.fillText(String(term.rank), lx, ly);
    ctx.lineWidth = 1;
    marks.push({ rank: term.rank, x: cx, y: cy });
  }
  return { transform: t, domain, clip, changed: changes.length, marks };
}

// A legend: what the colours show, then a swatch of the scale between its two ends' labels.
export function legend(element, scale, lo, hi, text) {
  element.replaceChildren();
  const c = document.createElement("canvas");
  c.width = 140;
  c.height = 10;
  const ctx = c.getContext("2d");
  for (let x = 0; x < 140; ++x) {
    ctx.fillStyle = scale(x / 139);
    ctx.fillRect(x, 0, 1, 10);
  }
  const description = document.createElement("span");
  description.className = "description";
  description.textContent = text;
  element.append(description, lo, c, hi);
}
