"""fnet from Python: a JSON-RPC client of fnet-server whose series are numpy arrays
(fnet.Client, numpy only), readers for the analysis stores and run files (fnet.store, with h5py), and
the paper's figures with matplotlib (fnet.figures). `python3 -m fnet plot ...` draws them from the command
line; fnet.to_gudhi gives a diagram in the sublevel form GUDHI and persim read."""

try:
    import numpy  # noqa: F401
except ImportError as e:  # a python3 other than Debian's (a pyenv one, say) may lack it
    raise ImportError(f"fnet needs numpy: Debian's python3 (/usr/bin/python3) with python3-numpy ({e})") from e

from fnet.arrays import Result
from fnet.rpc import DEFAULT_DIM, DEFAULT_HOST, DEFAULT_PORT, Client, RpcError, Subscription
from fnet import store
from fnet.sublevel import to_gudhi

__all__ = ["Client", "RpcError", "Subscription", "Result", "store", "to_gudhi", "DEFAULT_DIM", "DEFAULT_HOST",
           "DEFAULT_PORT"]
