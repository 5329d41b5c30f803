"""Perlin noise and POV-Ray patterns from libudm1, over numpy arrays.

    >>> import numpy as np, udm1
    >>> n = udm1.Noise()                       # Perlin's reference table
    >>> float(n.noise(np.array([[3.14, 42, 7]]))[0])
    0.13691995878400012
    >>> img = udm1.Noise("wr", seed=3).pattern_grid("marble", 256, 256, turbulence=0.5)
"""

from __future__ import annotations

import ctypes

import numpy as np

from . import _native
from ._convert import choice, flag, real, real_array, text, u32, u64
from ._native import lib
from .errors import check

KINDS = {"improved": 0, "classic": 1}
WAVES = {"default": 0, "ramp": 1, "triangle": 2, "sine": 3, "scallop": 4, "cubic": 5, "poly": 6}


def patterns() -> list[str]:
    """The pattern names, in their order."""
    out, k = [], 1
    while (name := lib.udm1_pattern_name(k)) is not None:
        out.append(name.decode())
        k += 1
    return out


CELL_OUTPUTS = {"f1": 0, "f2": 1, "f3": 2, "f2-f1": 3, "cell": 4}
CELL_METRICS = {"euclidean": 0, "manhattan": 1, "chebyshev": 2, "minkowski": 3}


def _real(v, name: str, where: str = "udm1.Noise") -> float:
    """A finite real parameter (the converter's rule: numpy scalars taken; bools, strings, complex refused)."""
    return real(v, name, where=where)


def _reals(v, name: str, count: int, where: str = "udm1.Noise") -> list[float]:
    """`count` finite real numbers given as a list, tuple or array."""
    values = real_array(v, name, where=where)
    if values.shape != (count,):
        raise ValueError(f"{where}: {name} must be {count} numbers, not an array of shape {values.shape}")
    return [_real(x, f"{name}[{k}]", where) for k, x in enumerate(values.tolist())]


_PRECISIONS = {"float32": np.float32, "float64": np.float64}


def _precision(dtype, where: str):
    """dtype= of the evaluations: None (from the points), float32 or float64."""
    if dtype is None:
        return None
    try:
        dt = np.dtype(dtype)
    except TypeError:
        dt = None
    if dt is None or dt.name not in _PRECISIONS:
        raise ValueError(f"{where}: dtype {dtype!r} is not float32 or float64")
    return _PRECISIONS[dt.name]


def _coordinates(points, dtype, lo: int, hi: int, where: str):
    """Points as rows of an (n, d) array or as d coordinate arrays (lo <= d <= hi), through the package's
    converter (real numbers only): the axes' addresses, the stride, n, the precision (float32 points:
    float32, else float64; dtype= forces one) and the arrays to keep alive during the call."""
    forced = _precision(dtype, where)
    if isinstance(points, (tuple, list)) and len(points) and np.ndim(points[0]) == 1:
        cols = [real_array(a, f"points[{k}]", where=where, float32=True) for k, a in enumerate(points)]
        if not lo <= len(points) <= hi:
            raise ValueError(f"{where}: give {lo} to {hi} coordinate arrays, not {len(points)}")
        real_type = forced or (np.float32 if all(c.dtype == np.float32 for c in cols) else np.float64)
        cols = [np.ascontiguousarray(c, dtype=real_type) for c in cols]
        n = cols[0].shape[0]
        if any(c.shape != (n,) for c in cols):
            raise ValueError(f"{where}: the coordinate arrays must have one shape, (n,)")
        return [c.ctypes.data for c in cols], 1, n, real_type, cols
    arr = real_array(points, "points", where=where, float32=True)
    if arr.ndim == 1:
        arr = arr[:, None]
    if arr.ndim != 2 or not lo <= arr.shape[1] <= hi:
        raise ValueError(f"{where}: points must be an (n, {lo}..{hi}) array or {lo} to {hi} coordinate arrays")
    real_type = forced or (np.float32 if arr.dtype == np.float32 else np.float64)
    x = np.ascontiguousarray(arr, dtype=real_type)
    n, d = x.shape
    return [x.ctypes.data + k * x.itemsize for k in range(d)], max(d, 1), n, real_type, x


class Noise:
    """A lattice noise with tables from Perlin's permutation (table=None),
    drand48 ("drand48") or any udm1 preset; kind "improved" (Perlin 2002) or
    "classic" (Perlin 1985); period: an int, or 3 or 4 ints (x, y, z and the 4D
    noise's w; 0 = not periodic)."""

    def __init__(self, table: str | None = None, seed: int = 0, kind: str = "improved", period=0):
        self._handle = None
        where = "udm1.Noise"
        kind = choice(kind, "kind", KINDS, where=where)
        if table is not None:
            text(table, "table", where=where)
        if isinstance(period, (list, tuple, np.ndarray)):
            given = np.asarray(period, dtype=object).ravel()
            periods = [u32(p, f"period[{k}]", where=where) for k, p in enumerate(given)]
        else:
            periods = [u32(period, "period", where=where)] * 4
        if len(periods) == 3:
            periods.append(0)
        if len(periods) != 4:
            raise ValueError("udm1.Noise: period must be a non-negative int or 3 or 4 of them")
        desc = _native.NoiseDesc()
        lib.udm1_noise_desc_init(ctypes.byref(desc))
        desc.kind = KINDS[kind]
        desc.table = table.encode() if table else None
        desc.seed = u64(seed, "seed", where=where)
        for i, p in enumerate(periods[:3]):
            desc.period[i] = p
        desc.period_w = periods[3]
        handle = ctypes.c_void_p()
        check(lib.udm1_noise_create(ctypes.byref(desc), ctypes.byref(handle)))
        self._handle = handle
        self.table, self.seed, self.kind, self.period = table or "perlin", desc.seed, kind, tuple(periods)

    def __del__(self):
        if getattr(self, "_handle", None) is not None and lib is not None:
            lib.udm1_noise_destroy(self._handle)
            self._handle = None

    def __repr__(self):
        return f"udm1.Noise({self.table!r}, seed={self.seed}, kind={self.kind!r}, period={self.period})"

    def tables(self) -> tuple[np.ndarray, np.ndarray]:
        """(permutation (256,) uint8, gradients (256, 3))."""
        perm = np.empty(256, dtype=np.uint8)
        grad = np.empty((256, 3))
        check(lib.udm1_noise_tables(self._handle, perm.ctypes.data, grad.ctypes.data))
        return perm, grad

    def cellular_offsets(self) -> np.ndarray:
        """The cellular noise's 256 feature point offsets b, (256, 3) uint8: entry h's point sits at
        1/2 + jitter ((b + 1/2) / 256 - 1/2) in its cell."""
        raw = np.empty((256, 3), dtype=np.uint8)
        check(lib.udm1_cellular_offsets(self._handle, raw.ctypes.data))
        return raw

    def noise(self, points, gradient: bool = False, dtype=None):
        """Noise at n points, d = 1..4 coordinates each (4D: improved noise only): the rows of an (n, d)
        array, or d separate arrays of n coordinates (a tuple or list, as x, y, z).

        float32 points are evaluated in float (udm1_noise_eval_f32: SIMD over the points, the same bits
        on every machine), anything else in double (the per-point functions' values, bit for bit);
        dtype= forces the precision ("float32" or "float64"). Returns the values, an (n,) array; with
        gradient=True, (values, gradients) with gradients of shape (n, d): d noise / d x_k, analytic."""
        gradient = flag(gradient, "gradient", where="udm1.Noise.noise")
        ptrs, stride, n, real_type, keep = _coordinates(points, dtype, 1, 4, "udm1.Noise.noise")
        d = len(ptrs)
        values = np.empty(n, dtype=real_type)  # written whole by the call, or refused before any write
        grads = np.empty((n, d), dtype=real_type) if gradient else None
        arg = (ctypes.c_void_p * d)(*ptrs)
        fn = lib.udm1_noise_eval_f32 if real_type == np.float32 else lib.udm1_noise_eval
        check(fn(self._handle, d, arg, stride, n, values.ctypes.data, grads.ctypes.data if gradient else None))
        del keep
        return (values, grads) if gradient else values

    def cellular(self, points, output: str = "f1", metric: str = "euclidean", jitter: float = 1.0,
                 exponent: float = 2.0, dtype=None) -> np.ndarray:
        """Cellular (Worley) noise at n points of 2 or 3 coordinates (rows of an (n, d) array or d coordinate
        arrays), one feature point per unit cell placed by this noise's table (a udm1 sequence's points,
        a hash or drand48) and periodic with the noise's period. output: "f1", "f2", "f3", "f2-f1" (distances
        to the nearest feature points, in cell units) or "cell" (the nearest point's table entry / 255);
        metric: "euclidean", "manhattan", "chebyshev" or "minkowski" (with exponent); jitter in [0, 1]: how
        far a point strays from its cell's centre (1: anywhere in the cell). float32 points are evaluated
        in float, others in double (dtype= forces one). The search is exact in every case."""
        where = "udm1.Noise.cellular"
        output = choice(output, "output", CELL_OUTPUTS, where=where)
        metric = choice(metric, "metric", CELL_METRICS, where=where)
        ptrs, stride, n, real_type, keep = _coordinates(points, dtype, 2, 3, where)
        p = _native.CellularParams()
        lib.udm1_cellular_params_init(ctypes.byref(p))
        p.output, p.metric = CELL_OUTPUTS[output], CELL_METRICS[metric]
        p.jitter, p.exponent = _real(jitter, "jitter", where), _real(exponent, "exponent", where)
        out = np.empty(n, dtype=real_type)  # written whole by the call, or refused before any write
        arg = (ctypes.c_void_p * len(ptrs))(*ptrs)
        fn = lib.udm1_cellular_eval_f32 if real_type == np.float32 else lib.udm1_cellular_eval
        check(fn(self._handle, ctypes.byref(p), len(ptrs), arg, stride, n, out.ctypes.data))
        del keep
        return out

    def _params(self, pattern: str, octaves=None, omega=None, lacunarity=None, turbulence=None, frequency=None,
                phase=None, wave=None, exponent=None, agate_turb=None, form=None, metric=None, offset=None,
                solid=None) -> _native.PatternParams:
        where = "udm1.Noise"
        code = lib.udm1_pattern_from_name(text(pattern, "pattern", where=where).encode())
        if code == 0:
            raise ValueError(f"udm1: unknown pattern {pattern!r}; known: {patterns()}")
        p = _native.PatternParams()
        lib.udm1_pattern_params_init(ctypes.byref(p), code)
        if octaves is not None:
            p.octaves = u32(octaves, "octaves", where=where)
        if omega is not None:
            p.omega = _real(omega, "omega")
        if lacunarity is not None:
            p.lambda_ = _real(lacunarity, "lacunarity")
        if turbulence is not None:  # one number for the three axes, or three
            scalar = not isinstance(turbulence, (list, tuple, np.ndarray)) or np.ndim(turbulence) == 0
            t = [_real(turbulence, "turbulence")] * 3 if scalar else _reals(turbulence, "turbulence", 3)
            for i in range(3):
                p.turbulence[i] = t[i]
        if frequency is not None:
            p.frequency = _real(frequency, "frequency")
        if phase is not None:
            p.phase = _real(phase, "phase")
        if wave is not None:
            if not isinstance(wave, str) or wave not in WAVES:
                raise ValueError(f"udm1: unknown wave {wave!r}; known: {sorted(WAVES)}")
            p.wave = WAVES[wave]
        if exponent is not None:
            p.exponent = _real(exponent, "exponent")
        if agate_turb is not None:
            p.agate_turb = _real(agate_turb, "agate_turb")
        if form is not None:  # crackle's: the weights of F1, F2, F3
            for i, f in enumerate(_reals(form, "form", 3)):
                p.crackle_form[i] = f
        if metric is not None:
            p.crackle_metric = _real(metric, "metric")
        if offset is not None:
            p.crackle_offset = _real(offset, "offset")
        if solid is not None:
            p.crackle_solid = 1 if flag(solid, "solid", where=where) else 0
        return p

    def pattern(self, name: str, points, gradient: bool = False, **params):
        """A pattern ("marble", "fbm", "crackle", ...) at the rows of an (n, 3) array. gradient=True (the raw
        noise patterns noise, fbm, turbulence, ridged): (values, gradients (n, 3)), analytic, the values
        bit for bit those of gradient=False. Parameters: octaves, omega, lacunarity, turbulence, frequency,
        phase, wave, exponent, agate_turb; crackle's form, metric, offset, solid."""
        where = "udm1.Noise.pattern"
        gradient = flag(gradient, "gradient", where=where)
        x = real_array(points, "points", where=where)
        if x.ndim != 2 or x.shape[1] != 3:
            raise ValueError(f"{where}: points must be an (n, 3) array, not shape {x.shape}")
        p = self._params(name, **params)
        out = np.empty(x.shape[0])  # written whole by the call, or refused before any write
        if gradient:
            grads = np.empty((x.shape[0], 3))
            check(lib.udm1_pattern_gradient(self._handle, ctypes.byref(p), x.ctypes.data, x.shape[0], 3,
                                            out.ctypes.data, grads.ctypes.data))
            return out, grads
        check(lib.udm1_pattern_points(self._handle, ctypes.byref(p), x.ctypes.data, x.shape[0], 3, out.ctypes.data))
        return out

    def pattern_grid(self, name: str, width: int, height: int, origin=(0.0, 0.0, 0.0), size=(4.0, 4.0),
                     **params) -> np.ndarray:
        """A (height, width) float32 image of a pattern over the rectangle origin + [0, size) in x, y
        (origin: 3 finite numbers, size: 2)."""
        where = "udm1.Noise.pattern_grid"
        p = self._params(name, **params)
        width, height = u32(width, "width", where=where), u32(height, "height", where=where)
        origin, size = _reals(origin, "origin", 3, where), _reals(size, "size", 2, where)
        fits = 0 < width <= 65536 and 0 < height <= 65536  # otherwise the library's own check speaks
        out = np.empty((height, width) if fits else 0, dtype=np.float32)  # written whole, or refused
        o = (ctypes.c_double * 3)(*origin)
        sx = (ctypes.c_double * 3)(size[0] / width if width else 0.0, 0.0, 0.0)
        sy = (ctypes.c_double * 3)(0.0, size[1] / height if height else 0.0, 0.0)
        check(lib.udm1_pattern_grid(self._handle, ctypes.byref(p), width, height, 0, height, o, sx, sy,
                                    out.ctypes.data))
        return out
