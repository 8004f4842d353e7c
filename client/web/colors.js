// Colour scales of the dashboard: a sequential one for forces (pale for weak contacts, dark red
// for the strongest, as force chains read in the paper's Fig. 1), a diverging one for changes
// (blue: weaker, red: stronger), and a heat scale for the block table.

const FORCE = [[255, 237, 160], [254, 178, 76], [240, 59, 32], [189, 0, 38], [74, 0, 16]];
const CHANGE = [[33, 102, 172], [146, 197, 222], [235, 235, 235], [244, 165, 130], [178, 24, 43]];
const HEAT = [[255, 255, 204], [253, 141, 60], [189, 0, 38]];

function along(stops, t) {
  const u = Math.min(Math.max(t, 0), 1) * (stops.length - 1);
  const k = Math.min(Math.floor(u), stops.length - 2);
  const f = u - k;
  const c = stops[k].map((v, i) => Math.round(v + f * (stops[k + 1][i] - v)));
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}

export const forceColor = (t) => along(FORCE, t);    // t in [0, 1]
export const changeColor = (t) => along(CHANGE, t);  // t in [-1, 1] mapped to [0, 1] by the caller
export const heatColor = (t) => along(HEAT, t);

// The colours of the curves: one per metric or series, distinguishable in print too.
export const SERIES_COLORS = ["#1f5fbf", "#d1495b", "#2a9d55", "#8f5bb3", "#e08a00"];
