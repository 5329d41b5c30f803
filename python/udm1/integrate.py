"""Monte Carlo and quasi-Monte Carlo integrals over [0, 1)^d with any udm1 sampler,
summed exactly (udm1.exact_sum), so that the estimate of n samples is the same bit for
bit however the index range [0, n) is split: in chunks here, or over a Dask cluster
(udm1.distributed.integrate).

    est = udm1.integrate(lambda x: np.prod(x, axis=1), "wr", d=4, n=1 << 20, seed=1)
    est.value, est.stderr

To a tolerance instead of a sample count (see `integrate` and `ToleranceResult`):

    r = udm1.integrate(f, "wr", d=8, abs_tol=1e-6, transform="c1")
    r.estimate, r.error_bound, r.n_total, r.met
"""

from __future__ import annotations

import ctypes
import functools
import math
import threading
import time
from dataclasses import dataclass, field

import numpy as np

from ._convert import U32, U64, choice, flag, function, integer, real, real_array, text, u64
from ._native import lib
from .errors import UDM1Error, check
from .exact_sum import ExactSum, sqrt_fraction
from .sequence import Preset, Sequence, _randomize_code, presets

WHERE = "udm1.integrate"
_INVALID_ARGUMENT = 2


@dataclass(frozen=True)
class IntegralSpec:
    """What an integral is: the sampler, its dimensions, the total sample count n (point
    sets use K = n), the seed and randomization. Picklable: workers rebuild the sequence."""

    sampler: str
    d: int
    n: int
    seed: int = 0
    randomize: object = True
    stream: int = 0

    def __post_init__(self):  # every field through the converter: a spec that exists is a valid one
        _preset(text(self.sampler, "sampler", where=WHERE))
        object.__setattr__(self, "d", integer(self.d, "d", 1, U32, where=WHERE))
        object.__setattr__(self, "n", integer(self.n, "n", 1, U64, where=WHERE))
        object.__setattr__(self, "seed", u64(self.seed, "seed", where=WHERE))
        object.__setattr__(self, "randomize", _randomize(self.randomize))
        object.__setattr__(self, "stream", u64(self.stream, "stream", where=WHERE))

    def sequence(self) -> Sequence:
        info = _preset(self.sampler)
        k = self.n if info.point_set else 0
        return Sequence(self.sampler, self.d, point_count=k, seed=self.seed, randomize=self.randomize)


@dataclass(frozen=True)
class Integral:
    """An estimate: the exact sums of f and f^2 over sample indices [first, first + count) (sum_sq None
    where it was not kept: the tolerance rules' replicates, whose rule does not use it)."""

    spec: IntegralSpec
    first: int
    count: int
    sum: ExactSum
    sum_sq: ExactSum | None

    @property
    def value(self) -> float:
        """The mean of f over the samples: the exact sum divided by the count, rounded once."""
        return self.sum.mean(self.count)

    @property
    def stderr(self) -> float:
        """sqrt(sample variance / count): the standard error for independent samples (for
        low-discrepancy points an upper estimate only; use randomized replicates). From the exact sums
        of f and of f^2, in exact rational arithmetic, rounded once: finite and exact to the last bit at
        any finite magnitude of f (it is at most max |f|). NaN for fewer than 2 samples."""
        if self.sum_sq is None:
            raise ValueError("udm1.Integral: the sum of squares was not kept for this estimate (squares=False)")
        if self.count < 2:
            return float("nan")
        s, q, c = self.sum.fraction(), self.sum_sq.fraction(), self.count
        var = (q - s * s / c) / (c - 1)  # >= 0: exact
        return sqrt_fraction(var / c)

    def __add__(self, other: "Integral") -> "Integral":
        """Join two adjacent ranges of the same integral (exact)."""
        if not isinstance(other, Integral):
            return NotImplemented
        if other.spec != self.spec:
            raise ValueError("Integral: the two estimates are of different integrals")
        a, b = (self, other) if self.first <= other.first else (other, self)
        if a.first + a.count != b.first:
            raise ValueError(f"Integral: ranges [{a.first}, {a.first + a.count}) and "
                             f"[{b.first}, {b.first + b.count}) are not adjacent")
        sum_sq = None if a.sum_sq is None or b.sum_sq is None else a.sum_sq + b.sum_sq
        return Integral(self.spec, a.first, a.count + b.count, a.sum + b.sum, sum_sq)


def _preset(name: str) -> Preset:
    name = text(name, "sampler", where=WHERE)
    for p in _presets():
        if p.name == name.split("+")[0] or p.name == name:
            return p
    raise ValueError(f"udm1.integrate: unknown sampler '{name}' (udm1.presets() lists them)")


def _randomize(randomize):
    """randomize as Sequence takes it (True, False, None or a name), checked; numpy bools as bools."""
    _randomize_code(randomize)
    return bool(randomize) if isinstance(randomize, np.bool_) else randomize


def _chunk(chunk) -> int:
    return integer(chunk, "chunk", 1, U64, where=WHERE)


def _range(first, count) -> tuple[int, int]:
    return u64(first, "first", where=WHERE), u64(count, "count", where=WHERE)


def _spec(spec) -> "IntegralSpec":
    if not isinstance(spec, IntegralSpec):
        raise TypeError(f"udm1.integrate: spec must be an IntegralSpec, not {type(spec).__name__}")
    return spec


@functools.lru_cache(maxsize=1)
def _presets() -> tuple[Preset, ...]:
    return tuple(presets())  # the library's table does not change while it is loaded


def integrate_range(f, spec: IntegralSpec, first: int, count: int, chunk: int = 1 << 16,
                    squares: bool = True) -> Integral:
    """f over sample indices [first, first + count) of spec's sequence, in chunks of `chunk` points.
    f takes an (m, d) float64 array and returns m finite real values. squares=False: no sum of squares
    (sum_sq None, no stderr; what the tolerance rules need, at less cost)."""
    return replicate_ranges(f, [_spec(spec)], first, count, chunk, squares)[0]


def integrate(f, sampler: str, d: int, n: int | None = None, *, seed: int = 0, randomize=True, stream: int = 0,
              chunk: int = 1 << 16, abs_tol: float | None = None, rel_tol: float | None = None,
              n_max: int = 1 << 24, n_init: int = 1 << 8, replications: int = 16, confidence: float = 0.99,
              transform: str | None = None, criterion: str | None = None, strict: bool = True):
    """The integral of f over [0, 1)^d with `sampler`, in one process.

    With n: the estimate from samples [0, n) of stream `stream`, an `Integral` (udm1.distributed.integrate
    gives the same bit for bit from a cluster).

    With abs_tol and/or rel_tol: samples until the estimate is within max(abs_tol, rel_tol |I|) of
    the integral I, and returns a `ToleranceResult`. Two stopping rules (`criterion`; by default
    "lattice" for the sampler "lattice-seq", "replications" for every other):

    criterion="lattice" (sampler "lattice-seq", the embedded rank-1 lattice): one randomly shifted
    lattice, doubled from n_init points (a power of two) until the bound from its Fourier structure is
    within the tolerance: the points of each power of two n are a lattice, so the discrete Fourier
    transform of the values gives f's Fourier coefficients aliased mod the lattice, and the rule's error
    is the sum of those aliased onto the mean. The bound is FOURIER_FUDGE 2^-m times the sum of the
    transform's magnitudes at wavenumbers [2^(m-5), 2^(m-4)) (n = 2^m), the wavenumbers ordered at each
    doubling so that larger coefficients come first (Jimenez Rugama and Hickernell 2016, "Adaptive
    multidimensional integration based on rank-1 lattices", the rule of QMCPy's CubQMCLatticeG, with its
    constants). Assumption: f lies in their cone: its Fourier coefficients decay steadily, so that the
    ones aliased onto the mean are bounded by those measured. Then the bound holds for every shift, not
    at a confidence (`confidence` is not used; the result's is None); a spiky or discontinuous f can
    break the assumption. Periodize a non-periodic f (transform="baker", as CubQMCLatticeG does).

    criterion="replications": `replications` independent randomizations of the sampler (the streams
    0, 1, ... of one seed: independent random shifts for Kronecker sequences, independent scramblings
    for nets; n_init points each, doubled until the tolerance is met or n_max evaluations would be
    passed), and a Student-t interval over the replicates' estimates. Assumption: the replicates are independent
    and unbiased (true by construction) and their mean is close to normal (the t interval is then
    conservative for the sizes used here; heavy-tailed replicates, e.g. of a discontinuous integrand
    at small n, can make it optimistic). Each replicate is summed exactly, so the result does not
    depend on how the work was split. `transform` periodizes f first (TRANSFORMS: "tent" = "baker",
    applied by the library to a randomized sampler's points as the sampler NAME+tent; "c0", "c1",
    "c2"), which helps Kronecker and lattice rules on non-periodic integrands. If the
    tolerance is not met within n_max, raises ToleranceNotMet whose `.result` holds the partial
    estimate (met False); strict=False returns that result instead. The tolerance rules draw the
    streams they name, so `stream` must be 0 with a tolerance (vary `seed` instead).

    Every argument is checked before f is first called (udm1.UDM1Error, a ValueError, or TypeError,
    naming it), the tolerance rule's ones also with n: chunk, n, n_init, n_max and replications are
    integers (integral floats taken), chunk >= 1; abs_tol and rel_tol positive finite reals, confidence
    in [0.5, 1); transform and criterion names; seed and stream in [0, 2^64). f's values must be finite
    real numbers (not complex, bool or strings). Any finite magnitude works: the sums of f and f^2 are
    exact (Integral.stderr is finite and exact to its last bit), the replicates' statistics and the
    lattice's transform are taken at a power-of-two scale of the values when they are beyond 2^+-400 (an
    error bound past the double range is inf, and the tolerance is then not met)."""
    f = function(f, "f", where=WHERE)
    tolerance = abs_tol is not None or rel_tol is not None
    if tolerance and n is not None:
        raise ValueError("udm1.integrate: give n, or a tolerance (abs_tol, rel_tol), not both")
    stream = u64(stream, "stream", where=WHERE)
    rule = _tolerance_arguments(f, sampler, d, abs_tol, rel_tol, n_max, n_init, replications, confidence, transform,
                                criterion, seed, randomize, chunk, strict, tolerance)
    if tolerance:
        if stream != 0:
            raise ValueError(f"udm1.integrate: stream = {stream} with a tolerance: its rules draw streams 0 .. "
                             f"replications - 1 of the seed (vary seed instead)")
        return _integrate_to_tolerance(rule, None, None)
    if n is None:
        raise ValueError("udm1.integrate: give n (the sample count) or a tolerance (abs_tol, rel_tol)")
    spec = IntegralSpec(rule.sampler, rule.d, integer(n, "n", 1, U64, where=WHERE), rule.seed, rule.randomize, stream)
    spec.sequence()  # the library's checks (dimensions, randomization, point count) before f is called
    return integrate_range(rule.g, spec, 0, spec.n, rule.chunk)


def replicate_ranges(f, specs, first: int, count: int, chunk: int = 1 << 16, squares: bool = True) -> list[Integral]:
    """integrate_range of [first, first + count) for each spec. Specs that differ only in their stream
    (replicates) share one sequence and one call of f per chunk (f sees their points stacked): the same
    Integrals, bit for bit, at a fraction of the calls."""
    f = function(f, "f", where=WHERE)
    specs = [_spec(s) for s in specs]
    if not specs:
        raise ValueError("udm1.integrate: no specs")
    first, count = _range(first, count)
    chunk, squares = _chunk(chunk), flag(squares, "squares", where=WHERE)
    base = specs[0]
    if any((s.sampler, s.d, s.n, s.seed, s.randomize) != (base.sampler, base.d, base.n, base.seed, base.randomize)
           for s in specs):
        return [replicate_ranges(f, [s], first, count, chunk, squares)[0] for s in specs]
    if first + count > base.n:
        raise ValueError(f"udm1.integrate: range [{first}, {first + count}) is not inside [0, {base.n})")
    seq = base.sequence()
    sums = [(ExactSum(), ExactSum() if squares else None) for _ in specs]
    step = max(1, chunk // len(specs))
    for start in range(first, first + count, step):
        m = min(step, first + count - start)
        if len(specs) > 1:  # the replicates' points stacked, each written in place (every row: one fill each)
            x = np.empty((len(specs) * m, base.d))
            for r, s in enumerate(specs):
                seq.points(m, start, stream=s.stream, out=x[r * m:(r + 1) * m])
        else:
            x = seq.points(m, start, stream=base.stream)
        y = _checked(f, x, start, m, [s.stream for s in specs] if len(specs) > 1 else None)
        for r, (total, total_sq) in enumerate(sums):
            yr = y[r * m:(r + 1) * m]
            total.add(yr)
            if squares:
                total_sq.add_squares(yr)
    return [Integral(s, first, count, a, b) for s, (a, b) in zip(specs, sums)]


# ---- periodizing transforms ----

def _poly(c):
    return np.polynomial.polynomial.Polynomial(c)


# name: (phi, phi') with phi a map of [0, 1] onto itself; f(phi(x)) prod phi'(x) has f's integral
_C0 = _poly([0, 0, 3, -2])                    # 3x^2 - 2x^3, phi' = 6x(1 - x): C0 at the ends
_C1 = _poly([0, 0, 0, 10, -15, 6])            # phi' = 30 x^2 (1 - x)^2
_C2 = _poly([0, 0, 0, 0, 35, -84, 70, -20])   # phi' = 140 x^3 (1 - x)^3
TRANSFORMS = {
    "tent": (lambda x: 1 - np.abs(2 * x - 1), None),  # measure-preserving: no weight (Hickernell 2002)
    "baker": (lambda x: 1 - np.abs(2 * x - 1), None),  # the baker's transform: the tent, by its other name
    "c0": (_C0, _C0.deriv()),
    "c1": (_C1, _C1.deriv()),
    "c2": (_C2, _C2.deriv()),
}


def _transform(transform) -> str | None:
    return None if transform is None else choice(transform, "transform", TRANSFORMS, where=WHERE)


def _transformed(f, sampler: str, transform: str | None, randomize=True) -> tuple[str, object]:
    """(sampler, integrand) with the transform applied: the tent (baker's) of a randomized sampler by
    the library, on the points' 0.64 fixed point values (the sampler NAME+tent: one bit more than the
    double's and no pass over the points in Python), the others, and the tent of an unrandomized
    sampler, by periodized (the fixed point tent takes x = 1/2 to 0, not 1: a randomized value is never
    exactly 1/2)."""
    transform = _transform(transform)
    if transform in ("tent", "baker") and "+" not in sampler and _randomize_code(randomize) != 0:
        return sampler + "+tent", f
    return sampler, (periodized(f, transform) if transform else f)


def periodized(f, transform: str):
    """f composed with a periodizing transform of every coordinate, times its Jacobian: the same
    integral over [0, 1)^d, and a periodic integrand (tent: continuous; c0, c1, c2: with 0, 1 or 2
    derivatives vanishing at the ends too)."""
    phi, dphi = TRANSFORMS[choice(transform, "transform", TRANSFORMS, where=WHERE)]

    def g(x):
        y = _values(f(phi(x)))
        return y if dphi is None else y.reshape(-1) * np.prod(dphi(x), axis=1)

    return g


# ---- integration to a tolerance ----

class ToleranceNotMet(RuntimeError):
    """The tolerance was not reached within n_max evaluations; `.result` is the partial estimate."""

    def __init__(self, message: str, result: "ToleranceResult"):
        super().__init__(message)
        self.result = result


@dataclass
class ToleranceResult:
    """An integral to a tolerance: the estimate, the error bound at the confidence asked (the
    interval's half-width), points per replicate n and evaluations in all, the time, and whether the
    tolerance was met. history: (n, estimate, bound) after each doubling."""

    estimate: float
    error_bound: float
    n: int
    n_total: int
    replications: int
    seconds: float
    met: bool
    abs_tol: float | None
    rel_tol: float | None
    confidence: float | None  # None for the lattice criterion (a bound, not an interval)
    criterion: str = "replications"
    history: list = field(default_factory=list)

    def tolerance(self) -> float:
        return _tolerance(self.abs_tol, self.rel_tol, self.estimate)


def _t_quantile(q: float, dof: int) -> float:
    from scipy.stats import t
    return float(t.ppf(q, dof))


CRITERIA = ("replications", "lattice")
FOURIER_FUDGE = 5.0  # the bound's constant: FOURIER_FUDGE 2^-m times the measured coefficients (CubQMCLatticeG's)
FOURIER_LAG = 4      # the coefficients measured: wavenumbers [2^(m - LAG - 1), 2^(m - LAG))
FOURIER_BUFFER = 1 << 20  # the most points of a lattice criterion's buffers kept for the thread's next
                          # call (see _Workspace)


@functools.lru_cache(maxsize=32)
def _bit_reversal(m: int) -> np.ndarray:
    """k -> the bit reversal of k in m bits, for k < 2^m (an involution; read-only, cached)."""
    if m == 0:
        r = np.zeros(1, dtype=np.intp)
    else:  # the reversal of 2k is half that of k, plus the top bit for the odd ones
        half = _bit_reversal(m - 1)
        r = np.empty(1 << m, dtype=np.intp)
        r[0::2] = half
        r[1::2] = half + (1 << (m - 1))
    r.flags.writeable = False
    return r


def _rfft(y: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
    """The transform of real values at wavenumbers 0 .. n / 2 (the rest are their conjugates), into
    `out` where numpy takes it (2.0 and later: no fresh pages to fault in)."""
    if out is not None and _NUMPY_FFT_OUT:
        return np.fft.rfft(y, out=out)
    from scipy.fft import rfft

    return rfft(y)


_NUMPY_FFT_OUT = int(np.__version__.split(".")[0]) >= 2


class _Workspace:
    """A lattice criterion's C object (udm1/lattice_bound.h) and the arrays that feed it: the new values
    in lattice order and their transform. One per thread is kept between calls (up to FOURIER_BUFFER
    points), because first touching fresh pages costs as much as the arithmetic; a criterion takes it
    out of the cache while it runs, so two never share it."""

    __slots__ = ("handle", "capacity", "ordered", "t")
    _cache = threading.local()

    def __init__(self, capacity: int):
        handle = ctypes.c_void_p()
        check(lib.udm1_lattice_bound_create(FOURIER_LAG, FOURIER_FUDGE, capacity, ctypes.byref(handle)))
        self.handle = handle
        self._arrays(capacity)

    def _arrays(self, capacity: int) -> None:
        self.capacity = capacity
        self.ordered = np.empty(capacity // 2)        # the new values in lattice order
        self.t = np.empty(capacity // 4 + 1, dtype=complex)  # their transform

    def grow(self, capacity: int) -> None:
        """Room for `capacity` points: the C object grows itself, the arrays here are scratch."""
        if capacity > self.capacity:
            self._arrays(capacity)

    def __del__(self):
        handle, self.handle = getattr(self, "handle", None), None
        if handle is not None and lib is not None:
            lib.udm1_lattice_bound_destroy(handle)

    @classmethod
    def take(cls, capacity: int) -> "_Workspace":
        cached = getattr(cls._cache, "workspace", None)
        if cached is not None:
            cls._cache.workspace = None
            lib.udm1_lattice_bound_reset(cached.handle)
            cached.grow(capacity)
            return cached
        return cls(capacity)

    def give_back(self) -> None:
        if self.capacity <= FOURIER_BUFFER and lib.udm1_lattice_bound_points(self.handle) <= FOURIER_BUFFER:
            self._cache.workspace = self


class LatticeFourier:
    """The discrete Fourier transform of f over the embedded lattice's first n = 2^m points, kept as n
    doubles, the wavenumber order of its coefficients and the bound read from them (see integrate,
    criterion "lattice"): the library's udm1_lattice_bound (udm1/lattice_bound.h), fed the transform of
    each doubling's new values in lattice order (numpy's real FFT).

    Point i of the sequence is lattice point k = bitrev_m(i) of {k z / n}: the transform over k of the
    values, divided by n, is Y[l] = sum of f's Fourier coefficients over the wavenumbers h with
    h.z = l (mod n), each times a phase of the shift; Y[0] is the rule's mean. Doubling adds the odd
    lattice points, so class l of n splits into l and l + n of 2n; the order puts, within each such
    split, the larger coefficient first, level by level (the same rule as QMCPy's kappa map).

    `capacity` points are made room for to begin with, so that the doublings reuse memory rather than
    allocate (see _Workspace)."""

    def __init__(self, y: np.ndarray, capacity: int = 0):
        y = real_array(y, "y", where=WHERE).ravel()
        n = y.size
        self.m = n.bit_length() - 1
        if n != 1 << self.m or self.m <= FOURIER_LAG:
            raise ValueError(f"udm1.integrate: the lattice criterion needs a power of two above 2^{FOURIER_LAG} "
                             f"points, not {n}")
        capacity = min(integer(capacity, "capacity", 0, U64, where=WHERE), FOURIER_BUFFER)
        self._w = _Workspace.take(max(n, 1 << (capacity.bit_length() - 1) if capacity > 0 else 0))
        self._add(y)

    def _add(self, y: np.ndarray) -> None:
        n, w = y.size, self._w
        w.grow(2 * n)
        ordered = np.take(y, _bit_reversal(n.bit_length() - 1), out=w.ordered[:n], mode="clip")
        t = _rfft(ordered, w.t[:n // 2 + 1])
        check(lib.udm1_lattice_bound_add(w.handle, t.ctypes.data, n))

    def release(self) -> None:
        """Done: the C object goes back to this thread's cache for the next criterion (this object's
        state goes with it: it is unusable after)."""
        w, self._w = self._w, None
        if w is not None:
            w.give_back()

    @property
    def order(self) -> np.ndarray:
        """Position p -> the wavenumber class at p (0 first)."""
        out = np.empty(1 << self.m, dtype=np.uint64)
        check(lib.udm1_lattice_bound_order(self._w.handle, 0, out.size, out.ctypes.data))
        return out

    @property
    def y(self) -> np.ndarray:
        """Y[l] for l < n: the sum of f's coefficients aliased to class l."""
        out = np.empty(1 << self.m, dtype=complex)
        check(lib.udm1_lattice_bound_coefficients(self._w.handle, 0, out.size, out.ctypes.data))
        return out

    def double(self, y_new: np.ndarray) -> None:
        """Take the values of the next n points (sequence indices n .. 2n - 1)."""
        n = 1 << self.m
        y_new = real_array(y_new, "y_new", where=WHERE).ravel()
        if y_new.size != n:
            raise ValueError(f"udm1.integrate: doubling {n} points needs {n} new values, not {y_new.size}")
        self._add(y_new)
        self.m += 1

    def bound(self) -> float:
        out = ctypes.c_double()
        check(lib.udm1_lattice_bound_error(self._w.handle, ctypes.byref(out)))
        return out.value


def values_range(f, spec: IntegralSpec, first: int, count: int, chunk: int = 1 << 16,
                 seq: Sequence | None = None, copy: bool = True) -> tuple[np.ndarray, ExactSum]:
    """f at sample indices [first, first + count) of spec's sequence (or `seq`, that sequence already
    made), and their exact sum. The values are an array of their own (copy=False: maybe f's own array,
    for a caller that uses them before it calls f again)."""
    f, spec = function(f, "f", where=WHERE), _spec(spec)
    first, count = _range(first, count)
    chunk = _chunk(chunk)
    if first + count > spec.n:
        raise ValueError(f"udm1.integrate: range [{first}, {first + count}) is not inside [0, {spec.n})")
    seq = seq or spec.sequence()
    if count <= chunk:
        y = _checked(f, seq.points(count, first, stream=spec.stream), first) if count else np.zeros(0)
        if copy:
            y = y.copy()
    else:  # chunk by chunk into one array (each copied at once: f may hand back one buffer every time)
        y = np.empty(count)
        done = 0
        while done < count:  # every element written: chunk >= 1, the last chunk up to count
            m = min(chunk, count - done)
            y[done:done + m] = _checked(f, seq.points(m, first + done, stream=spec.stream), first + done)
            done += m
    return y, ExactSum().add(y)


def _values(y) -> np.ndarray:
    """An integrand's values through the package's converter: real numbers only (no complex values, bools,
    strings), as float64."""
    return real_array(y, "f(x)", where=WHERE)


def _checked(f, x: np.ndarray, start: int, rows: int | None = None, streams=None) -> np.ndarray:
    """f(x) as m finite values, x the points of samples start, start + 1, ... (`rows` of them per stream
    of `streams` stacked, when several), or one ValueError naming the sample, its stream and point."""
    y = _values(f(x))
    if y.shape not in ((x.shape[0],), (x.shape[0], 1)):
        raise ValueError(f"udm1.integrate: f returned shape {y.shape} for {x.shape[0]} points (want ({x.shape[0]},))")
    y = y.reshape(-1)
    with np.errstate(over="ignore", invalid="ignore"):
        if math.isfinite(float(np.add.reduce(y))):  # a NaN or an infinity makes the sum so (one pass)
            return y
    bad = np.flatnonzero(~np.isfinite(y))  # or the sum overflowed: then none is found
    if bad.size:
        k = int(bad[0])
        rows = rows or x.shape[0]
        which = f" of stream {streams[k // rows]}" if streams else ""
        raise ValueError(f"udm1.integrate: f is {float(y[k])!r} at sample {start + k % rows}{which} (point {x[k].tolist()})")
    return y


@dataclass(frozen=True)
class _Rule:
    """A tolerance rule's arguments, every one checked: the integrand (transformed), the sampler's name
    (with +tent where the library applies the tent), and the rest as integrate_to_tolerance takes them."""

    g: object
    sampler: str
    d: int
    abs_tol: float | None
    rel_tol: float | None
    n_max: int
    n_init: int
    replications: int
    confidence: float
    criterion: str
    seed: int
    randomize: object
    chunk: int
    strict: bool
    point_set: bool


def _tolerance(abs_tol, rel_tol, estimate: float) -> float:
    return max(abs_tol or 0.0, (rel_tol or 0.0) * abs(estimate))


def _positive(tol, name: str) -> float | None:
    if tol is None:
        return None
    v = real(tol, name, finite=False, where=WHERE)  # the kind first: bools, strings, complex refused
    if not (math.isfinite(v) and v > 0):
        raise UDM1Error(_INVALID_ARGUMENT, f"udm1.integrate: {name} must be a positive finite number, not {tol!r}")
    return v


def _tolerance_arguments(f, sampler, d, abs_tol, rel_tol, n_max, n_init, replications, confidence, transform,
                         criterion, seed, randomize, chunk, strict, tolerance: bool = True) -> _Rule:
    """Every argument of a tolerance rule checked, before anything runs (with tolerance=False: each one's
    kind and range only, for integrate with n, which does not use them)."""
    f = function(f, "f", where=WHERE)
    abs_tol, rel_tol = _positive(abs_tol, "abs_tol"), _positive(rel_tol, "rel_tol")
    if tolerance and abs_tol is None and rel_tol is None:
        raise ValueError("udm1.integrate: give abs_tol or rel_tol")
    confidence = real(confidence, "confidence", lo=0.5, hi=1.0, hi_open=True, where=WHERE)
    replications = integer(replications, "replications", 2, U32, where=WHERE)
    n_init = integer(n_init, "n_init", 2, U64, where=WHERE)
    n_max = integer(n_max, "n_max", 1, U64, where=WHERE)
    chunk, strict = _chunk(chunk), flag(strict, "strict", where=WHERE)
    info = _preset(sampler)
    d, seed, randomize = integer(d, "d", 1, U32, where=WHERE), u64(seed, "seed", where=WHERE), _randomize(randomize)
    lattice_seq = sampler.split("+")[0] == "lattice-seq"
    if criterion is None:
        criterion = "lattice" if lattice_seq else "replications"
    criterion = choice(criterion, "criterion", CRITERIA, where=WHERE)
    name, g = _transformed(f, sampler, transform, randomize)
    rule = _Rule(g, name, d, abs_tol, rel_tol, n_max, n_init, replications, confidence, criterion, seed, randomize,
                 chunk, strict, info.point_set)
    if not tolerance:
        return rule
    if criterion == "lattice":
        if not lattice_seq:
            raise ValueError(f"udm1.integrate: criterion 'lattice' needs the sampler 'lattice-seq' (a lattice at "
                             f"every power of two), not {sampler!r}")
        if n_init & (n_init - 1) or n_init <= 1 << FOURIER_LAG:
            raise ValueError(f"udm1.integrate: criterion 'lattice' needs n_init a power of two above "
                             f"{1 << FOURIER_LAG}, not {n_init}")
        if n_init > n_max:
            raise ValueError(f"udm1.integrate: n_max {n_max} is below n_init = {n_init}")
    elif n_init * replications > n_max:
        raise ValueError(f"udm1.integrate: n_max {n_max} is below the first round's n_init x replications = "
                         f"{n_init * replications}")
    # the library's checks (dimensions, randomization, point count) before f is first called
    IntegralSpec(name, d, n_init if info.point_set else n_max, seed, randomize, 0).sequence()
    return rule


def integrate_to_tolerance(f, sampler: str, d: int, *, abs_tol=None, rel_tol=None, n_max: int = 1 << 24,
                           n_init: int = 1 << 8, replications: int = 16, confidence: float = 0.99,
                           transform: str | None = None, criterion: str | None = None, seed: int = 0,
                           randomize=True, chunk: int = 1 << 16, strict: bool = True, ranges=None,
                           values=None) -> ToleranceResult:
    """udm1.integrate with a tolerance (see there). `ranges(f, specs, first, count)`, if given, computes
    the replicates' Integrals of [first, first + count), and `values(f, spec, first, count)` the values
    and their ExactSum of one range for the lattice criterion (udm1.distributed passes a cluster's)."""
    rule = _tolerance_arguments(f, sampler, d, abs_tol, rel_tol, n_max, n_init, replications, confidence, transform,
                                criterion, seed, randomize, chunk, strict)
    for name, fn in (("ranges", ranges), ("values", values)):
        if fn is not None:
            function(fn, name, where=WHERE)
    return _integrate_to_tolerance(rule, ranges, values)


def _scale_exponent(amax: float) -> int:
    """e such that values of magnitude up to amax, times 2^-e, stay well inside the double range in sums,
    squares and transforms: 0 (no scaling, the values as they are) for amax in [2^-400, 2^400], where
    their squares stay normal doubles; else amax's binary exponent (values below 1 then)."""
    if amax == 0 or 2.0 ** -400 <= amax <= 2.0 ** 400:
        return 0
    return math.frexp(amax)[1]


def _ldexp(x: float, e: int) -> float:
    """x 2^e: +-inf past the double range."""
    try:
        return math.ldexp(x, e)
    except OverflowError:
        return math.copysign(math.inf, x)


def _integrate_to_tolerance(rule: _Rule, ranges, values) -> ToleranceResult:
    t0 = time.perf_counter()
    if rule.criterion == "lattice":
        spec = IntegralSpec(rule.sampler, rule.d, rule.n_max, rule.seed, rule.randomize, 0)
        return _lattice_to_tolerance(rule.g, spec, rule.abs_tol, rule.rel_tol, rule.n_max, rule.n_init, rule.chunk,
                                     rule.strict, values, t0)
    replications, n_max = rule.replications, rule.n_max
    quantile = _t_quantile(0.5 + rule.confidence / 2, replications - 1)

    def specs(n_set):
        return [IntegralSpec(rule.sampler, rule.d, n_set, rule.seed, rule.randomize, r) for r in range(replications)]

    if ranges is None:
        def ranges(fn, sp, first, count):
            return replicate_ranges(fn, sp, first, count, rule.chunk, squares=False)  # the rule uses the means

    n, parts, history = rule.n_init, None, []
    while True:
        if rule.point_set:  # a point set of n points: a new set at each n
            parts = ranges(rule.g, specs(n), 0, n)
        else:  # an extensible sequence: the next [n / 2, n) joins the sums of [0, n / 2)
            sp = specs(n_max)
            if parts is None:
                parts = ranges(rule.g, sp, 0, n)
            else:
                more = ranges(rule.g, sp, n // 2, n - n // 2)
                parts = [a + b for a, b in zip(parts, more)]
        means = np.array([p.value for p in parts])
        e = _scale_exponent(float(np.max(np.abs(means))))  # a power of two: exact, and 0 at ordinary magnitudes
        scaled = np.ldexp(means, -e) if e else means
        estimate = _ldexp(float(np.mean(scaled)), e)
        bound = _ldexp(quantile * float(np.std(scaled, ddof=1)) / math.sqrt(replications), e)
        history.append((n, estimate, bound))
        met = bound <= _tolerance(rule.abs_tol, rule.rel_tol, estimate)
        if met or 2 * n * replications > n_max:
            break
        n *= 2
    result = ToleranceResult(estimate, bound, n, n * replications, replications, time.perf_counter() - t0, met,
                             rule.abs_tol, rule.rel_tol, rule.confidence, history=history)
    return _refuse(result, rule.strict, n_max, f"{n} points x {replications} replications")


def _refuse(result: ToleranceResult, strict: bool, n_max: int, where: str) -> ToleranceResult:
    if not result.met and strict:
        raise ToleranceNotMet(
            f"udm1.integrate: tolerance {result.tolerance():.3g} not met within n_max = {n_max} evaluations (error "
            f"bound {result.error_bound:.3g} at {where}; estimate {result.estimate!r}); the partial result is in "
            f".result (or pass strict=False)", result)
    return result


def _lattice_to_tolerance(g, spec: IntegralSpec, abs_tol, rel_tol, n_max: int, n: int, chunk: int, strict: bool,
                          values, t0: float) -> ToleranceResult:
    """The lattice criterion (see integrate): one shifted embedded lattice, doubled until its Fourier bound
    is within the tolerance. The estimate is the exact mean of every value (split-independent). The
    transform is taken of the values times 2^-e, e fixed by the first n values (0 at ordinary magnitudes,
    see _scale_exponent), and the bound scaled back: exact, as the bound is linear in the values."""
    if values is None:
        seq = spec.sequence()

        def values(fn, sp, first, count):  # each range's values used before the next call of f
            return values_range(fn, sp, first, count, chunk, seq, copy=False)

    y, total = values(g, spec, 0, n)
    e = _scale_exponent(float(np.max(np.abs(y)))) if y.size else 0
    fourier = LatticeFourier(np.ldexp(y, -e) if e else y, capacity=n_max)
    history = []
    try:
        while True:
            estimate, bound = total.mean(n), _ldexp(fourier.bound(), e)
            history.append((n, estimate, bound))
            met = bound <= _tolerance(abs_tol, rel_tol, estimate)
            if met or 2 * n > n_max:
                break
            y, more = values(g, spec, n, n)
            fourier.double(np.ldexp(y, -e) if e else y)
            total = total + more
            n *= 2
    finally:
        fourier.release()
    result = ToleranceResult(estimate, bound, n, n, 1, time.perf_counter() - t0, met, abs_tol, rel_tol, None,
                             criterion="lattice", history=history)
    return _refuse(result, strict, n_max, f"{n} lattice points")
