"""Exact sums of float64 values, so that a Monte Carlo estimate does not depend on
how its samples were split, ordered or grouped.

Every finite double is an integer multiple of 2^-1074. ``ExactSum.add`` has the
library add the values exactly into a 2304-bit fixed point integer (udm1_exact_sum_add,
udm1/exact_sum.h) and keeps it as one Python integer: the exact sum times 2^1126.
Adding two ``ExactSum`` objects adds the integers. ``mean()`` divides once with
Python's correctly rounded integer division. So any split of the same values, summed
in any order on any number of machines, gives the same result bit for bit: the
correctly rounded exact mean.
"""

from __future__ import annotations

import numpy as np

from ._native import EXACT_SUM_WORDS, lib
from .errors import check

STATUS_INVALID_ARGUMENT = 2  # UDM1_ERROR_INVALID_ARGUMENT: a value not finite

_BASE = 1126  # ExactSum.scaled is the exact sum times 2^_BASE (any scale of at least 2^1074 is exact)


class ExactSum:
    """The exact sum of float64 values and their count; ``+`` merges two sums."""

    __slots__ = ("scaled", "count")

    def __init__(self, scaled: int = 0, count: int = 0):
        self.scaled = int(scaled)  # the exact sum times 2^_BASE
        self.count = int(count)

    def add(self, values) -> "ExactSum":
        """Add finite float64 values (any shape); returns self. Raises ValueError on NaN or infinity."""
        x = np.ascontiguousarray(values, dtype=np.float64).ravel()
        words = np.zeros(EXACT_SUM_WORDS, dtype=np.uint64)
        status = lib.udm1_exact_sum_add(x.ctypes.data, x.size, words.ctypes.data)
        if status == STATUS_INVALID_ARGUMENT:
            bad = int(np.flatnonzero(~np.isfinite(x))[0])
            raise ValueError(f"ExactSum.add: value {bad} is {float(x[bad])!r}, not finite")
        check(status)
        self.scaled += int.from_bytes(words.tobytes(), "little", signed=True) << (_BASE - 1074)
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
