"""fnet from Python: a JSON-RPC client of fnet-server whose series are numpy arrays
(fnet.Client), readers for the analysis stores and run files (fnet.store), and the paper's figures
with matplotlib (fnet.figures). `python3 -m fnet plot ...` draws them from the command line."""

from fnet.arrays import Result
from fnet.rpc import DEFAULT_HOST, DEFAULT_PORT, Client, RpcError, Subscription
from fnet import store

__all__ = ["Client", "RpcError", "Subscription", "Result", "store", "DEFAULT_HOST", "DEFAULT_PORT"]
