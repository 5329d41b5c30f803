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
from ._convert import u32, u64
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


class Noise:
    """A lattice noise with tables from Perlin's permutation (table=None),
    drand48 ("drand48") or any udm1 preset; kind "improved" (Perlin 2002) or
    "classic" (Perlin 1985); period: an int or 3 ints (0 = not periodic)."""

    def __init__(self, table: str | None = None, seed: int = 0, kind: str = "improved", period=0):
        self._handle = None
        if kind not in KINDS:
            raise ValueError(f"udm1.Noise: kind {kind!r} is not one of {sorted(KINDS)}")
        periods = [period] * 3 if np.isscalar(period) else list(period)
        if len(periods) != 3:
            raise ValueError("udm1.Noise: period must be a non-negative int or 3 of them")
        periods = [u32(p, "period") for p in periods]
        desc = _native.NoiseDesc()
        lib.udm1_noise_desc_init(ctypes.byref(desc))
        desc.kind = KINDS[kind]
        desc.table = table.encode() if table else None
        desc.seed = u64(seed, "seed")
        for i, p in enumerate(periods):
            desc.period[i] = p
        handle = ctypes.c_void_p()
        check(lib.udm1_noise_create(ctypes.byref(desc), ctypes.byref(handle)))
        self._handle = handle
        self.table, self.seed, self.kind, self.period = table or "perlin", seed, kind, tuple(periods)

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

    def noise(self, points) -> np.ndarray:
        """Noise at the rows of an (n, d) array, d = 1, 2 or 3."""
        x = np.ascontiguousarray(np.asarray(points, dtype=np.float64))
        if x.ndim == 1:
            x = x[:, None]
        if x.ndim != 2 or not 1 <= x.shape[1] <= 3:
            raise ValueError("udm1.Noise.noise: points must be an (n, 1|2|3) array")
        out = np.empty(x.shape[0])
        check(lib.udm1_noise_points(self._handle, x.shape[1], x.ctypes.data, x.shape[0], x.shape[1], out.ctypes.data))
        return out

    def _params(self, pattern: str, octaves=None, omega=None, lacunarity=None, turbulence=None, frequency=None,
                phase=None, wave=None, exponent=None, agate_turb=None) -> _native.PatternParams:
        code = lib.udm1_pattern_from_name(pattern.encode())
        if code == 0:
            raise ValueError(f"udm1: unknown pattern {pattern!r}; known: {patterns()}")
        p = _native.PatternParams()
        lib.udm1_pattern_params_init(ctypes.byref(p), code)
        if octaves is not None:
            p.octaves = u32(octaves, "octaves")
        if omega is not None:
            p.omega = float(omega)
        if lacunarity is not None:
            p.lambda_ = float(lacunarity)
        if turbulence is not None:
            t = [float(turbulence)] * 3 if np.isscalar(turbulence) else [float(v) for v in turbulence]
            for i in range(3):
                p.turbulence[i] = t[i]
        if frequency is not None:
            p.frequency = float(frequency)
        if phase is not None:
            p.phase = float(phase)
        if wave is not None:
            if wave not in WAVES:
                raise ValueError(f"udm1: unknown wave {wave!r}; known: {sorted(WAVES)}")
            p.wave = WAVES[wave]
        if exponent is not None:
            p.exponent = float(exponent)
        if agate_turb is not None:
            p.agate_turb = float(agate_turb)
        return p

    def pattern(self, name: str, points, **params) -> np.ndarray:
        """A pattern ("marble", "fbm", ...) at the rows of an (n, 3) array."""
        x = np.ascontiguousarray(np.asarray(points, dtype=np.float64))
        if x.ndim != 2 or x.shape[1] != 3:
            raise ValueError("udm1.Noise.pattern: points must be an (n, 3) array")
        p = self._params(name, **params)
        out = np.empty(x.shape[0])
        check(lib.udm1_pattern_points(self._handle, ctypes.byref(p), x.ctypes.data, x.shape[0], 3, out.ctypes.data))
        return out

    def pattern_grid(self, name: str, width: int, height: int, origin=(0.0, 0.0, 0.0), size=(4.0, 4.0),
                     **params) -> np.ndarray:
        """A (height, width) float32 image of a pattern over the rectangle origin + [0, size) in x, y."""
        p = self._params(name, **params)
        width, height = u32(width, "width"), u32(height, "height")
        fits = 0 < width <= 65536 and 0 < height <= 65536  # otherwise the library's own check speaks
        out = np.empty((height, width) if fits else 0, dtype=np.float32)
        o = (ctypes.c_double * 3)(*[float(v) for v in origin])
        sx = (ctypes.c_double * 3)(float(size[0]) / width if width else 0.0, 0.0, 0.0)
        sy = (ctypes.c_double * 3)(0.0, float(size[1]) / height if height else 0.0, 0.0)
        check(lib.udm1_pattern_grid(self._handle, ctypes.byref(p), width, height, 0, height, o, sx, sy,
                                    out.ctypes.data))
        return out
