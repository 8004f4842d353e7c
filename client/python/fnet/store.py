"""Readers for fnet's HDF5 files, live or finished (h5py in SWMR mode):

- the analysis store fnet-server writes per run, `DATA_DIR/RUN.h5` (proto/store.md), and
- the run file fnet-simd writes with `--out` (proto/run_file.md; also the older `fnet-run-1`).

Both are appended to while they are read: call `refresh()` to see frames committed since.
"""

import json

import numpy as np

from fnet.arrays import Result
from fnet.rpc import DEFAULT_DIM

METRICS = ("bottleneck", "wasserstein1", "wasserstein2")
FORCES = ("normal", "tangential")
# fnet-store-2 adds each frame's network, fnet-store-3 its dimension and the z of 3D frames.
STORE_SCHEMAS = ("fnet-store-1", "fnet-store-2", "fnet-store-3")
RUN_SCHEMAS = ("fnet-run-1", "fnet-run-2", "fnet-run-3")  # fnet-run-3 adds dimension and particle_z


def series_key(metric, dim, force):
    """'wasserstein2/pd1/normal': how the API and a store's `series` attribute name a stored series."""
    if metric not in METRICS:
        raise ValueError(f"metric: the store holds {', '.join(METRICS)}, not {metric!r}")
    if dim not in (0, 1):
        raise ValueError(f"dim: 0 or 1, not {dim!r}")
    if force not in FORCES:
        raise ValueError(f"force: normal or tangential, not {force!r}")
    return f"{metric}/pd{dim}/{force}"


# The columns of `distances` in stores written before the `series` attribute named them.
_UNNAMED_LAYOUT = tuple(f"{m}/pd{d}/{f}" for m in METRICS for d in (0, 1) for f in FORCES)


def distance_column(store_file, metric, dim, force):
    """The column of a store's `distances` holding one of its twelve distances, as the store's
    `series` attribute names them."""
    key = series_key(metric, dim, force)
    layout = store_file.attrs.get("series")
    keys = _text(layout).split(",") if layout is not None else list(_UNNAMED_LAYOUT)
    if key not in keys:
        raise ValueError(f"{store_file.filename}: attribute 'series' does not name {key}")
    return keys.index(key)


def _text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def _fixed_strings(dataset, n):
    return [bytes(v).rstrip(b"\0").decode() for v in dataset[:n]]


def _h5py():
    """h5py, imported here rather than with fnet: the RPC client works without it."""
    try:
        import h5py
    except ImportError as e:  # a python3 other than Debian's (a pyenv one, say) may lack it
        raise ImportError(f"fnet.store reads HDF5 files with h5py: Debian's python3 (/usr/bin/python3) with "
                          f"python3-h5py ({e})") from e
    return h5py


def _open(path):
    return _h5py().File(path, "r", libver="latest", swmr=True)


class _SwmrFile:
    """An HDF5 file of fnet opened read-only in SWMR mode, its schema one of `schemas` (else
    ValueError naming the file and the schemas); a context manager that closes it."""

    def __init__(self, path, schemas):
        self.path = str(path)
        self.file = _open(self.path)
        self.schema = _text(self.file.attrs.get("schema", ""))
        if self.schema not in schemas:
            self.file.close()
            raise ValueError(f"{self.path}: schema {self.schema!r}, expected one of {', '.join(schemas)}")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self.file.close()


class Store(_SwmrFile):
    """An analysis store (schema fnet-store-1, -2 or -3), opened read-only in SWMR mode."""

    def __init__(self, path):
        super().__init__(path, STORE_SCHEMAS)
        self.run_id = _text(self.file.attrs["run_id"])
        self.refresh()

    def refresh(self):
        """Reads the frames committed so far: `frame` first, then every column up to its length."""
        f = self.file
        f["frame"].refresh()
        n = len(f["frame"])
        cols = {}
        for name in ("frame", "step", "time", "rho", "z", "previous", "distances", "counts", "offsets",
                     "committed_at"):
            f[name].refresh()
            cols[name] = f[name][:n]
        f["points"].refresh()
        points = f["points"][:]
        # A frame whose diagrams point past the end of `points`, or whose network past the end of
        # the network datasets, is not committed.
        committed = cols["offsets"][:, 4] <= len(points)
        if "network_offsets" in f:
            for name in ("network_offsets", "particles", "contact_pairs", "contact_forces"):
                f[name].refresh()
            net = f["network_offsets"][:n]
            if len(net) < n:
                committed[len(net):] = False
                net = np.vstack([net, np.zeros((n - len(net), net.shape[1]), dtype=net.dtype)])
            committed &= (net[:, 1] <= len(f["particles"])) & (net[:, 3] <= min(len(f["contact_pairs"]),
                                                                                 len(f["contact_forces"])))
            if "particle_z" in f:
                f["particle_z"].refresh()
                committed &= net[:, 1] <= len(f["particle_z"])
        if not committed.all():
            n = int(np.argmin(committed))
            cols = {k: v[:n] for k, v in cols.items()}
        self._cols, self._points = cols, points
        return len(cols["frame"])

    @property
    def frames(self):
        """The committed frame indices, ascending."""
        return self._cols["frame"].astype(np.int64)

    def announcement(self):
        """The run's current announcement as a dict (None before it was seen)."""
        d = self.file["announcements"]
        d.refresh()
        if len(d) == 0:
            return None
        a = json.loads(_fixed_strings(d, len(d))[-1])
        a.setdefault("ensemble", "")
        return a

    def series(self, metric, dim=DEFAULT_DIM, force="normal"):
        """One of the twelve stored series (floor convention), as Client.series returns it: value
        NaN for the first frame."""
        c = self._cols
        previous = c["previous"].astype(np.int64)
        value = c["distances"][:, distance_column(self.file, metric, dim, force)].astype(np.float64)
        value[previous < 0] = np.nan
        return Result(run=self.run_id, metric=metric, dim=dim, force=force, essential="floor",
                      frame=self.frames, step=c["step"].astype(np.int64), time=c["time"].astype(np.float64),
                      rho=c["rho"].astype(np.float64), z=c["z"].astype(np.float64), previous=previous, value=value,
                      infinite=np.zeros(len(value), dtype=bool))

    def _row(self, frame):
        rows = np.flatnonzero(self._cols["frame"] == frame)
        if len(rows) == 0:
            raise KeyError(f"run {self.run_id!r} has no committed frame {frame}")
        return int(rows[0])

    def diagram(self, frame, dim=DEFAULT_DIM, force="normal"):
        """A frame's diagram as an (n, 2) array of birth, death (death -1: never dies)."""
        series_key("bottleneck", dim, force)  # checks dim and force
        d = FORCES.index(force) * 2 + dim  # the order of `offsets`: normal PD0, PD1, tangential PD0, PD1
        o = self._cols["offsets"][self._row(frame)]
        return np.array(self._points[o[d]:o[d + 1]], dtype=np.float64).reshape(-1, 2)

    def counts(self, frame, force="normal"):
        """(vertices, edges, triangles) of a frame's force network."""
        c = self._cols["counts"][self._row(frame)]
        k = FORCES.index(force) * 3
        return tuple(int(v) for v in c[k:k + 3])

    def network(self, frame):
        """The force network a frame was analyzed from, as a Frame (particles, particle_z,
        contact_pairs, contact_forces; no wall contacts), if the store keeps it (schema fnet-store-2 or later);
        else None."""
        row = self._row(frame)
        f = self.file
        if "has_network" not in f:
            return None
        for name in ("has_network", "network_offsets", "particles", "contact_pairs", "contact_forces"):
            f[name].refresh()
        if not f["has_network"][row]:
            return None
        p0, p1, c0, c1 = (int(v) for v in f["network_offsets"][row])
        dimension, particle_z = _dimension_and_z(f, row, p0, p1)
        c = self._cols
        return Frame(index=int(frame), run=self.run_id, step=int(c["step"][row]), time=float(c["time"][row]),
                     rho=float(c["rho"][row]), z=float(c["z"][row]), dimension=dimension, particle_z=particle_z,
                     particles=np.asarray(f["particles"][p0:p1], dtype=np.float64).reshape(-1, 3),
                     contact_pairs=np.asarray(f["contact_pairs"][c0:c1], dtype=np.int64).reshape(-1, 2),
                     contact_forces=np.asarray(f["contact_forces"][c0:c1], dtype=np.float64).reshape(-1, 2),
                     wall_contact_particles=np.zeros(0, dtype=np.int64),
                     wall_contact_forces=np.zeros((0, 2), dtype=np.float64))

    def rejected(self):
        """[(frame, reason), ...] of the rejected frames."""
        f = self.file
        f["rejected_frame"].refresh()
        f["rejected_reason"].refresh()
        n = min(len(f["rejected_frame"]), len(f["rejected_reason"]))
        return list(zip((int(v) for v in f["rejected_frame"][:n]), _fixed_strings(f["rejected_reason"], n)))


def _dimension_and_z(f, row, p0, p1):
    """Row `row`'s dimension and the z of its particles, rows p0:p1 (2 and zeros in a file from
    before 3D frames)."""
    if "dimension" not in f:
        return 2, np.zeros(p1 - p0)
    for name in ("dimension", "particle_z"):
        f[name].refresh()
    return int(f["dimension"][row]), np.asarray(f["particle_z"][p0:p1], dtype=np.float64).reshape(-1)


class Frame(Result):
    """One frame of a run file: index, step, time, rho, z (the coordination number), dimension (2
    or 3), particles (N, 3: x, y, r), particle_z (N,: each particle's z, 0 in 2D), contact_pairs
    (M, 2: i < j), contact_forces (M, 2: signed F_n, |F_t|), wall_contact_particles (W,),
    wall_contact_forces (W, 2)."""

    def forces(self, force="normal"):
        """The contacts' force of one kind, as magnitudes."""
        if force not in FORCES:
            raise ValueError(f"force: normal or tangential, not {force!r}")
        return np.abs(self.contact_forces[:, FORCES.index(force)])


class RunFile(_SwmrFile):
    """A run file of fnet-simd (schema fnet-run-3 or -2, or the per-frame groups of fnet-run-1)."""

    _ATTRS = ("particles", "polydispersity", "friction", "k_n", "restitution", "kt_over_kn", "compression_speed",
              "dt", "final_density", "frames_planned", "seed")

    def __init__(self, path):
        super().__init__(path, RUN_SCHEMAS)
        a = self.file.attrs
        self.run_id = _text(a["run_id"])
        self.attrs = {k: a[k].item() for k in self._ATTRS if k in a}
        self.attrs["ensemble"] = _text(a["ensemble"]) if "ensemble" in a else ""
        self.config = json.loads(_text(a["config_json"])) if "config_json" in a else {}
        self.refresh()

    def refresh(self):
        """Reads which frames are committed so far; returns their number."""
        if self.schema == "fnet-run-1":
            groups = self.file["frames"] if "frames" in self.file else {}
            self._groups = {int(g.attrs["frame"]): name for name, g in groups.items()}
            self._frames = np.array(sorted(self._groups), dtype=np.int64)
        else:
            self.file["frame"].refresh()
            n = len(self.file["frame"])
            self._frames = self.file["frame"][:n].astype(np.int64)
            for name in ("step", "time", "rho", "z", "offsets"):
                self.file[name].refresh()
            self._offsets = self.file["offsets"][:n]
        return len(self._frames)

    @property
    def frames(self):
        """The committed frame indices, ascending."""
        return self._frames

    def frame(self, index):
        """Frame `index` (its index in the run, as fnet-simd numbers frames)."""
        rows = np.flatnonzero(self._frames == index)
        if len(rows) == 0:
            raise KeyError(f"run file {self.path} has no committed frame {index}")
        k = int(rows[0])
        names = ("particles", "contact_pairs", "contact_forces", "wall_contact_particles", "wall_contact_forces")
        if self.schema == "fnet-run-1":
            g = self.file["frames"][self._groups[index]]
            data = {name: g[name][:] for name in names}
            head = {name: g.attrs[name].item() for name in ("step", "time", "rho", "z")}
            head["dimension"], head["particle_z"] = 2, np.zeros(np.asarray(data["particles"]).size // 3)
        else:
            f = self.file
            p0, p1, c0, c1, w0, w1 = (int(v) for v in self._offsets[k])
            for name in names:
                f[name].refresh()
            data = {"particles": f["particles"][p0:p1], "contact_pairs": f["contact_pairs"][c0:c1],
                    "contact_forces": f["contact_forces"][c0:c1], "wall_contact_particles":
                    f["wall_contact_particles"][w0:w1], "wall_contact_forces": f["wall_contact_forces"][w0:w1]}
            head = {name: f[name][k].item() for name in ("step", "time", "rho", "z")}
            head["dimension"], head["particle_z"] = _dimension_and_z(f, k, p0, p1)
        return Frame(index=int(index), run=self.run_id, **head,
                     particles=np.asarray(data["particles"], dtype=np.float64).reshape(-1, 3),
                     contact_pairs=np.asarray(data["contact_pairs"], dtype=np.int64).reshape(-1, 2),
                     contact_forces=np.asarray(data["contact_forces"], dtype=np.float64).reshape(-1, 2),
                     wall_contact_particles=np.asarray(data["wall_contact_particles"], dtype=np.int64).reshape(-1),
                     wall_contact_forces=np.asarray(data["wall_contact_forces"], dtype=np.float64).reshape(-1, 2))


def open_store(path):
    """An analysis store (proto/store.md)."""
    return Store(path)


def open_run_file(path):
    """A run file of fnet-simd (proto/run_file.md)."""
    return RunFile(path)
