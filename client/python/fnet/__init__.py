"""fnet from Python: a JSON-RPC client of fnet-server whose series are numpy arrays
(fnet.Client), readers for the analysis stores and run files (fnet.store), and the paper's figures
with matplotlib (fnet.figures). `python3 -m fnet plot ...` draws them from the command line."""

try:
    import h5py  # noqa: F401
    import numpy  # noqa: F401
except ImportError as e:  # a python3 other than Debian's (a pyenv one, say) may lack them
    raise ImportError(f"fnet needs numpy and h5py: Debian's python3 (/usr/bin/python3) with python3-numpy and "
                      f"python3-h5py ({e})") from e

from fnet.arrays import Result
from fnet.rpc import DEFAULT_HOST, DEFAULT_PORT, Client, RpcError, Subscription
from fnet import store

__all__ = ["Client", "RpcError", "Subscription", "Result", "store", "DEFAULT_HOST", "DEFAULT_PORT"]
