"""How the served JSON becomes numpy: null distances as NaN, infinite ones as +inf."""

import numpy as np


class Result(dict):
    """A dict whose keys are also attributes (`s.rho` is `s["rho"]`)."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None

    def __setattr__(self, name, value):
        self[name] = value


def float_array(values, infinite=None):
    """A float64 array of `values`: null is NaN; where `infinite[k]` is true, +inf."""
    out = np.array([np.nan if v is None else v for v in values], dtype=np.float64)
    if infinite is not None:
        out[np.asarray(infinite, dtype=bool)] = np.inf
    return out


def index_array(values):
    """An int64 array of frame indices: null (no such frame) is -1."""
    return np.array([-1 if v is None else v for v in values], dtype=np.int64)
