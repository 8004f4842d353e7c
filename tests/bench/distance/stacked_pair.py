"""The "30 000-point stacked pair": PD1s of 38 LAMMPS frame pairs stacked into one diagram pair.

usage: stacked_pair.py FNET_ANALYZE FRAMES_DIR OUT_A.json OUT_B.json [--pairs 38] [--force normal,tangential]

FRAMES_DIR holds frame_NNNN_{contacts,particles}.csv (tests/data/lammps-mu0.5-seed777: 11 frames of
one 2 000-disk compression; frames 0-4 have no loops, so the pairs are taken among frames 5-10). The
pairs, nearest first, until --pairs are taken: gap 1 forward (t, t + 1), gap 1 backward (t + 1, t),
then gaps 2, 3, ... alike, each direction for the normal and then the tangential forces, t
ascending: the 20 pairs of gap 1, the 16 of gap 2 and the first 2 of gap 3 make the 38 pairs, 30 563
points in A and 32 436 in B (floor convention: a class that never dies dies at 0;
points on the diagonal dropped). Copy k of a pair is moved along the diagonal by k * OFFSET, both
coordinates: persistence (the cost to the diagonal) and distances within a copy are unchanged, and
a pair of points from different copies is farther apart than both their diagonal costs together,
so no optimal matching uses it - W_q^q of the stack is the sum of the 38 pairs' W_q^q (the copies
do not interact), while no single death line holds most points any more. Deterministic.
"""
import json
import os
import subprocess
import sys


def diagram(exe, frames, frame, force, cache):
    key = (frame, force)
    if key not in cache:
        out = subprocess.run([exe, "diagram", "--contacts", os.path.join(frames, f"frame_{frame:04d}_contacts.csv"),
                              "--particles", os.path.join(frames, f"frame_{frame:04d}_particles.csv"),
                              "--force", force], capture_output=True, text=True, check=True).stdout
        cache[key] = [(b, 0.0 if d == -1 else d) for b, d in json.loads(out)["pd1"]]
    return cache[key]


FIRST_FRAME, LAST_FRAME = 5, 10  # the frames with loops: PD1 of 200 to 1 268 points


def pair_list(count, forces):
    """Frame pairs nearest first: gap 1, 2, 3, ..., each gap forward (t, t + gap) then backward
    (t + gap, t), each direction for every force, t ascending."""
    pairs = []
    for gap in range(1, LAST_FRAME - FIRST_FRAME + 1):
        for forward in (True, False):
            for f in forces:
                for t in range(FIRST_FRAME, LAST_FRAME - gap + 1):
                    pairs.append((t, t + gap, f) if forward else (t + gap, t, f))
    return pairs[:count]


def stacked(exe, frames, count, forces):
    cache = {}
    pairs = pair_list(count, forces)
    top = 0.0
    for s, t, f in pairs:
        for p in diagram(exe, frames, s, f, cache) + diagram(exe, frames, t, f, cache):
            top = max(top, abs(p[0]), abs(p[1]))
    offset = 4 * top + 1  # > any coordinate range within a copy plus both diagonal costs
    a, b = [], []
    for k, (s, t, f) in enumerate(pairs):
        shift = k * offset
        a += [[x + shift, y + shift] for x, y in diagram(exe, frames, s, f, cache) if x != y]
        b += [[x + shift, y + shift] for x, y in diagram(exe, frames, t, f, cache) if x != y]
    return a, b, pairs


def main(argv):
    exe, frames, out_a, out_b = argv[1:5]
    count, forces = 38, ["normal", "tangential"]
    rest = argv[5:]
    for k in range(0, len(rest), 2):
        if rest[k] == "--pairs":
            count = int(rest[k + 1])
        elif rest[k] == "--force":
            forces = rest[k + 1].split(",")
    a, b, pairs = stacked(exe, frames, count, forces)
    for path, points in ((out_a, a), (out_b, b)):
        with open(path, "w") as f:
            json.dump({"pd0": [], "pd1": points}, f)
    print(f"{len(pairs)} pairs stacked: {len(a)} points in A, {len(b)} in B", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv)
