"""Exact sums of float64 values and of their squares, so that a Monte Carlo estimate and its variance
do not depend on how the samples were split, ordered or grouped, at any finite magnitude.

Every finite double is an integer multiple of 2^-1074, so every square of one is an integer multiple
of 2^-2148. ``ExactSum`` keeps its sum as one Python integer: the exact sum times 2^2148, of any size.
``add`` has the library add the values exactly into a 2304-bit fixed point integer
(udm1_exact_sum_add, udm1/exact_sum.h); ``add_squares`` adds the exact squares: each value x is
written x = f 2^e with 1/2 <= |f| < 1 (numpy's frexp, exact), f^2 = hi + lo exactly (Dekker's product:
no overflow or underflow can occur at that scale), and the parts, rescaled by a power of two into a
band of the double range, are added by the library band by band and shifted into place. Nothing is
rounded, so neither x^2 overflowing (|x| > 1.3e154) nor underflowing (|x| < 1.5e-154) loses anything.
Adding two ``ExactSum`` objects adds the integers. ``value()`` and ``mean()`` divide once with Python's
correctly rounded integer division: any split of the same values, summed in any order on any number
of machines, gives the same result bit for bit. A result past the double range (a sum of values near
1.8e308, or any sum of squares past it) is +inf or -inf, as IEEE rounding gives it; ``fraction()``
keeps the exact value.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from ._convert import integer, real_array
from ._native import EXACT_SUM_WORDS, lib
from .errors import check

STATUS_INVALID_ARGUMENT = 2  # UDM1_ERROR_INVALID_ARGUMENT: a value not finite

_BASE = 2148  # ExactSum.scaled is the exact sum times 2^_BASE: every double and every square of one is a
              # multiple of 2^-2148
_LIBRARY_BASE = 1074  # the library's words: the sum times 2^1074
_BAND = 1024  # add_squares: a square (hi + lo) 2^t is added as (hi + lo) 2^(t - _BAND k), k = round(t / _BAND)
_DIRECT = 2.0 ** 400  # add_squares: values with |x| in [2^-400, 2^400] (or 0) need no rescaling (below)


def _ratio(num: int, den: int) -> float:
    """num / den (den > 0) rounded once to the nearest double: +-inf past the double range."""
    try:
        return num / den
    except OverflowError:
        return math.inf if num > 0 else -math.inf


_SPLIT = 134217729.0  # 2^27 + 1: Veltkamp's split of a double into two 26-bit halves
_BLOCK = 8192  # add_squares works in blocks this long, in scratch arrays made once per call (64 KiB each:
               # no fresh pages per temporary, and the block stays in the cache across the passes)


def _square_parts(f: np.ndarray, scratch: np.ndarray | None = None) -> np.ndarray:
    """[hi, lo] (the first 2 len(f) values of the scratch, 4 len(f) long) with f^2 = hi + lo exactly, for f
    whose squares neither overflow nor lose bits below the smallest double (Dekker 1971: the Veltkamp
    split, products exact in round to nearest, the error terms added in his order: fh fh - hi, then fh fl
    twice, then fl fl)."""
    m = f.size
    scratch = np.empty(4 * m) if scratch is None else scratch
    hi, lo, fh, fl = scratch[:m], scratch[m:2 * m], scratch[2 * m:3 * m], scratch[3 * m:4 * m]
    np.multiply(f, f, out=hi)
    np.multiply(f, _SPLIT, out=fh)  # c
    np.subtract(fh, f, out=fl)      # c - f
    np.subtract(fh, fl, out=fh)     # fh = c - (c - f)
    np.subtract(f, fh, out=fl)      # fl = f - fh
    np.multiply(fh, fh, out=lo)
    lo -= hi
    np.multiply(fh, fl, out=fh)     # fh fl (fh is not needed after it)
    lo += fh
    lo += fh
    np.multiply(fl, fl, out=fl)
    lo += fl
    return scratch[:2 * m]


class ExactSum:
    """The exact sum of float64 values (or of their squares) and their count; ``+`` merges two sums."""

    __slots__ = ("scaled", "count")

    def __init__(self, scaled: int = 0, count: int = 0):
        self.scaled = integer(scaled, "scaled", None, None, where="udm1.ExactSum")  # the exact sum times 2^_BASE
        self.count = integer(count, "count", 0, None, where="udm1.ExactSum")

    def _add_words(self, x: np.ndarray, shift: int = 0) -> None:
        """Add finite doubles x times 2^shift (shift a multiple of _BAND; the result an exact multiple of
        2^-_BASE) to the integer."""
        words = np.zeros(EXACT_SUM_WORDS, dtype=np.uint64)
        check(lib.udm1_exact_sum_add(x.ctypes.data, x.size, words.ctypes.data))
        self._take_words(words, shift)

    def _take_words(self, words: np.ndarray, shift: int = 0) -> None:
        """Add the library's sum (its words) times 2^shift to the integer."""
        total = int.from_bytes(words.tobytes(), "little", signed=True)
        s = _BASE - _LIBRARY_BASE + shift
        self.scaled += total << s if s >= 0 else total >> -s  # exact: see add_squares

    def _values(self, values, what: str) -> np.ndarray:
        x = real_array(values, "values", where=f"udm1.ExactSum.{what}", exact=True).ravel()
        finite = np.isfinite(x)
        if not finite.all():
            bad = int(np.flatnonzero(~finite)[0])
            raise ValueError(f"ExactSum.{what}: value {bad} is {float(x[bad])!r}, not finite")
        return x

    def add(self, values) -> "ExactSum":
        """Add finite values (real numbers of any shape, exactly doubles); returns self. Raises ValueError
        on NaN or infinity (nothing added), TypeError on bools, complex numbers or strings."""
        x = self._values(values, "add")
        self._add_words(x)
        self.count += x.size
        return self

    def add_squares(self, values) -> "ExactSum":
        """Add the exact squares of finite values; returns self (count grows by their number)."""
        x = self._values(values, "add_squares")
        a = np.abs(x)
        if a.size == 0 or (a.max() <= _DIRECT and np.min(a, where=a > 0, initial=1.0) >= 1 / _DIRECT):
            # x^2 <= 2^800 and its low part a multiple of 2^-906 at least: Dekker's product as it is, block
            # by block into the library's words
            words = np.zeros(EXACT_SUM_WORDS, dtype=np.uint64)
            scratch = np.empty(4 * min(_BLOCK, x.size))
            for start in range(0, x.size, _BLOCK):
                block = x[start:start + _BLOCK]
                parts = _square_parts(block, scratch[:4 * block.size])
                check(lib.udm1_exact_sum_add(parts.ctypes.data, parts.size, words.ctypes.data))
            self._take_words(words)
        else:  # x = f 2^e; x^2 = (hi + lo) 2^t, t = 2e, added in bands of the exponent t
            f, e = np.frexp(x)
            parts = _square_parts(f)
            hi, lo = parts[:f.size], parts[f.size:]
            t = 2 * e.astype(np.int64)
            band = np.floor_divide(t + _BAND // 2, _BAND)  # t - _BAND band in [-512, 512): parts in range
            for k in np.unique(band):
                sel = band == k
                r = t[sel] - _BAND * int(k)
                # hi 2^r <= 2^512; lo a multiple of 2^(r - 106) >= 2^-618: both exact doubles. The band's sum
                # times 2^(_BAND k) is a multiple of 2^-_BASE (every square is), so the shift is exact.
                self._add_words(np.concatenate([np.ldexp(hi[sel], r), np.ldexp(lo[sel], r)]), _BAND * int(k))
        self.count += x.size
        return self

    def __add__(self, other: "ExactSum") -> "ExactSum":
        if not isinstance(other, ExactSum):
            return NotImplemented
        return ExactSum(self.scaled + other.scaled, self.count + other.count)

    def __eq__(self, other) -> bool:
        return isinstance(other, ExactSum) and (self.scaled, self.count) == (other.scaled, other.count)

    def __repr__(self) -> str:
        return f"ExactSum(sum={self.value()!r}, count={self.count})"

    def value(self) -> float:
        """The exact sum, rounded once to the nearest double (+-inf past the double range)."""
        return _ratio(self.scaled, 1 << _BASE)

    def mean(self, n: int | None = None) -> float:
        """The exact sum divided by n (default: the count), rounded once (+-inf past the double range)."""
        n = self.count if n is None else integer(n, "n", 0, None, where="udm1.ExactSum.mean")
        if n <= 0:
            raise ValueError("ExactSum.mean: no values")
        return _ratio(self.scaled, n << _BASE)

    def fraction(self) -> Fraction:
        """The exact sum as a fractions.Fraction."""
        return Fraction(self.scaled, 1 << _BASE)


def sqrt_fraction(x: Fraction) -> float:
    """sqrt(x) of a non-negative rational, correctly rounded to a double at any magnitude (+inf past the
    double range): an integer square root of at least 64 bits and a sticky bit for what it leaves."""
    if x <= 0:
        return 0.0
    p, q = x.numerator, x.denominator
    s = max(0, (130 - (p.bit_length() - q.bit_length())) // 2 + 1)
    t, rest = divmod(p << (2 * s), q)
    r = math.isqrt(t)
    inexact = rest != 0 or r * r != t
    return _ratio((r << 1) | inexact, 1 << (s + 1))
