"""The integers that cross into C: ctypes would wrap a Python int silently to the C type's width (a
negative count, a seed past 2^64, a float truncated). Every argument goes through integer() first,
which refuses with udm1.UDM1Error (a ValueError, status UDM1_ERROR_INVALID_ARGUMENT) naming the
argument, or TypeError for what is not a number."""

from __future__ import annotations

import numbers
import operator

from .errors import UDM1Error

_INVALID_ARGUMENT = 2

U32 = (1 << 32) - 1
U64 = (1 << 64) - 1
U128 = (1 << 128) - 1


def integer(value, name: str, lo: int = 0, hi: int = U64) -> int:
    """value as an int in [lo, hi]: any integer type, or a float with an integral value."""
    if isinstance(value, numbers.Integral) or hasattr(value, "__index__"):
        v = operator.index(value)
    elif isinstance(value, numbers.Real):
        f = float(value)
        if f != f or f in (float("inf"), float("-inf")) or not f.is_integer():
            raise UDM1Error(_INVALID_ARGUMENT, f"udm1: {name} = {value!r} is not an integer")
        v = int(f)
    else:
        raise TypeError(f"udm1: {name} must be an integer, not {type(value).__name__}")
    if not lo <= v <= hi:
        raise UDM1Error(_INVALID_ARGUMENT, f"udm1: {name} = {v} is outside [{lo}, {hi}]")
    return v


def u32(value, name: str) -> int:
    return integer(value, name, 0, U32)


def u64(value, name: str) -> int:
    return integer(value, name, 0, U64)
