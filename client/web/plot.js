// Line charts on a canvas: linear or logarithmic y, an optional second y axis (Z), bands
// (mean ± standard error), vertical marks (ρ_J) and points that can be clicked. plot() draws
// the whole chart from a spec and returns what the page needs to find a point under the pointer.
//
// spec = {x: {label}, y: {label, log}, y2: {label} | null, series: [{name, color, axis: "y"|"y2",
//   points: [{x, y, lo?, hi?, key?}], line, markers, band, dash}], vlines: [{x, label, color}],
//   selected: key | null, empty: text shown when no series has a point}
// A point whose y is null is a gap; on a log axis a y <= 0 is marked on the bottom edge.

const MARGIN = { left: 66, right: 60, top: 28, bottom: 42 };

// Sizes the canvas's backing store to its displayed size; returns the 2D context in CSS pixels.
export function fitCanvas(canvas) {
  const ratio = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(canvas.clientWidth)), h = Math.max(1, Math.round(canvas.clientHeight));
  if (canvas.width !== Math.round(w * ratio) || canvas.height !== Math.round(h * ratio)) {
    canvas.width = Math.round(w * ratio);
    canvas.height = Math.round(h * ratio);
  }
  const ctx = canvas.getContext("2d");
  ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  ctx.clearRect(0, 0, w, h);
  return { ctx, w, h };
}

function niceStep(span, count) {
  const raw = span / Math.max(count, 1);
  const power = Math.pow(10, Math.floor(Math.log10(raw)));
  const f = raw / power;
  return (f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10) * power;
}

function linearTicks(lo, hi, count) {
  const step = niceStep(hi - lo, count);
  const ticks = [];
  for (let t = Math.ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step) ticks.push(Math.abs(t) < step * 1e-9 ? 0 : t);
  return { ticks, step };
}

// The range of a linear axis holding every value, a little wider.
function linearRange(values) {
  let lo = Math.min(...values), hi = Math.max(...values);
  if (!isFinite(lo)) return [0, 1];
  if (lo === hi) {
    const d = lo === 0 ? 1 : Math.abs(lo) * 0.1;
    return [lo - d, hi + d];
  }
  const pad = (hi - lo) * 0.04;
  return [lo - pad, hi + pad];
}

function logRange(values) {
  const positive = values.filter((v) => v > 0);
  if (!positive.length) return [0.1, 10];
  // A little room on either side (a factor 1.4), so that no point sits on the frame.
  const lo = Math.min(...positive) / 1.4, hi = Math.max(...positive) * 1.4;
  return hi / lo < 10 ? [Math.sqrt(lo * hi) / 3.2, Math.sqrt(lo * hi) * 3.2] : [lo, hi];
}

export function formatNumber(v, digits = 3) {
  if (v === null || v === undefined || !isFinite(v)) return "–";
  if (v === 0) return "0";
  const a = Math.abs(v);
  if (a >= 1e4 || a < 1e-3) return v.toExponential(Math.max(digits - 1, 0)).replace("e", "·10^").replace("+", "");
  return Number(v.toPrecision(digits)).toString();
}

function tickLabel(v, step) {
  if (v === 0) return "0";
  const decimals = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  return Math.abs(v) >= 1e4 || Math.abs(v) < 1e-3 ? formatNumber(v, 2) : v.toFixed(Math.min(decimals, 6));
}

function decadeLabel(k) {
  if (k >= -2 && k <= 3) return String(Math.pow(10, k)).replace(/^0\./, "0.");
  return "10" + String(k).replace("-", "⁻").replace(/[0-9]/g, (d) => "⁰¹²³⁴⁵⁶⁷⁸⁹"[d]);
}

export function plot(canvas, spec) {
  const { ctx, w, h } = fitCanvas(canvas);
  const right = spec.y2 ? MARGIN.right : 18;
  const box = { x0: MARGIN.left, x1: w - right, y0: MARGIN.top, y1: h - MARGIN.bottom };
  const all = spec.series.flatMap((s) => s.points);
  const onY = spec.series.filter((s) => (s.axis || "y") === "y").flatMap((s) => s.points);
  const onY2 = spec.series.filter((s) => s.axis === "y2").flatMap((s) => s.points);
  const layout = { points: [], box };
  ctx.font = "12px system-ui, 'DejaVu Sans', sans-serif";
  if (!all.length) {
    ctx.fillStyle = "#6b6b70";
    ctx.textAlign = "center";
    ctx.fillText(spec.empty || "no data yet", w / 2, h / 2);
    layout.hit = () => null;
    return layout;
  }

  const xs = all.map((p) => p.x).concat((spec.vlines || []).map((v) => v.x)).filter((v) => v !== null && isFinite(v));
  const [xlo, xhi] = spec.x.range || linearRange(xs);
  const yValues = onY.flatMap((p) => [p.y, p.lo, p.hi]).filter((v) => v !== null && v !== undefined && isFinite(v));
  const log = !!spec.y.log;
  const [ylo, yhi] = spec.y.range || (log ? logRange(yValues) : linearRange(yValues.length ? yValues : [0, 1]));
  const y2Values = onY2.map((p) => p.y).filter((v) => v !== null && isFinite(v));
  const [zlo, zhi] = spec.y2 ? spec.y2.range || linearRange(y2Values.length ? y2Values : [0, 1]) : [0, 1];

  const sx = (x) => box.x0 + ((x - xlo) / (xhi - xlo)) * (box.x1 - box.x0);
  const sy = log
    ? (y) => box.y1 - ((Math.log10(y) - Math.log10(ylo)) / (Math.log10(yhi) - Math.log10(ylo))) * (box.y1 - box.y0)
    : (y) => box.y1 - ((y - ylo) / (yhi - ylo)) * (box.y1 - box.y0);
  const sz = (z) => box.y1 - ((z - zlo) / (zhi - zlo)) * (box.y1 - box.y0);
  layout.sx = sx;
  layout.sy = sy;

  // Grid and axes.
  ctx.strokeStyle = "#ececef";
  ctx.fillStyle = "#3a3a3d";
  ctx.lineWidth = 1;
  const xt = linearTicks(xlo, xhi, Math.max(3, Math.floor((box.x1 - box.x0) / 90)));
  ctx.textAlign = "center";
  ctx.textBaseline = "top";
  for (const t of xt.ticks) {
    const px = Math.round(sx(t)) + 0.5;
    ctx.beginPath();
    ctx.moveTo(px, box.y0);
    ctx.lineTo(px, box.y1);
    ctx.stroke();
    ctx.fillText(tickLabel(t, xt.step), px, box.y1 + 5);
  }
  ctx.textAlign = "right";
  ctx.textBaseline = "middle";
  if (log) {
    // Decades labelled; with fewer than two in range, 2 and 5 times them too.
    const k0 = Math.floor(Math.log10(ylo)), k1 = Math.ceil(Math.log10(yhi));
    const decades = k1 - k0;
    const labelled = Math.ceil(Math.log10(ylo) - 1e-9) > Math.floor(Math.log10(yhi) + 1e-9) - 1;
    for (let k = k0; k <= k1; ++k) {
      for (let m = 1; m < 10; ++m) {
        const v = m * Math.pow(10, k);
        if (v < ylo * (1 - 1e-9) || v > yhi * (1 + 1e-9) || (decades > 5 && m > 1)) continue;
        const py = Math.round(sy(v)) + 0.5;
        ctx.strokeStyle = m === 1 ? "#e2e2e6" : "#f3f3f5";
        ctx.beginPath();
        ctx.moveTo(box.x0, py);
        ctx.lineTo(box.x1, py);
        ctx.stroke();
        if (m === 1) ctx.fillText(decadeLabel(k), box.x0 - 6, py);
        else if (labelled && (m === 2 || m === 5)) ctx.fillText(formatNumber(v, 2), box.x0 - 6, py);
      }
    }
  } else {
    const yt = linearTicks(ylo, yhi, Math.max(3, Math.floor((box.y1 - box.y0) / 45)));
    for (const t of yt.ticks) {
      const py = Math.round(sy(t)) + 0.5;
      ctx.beginPath();
      ctx.moveTo(box.x0, py);
      ctx.lineTo(box.x1, py);
      ctx.stroke();
      ctx.fillText(tickLabel(t, yt.step), box.x0 - 6, py);
    }
  }
  if (spec.y2) {
    ctx.textAlign = "left";
    const zt = linearTicks(zlo, zhi, Math.max(3, Math.floor((box.y1 - box.y0) / 45)));
    ctx.fillStyle = spec.y2.color || "#6b6b70";
    for (const t of zt.ticks) ctx.fillText(tickLabel(t, zt.step), box.x1 + 6, sz(t));
  }
  ctx.strokeStyle = "#9a9aa0";
  ctx.strokeRect(box.x0 + 0.5, box.y0 + 0.5, box.x1 - box.x0, box.y1 - box.y0);

  // Axis labels.
  ctx.fillStyle = "#3a3a3d";
  ctx.textAlign = "center";
  ctx.textBaseline = "bottom";
  ctx.fillText(spec.x.label, (box.x0 + box.x1) / 2, h - 4);
  ctx.save();
  ctx.translate(14, (box.y0 + box.y1) / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.textBaseline = "middle";
  ctx.fillText(spec.y.label + (log ? " (log)" : ""), 0, 0);
  ctx.restore();
  if (spec.y2) {
    ctx.save();
    ctx.translate(w - 12, (box.y0 + box.y1) / 2);
    ctx.rotate(Math.PI / 2);
    ctx.textBaseline = "middle";
    ctx.fillStyle = spec.y2.color || "#6b6b70";
    ctx.fillText(spec.y2.label, 0, 0);
    ctx.restore();
  }

  ctx.save();
  ctx.beginPath();
  ctx.rect(box.x0, box.y0 - 6, box.x1 - box.x0, box.y1 - box.y0 + 12);
  ctx.clip();

  // Vertical marks.
  for (const v of spec.vlines || []) {
    if (v.x === null || !isFinite(v.x)) continue;
    const px = Math.round(sx(v.x)) + 0.5;
    ctx.strokeStyle = v.color || "#555";
    ctx.setLineDash([5, 4]);
    ctx.beginPath();
    ctx.moveTo(px, box.y0);
    ctx.lineTo(px, box.y1);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = v.color || "#555";
    ctx.textAlign = "left";
    ctx.textBaseline = "top";
    ctx.fillText(v.label, px + 4, box.y0 + 2);
  }

  const ok = (y) => y !== null && y !== undefined && isFinite(y) && (!log || y > 0);
  for (const s of spec.series) {
    const scale = s.axis === "y2" ? sz : sy;
    // Band: lo .. hi, broken where a bound is missing.
    if (s.band) {
      ctx.fillStyle = s.color;
      ctx.globalAlpha = 0.2;
      let run = [];
      const flush = () => {
        if (run.length > 1) {
          ctx.beginPath();
          run.forEach((p, k) => (k ? ctx.lineTo(sx(p.x), scale(p.hi)) : ctx.moveTo(sx(p.x), scale(p.hi))));
          for (let k = run.length - 1; k >= 0; --k) ctx.lineTo(sx(run[k].x), scale(run[k].lo));
          ctx.closePath();
          ctx.fill();
        }
        run = [];
      };
      for (const p of s.points) (ok(p.lo) && ok(p.hi) ? run.push(p) : flush());
      flush();
      ctx.globalAlpha = 1;
    }
    if (s.line !== false) {
      ctx.strokeStyle = s.color;
      ctx.lineWidth = s.width || 1.6;
      ctx.setLineDash(s.dash || []);
      ctx.beginPath();
      let drawing = false;
      for (const p of s.points) {
        if (!ok(p.y)) {
          drawing = false;
          continue;
        }
        if (drawing) ctx.lineTo(sx(p.x), scale(p.y));
        else ctx.moveTo(sx(p.x), scale(p.y));
        drawing = true;
      }
      ctx.stroke();
      ctx.setLineDash([]);
      ctx.lineWidth = 1;
    }
    if (s.markers) {
      for (const p of s.points) {
        if (p.y === null || p.y === undefined || !isFinite(p.y)) continue;
        const px = sx(p.x);
        ctx.fillStyle = s.color;
        ctx.strokeStyle = s.color;
        if (log && p.y <= 0) {  // below a log axis: an open triangle on its bottom edge
          ctx.beginPath();
          ctx.moveTo(px, box.y1 - 8);
          ctx.lineTo(px - 4, box.y1);
          ctx.lineTo(px + 4, box.y1);
          ctx.closePath();
          ctx.stroke();
          layout.points.push({ series: s, point: p, px, py: box.y1 - 3 });
          continue;
        }
        const py = scale(p.y);
        ctx.beginPath();
        ctx.arc(px, py, s.radius || 2.6, 0, 2 * Math.PI);
        ctx.fill();
        layout.points.push({ series: s, point: p, px, py });
        if (spec.selected !== undefined && spec.selected !== null && p.key === spec.selected) {
          ctx.lineWidth = 2;
          ctx.strokeStyle = "#111";
          ctx.beginPath();
          ctx.arc(px, py, 7, 0, 2 * Math.PI);
          ctx.stroke();
          ctx.lineWidth = 1;
        }
      }
    }
  }
  ctx.restore();

  // Legend, above the frame.
  ctx.textAlign = "left";
  ctx.textBaseline = "middle";
  let lx = box.x0;
  const ly = box.y0 - 13;
  for (const s of spec.series) {
    if (!s.name) continue;
    const label = s.name;
    const width = ctx.measureText(label).width;
    ctx.strokeStyle = s.color;
    ctx.fillStyle = s.color;
    ctx.lineWidth = 2;
    ctx.setLineDash(s.dash || []);
    ctx.beginPath();
    ctx.moveTo(lx, ly);
    ctx.lineTo(lx + 16, ly);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.lineWidth = 1;
    if (s.markers) {
      ctx.beginPath();
      ctx.arc(lx + 8, ly, 2.6, 0, 2 * Math.PI);
      ctx.fill();
    }
    ctx.fillStyle = "#3a3a3d";
    ctx.fillText(label, lx + 20, ly);
    lx += width + 34;
  }
  if (log && layout.points.some((p) => p.point.y !== null && p.point.y <= 0)) {
    ctx.textAlign = "right";
    ctx.fillStyle = "#6b6b70";
    ctx.fillText("△ on the axis: 0", box.x1, ly);
  }

  layout.hit = (px, py, radius = 9) => {
    let best = null, bestD = radius * radius;
    for (const p of layout.points) {
      const d = (p.px - px) ** 2 + (p.py - py) ** 2;
      if (d <= bestD) {
        best = p;
        bestD = d;
      }
    }
    return best;
  };
  return layout;
}
