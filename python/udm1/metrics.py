"""Quality metrics from libudm1: discrepancies with scipy's definitions."""

from __future__ import annotations

import ctypes

import numpy as np

from ._convert import choice, flag, real_array, text, u32, u64
from ._native import lib
from .errors import check

METHODS = {"L2-star": 1, "CD": 2, "WD": 3, "MD": 4}


def discrepancy(sample, method: str = "CD") -> float:
    """Discrepancy of an (n, d) sample in [0, 1]^d, as scipy.stats.qmc.discrepancy
    (CD, WD, MD squared; L2-star square-rooted), computed by libudm1."""
    method = choice(method, "method", METHODS, where="udm1.discrepancy")
    x = _points2d(sample, "discrepancy")
    out = ctypes.c_double()
    check(lib.udm1_discrepancy(x.ctypes.data, x.shape[0], x.shape[1], x.shape[1], METHODS[method], ctypes.byref(out)))
    return out.value


def discrepancy_random(n: int, d: int, method: str = "CD") -> float:
    """The discrepancy of n independent uniform points (E[D^2]; sqrt of it for L2-star)."""
    where = "udm1.discrepancy_random"
    method = choice(method, "method", METHODS, where=where)
    out = ctypes.c_double()
    check(lib.udm1_discrepancy_random(u64(n, "n", where=where), u32(d, "d", where=where), METHODS[method],
                                      ctypes.byref(out)))
    return out.value


def _points2d(sample, name: str, min_d: int = 1) -> np.ndarray:
    """sample as a C-contiguous (n, d) float64 array, through the package's converter (real numbers
    only: no bools, complex values or strings)."""
    x = real_array(sample, "sample", where=f"udm1.{name}")
    if x.ndim != 2 or x.shape[1] < min_d:
        raise ValueError(f"udm1.{name}: sample must be an (n, d) array with d >= {min_d}, not shape {x.shape}")
    return x


def star_discrepancy(sample) -> float:
    """Exact star discrepancy of an (n, 2) sample (n <= 16384), O(n^2)."""
    x = _points2d(sample, "star_discrepancy", 2)
    out = ctypes.c_double()
    check(lib.udm1_star_discrepancy_2d(x.ctypes.data, x.shape[0], x.shape[1], ctypes.byref(out)))
    return out.value


def min_distance(sample, toroidal: bool = False) -> float:
    """Smallest pairwise distance of an (n, d) sample (multiply by sqrt(n) to normalise)."""
    x = _points2d(sample, "min_distance")
    out = ctypes.c_double()
    toroidal = flag(toroidal, "toroidal", where="udm1.min_distance")
    check(lib.udm1_min_distance(x.ctypes.data, x.shape[0], x.shape[1], x.shape[1], int(toroidal), ctypes.byref(out)))
    return out.value


def integrands() -> dict:
    """{name: code} of the test integrands (see udm1.h)."""
    out = {}
    for code in range(1, 64):
        name = lib.udm1_integrand_name(code)
        if name:
            out[name.decode()] = code
    return out


def _integrand_code(integrand) -> int:
    if isinstance(integrand, str):
        table = integrands()
        if integrand not in table:
            raise ValueError(f"udm1: unknown integrand {integrand!r}; known: {sorted(table)}")
        return table[integrand]
    if isinstance(integrand, bytes):
        text(integrand, "integrand")  # refused: a name is a str
    return u32(integrand, "integrand")


def integrand(name, sample) -> np.ndarray:
    """Values of a test integrand at the rows of an (n, d) sample."""
    x = _points2d(sample, "integrand")
    out = np.empty(x.shape[0])
    check(lib.udm1_integrand_eval(_integrand_code(name), x.shape[1], x.ctypes.data, x.shape[0], x.shape[1],
                                  out.ctypes.data))
    return out


def integrand_exact(name, d: int) -> float:
    """The exact integral of a test integrand over [0,1]^d."""
    out = ctypes.c_double()
    check(lib.udm1_integrand_exact(_integrand_code(name), u32(d, "d", where="udm1.integrand_exact"), ctypes.byref(out)))
    return out.value
