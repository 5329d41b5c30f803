"""The package's one input converter: every scalar and array argument of a public function goes through
it before it is used or crosses into C, because ctypes and numpy coerce silently (ctypes wraps a
negative count or a seed past 2^64 to the C type's width; numpy casts complex values to their real
part, parses strings, takes bools as 0 and 1, and wraps a negative index cast to uint64).

- The kind is checked before any cast: a bool, complex number, string, bytes, None or other object
  where a number is meant is a TypeError naming the argument (in an array: naming the element).
- Integers are range-checked without wrapping. A float is taken as an integer when its value is
  integral, as a scalar and in an array alike (2.0 is 2; 2.5 is refused).
- Real numbers are checked finite where they must be, and against their range.
- numpy scalars (np.float32, np.int8, np.uint64, ...) and 0-d arrays are taken wherever Python numbers
  are.

Other refusals are udm1.UDM1Error (a ValueError, status UDM1_ERROR_INVALID_ARGUMENT) naming the
argument: "udm1.integrate: chunk = -5 is outside [1, 18446744073709551615]"."""

from __future__ import annotations

import math
import numbers
import operator

import numpy as np

from .errors import UDM1Error

_INVALID_ARGUMENT = 2

U32 = (1 << 32) - 1
U64 = (1 << 64) - 1
U128 = (1 << 128) - 1

_NOT_NUMBERS = "USVMm"  # array kinds that are not numbers: str, bytes, void (records), datetime, timedelta


def _refuse(where: str, message: str) -> UDM1Error:
    return UDM1Error(_INVALID_ARGUMENT, f"{where}: {message}")


def _kind_name(value) -> str:
    if isinstance(value, np.ndarray):
        return f"an array of {value.dtype}"
    return type(value).__name__


def _scalar(value, name: str, where: str):
    """A 0-d array as its numpy scalar; any other array is refused (a scalar is meant)."""
    if isinstance(value, np.ndarray):
        if value.ndim != 0:
            raise TypeError(f"{where}: {name} must be a number, not an array of shape {value.shape}")
        return value[()]
    return value


def _is_bool(value) -> bool:
    return isinstance(value, (bool, np.bool_))


def integer(value, name: str, lo: int | None = 0, hi: int | None = U64, *, where: str = "udm1") -> int:
    """value as an int in [lo, hi] (None: unbounded): any integer type, or a real number with an integral
    value. bools, complex numbers, strings and other objects are refused (TypeError)."""
    value = _scalar(value, name, where)
    if _is_bool(value):
        raise TypeError(f"{where}: {name} must be an integer, not bool")
    if isinstance(value, numbers.Integral) or (hasattr(value, "__index__") and not isinstance(value, np.generic)):
        v = operator.index(value)
    elif isinstance(value, numbers.Rational):  # a Fraction: exact
        if value.denominator != 1:
            raise _refuse(where, f"{name} = {value} is not an integer")
        v = int(value.numerator)
    elif isinstance(value, numbers.Real):
        f = float(value)
        if not math.isfinite(f) or not f.is_integer():
            raise _refuse(where, f"{name} = {value!r} is not an integer")
        v = int(f)
    else:
        raise TypeError(f"{where}: {name} must be an integer, not {_kind_name(value)}")
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        raise _refuse(where, f"{name} = {v} is outside [{'-inf' if lo is None else lo}, {'inf' if hi is None else hi}]")
    return v


def u32(value, name: str, *, where: str = "udm1") -> int:
    return integer(value, name, 0, U32, where=where)


def u64(value, name: str, *, where: str = "udm1") -> int:
    return integer(value, name, 0, U64, where=where)


def real(value, name: str, *, lo: float | None = None, hi: float | None = None, lo_open: bool = False,
         hi_open: bool = False, finite: bool = True, where: str = "udm1") -> float:
    """value as a float: any real number (int, float, Fraction, numpy integer or floating scalar, 0-d
    array), finite unless finite=False, inside [lo, hi] (an end open with lo_open / hi_open)."""
    value = _scalar(value, name, where)
    if _is_bool(value) or not isinstance(value, numbers.Real):
        raise TypeError(f"{where}: {name} must be a real number, not {_kind_name(value)}")
    try:
        f = float(value)
    except OverflowError:
        raise _refuse(where, f"{name} = {value!r} is outside the double range") from None
    if finite and not math.isfinite(f):
        raise _refuse(where, f"{name} = {f!r} is not finite")
    below = lo is not None and (f <= lo if lo_open else f < lo)
    above = hi is not None and (f >= hi if hi_open else f > hi)
    if below or above or f != f and (lo is not None or hi is not None):
        left, right = "(" if lo_open else "[", ")" if hi_open else "]"
        raise _refuse(where, f"{name} = {f!r} is outside {left}{'-inf' if lo is None else lo}, "
                             f"{'inf' if hi is None else hi}{right}")
    return f


def flag(value, name: str, *, where: str = "udm1") -> bool:
    """A yes/no argument: bool or numpy bool (or the integers 0 and 1)."""
    value = _scalar(value, name, where)
    if _is_bool(value):
        return bool(value)
    if isinstance(value, numbers.Integral) and int(value) in (0, 1):
        return bool(int(value))
    raise TypeError(f"{where}: {name} must be True or False, not {value!r}")


def text(value, name: str, *, where: str = "udm1") -> str:
    """A str argument (a name): str only, not bytes or a number."""
    if not isinstance(value, str):
        raise TypeError(f"{where}: {name} must be a string, not {_kind_name(value)}")
    return value


def choice(value, name: str, options, *, where: str = "udm1") -> str:
    """One of `options` (strings): anything else is refused naming them."""
    if isinstance(value, str) and value in options:
        return value
    if not isinstance(value, str):
        raise TypeError(f"{where}: {name} must be one of {', '.join(options)}, not {_kind_name(value)}")
    raise _refuse(where, f"{name} {value!r} is not one of {', '.join(options)}")


def function(value, name: str, *, where: str = "udm1"):
    if not callable(value):
        raise TypeError(f"{where}: {name} must be callable, not {_kind_name(value)}")
    return value


# ---- arrays ----

def _element(name: str, shape, k: int) -> str:
    """name[i] or name[i, j] of flat position k of an array of `shape`."""
    if len(shape) <= 1:
        return f"{name}[{k}]"
    return f"{name}[{', '.join(str(int(i)) for i in np.unravel_index(k, shape))}]"


def _check_items(values, name: str, where: str) -> None:
    """Refuse what numpy would coerce inside nested lists and tuples: bools (to 0 and 1, or to the other
    items' type), complex numbers, strings and None, and arrays of those."""
    stack = [(values, name)]
    while stack:
        seq, label = stack.pop()
        for k, v in enumerate(seq):
            if isinstance(v, (list, tuple)):
                stack.append((v, f"{label}[{k}]"))
            elif isinstance(v, np.ndarray):
                if v.dtype.kind in "bc" + _NOT_NUMBERS:
                    raise TypeError(f"{where}: {label}[{k}] is an array of {v.dtype}, not of real numbers")
            elif _is_bool(v) or v is None or isinstance(v, (str, bytes, complex, np.complexfloating)):
                raise TypeError(f"{where}: {label}[{k}] = {v!r} is not a real number")


def _numbers(values, name: str, where: str) -> np.ndarray:
    """values as an array whose kind is numbers (integer, floating, or objects to be taken one by one)."""
    if isinstance(values, np.ndarray):
        a = values
    else:
        if isinstance(values, (list, tuple)):
            _check_items(values, name, where)
        elif values is None or isinstance(values, (str, bytes, dict, set)):
            raise TypeError(f"{where}: {name} must be an array of numbers, not {_kind_name(values)}")
        try:
            a = np.asarray(values)
        except (ValueError, TypeError, OverflowError) as e:
            detail = str(e).splitlines()[0] if str(e) else type(e).__name__
            raise _refuse(where, f"{name} is not an array of numbers ({detail})") from None
    kind = a.dtype.kind
    if kind == "b":
        raise TypeError(f"{where}: {name} is an array of bools, not of numbers")
    if kind == "c":
        raise TypeError(f"{where}: {name} is an array of {a.dtype}: complex values are not taken")
    if kind in _NOT_NUMBERS:
        raise TypeError(f"{where}: {name} is an array of {a.dtype}, not of numbers")
    return a


def real_array(values, name: str, *, where: str = "udm1", float32: bool = False, exact: bool = False) -> np.ndarray:
    """values (an array, or nested lists of numbers) as a C-contiguous float64 array (float32 kept as
    float32 with float32=True). Integers and every floating type are cast; a value that leaves the
    double range in the cast is refused. exact=True also refuses a value the cast would round (an int64
    past 2^53, a long double's extra bits). Finiteness is left to the caller."""
    a = _numbers(values, name, where)
    if a.dtype.kind == "O":
        flat = []
        for k, v in enumerate(a.flat):
            f = real(v, _element(name, a.shape, k), finite=False, where=where)
            if exact and isinstance(v, numbers.Real) and not (f != f or f == v):
                raise _refuse(where, f"{_element(name, a.shape, k)} = {v!r} is not exactly a double")
            flat.append(f)
        return np.array(flat, dtype=np.float64).reshape(a.shape)
    target = np.float32 if float32 and a.dtype == np.float32 else np.float64
    with np.errstate(over="ignore", invalid="ignore"):
        out = np.ascontiguousarray(a, dtype=target)
    if a.dtype.kind == "f" and a.dtype.itemsize > 8:  # long double: may leave the double range
        lost = np.isfinite(a) & ~np.isfinite(out)
        if lost.any():
            k = int(np.flatnonzero(lost.ravel())[0])
            raise _refuse(where, f"{_element(name, a.shape, k)} = {a.ravel()[k]!r} is outside the double range")
    if exact and a.dtype not in (np.float16, np.float32, np.float64):
        with np.errstate(over="ignore", invalid="ignore"):
            rounded = out.astype(a.dtype) != a
        rounded |= ~np.isfinite(out) & np.isfinite(a) if a.dtype.kind == "f" else False
        if np.any(rounded):
            k = int(np.flatnonzero(np.ravel(rounded))[0])
            raise _refuse(where, f"{_element(name, a.shape, k)} = {a.ravel()[k]!r} is not exactly a double")
    return out


def index_array(values, name: str, *, where: str = "udm1", lo: int = 0, hi: int = U64) -> np.ndarray:
    """values (an array, or nested lists of integers) as a C-contiguous uint64 array, every element an
    integer in [lo, hi] (0 <= lo): integer arrays range-checked without wrapping, float arrays taken
    where every value is integral (the scalar rule)."""
    a = _numbers(values, name, where)
    kind = a.dtype.kind
    if kind == "O" or (kind == "f" and not isinstance(values, np.ndarray)):
        # objects, or a list that numpy made floats (it does so for [-1, 2**64 - 1]): one by one, exactly
        items = values if kind == "f" else a
        objs = np.asarray(items, dtype=object)
        flat = [integer(v, _element(name, objs.shape, k), lo, hi, where=where) for k, v in enumerate(objs.flat)]
        return np.array(flat, dtype=np.uint64).reshape(objs.shape)
    flat = a.ravel()
    if kind in "iu":
        info = np.iinfo(a.dtype)
        bad = np.zeros(flat.shape, dtype=bool)
        if lo > info.min:
            bad |= flat < a.dtype.type(lo)
        if hi < info.max:
            bad |= flat > a.dtype.type(hi)
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            raise _refuse(where, f"{_element(name, a.shape, k)} = {int(flat[k])} is outside [{lo}, {hi}]")
    else:  # floating: integral values only, inside the range
        with np.errstate(invalid="ignore"):
            integral = np.isfinite(flat) & (flat == np.floor(flat))
            inside = integral & (flat >= lo) & (flat < float(hi + 1))  # hi + 1 = 2^32 or 2^64: exact
        if not inside.all():
            k = int(np.flatnonzero(~inside)[0])
            what = "is not an integer" if not integral[k] else f"is outside [{lo}, {hi}]"
            raise _refuse(where, f"{_element(name, a.shape, k)} = {flat[k]!r} {what}")
    return np.ascontiguousarray(a, dtype=np.uint64)
