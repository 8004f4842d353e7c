// A persistence diagram (the paper's Fig. 3): each point (birth, death) of the superlevel
// filtration, birth ≥ death, in units of the frame's mean force; a class that never dies has
// death −1 and sits on the line drawn there.

import { plot } from "./plot.js";

export function drawDiagram(canvas, answer, color) {
  const points = answer ? answer.points : [];
  const top = Math.max(1, ...points.map((p) => p[0])) * 1.05;
  const never = points.filter((p) => p[1] === -1).length;
  return plot(canvas, {
    x: { label: "birth (force / mean force)", range: [0, top] },
    y: { label: "death", log: false, range: [-1.15, top] },
    series: [
      { name: "", color: "#b8b8bf", points: [{ x: 0, y: 0 }, { x: top, y: top }], width: 1 },
      { name: "", color: "#b8b8bf", points: [{ x: 0, y: -1 }, { x: top, y: -1 }], width: 1, dash: [4, 4] },
      {
        name: answer ? `PD${answer.dim}: ${points.length} points, ${never} never die (death −1)` : "",
        color, line: false, markers: true, radius: 2.4,
        points: points.map((p, k) => ({ x: p[0], y: p[1], key: k })),
      },
    ],
    empty: "no diagram yet",
  });
}
