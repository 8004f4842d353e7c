#!/usr/bin/env bash
# README's first command: installs what is missing, builds, and runs the main job on a small
# default. Until the streaming service lands this analyzes a shipped LAMMPS frame of a 2 000-disk
# compression: persistence diagrams of its normal-force network.
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/setup.sh
bash deploy/build.sh -DFNET_BUILD_TESTS=OFF
frame=tests/data/lammps-mu0.5-seed777/frame_0008
echo
echo "== fnet-analyze diagram on ${frame} (rho = 0.833, normal forces) =="
./build/server/analysis/fnet-analyze diagram --contacts "${frame}_contacts.csv" --particles "${frame}_particles.csv" \
  > build/quickstart-diagram.json
python3 - build/quickstart-diagram.json <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
print(f"vertices {d['vertices']}, edges {d['edges']}, triangles {d['triangles']}")
for dim in ("pd0", "pd1"):
    pts = d[dim]
    essential = sum(1 for b, e in pts if e == -1)
    print(f"{dim}: {len(pts)} points ({essential} never die); strongest: "
          + ", ".join(f"({b:.3f}, {e:.3f})" for b, e in pts[:3]))
print(f"full diagrams: {sys.argv[1]}")
PY
