"""udm1's samplers inside Mitsuba 3: ``Sampler "udm1"`` for the scalar and the LLVM (and CUDA) variants.

    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    import udm1.mitsuba
    udm1.mitsuba.register()          # registers "udm1" for the current variant
    scene = mi.load_dict({..., "sensor": {..., "sampler": {"type": "udm1", "preset": "wr",
                                                           "sample_count": 64, "randomize": "shift"}}})

or in XML: ``<sampler type="udm1"><string name="preset" value="sobol-owen"/>
<integer name="sample_count" value="64"/></sampler>``. Call ``register()`` again after switching
variants (a plugin is registered per variant).

Properties: ``preset`` (any udm1 preset, default "wr"), ``sample_count``, ``seed`` (the udm1 sequence's
seed, default 0), ``randomize`` ("default", "none", "shift", "owen", "permute" or "screen"; default the
preset's own), ``dimensions`` (D, default 64: dimensions past D are padded, as udm1's cursor pads them,
with independent hashed values), ``film_width`` (needed by "screen", which names pixels by (x, y)).

What each lane draws (the values are udm1's, bit for bit, as float32: top 24 bits of the 64-bit value):

- Vector variants (``llvm_*``, ``cuda_*``): Mitsuba traces a wavefront of W H spp lanes, lane
  ``k`` = pixel ``k // spp`` (row-major, ``y W + x``) and sample ``k % spp``; with several passes the
  sample index is ``pass * spp_per_pass + k % spp_per_pass`` (give ``film_width`` and
  ``film_height`` then, so that the sampler knows spp_per_pass). The stream is the pixel index
  ``y W + x`` combined with the render's seed (``seed * 2^32 + y W + x``); with "screen" it is
  ``(y << 32) | x`` and the render's seed is added to the sequence's. The index is the sample index.
  The Weyl presets (wr, wr-ao, we, wgr, wmmr, hwmmr, rd, golden, wopt) are computed in Dr.Jit
  operations from udm1's integer contract (64-bit products, the documented hash): no table, any
  number of samples. The other presets (sobol-owen, pmj02, halton, ...) are filled by the library at
  ``seed()``, one call per dimension for the whole wavefront, into a table of D float32 values per
  lane (memory: 4 D bytes per sample; 128 x 128 x 256 spp at D = 32 is 537 MB).
- Scalar variants: Mitsuba seeds the sampler once per pixel (and pass) with a seed unique in the
  render (``seed W H + block b^2 + i``); that seed is the stream, the count of ``advance()`` calls the
  index, and every draw is one call of the library's cursor (udm1_cursor_1d).

Dimensions: the k-th value a sample draws is dimension k (a 2D draw takes two), in the order
Mitsuba's integrator asks for them (the path tracer: the film position first, then per bounce the
emitter's 2D, the BSDF's 1D and 2D, Russian roulette's 1D). Every lane advances its dimension on
every draw, so a dimension means the same draw on every path.
"""

from __future__ import annotations

import ctypes
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from . import _native
from .errors import check
from .sequence import Sequence

GOLDEN_GAMMA = 0x9E3779B97F4A7C15
SEED_SALT = int.from_bytes(b"udm1SEED", "big")
M64 = (1 << 64) - 1
WEYL_PRESETS = {"wr", "wr-ao", "we", "wgr", "wmmr", "hwmmr", "rd", "golden", "wopt"}
RANDOMIZE = ("default", "none", "shift", "owen", "permute", "screen")
BUFFER = 16  # scalar variants: the draws of a sample made in one cursor fill


def _mix64_int(z: int) -> int:
    """Stafford's Mix13 finalizer on a Python int (udm1's hash.h, part of the ABI)."""
    z &= M64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & M64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & M64
    return z ^ (z >> 31)


def _options(props) -> dict:
    def get(name, default):
        return props[name] if name in props else default

    o = {"preset": str(get("preset", "wr")), "seed": int(get("seed", 0)), "randomize": str(get("randomize", "default")),
         "dimensions": int(get("dimensions", 64)), "film_width": int(get("film_width", 0)),
         "film_height": int(get("film_height", 0))}
    if o["randomize"] not in RANDOMIZE:
        raise ValueError(f"udm1 sampler: randomize {o['randomize']!r} is not one of {', '.join(RANDOMIZE)}")
    if not 1 <= o["dimensions"] <= 65536:
        raise ValueError(f"udm1 sampler: dimensions {o['dimensions']} is not in 1..65536")
    if o["seed"] < 0 or o["film_width"] < 0 or o["film_height"] < 0:
        raise ValueError("udm1 sampler: seed, film_width and film_height must not be negative")
    return o


def _sequence(o: dict, spp: int, extra_seed: int = 0) -> Sequence:
    """The udm1 sequence of a sampler: D dimensions (at most the preset's), point sets of spp points."""
    from .sequence import presets

    info = {p.name: p for p in presets()}.get(o["preset"])
    if info is None:
        raise ValueError(f"udm1 sampler: preset {o['preset']!r} is not a udm1 preset ({', '.join(sorted(p.name for p in presets()))})")
    d = min(o["dimensions"], info.max_dimensions)
    randomize = True if o["randomize"] == "default" else o["randomize"]
    return Sequence(o["preset"], d, point_count=spp if info.point_set else 0, seed=(o["seed"] + extra_seed) & M64,
                    randomize=randomize, screen_spp=spp if o["randomize"] == "screen" else 0)


def sampler_class():
    """The udm1 sampler class for Mitsuba's current variant."""
    import drjit as dr
    import mitsuba as mi

    jit = dr.is_jit_v(mi.Float)

    class Udm1Sampler(mi.Sampler):
        def __init__(self, props=None):
            props = mi.Properties() if props is None else props
            super().__init__(props)
            self._o = _options(props)
            if self._o["randomize"] == "screen" and not jit:
                raise ValueError("udm1 sampler: randomize 'screen' needs a vector variant (llvm_*, cuda_*): the scalar "
                                 "variants do not tell a sampler its pixel's position")
            if self._o["randomize"] == "screen" and not self._o["film_width"]:
                raise ValueError("udm1 sampler: randomize 'screen' needs film_width (pixels are named (x, y))")
            self._spp = self.sample_count()
            self._seq = _sequence(self._o, self._spp)
            self._seq_seed = 0
            self._pass = 0
            if jit:
                self._dim = mi.UInt32(0)
                self._stale = False
                self._render_seed = 0
            else:
                self._cursor = _native.Cursor()
                self._stream, self._index, self._started = 0, 0, False
                self._buf, self._pos = [], 0

        # ---- configuration ----
        def _copy(self):
            s = Udm1Sampler.__new__(Udm1Sampler)
            mi.Sampler.__init__(s, mi.Properties())
            s._o, s._spp, s._seq, s._seq_seed, s._pass = dict(self._o), self._spp, self._seq, self._seq_seed, 0
            s.set_sample_count(self.sample_count())
            if jit:
                s._dim, s._stale, s._render_seed = mi.UInt32(0), False, self._render_seed
            else:
                s._cursor, s._stream, s._index, s._started = _native.Cursor(), 0, 0, False
                s._buf, s._pos = [], 0
            return s

        def set_sample_count(self, spp):
            super().set_sample_count(spp)
            if hasattr(self, "_o") and spp != self._spp:
                self._spp = spp
                self._seq = _sequence(self._o, spp, self._seq_seed)

        def fork(self):
            return self._copy()

        def clone(self):
            s = self._copy()
            if jit:
                if self.wavefront_size() > 0:
                    mi.Sampler.seed(s, 0, self.wavefront_size())
                s.__dict__.update(self.__dict__)  # Dr.Jit arrays are values: sharing them is a copy
            else:
                s._stream, s._index, s._started = self._stream, self._index, self._started
                s._buf, s._pos = list(self._buf), self._pos
                ctypes.memmove(ctypes.byref(s._cursor), ctypes.byref(self._cursor), ctypes.sizeof(_native.Cursor))
            return s

        def to_string(self):
            return (f"Udm1Sampler[preset={self._o['preset']}, sample_count={self.sample_count()}, "
                    f"randomize={self._seq.randomization}, dimensions={self._seq.d}]")

        # ---- scalar variants: the library's cursor ----
        if not jit:
            def seed(self, seed, wavefront_size=0xFFFFFFFF):
                super().seed(int(seed) & 0xFFFFFFFF, wavefront_size)  # (Mitsuba's own seeds are 32-bit)
                self._stream, self._index, self._started = int(seed) & M64, 0, False
                self._buf, self._pos = [], 0

            def advance(self):  # (not the base's: from Python it calls this override back)
                self._index += 1
                self._started = False  # started at the next draw: Mitsuba advances past a point set's last sample
                self._buf, self._pos = [], 0

            def _cursor_ref(self):
                if not self._started:
                    check(_native.lib.udm1_cursor_start(ctypes.byref(self._cursor), self._seq.handle, self._stream,
                                                        self._index, 0))
                    self._started = True
                return ctypes.byref(self._cursor)

            def _next(self) -> float:
                """The next draw: a sample's first BUFFER draws come from one cursor fill (a Python call per
                draw is the cost here, not the library's), the rest one by one."""
                if self._pos < len(self._buf):
                    self._pos += 1
                    return self._buf[self._pos - 1]
                c = self._cursor_ref()
                if self._pos == 0 and BUFFER:
                    out = (ctypes.c_float * BUFFER)()
                    _native.lib.udm1_cursor_fill(c, BUFFER, out)
                    self._buf, self._pos = list(out), 1
                    return self._buf[0]
                return _native.lib.udm1_cursor_1d(c)

            def next_1d(self, active=True):
                return self._next()

            def next_2d(self, active=True):
                x = self._next()
                return mi.Point2f(x, self._next())

        # ---- vector variants: Dr.Jit arrays over the wavefront ----
        else:
            def seed(self, seed, wavefront_size=0xFFFFFFFF):
                super().seed(seed, wavefront_size)
                render_seed = int(seed) if isinstance(seed, int) else int(dr.slice(mi.UInt32(seed)))
                self._pass = 0
                self._render_seed = render_seed
                if self._o["randomize"] == "screen" and render_seed != self._seq_seed:
                    self._seq_seed = render_seed
                    self._seq = _sequence(self._o, self.sample_count(), render_seed)
                self._stale = True  # the state is made at the pass's first draw (after a render, none comes)

            def advance(self):  # (not the base's: from Python it calls this override back)
                self._pass += 1
                self._stale = True

            def schedule_state(self):
                super().schedule_state()
                dr.schedule(self._dim)

            def _spp_per_pass(self) -> int:
                w, h, spp = self._o["film_width"], self._o["film_height"], self.sample_count()
                lanes = self.wavefront_size()
                if w and h and lanes % (w * h) == 0:
                    return lanes // (w * h)
                if self._pass:
                    raise ValueError("udm1 sampler: a render in several passes needs film_width and film_height (the "
                                     "sampler cannot tell the samples per pass otherwise)")
                return spp

            def _setup(self):
                """Per-lane state of a pass: stream keys, sample and sequence indices; per-dimension tables."""
                lanes = self.wavefront_size()
                spp_pass = self._spp_per_pass()
                lane = dr.arange(mi.UInt32, lanes)
                pixel = lane // spp_pass
                # per-render numbers enter the kernels as opaque parameters, not literals: one compilation
                # serves every render seed and pass
                sample = dr.opaque(mi.UInt64, self._pass * spp_pass) + mi.UInt64(lane % spp_pass)
                seq, o = self._seq, self._o
                screen = o["randomize"] == "screen"
                if screen:
                    w = o["film_width"]
                    stream = (mi.UInt64(pixel // w) << 32) | mi.UInt64(pixel % w)
                else:
                    stream = (dr.opaque(mi.UInt64, self._render_seed) << 32) + mi.UInt64(pixel)
                S = _mix64_int(seq.seed ^ SEED_SALT)
                self._S = dr.opaque(mi.UInt64, S)
                self._n = sample
                self._dim = dr.zeros(mi.UInt32, lanes)
                self._weyl = o["preset"] in WEYL_PRESETS
                mode = seq.randomization
                self._mode = mode
                T = _mix64(_mix64(stream + GOLDEN_GAMMA) ^ self._S)  # udm1_stream_key(S, stream)
                # the key padding hashes: the stream itself in screen mode, else its key
                self._pkey = stream if screen else T
                if self._weyl:
                    d = seq.d
                    plain = Sequence(o["preset"], d, randomize=False)  # the base offsets o_j
                    ahi, alo, const, kj = [], [], [], []
                    for j in range(d):
                        a = seq.alpha(j)
                        ahi.append(a >> 64)
                        alo.append(a & M64)
                        K = _mix64_int(S + (j + 1) * GOLDEN_GAMMA)
                        c = plain.offset(j)
                        if mode == "screen":
                            c = (c + _mix64_int(S + K)) & M64
                        const.append(c)
                        kj.append(K)
                    self._tables = tuple(mi.UInt64(np.array(t, dtype=np.uint64)) for t in (ahi, alo, const, kj))
                    self._skey = T
                    if screen:
                        self._idx = sample + _morton(stream) * mi.UInt64(self.sample_count())
                    else:
                        self._idx = sample
                else:
                    self._table_fill(stream, sample, lanes)

            def _table_fill(self, stream, sample, lanes):
                """The library's values of every lane for dimensions [0, D): D float32 columns, filled by
                udm1_seq_fill_points_f64 on every core (ctypes releases the GIL during the call)."""
                dr.eval(stream, sample)
                s_np = np.asarray(stream.numpy(), dtype=np.uint64)
                i_np = np.asarray(sample.numpy(), dtype=np.uint64)
                d = self._seq.d
                table = np.empty((d, lanes), dtype=np.float32)

                def fill(a, b):
                    for j in range(d):  # a row of the table at a time: contiguous writes
                        v = self._seq.points_at(s_np[a:b], i_np[a:b], dims=range(j, j + 1))[:, 0]
                        # the float32 value is the top 24 bits: exact from the double's top 53
                        v *= 16777216.0
                        np.floor(v, out=v)
                        v *= 1.0 / 16777216.0
                        table[j, a:b] = v

                workers = max(1, min(os.cpu_count() or 1, lanes // 4096))
                bounds = np.linspace(0, lanes, workers + 1).astype(int)
                with ThreadPoolExecutor(workers) as pool:
                    list(pool.map(fill, bounds[:-1], bounds[1:]))
                self._table = mi.Float(table.ravel())
                self._lanes = lanes
                self._lane = dr.arange(mi.UInt32, lanes)

            def _raw(self, j):
                """Raw 64-bit value of dimension j (per lane) of each lane's (stream, sample)."""
                inside = j < self._seq.d
                kp = _mix64(self._S + (mi.UInt64(j) + 1) * GOLDEN_GAMMA)
                pad = _mix64(_mix64(self._pkey + kp) + (self._n + 1) * GOLDEN_GAMMA)
                if not self._weyl:
                    return inside, pad
                jj = dr.minimum(j, self._seq.d - 1)
                ahi, alo, const, kj = (dr.gather(mi.UInt64, t, jj) for t in self._tables)
                off = const + _mix64(self._skey + kj) if self._mode == "shift" else const
                raw = off + self._idx * ahi + _mulhi64(self._idx, alo)
                return inside, dr.select(inside, raw, pad)

            def next_1d(self, active=True):
                if self._stale:
                    self._stale = False
                    self._setup()
                j = self._dim
                self._dim = j + 1
                inside, raw = self._raw(j)
                value = mi.Float(mi.UInt32(raw >> 40)) * (1.0 / 16777216.0)
                if not self._weyl:
                    jj = dr.minimum(j, self._seq.d - 1)
                    table = dr.gather(mi.Float, self._table, jj * self._lanes + self._lane, inside)
                    value = dr.select(inside, table, value)
                return value

            def next_2d(self, active=True):
                x = self.next_1d(active)
                return mi.Point2f(x, self.next_1d(active))

    def _mix64(z):
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9
        z = (z ^ (z >> 27)) * 0x94D049BB133111EB
        return z ^ (z >> 31)

    def _mulhi64(a, b):
        """The high 64 bits of the 128-bit product a b (Dr.Jit has no 64-bit mul_hi): four 32 x 32 products."""
        m = 0xFFFFFFFF
        a0, a1, b0, b1 = a & m, a >> 32, b & m, b >> 32
        lo, mid1, mid2 = a0 * b0, a1 * b0, a0 * b1
        cross = (lo >> 32) + (mid1 & m) + mid2  # at most 2^64 - 1
        return a1 * b1 + (mid1 >> 32) + (cross >> 32)

    def _spread(v):
        v = v & 0xFFFFFFFF
        v = (v | (v << 16)) & 0x0000FFFF0000FFFF
        v = (v | (v << 8)) & 0x00FF00FF00FF00FF
        v = (v | (v << 4)) & 0x0F0F0F0F0F0F0F0F
        v = (v | (v << 2)) & 0x3333333333333333
        return (v | (v << 1)) & 0x5555555555555555

    def _morton(stream):
        return _spread(stream) | (_spread(stream >> 32) << 1)

    return Udm1Sampler


def register(name: str = "udm1"):
    """Register the udm1 sampler under `name` for Mitsuba's current variant (mi.set_variant first)."""
    import mitsuba as mi

    cls = sampler_class()
    mi.register_sampler(name, lambda props: cls(props))
    return cls
