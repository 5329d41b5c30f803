"""Quality metrics from libudm1: discrepancies with scipy's definitions."""

from __future__ import annotations

import ctypes

import numpy as np

from ._native import lib
from .sequence import check

METHODS = {"L2-star": 1, "CD": 2, "WD": 3, "MD": 4}


def discrepancy(sample, method: str = "CD") -> float:
    """Discrepancy of an (n, d) sample in [0, 1]^d, as scipy.stats.qmc.discrepancy
    (CD, WD, MD squared; L2-star square-rooted), computed by libudm1."""
    if method not in METHODS:
        raise ValueError(f"udm1.discrepancy: method {method!r} is not one of {sorted(METHODS)}")
    x = np.ascontiguousarray(np.asarray(sample, dtype=np.float64))
    if x.ndim != 2:
        raise ValueError("udm1.discrepancy: sample must be a 2D array (n, d)")
    out = ctypes.c_double()
    check(lib.udm1_discrepancy(x.ctypes.data, x.shape[0], x.shape[1], x.shape[1], METHODS[method], ctypes.byref(out)))
    return out.value


def discrepancy_random(n: int, d: int, method: str = "CD") -> float:
    """The discrepancy of n independent uniform points (E[D^2]; sqrt of it for L2-star)."""
    if method not in METHODS:
        raise ValueError(f"udm1.discrepancy_random: method {method!r} is not one of {sorted(METHODS)}")
    out = ctypes.c_double()
    check(lib.udm1_discrepancy_random(int(n), int(d), METHODS[method], ctypes.byref(out)))
    return out.value
