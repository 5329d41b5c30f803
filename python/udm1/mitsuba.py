"""udm1's samplers inside Mitsuba 3: ``Sampler "udm1"`` for the scalar and the LLVM (and CUDA) variants.

    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    import udm1.mitsuba
    udm1.mitsuba.register()          # registers "udm1" for the current variant
    scene = mi.load_dict({..., "sensor": {..., "film": {"type": "hdrfilm", "width": 256, "height": 192},
                                          "sampler": {"type": "udm1", "preset": "wr", "sample_count": 64,
                                                      "randomize": "shift", "film_width": 256,
                                                      "film_height": 192}}})

``register()`` makes the native plugin (integrations/mitsuba3, C++: the same values at Mitsuba's own speed,
in every variant) available when it is built for the installed Mitsuba (``python -m udm1.mitsuba build``,
udm1/mitsuba_build.py; docs/mitsuba.md), and this module's Python sampler otherwise. The native plugin takes
the same properties, tells a pass's samples from Mitsuba (film_width and film_height are optional there;
"screen" needs them) and draws what is described below, bit for bit.

or in XML: ``<sampler type="udm1"><string name="preset" value="sobol-owen"/>
<integer name="sample_count" value="64"/><integer name="film_width" value="256"/>
<integer name="film_height" value="192"/></sampler>`` (the film's size: the vector variants need it).
Call ``register()`` again after switching variants (a plugin is registered per variant).

Properties (each checked when the scene loads: a bad one is refused with one line naming it; Mitsuba
prints that line last, after its own "failed to instantiate" and the Python traceback):

- ``preset``: a string, any udm1 preset (``udm1.presets()``), also with the tent transform
  ("NAME+tent"); default "wr".
- ``sample_count``: an integer in [1, 2^32 - 1], the samples per pixel (default 4); for a point set
  (epis, hammersley, pmj02, lattice, ...) its K, so at most the library's limit for that preset (pmj02
  2^20, lattice 2^24).
- ``seed``: an integer in [0, 2^63), the udm1 sequence's seed (default 0). (The library takes seeds up to
  2^64 - 1; Mitsuba's integer properties stop at 2^63 - 1, and a larger value reaches the sampler as a
  float, which is refused.)
- ``randomize``: "default" (the preset's own), "none", "shift", "owen", "permute" or "screen" (the
  library's fixed scheme, N = sample_count: udm1/seq.h, desc.screen_spp). Every
  combination the library accepts is drawn as the library draws it; the library refuses "screen" for
  every kind but the Weyl sequences, and the sampler refuses it in the scalar variants (they do not
  tell a sampler its pixel's position).
- ``dimensions``: an integer D in [1, the preset's dimensions] (default 64, or the preset's own when it
  has fewer): draws past D are padded, as udm1's cursor pads them, with independent hashed values.
- ``film_width``, ``film_height``: integers in [1, 2^32 - 1], the film's crop size in pixels (plus twice
  the filter's border with the film's sample_border); needed in the vector variants, which tell each
  lane's pixel and sample from them and refuse, at a pass's first draw, a wavefront that is not the
  film's pixels times a divisor of sample_count. (Mitsuba does not tell a sampler the samples of a pass,
  which it sets apart from the render's when a render has more than 2^32 - 1 samples or the integrator
  a samples_per_pass.) Pixels are numbered in the crop window. Unused in the scalar variants.

Integers must be integers: a float, a bool or a string where an integer is meant is refused, as is a
non-string preset or randomize.

What each lane draws (the values are udm1's, bit for bit, as float32: the top 24 bits of the 64-bit
value):

- Vector variants (``llvm_*``, ``cuda_*``): Mitsuba traces a wavefront of W H spp lanes, lane
  ``k`` = pixel ``k // spp`` (row-major, ``y W + x``) and sample ``k % spp``; with several passes the
  sample index is ``pass * spp_per_pass + k % spp_per_pass``, spp_per_pass being the wavefront's size
  over W H. The stream is the pixel index ``y W + x`` combined with the render's seed
  (``render_seed * 2^32 + y W + x``); with "screen" it is ``(y << 32) | x`` and the render's seed is
  added to the sequence's. The index is the sample index.
  The Weyl presets (wr, wr-ao, we, wgr, wmmr, hwmmr, rd, golden, wopt, and their "+tent") are computed
  in Dr.Jit operations from udm1's integer contract (64-bit products, the documented hash, the
  permute's XOR and the Owen scrambling of udm1/seq.h, the tent): no table, any number of samples. The
  other presets (sobol-owen, pmj02, halton, the point sets, ...) are filled by the library at the
  pass's first draw, one call per dimension for the whole wavefront, into a table of D float32 values
  per lane (memory: 4 D bytes per sample; 128 x 128 x 256 spp at D = 32 is 537 MB).
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
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from . import _native
from .errors import check
from .sequence import Sequence, presets

GOLDEN_GAMMA = 0x9E3779B97F4A7C15
SEED_SALT = int.from_bytes(b"udm1SEED", "big")
M64 = (1 << 64) - 1
U32 = (1 << 32) - 1
WEYL_PRESETS = {"wr", "wr-ao", "we", "wgr", "wmmr", "hwmmr", "rd", "golden", "wopt"}
RANDOMIZE = ("default", "none", "shift", "owen", "permute", "screen")
TENT = "+tent"
DEFAULT_DIMENSIONS = 64
BUFFER = 16  # scalar variants: the draws of a sample made in one cursor fill
OWEN_LOW_SALT = 0x4F57454E00000000  # seq/scramble.h's udm1_owen64: the low half's salt ("OWEN")


def _mix64_int(z: int) -> int:
    """Stafford's Mix13 finalizer on a Python int (udm1's hash.h, part of the ABI)."""
    z &= M64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & M64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & M64
    return z ^ (z >> 31)


def _fail(message: str):
    raise ValueError(f"udm1 sampler: {message}")


def _preset_info(name: str):
    """The preset a name stands for ("NAME" or "NAME+tent"): its udm1.Preset; refused otherwise."""
    base = name[: -len(TENT)] if name.endswith(TENT) else name
    info = {p.name: p for p in presets()}.get(base)
    if info is None:
        names = ", ".join(p.name for p in presets())
        _fail(f"preset {name!r} is not a udm1 preset ({names}, each also as NAME{TENT})")
    return info


def _integer(props, name: str, default: int, lo: int, hi: int, why: str = "") -> int:
    """An integer property in [lo, hi], refused with one line naming it when it is anything else (`why`
    said after the range)."""
    if name not in props:
        return default
    v = props[name]
    if type(v) is float and float(v).is_integer() and abs(v) >= 2.0**63:
        _fail(f"{name} {v!r} is not in [{lo}, {hi}] (Mitsuba's integer properties hold at most 2^63 - 1: a larger "
              "integer arrives as a float)")
    if type(v) is not int:
        _fail(f"{name} {v!r} is not an integer (a {type(v).__name__})")
    if not lo <= v <= hi:
        _fail(f"{name} {v} is not in [{lo}, {hi}]" + (f" ({why})" if why else ""))
    return v


def _string(props, name: str, default: str) -> str:
    if name not in props:
        return default
    v = props[name]
    if type(v) is not str:
        _fail(f"{name} {v!r} is not a string (a {type(v).__name__})")
    return v


def _options(props) -> dict:
    """Every property of the sampler, checked (see the module's docstring)."""
    preset = _string(props, "preset", "wr")
    info = _preset_info(preset)
    randomize = _string(props, "randomize", "default")
    if randomize not in RANDOMIZE:
        _fail(f"randomize {randomize!r} is not one of {', '.join(RANDOMIZE)}")
    o = {"preset": preset, "point_set": info.point_set, "randomize": randomize,
         "weyl": (preset[: -len(TENT)] if preset.endswith(TENT) else preset) in WEYL_PRESETS,
         "tent": preset.endswith(TENT),
         "sample_count": _integer(props, "sample_count", 4, 1, U32),
         "seed": _integer(props, "seed", 0, 0, (1 << 63) - 1),
         "dimensions": _integer(props, "dimensions", min(DEFAULT_DIMENSIONS, info.max_dimensions), 1,
                                info.max_dimensions, f"preset {preset!r} has {info.max_dimensions}"),
         "film_width": _integer(props, "film_width", 0, 1, U32),
         "film_height": _integer(props, "film_height", 0, 1, U32)}
    return o


def _sequence(o: dict, spp: int, extra_seed: int = 0) -> Sequence:
    """The udm1 sequence of a sampler: D dimensions, point sets of spp points, fixed screen-space
    randomization at spp samples per pixel. The library's refusal (a randomization its kind does not
    have, a point count past the preset's limit) becomes one line naming the properties."""
    try:
        return Sequence(o["preset"], o["dimensions"], point_count=spp if o["point_set"] else 0,
                        seed=(o["seed"] + extra_seed) & M64,
                        randomize=True if o["randomize"] == "default" else o["randomize"],
                        screen_spp=spp if o["randomize"] == "screen" else 0)
    except ValueError as exc:
        refusal = str(exc)
    _fail(f"preset {o['preset']!r} with randomize {o['randomize']!r}, sample_count {spp} and dimensions "
          f"{o['dimensions']} is refused by udm1: {refusal}")


def _sample_count(spp) -> int:
    if type(spp) is not int or not 1 <= spp <= U32:
        _fail(f"sample_count {spp!r} is not an integer in [1, {U32}]")
    return spp


def _passes(o: dict, lanes: int, spp: int) -> int:
    """The samples per pixel of one pass of a wavefront of `lanes` lanes (vector variants), from the film's
    size; refused (one line) where the wavefront is not the film's pixels times a divisor of spp."""
    w, h = o["film_width"], o["film_height"]
    pixels = w * h
    if lanes == 0 or lanes % pixels or spp % (lanes // pixels):
        _fail(f"a wavefront of {lanes} samples is not film_width x film_height ({w} x {h}) times a divisor of "
              f"sample_count {spp} (film_width and film_height are the film's crop size, plus twice the filter's "
              "border with sample_border)")
    return lanes // pixels


def sampler_class():
    """The udm1 sampler class for Mitsuba's current variant."""
    import drjit as dr
    import mitsuba as mi

    jit = dr.is_jit_v(mi.Float)

    class Udm1Sampler(mi.Sampler):
        def __init__(self, props=None):
            props = mi.Properties() if props is None else props
            o = _options(props)
            # the base class reads sample_count and seed as 32-bit: it is given the checked sample count only
            # (the udm1 seed is this sampler's; Mitsuba's own base seed is not used)
            base = mi.Properties()
            base["sample_count"] = o["sample_count"]
            super().__init__(base)
            if o["randomize"] == "screen" and not jit:
                _fail("randomize 'screen' needs a vector variant (llvm_*, cuda_*): the scalar variants do not tell "
                      "a sampler its pixel's position")
            if jit and not (o["film_width"] and o["film_height"]):
                _fail("film_width and film_height are needed in the vector variants: the film's crop size, from "
                      "which the sampler tells each lane's pixel and sample")
            self._o = o
            self._spp = o["sample_count"]
            self._seq = _sequence(o, self._spp)
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
            spp = _sample_count(spp)
            if hasattr(self, "_o") and spp != self._spp:
                seq = _sequence(self._o, spp, self._seq_seed)  # (checked before anything changes)
                self._spp, self._seq = spp, seq
            super().set_sample_count(spp)

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
                seed = int(seed)
                if not 0 <= seed <= M64:
                    _fail(f"seed({seed}): a stream id is in [0, 2^64)")
                super().seed(seed & 0xFFFFFFFF, wavefront_size)  # (Mitsuba's own seeds are 32-bit)
                self._stream, self._index, self._started = seed, 0, False
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
                render_seed = int(seed) if isinstance(seed, int) else int(dr.slice(mi.UInt32(seed)))
                if not 0 <= render_seed <= U32:
                    _fail(f"seed({render_seed}): a render's seed is in [0, 2^32)")
                super().seed(seed, wavefront_size)
                self._pass = 0
                self._render_seed = render_seed
                if self._o["randomize"] == "screen" and render_seed != self._seq_seed:
                    self._seq = _sequence(self._o, self.sample_count(), render_seed)
                    self._seq_seed = render_seed
                # the state is made, and the wavefront checked, at the pass's first draw: after a render Mitsuba
                # seeds the sampler again with a wavefront of 1 to release its state, and draws nothing
                self._stale = True

            def advance(self):  # (not the base's: from Python it calls this override back)
                self._pass += 1
                self._stale = True

            def schedule_state(self):
                super().schedule_state()
                dr.schedule(self._dim)

            def _setup(self):
                """Per-lane state of a pass: stream ids and sample indices, and the draws made from them."""
                o = self._o
                lanes = self.wavefront_size()
                spp_pass = _passes(o, lanes, self.sample_count())
                lane = dr.arange(mi.UInt32, lanes)
                pixel = lane // spp_pass
                # per-render numbers enter the kernels as opaque parameters, not literals: one compilation
                # serves every render seed and pass
                sample = dr.opaque(mi.UInt64, self._pass * spp_pass) + mi.UInt64(lane % spp_pass)
                if o["randomize"] == "screen":
                    w = o["film_width"]
                    stream = (mi.UInt64(pixel // w) << 32) | mi.UInt64(pixel % w)
                else:
                    stream = (dr.opaque(mi.UInt64, self._render_seed) << 32) + mi.UInt64(pixel)
                self._draws = Draws(self._seq, o, stream, sample, self.sample_count())
                self._dim = dr.zeros(mi.UInt32, lanes)

            def next_1d(self, active=True):
                if self._stale:
                    self._stale = False
                    self._setup()
                j = self._dim
                self._dim = j + 1
                return self._draws.value(j)

            def next_2d(self, active=True):
                x = self.next_1d(active)
                return mi.Point2f(x, self.next_1d(active))

    Draws = draws_class() if jit else None
    return Udm1Sampler


def draws_class():
    """For a vector variant: the class that makes the values of a udm1 sequence for lanes of Dr.Jit
    arrays, Draws(seq, options, stream, sample, spp).value(j) the float32 values of dimension j (a
    UInt32 per lane) at each lane's (stream, sample); what the sampler draws."""
    import drjit as dr
    import mitsuba as mi

    def mix64(z):
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9
        z = (z ^ (z >> 27)) * 0x94D049BB133111EB
        return z ^ (z >> 31)

    def mulhi64(a, b):
        """The high 64 bits of the 128-bit product a b (Dr.Jit has no 64-bit mul_hi): four 32 x 32 products."""
        m = 0xFFFFFFFF
        a0, a1, b0, b1 = a & m, a >> 32, b & m, b >> 32
        lo, mid1, mid2 = a0 * b0, a1 * b0, a0 * b1
        cross = (lo >> 32) + (mid1 & m) + mid2  # at most 2^64 - 1
        return a1 * b1 + (mid1 >> 32) + (cross >> 32)

    def spread(v):
        v = v & 0xFFFFFFFF
        v = (v | (v << 16)) & 0x0000FFFF0000FFFF
        v = (v | (v << 8)) & 0x00FF00FF00FF00FF
        v = (v | (v << 4)) & 0x0F0F0F0F0F0F0F0F
        v = (v | (v << 2)) & 0x3333333333333333
        return (v | (v << 1)) & 0x5555555555555555

    def morton(stream):
        return spread(stream) | (spread(stream >> 32) << 1)

    def reverse32(x):
        x = ((x >> 1) & 0x55555555) | ((x & 0x55555555) << 1)
        x = ((x >> 2) & 0x33333333) | ((x & 0x33333333) << 2)
        x = ((x >> 4) & 0x0F0F0F0F) | ((x & 0x0F0F0F0F) << 4)
        x = ((x >> 8) & 0x00FF00FF) | ((x & 0x00FF00FF) << 8)
        return (x >> 16) | (x << 16)

    def owen_hash32(x, seed):
        x ^= x * 0x3D20ADEA
        x += seed
        x *= (seed >> 16) | 1
        x ^= x * 0x05526C56
        x ^= x * 0x53A22864
        return x

    def owen64(v, r):
        """udm1_owen64 (seq/scramble.h): the top 32 digits Owen-scrambled by hashing, keyed by r's low half;
        the low 32 a hash of the scrambled top and r's high half."""
        top = mi.UInt64(reverse32(owen_hash32(reverse32(mi.UInt32(v >> 32)), mi.UInt32(r & 0xFFFFFFFF))))
        low = mix64(((top << 32) | (r >> 32)) ^ OWEN_LOW_SALT) & 0xFFFFFFFF
        return (top << 32) | low

    def tent(x):
        """udm1_tent: 1 - |2x - 1| exactly on the 0.64 value (2x below 1/2, 2 - 2x above)."""
        top = mi.UInt64(0) - (x >> 63)
        return ((x ^ top) - top) << 1

    def owned(cls, values: np.ndarray):
        """A Dr.Jit array of numpy's values in Dr.Jit's own memory: an array made from numpy keeps numpy's
        alignment, which enters the kernels' code (and so their cache key): every new table would compile
        the render's kernels again."""
        x = cls(values) + dr.opaque(cls, 0)  # (exact: the values here are integers, or floats >= +0.0)
        dr.eval(x)
        return x

    class Draws:
        def __init__(self, seq: Sequence, o: dict, stream, sample, spp: int):
            self._d = dr.opaque(mi.UInt32, seq.d)  # (opaque: one compilation serves every D)
            mode = seq.randomization
            self._mode, self._tent, self._weyl = mode, o["tent"], o["weyl"]
            S = _mix64_int(seq.seed ^ SEED_SALT)
            self._S = dr.opaque(mi.UInt64, S)
            screen = mode == "screen"
            T = mix64(mix64(stream + GOLDEN_GAMMA) ^ self._S)  # udm1_stream_key(S, stream)
            self._key = T
            self._n = sample
            self._pkey = stream if screen else T  # padding hashes the stream key (in screen mode the stream)
            if self._weyl:
                plain = Sequence(o["preset"], seq.d, randomize=False)  # the base offsets o_j
                ahi, alo, base = [], [], []
                for j in range(seq.d):
                    a = seq.alpha(j)
                    ahi.append(a >> 64)
                    alo.append(a & M64)
                    c = plain.offset(j)
                    if screen:  # the fixed scheme's one shift u_j = mix(S + K_j)
                        c = (c + _mix64_int(S + _mix64_int(S + (j + 1) * GOLDEN_GAMMA))) & M64
                    base.append(c)
                self._tables = tuple(owned(mi.UInt64, np.array(t, dtype=np.uint64)) for t in (ahi, alo, base))
                self._idx = sample + morton(stream) * dr.opaque(mi.UInt64, spp) if screen else sample
            else:
                self._table_fill(seq, stream, sample)

        def _table_fill(self, seq, stream, sample):
            """The library's values of every lane for dimensions [0, D): D float32 columns, filled by
            udm1_seq_fill_points_f64 on every core (ctypes releases the GIL during the call)."""
            dr.eval(stream, sample)
            s_np = np.asarray(stream.numpy(), dtype=np.uint64)
            i_np = np.asarray(sample.numpy(), dtype=np.uint64)
            lanes, d = len(s_np), seq.d
            table = np.empty((d, lanes), dtype=np.float32)

            def fill(a, b):
                for j in range(d):  # a row of the table at a time: contiguous writes
                    v = seq.points_at(s_np[a:b], i_np[a:b], dims=range(j, j + 1))[:, 0]
                    # the float32 value is the top 24 bits: exact from the double's top 53
                    v *= 16777216.0
                    np.floor(v, out=v)
                    v *= 1.0 / 16777216.0
                    table[j, a:b] = v

            workers = max(1, min(os.cpu_count() or 1, lanes // 4096))
            bounds = np.linspace(0, lanes, workers + 1).astype(int)
            with ThreadPoolExecutor(workers) as pool:
                list(pool.map(fill, bounds[:-1], bounds[1:]))
            self._table = owned(mi.Float, table.ravel())
            self._lanes = dr.opaque(mi.UInt32, lanes)
            self._lane = dr.arange(mi.UInt32, lanes)

        def _weyl_raw(self, jj, kj):
            """Raw 64-bit value of Weyl dimension jj < D (per lane), its key K_j = kj, the sequence's
            randomization applied."""
            ahi, alo, base = (dr.gather(mi.UInt64, t, jj) for t in self._tables)
            mode = self._mode
            if mode in ("shift", "permute", "owen"):
                word = mix64(self._key + kj)  # udm1_shift(T, K_j)
            if mode == "shift":
                base = base + word
            raw = base + self._idx * ahi + mulhi64(self._idx, alo)
            if mode == "permute":
                raw = raw ^ word
            elif mode == "owen":
                raw = owen64(raw, word)
            return tent(raw) if self._tent else raw

        def value(self, j):
            """Dimension j (UInt32 per lane) of each lane's point, as float32."""
            inside = j < self._d
            jj = dr.minimum(j, self._d - 1)
            kj = mix64(self._S + (mi.UInt64(j) + 1) * GOLDEN_GAMMA)  # udm1_dim_key(S, j), inside or past D
            raw = mix64(mix64(self._pkey + kj) + (self._n + 1) * GOLDEN_GAMMA)  # udm1_pad
            if self._weyl:
                raw = dr.select(inside, self._weyl_raw(jj, kj), raw)
            value = mi.Float(mi.UInt32(raw >> 40)) * (1.0 / 16777216.0)
            if not self._weyl:
                table = dr.gather(mi.Float, self._table, jj * self._lanes + self._lane, inside)
                value = dr.select(inside, table, value)
            return value

    return Draws


_NOTED = []


def register(name: str = "udm1", native: bool | None = None):
    """Make Sampler "udm1" available for Mitsuba's current variant (mi.set_variant first).

    native=None (the default): the native plugin when it is built for the installed Mitsuba (``python -m
    udm1.mitsuba build``), its folder prepended to Mitsuba's file resolver, which finds plugins/udm1.so
    there, in every variant; else this module's Python sampler, registered under `name` for the current
    variant, with a one-line note on stderr (once per process). native=True: the native plugin or
    udm1.mitsuba_build.BuildError; native=False: the Python sampler. The native plugin's name is "udm1";
    a Python sampler registered under "udm1" in this process and variant shadows it.
    Returns the plugin's folder (native) or the Python sampler's class."""
    import mitsuba as mi

    from . import mitsuba_build

    folder = mitsuba_build.built() if native is not False else None
    if native and folder is None:
        raise mitsuba_build.BuildError(f"the native plugin is not built for Mitsuba {mi.__version__} (python -m "
                                       "udm1.mitsuba build)")
    if native and name != "udm1":
        raise mitsuba_build.BuildError(f"the native plugin is named 'udm1' (its file's name), not {name!r}")
    if folder is not None and name == "udm1":
        resolver = mi.file_resolver()
        if str(folder) not in [str(resolver[i]) for i in range(len(resolver))]:
            resolver.prepend(str(folder))
        return folder
    if native is None and not _NOTED:
        _NOTED.append(True)
        print(f"udm1.mitsuba: the native plugin is not built for Mitsuba {mi.__version__} (python -m udm1.mitsuba "
              "build): using the Python sampler", file=sys.stderr)
    cls = sampler_class()
    mi.register_sampler(name, lambda props: cls(props))
    return cls


def main(argv=None) -> int:
    """python -m udm1.mitsuba build [--out DIR] [-j N] [--verbose]: compile the native plugin."""
    import argparse

    from . import mitsuba_build

    ap = argparse.ArgumentParser(prog="python -m udm1.mitsuba",
                                 description="udm1's Mitsuba 3 sampler: build the native plugin")
    sub = ap.add_subparsers(dest="command", required=True)
    b = sub.add_parser("build", help="compile the native plugin against the installed Mitsuba")
    b.add_argument("--out", help="the folder that gets plugins/udm1.so (default: inside this package, "
                                 "udm1/_mitsuba/mitsuba-<version>)")
    b.add_argument("-j", "--jobs", type=int, default=2, help="parallel compile jobs (default 2)")
    b.add_argument("--test-variants", action="store_true", help="scalar_rgb and llvm_ad_rgb only (faster)")
    b.add_argument("--verbose", action="store_true", help="show the compiler's output")
    args = ap.parse_args(argv)
    try:
        folder = mitsuba_build.build(args.out, jobs=args.jobs, test_variants=args.test_variants, verbose=args.verbose)
    except mitsuba_build.BuildError as exc:
        print(f"udm1.mitsuba build: {exc}", file=sys.stderr)
        return 1
    print(f"built {folder / 'plugins' / 'udm1.so'} (udm1.mitsuba.register() uses it; mitsuba -a {folder} ...)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
