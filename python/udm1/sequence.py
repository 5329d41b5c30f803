"""The Sequence class: a udm1_seq handle returning numpy arrays."""

from __future__ import annotations

import ctypes
import numbers
from dataclasses import dataclass

import numpy as np

from . import _native
from ._convert import U128, index_array, integer, real, text, u32, u64
from ._native import lib
from .errors import check
from .metrics import _integrand_code

ALPHA_SQRT, ALPHA_FIXED, ALPHA_DOUBLE = 1, 2, 3
RANDOMIZE = {"none": 0, "default": 1, "shift": 2, "permute": 3, "owen": 4, "screen": 5}


@dataclass(frozen=True)
class Sqrt:
    """Generator sqrt(k), computed exactly by the library."""

    k: int


@dataclass(frozen=True)
class Fixed:
    """Generator given by its fractional part in 0.128 fixed point: value / 2^128."""

    value: int


def _alpha_struct(a, name: str = "alpha") -> _native.Alpha:
    s = _native.Alpha()
    if isinstance(a, Sqrt):
        s.kind, s.k = ALPHA_SQRT, u64(a.k, "Sqrt.k")
    elif isinstance(a, Fixed):
        v = integer(a.value, "Fixed.value", 0, U128)
        s.kind, s.fixed_hi, s.fixed_lo = ALPHA_FIXED, v >> 64, v & ((1 << 64) - 1)
    elif isinstance(a, numbers.Real) and not isinstance(a, (bool, np.bool_)):
        s.kind, s.value = ALPHA_DOUBLE, real(a, name, finite=False)  # the library names a non-finite one
    else:
        raise TypeError(f"udm1: {name} = {a!r} is not udm1.Sqrt, udm1.Fixed or a real number")
    return s


def _alpha_array(alphas):
    arr = (_native.Alpha * len(alphas))()
    for i, a in enumerate(alphas):
        arr[i] = _alpha_struct(a, f"alphas[{i}]")
    return arr


@dataclass(frozen=True)
class Preset:
    name: str
    description: str
    max_dimensions: int
    point_set: bool


def presets() -> list[Preset]:
    """Every preset of the library, in its order."""
    out = []
    info = _native.PresetInfo()
    for i in range(lib.udm1_preset_count()):
        check(lib.udm1_preset_get(i, ctypes.byref(info)))
        out.append(Preset(info.name.decode(), info.description.decode(), info.max_dimensions, bool(info.flags & 1)))
    return out


_DTYPES = {
    np.dtype(np.float64): ("udm1_seq_fill_f64", "udm1_seq_sample_f64", ctypes.c_double),
    np.dtype(np.float32): ("udm1_seq_fill_f32", "udm1_seq_sample_f32", ctypes.c_float),
    np.dtype(np.uint64): ("udm1_seq_fill_u64", "udm1_seq_sample_u64", ctypes.c_uint64),
}


def _dtype(dtype) -> np.dtype:
    try:
        dt = np.dtype(dtype)
    except TypeError as exc:
        raise ValueError(f"udm1: dtype {dtype!r} is not a dtype ({exc})") from None
    if dt not in _DTYPES:
        raise ValueError(f"udm1: dtype {dt} is not supported; use float64, float32 or uint64 (raw 0.64 fixed point)")
    return dt


def _offsets(offsets, d: int) -> np.ndarray:
    """offsets as d uint64 values, each checked (numpy would wrap a negative or a too large one)."""
    values = index_array(offsets, "offsets", where="udm1.Sequence")
    if values.shape != (d,):
        raise ValueError(f"udm1.Sequence: offsets must have {d} entries, not shape {values.shape}")
    return values


class Sequence:
    """A udm1 sequence or point set.

    ``Sequence("wr", 8, seed=7)``: a preset with a random shift per stream.
    ``Sequence("wr", 8, randomize=False)``: the deterministic sequence.
    ``randomize`` is True (the preset's default), False, or one of "shift",
    "permute", "owen", "screen" (see udm1.h).
    ``Sequence("wr", 2, seed=1, randomize="screen")``: screen-space blue noise at
    every sample count: with stream ``(y << 32) | x``, pixel (x, y) keeps the
    sequence's points shifted by ``x G + y H`` (docs/screen-space.md).
    ``screen_spp=16``: the fixed scheme, pixel (x, y) takes points ``m * 16 + n``
    of one shifted sequence, m its Morton index (blue at 16 samples).
    ``Sequence(alphas=[udm1.Sqrt(2), udm1.Sqrt(13)])``: your own generators.
    ``Sequence("episwr", 2, point_count=64, seed=1)``: a point set of K points.

    Point ``n`` of stream ``s`` is ``{offset_j + shift_j(seed, s) + n * alpha_j}``;
    indices start at 0 and point 0 equals the offset (see udm1.h).
    """

    def __init__(self, preset: str | None = None, d: int | None = None, *, alphas=None, point_count: int = 0,
                 seed: int = 0, randomize: bool = True, offsets=None, screen_spp: int = 0):
        self._handle = None
        where = "udm1.Sequence"
        if (preset is None) == (alphas is None):
            raise ValueError("udm1.Sequence: give either a preset name or alphas")
        if alphas is not None:
            if isinstance(alphas, (str, bytes)) or not hasattr(alphas, "__iter__"):
                raise TypeError(f"udm1.Sequence: alphas must be a list of generators, not {type(alphas).__name__}")
            alphas = list(alphas)
            if d is None:
                d = len(alphas)
            if u32(d, "d", where=where) != len(alphas):
                raise ValueError(f"udm1.Sequence: d = {d} but {len(alphas)} alphas")
        if d is None:
            raise ValueError("udm1.Sequence: d (the number of dimensions) is required with a preset")
        d = u32(d, "d", where=where)
        desc = _native.SeqDesc()
        lib.udm1_seq_desc_init(ctypes.byref(desc))
        desc.dimensions = d
        desc.point_count = u64(point_count, "point_count", where=where)
        desc.seed = u64(seed, "seed", where=where)
        desc.randomize = _randomize_code(randomize)
        desc.screen_spp = u32(screen_spp, "screen_spp", where=where)
        keep = []
        if preset is not None:
            desc.preset = text(preset, "preset", where=where).encode()
        else:
            arr = _alpha_array(alphas)
            keep.append(arr)
            desc.alphas = ctypes.cast(arr, ctypes.c_void_p)
        if offsets is not None:
            off = _offsets(offsets, d)
            keep.append(off)
            desc.offsets = off.ctypes.data_as(_native.u64p)
        handle = ctypes.c_void_p()
        check(lib.udm1_seq_create_desc(ctypes.byref(desc), ctypes.byref(handle)))
        self._handle = handle

    def __del__(self):
        handle = getattr(self, "_handle", None)
        if handle is not None and lib is not None:
            lib.udm1_seq_destroy(handle)
            self._handle = None

    def close(self) -> None:
        """Release the handle now (also done by the garbage collector)."""
        self.__del__()

    def __repr__(self):
        pc = f", point_count={self.point_count}" if self.point_count else ""
        return f"udm1.Sequence({self.name!r}, {self.d}{pc}, seed={self.seed}, randomize={self.randomized})"

    @property
    def handle(self):
        if self._handle is None:
            raise ValueError("udm1.Sequence: the sequence was closed")
        return self._handle

    @property
    def d(self) -> int:
        return lib.udm1_seq_dimensions(self.handle)

    @property
    def name(self) -> str:
        return lib.udm1_seq_name(self.handle).decode()

    @property
    def point_count(self) -> int:
        """K for a point set, 0 for a sequence."""
        return lib.udm1_seq_point_count(self.handle)

    @property
    def seed(self) -> int:
        return lib.udm1_seq_seed(self.handle)

    @property
    def randomized(self) -> bool:
        return lib.udm1_seq_randomize(self.handle) != 0

    @property
    def randomization(self) -> str:
        """The randomization applied ("none", "shift", "permute", "owen", "screen"; "default" for PRNG streams)."""
        code = lib.udm1_seq_randomization(self.handle)
        return [k for k, v in RANDOMIZE.items() if v == code][0]

    def alpha(self, dim: int) -> int:
        """Generator of dimension dim: its fractional part times 2^128, as an int."""
        hi, lo = ctypes.c_uint64(), ctypes.c_uint64()
        check(lib.udm1_seq_alpha(self.handle, u32(dim, "dim"), ctypes.byref(hi), ctypes.byref(lo)))
        return (hi.value << 64) | lo.value

    def offset(self, dim: int, stream: int = 0) -> int:
        """Total offset of dimension dim for a stream, times 2^64: the raw value of point 0."""
        out = ctypes.c_uint64()
        check(lib.udm1_seq_offset(self.handle, u64(stream, "stream"), u32(dim, "dim"), ctypes.byref(out)))
        return out.value

    def sample(self, index: int, dim: int, stream: int = 0, dtype=np.float64):
        """One value by random access; dtype float64, float32 or uint64 (raw 0.64)."""
        dt = _dtype(dtype)
        _, name, ctype = _DTYPES[dt]
        out = ctype()
        check(getattr(lib, name)(self.handle, u64(stream, "stream"), u64(index, "index"), u32(dim, "dim"),
                                 ctypes.byref(out)))
        return dt.type(out.value)

    def points(self, n: int, first: int = 0, *, stream: int = 0, dims=None, dtype=np.float64,
               out: np.ndarray | None = None) -> np.ndarray:
        """Points [first, first + n) as an (n, nd) array; dims is a range or slice
        of dimensions (default all). With out, fills that C-contiguous, writeable array."""
        d = self.d
        if dims is None:
            d0, nd = 0, d
        else:
            d0, nd = _dims(range(d)[dims] if isinstance(dims, slice) else dims, "udm1.Sequence.points")
        dt = _dtype(dtype)
        fill_name = _DTYPES[dt][0]
        n = u64(n, "n")
        first, stream = u64(first, "first"), u64(stream, "stream")
        fill = getattr(lib, fill_name)
        if out is None:
            # the library's checks first (a range past a point set, ...), before a large allocation: with no
            # output array it answers NULL_ARGUMENT only when everything else is valid
            st = fill(self.handle, stream, first, n, d0, nd, None, nd)
            if st not in (0, 1):
                check(st)
            out = np.empty((n, nd), dtype=dt)  # written whole by the fill below, or refused before any write
        elif (not isinstance(out, np.ndarray) or out.dtype != dt or out.shape != (n, nd) or not out.flags.c_contiguous
              or not out.flags.writeable):
            raise ValueError(f"udm1.Sequence.points: out must be a C-contiguous, writeable {dt} array of shape "
                             f"({n}, {nd})")
        check(fill(self.handle, stream, first, n, d0, nd, out.ctypes.data if n else None, nd))
        return out

    def points_at(self, streams, indices, *, dims=None) -> np.ndarray:
        """Point indices[k] of stream streams[k] for every k, as an (n, nd) float64 array (dims: a
        contiguous range of dimensions, default all; past the sequence's own they are padded, as
        the cursor pads them). What a wavefront renderer asks at each bounce: one call
        (udm1_seq_fill_points_f64), equal to per-point samples; keep a stream's points together.
        streams and indices are 1-D arrays of integers in [0, 2^64) (integral floats are taken, as
        for the scalar stream and index of points and sample)."""
        where = "udm1.Sequence.points_at"
        s = index_array(streams, "streams", where=where)
        i = index_array(indices, "indices", where=where)
        if s.ndim != 1 or s.shape != i.shape:
            raise ValueError(f"{where}: streams and indices must be 1-D arrays of one length, not shapes "
                             f"{s.shape} and {i.shape}")
        d0, nd = _dims(range(self.d) if dims is None else dims, where)
        out = np.empty((len(s), nd))  # written whole by the fill, or refused before any write
        check(lib.udm1_seq_fill_points_f64(self.handle, len(s), s.ctypes.data_as(_native.u64p),
                                           i.ctypes.data_as(_native.u64p), d0, nd, out.ctypes.data_as(_native.f64p)))
        return out

    def integration_error(self, integrand, d: int, n: int, randomizations: int = 32) -> tuple[float, float]:
        """(rmse, bias) of the mean of a test integrand over points [0, n) of streams
        0..R-1 against its exact integral (udm1_integration_error)."""

        rmse, bias = ctypes.c_double(), ctypes.c_double()
        check(lib.udm1_integration_error(self.handle, _integrand_code(integrand), u32(d, "d"), u64(n, "n"),
                                         u32(randomizations, "randomizations"), ctypes.byref(rmse), ctypes.byref(bias)))
        return rmse.value, bias.value

    def spectrum(self, n: int, size: int = 128, randomizations: int = 16, dim0: int = 0) -> np.ndarray:
        """Periodogram of dimensions (dim0, dim0+1), (size, size), zero frequency at the centre."""
        size = u32(size, "size")
        args = (u32(dim0, "dim0"), u64(n, "n"), u32(randomizations, "randomizations"), size)
        out = np.empty((size, size)) if size <= 1024 else np.empty(0)  # a larger size: the library refuses it
        check(lib.udm1_spectrum_2d(self.handle, *args, out.ctypes.data))
        return out

    def zoneplate(self, width: int, height: int, spp: int, dim0: int = 0) -> np.ndarray:
        """The zone plate test image (height, width), float32."""
        width, height = u32(width, "width"), u32(height, "height")
        args = (u32(dim0, "dim0"), width, height, u32(spp, "spp"))
        fits = width <= 16384 and height <= 16384  # larger: the library refuses it
        out = np.empty((height, width) if fits else 0, dtype=np.float32)
        check(lib.udm1_zoneplate(self.handle, *args, out.ctypes.data))
        return out

    def check(self, n: int = 256) -> dict:
        """udm1_seq_check: rationality, dependence and the worst 2D projection at n points."""
        rep = _native.AlphaReport()
        check(lib.udm1_seq_check(self.handle, u64(n, "n"), ctypes.byref(rep)))
        return _report_dict(rep)


def check_alphas(alphas, n: int = 256) -> dict:
    """udm1_alpha_check on user generators (Sqrt, Fixed or float)."""
    alphas = list(alphas)
    arr = _alpha_array(alphas)
    rep = _native.AlphaReport()
    check(lib.udm1_alpha_check(ctypes.cast(arr, ctypes.c_void_p), u32(len(alphas), "len(alphas)"), u64(n, "n"),
                               ctypes.byref(rep)))
    return _report_dict(rep)


def _report_dict(rep) -> dict:
    return {
        "rational": bool(rep.rational),
        "rational_dim": rep.rational_dim if rep.rational else None,
        "dependent": bool(rep.dependent),
        "dependent_exact": bool(rep.dependent_exact),
        "dependent_dims": tuple(rep.dependent_dims) if rep.dependent else None,
        "worst_dims": tuple(rep.worst_dims),
        "worst_l2_star": rep.worst_l2_star,
        "worst_wrap_around": rep.worst_wrap_around,
        "random_l2_star": rep.random_l2_star,
        "random_wrap_around": rep.random_wrap_around,
        "message": rep.message.decode(),
    }


def _dims(r, where: str) -> tuple[int, int]:
    """(first dimension, count) of a non-empty contiguous range of dimensions inside [0, 2^32)."""
    if not isinstance(r, range) or r.step != 1 or len(r) == 0:
        raise ValueError(f"{where}: dims must be a non-empty contiguous range, not {r!r}")
    d0, stop = u32(r.start, "dims", where=where), u32(r.stop, "dims", where=where)
    return d0, stop - d0


def _randomize_code(randomize) -> int:
    if randomize is True or randomize is np.True_:
        return RANDOMIZE["default"]
    if randomize is False or randomize is np.False_ or randomize is None:
        return RANDOMIZE["none"]
    if isinstance(randomize, str) and randomize in RANDOMIZE:
        return RANDOMIZE[randomize]
    raise ValueError(f"udm1.Sequence: randomize {randomize!r} is not True, False or one of {sorted(RANDOMIZE)}")


def version() -> str:
    return lib.udm1_version_string().decode()
