"""Where a result came from: fnet's version and commit, the date, and the convention, recorded in
everything the Python package writes (report.md, curves.csv's sidecar, figure metadata).

`describe(server_status=None, **extra)` returns one flat dict of text values. The package's own
version is `fnet.version.__version__`, equal to CMake's project version (a test checks it); the
commit is the git commit of the checkout the package was loaded from, or "unknown" outside one.
When a server's `server.status` answer is given, the version and commit of the fnet-server that
computed the numbers are recorded beside the package's."""

import datetime
import functools
import os
import subprocess

from fnet.version import __version__

SOURCE = "https://doi.org/10.1103/PhysRevE.90.052203"
METHOD = ("Kramar, Goulet, Kondic, Mischaikow, Evolution of force networks in dense particulate media, "
          "Phys. Rev. E 90, 052203 (2014)")


@functools.lru_cache(maxsize=1)
def package_commit():
    """The git commit of the checkout holding this package (with "-dirty" when it has uncommitted
    changes), or "unknown" when it is not in one or git is missing."""
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        head = subprocess.run(["git", "-C", here, "rev-parse", "HEAD"], capture_output=True, text=True, timeout=10)
        if head.returncode != 0:
            return "unknown"
        dirty = subprocess.run(["git", "-C", here, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, timeout=10)
        return head.stdout.strip() + ("-dirty" if dirty.returncode == 0 and dirty.stdout.strip() else "")
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def now_utc():
    """The current time as ISO 8601 UTC, to the second."""
    return datetime.datetime.now(datetime.timezone.utc).replace(microsecond=0).isoformat().replace("+00:00", "Z")


def describe(server_status=None, convention="floor", **extra):
    """{"fnet_version", "fnet_commit", "date", "convention", "method", ["server_version",
    "server_commit"], **extra} as text; extra values are converted with str()."""
    out = {
        "fnet_version": __version__,
        "fnet_commit": package_commit(),
        "date": now_utc(),
        "convention": convention,
        "method": METHOD,
    }
    if server_status:
        build = server_status.get("build") or {}
        out["server_version"] = str(build.get("version", "unknown"))
        out["server_commit"] = str(build.get("commit", "unknown"))
    out.update({k: str(v) for k, v in extra.items()})
    return out


def png_metadata(info):
    """Matplotlib `savefig(metadata=...)` for a PNG: the provenance as tEXt chunks (Software,
    Source, Creation Time and one "fnet:<key>" entry per field)."""
    meta = {"Software": f"fnet {info.get('fnet_version', __version__)} ({info.get('fnet_commit', 'unknown')})",
            "Source": SOURCE}
    for k, v in info.items():
        meta[f"fnet:{k}"] = str(v)
    return meta
