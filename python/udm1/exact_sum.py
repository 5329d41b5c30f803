"""Exact sums of float64 values, so that a Monte Carlo estimate does not depend on
how its samples were split, ordered or grouped.

Every finite double is m * 2^(e - 53) with an integer |m| < 2^53 (``numpy.frexp``).
``ExactSum.add`` buckets the values by exponent and adds their integer mantissas
exactly (split in 26-bit halves so that ``numpy.bincount``'s double accumulation
never rounds), then folds the buckets into one Python integer: the exact sum
times 2^1126. Adding two ``ExactSum`` objects adds the integers. ``mean()`` divides
once with Python's correctly rounded integer division. So any split of the same
values, summed in any order on any number of machines, gives the same result bit
for bit: the correctly rounded exact mean.
"""

from __future__ import annotations

import numpy as np

_BASE = 1126  # frexp gives e >= -1073 for every nonzero double: (e - 53) + 1126 >= 0, so every shift is exact
_HALF = 26    # mantissas are split in a high part (< 2^27 in magnitude) and a low part (< 2^26)
_BATCH = 1 << 24  # at most 2^24 values per bincount: |sum| < 2^51, exact in a double


class ExactSum:
    """The exact sum of float64 values and their count; ``+`` merges two sums."""

    __slots__ = ("scaled", "count")

    def __init__(self, scaled: int = 0, count: int = 0):
        self.scaled = int(scaled)  # the exact sum times 2^_BASE
        self.count = int(count)

    def add(self, values) -> "ExactSum":
        """Add finite float64 values (any shape); returns self. Raises ValueError on NaN or infinity."""
        x = np.ascontiguousarray(values, dtype=np.float64).ravel()
        if not np.all(np.isfinite(x)):
            bad = int(np.flatnonzero(~np.isfinite(x))[0])
            raise ValueError(f"ExactSum.add: value {bad} is {x[bad]!r}, not finite")
        for start in range(0, x.size, _BATCH):
            self.scaled += _exact_batch(x[start:start + _BATCH])
        self.count += x.size
        return self

    def __add__(self, other: "ExactSum") -> "ExactSum":
        return ExactSum(self.scaled + other.scaled, self.count + other.count)

    def __eq__(self, other) -> bool:
        return isinstance(other, ExactSum) and (self.scaled, self.count) == (other.scaled, other.count)

    def __repr__(self) -> str:
        return f"ExactSum(sum={self.value()!r}, count={self.count})"

    def value(self) -> float:
        """The exact sum, rounded once to the nearest double."""
        return self.scaled / (1 << _BASE)

    def mean(self, n: int | None = None) -> float:
        """The exact sum divided by n (default: the count), rounded once."""
        n = self.count if n is None else int(n)
        if n <= 0:
            raise ValueError("ExactSum.mean: no values")
        return self.scaled / (n << _BASE)

    def fraction(self):
        """The exact sum as a fractions.Fraction."""
        from fractions import Fraction

        return Fraction(self.scaled, 1 << _BASE)


def _exact_batch(x: np.ndarray) -> int:
    """The exact sum of x (finite, at most _BATCH values) times 2^_BASE, as a Python int."""
    if x.size == 0:
        return 0
    m, e = np.frexp(x)                           # x = m 2^e, 0.5 <= |m| < 1 (m = 0 for zeros)
    mant = (m * 9007199254740992.0).astype(np.int64)  # m 2^53: exact, |mant| < 2^53
    hi = mant >> _HALF                           # floor: mant = hi 2^26 + lo, 0 <= lo < 2^26
    lo = mant & ((1 << _HALF) - 1)
    e0 = int(e.min())
    idx = (e - e0).astype(np.intp)
    his = np.bincount(idx, weights=hi.astype(np.float64))  # integers below 2^51: exact
    los = np.bincount(idx, weights=lo.astype(np.float64))
    total = 0
    for k in np.flatnonzero((his != 0) | (los != 0)):
        # value = (hi 2^26 + lo) 2^(e - 53); times 2^_BASE: shift by e - 53 + _BASE >= 0 (e >= -1073)
        total += ((int(his[k]) << _HALF) + int(los[k])) << (int(k) + e0 - 53 + _BASE)
    return total
