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

from ._convert import integer, u32, u64
from ._native import lib
from .errors import check
from .exact_sum import ExactSum
from .sequence import Preset, Sequence, presets


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

    def sequence(self) -> Sequence:
        info = _preset(self.sampler)
        k = self.n if info.point_set else 0
        return Sequence(self.sampler, self.d, point_count=k, seed=self.seed, randomize=self.randomize)


@dataclass(frozen=True)
class Integral:
    """An estimate: the exact sums of f and f^2 over sample indices [first, first + count)."""

    spec: IntegralSpec
    first: int
    count: int
    sum: ExactSum
    sum_sq: ExactSum

    @property
    def value(self) -> float:
        """The mean of f over the samples: the exact sum divided by the count, rounded once."""
        return self.sum.mean(self.count)

    @property
    def stderr(self) -> float:
        """sqrt(sample variance / count): the standard error for independent samples (for
        low-discrepancy points an upper estimate only; use randomized replicates)."""
        if self.count < 2:
            return float("nan")
        from fractions import Fraction

        s, q, c = self.sum.fraction(), self.sum_sq.fraction(), self.count
        var = (q - s * s / c) / (c - 1)
        return float(max(var, Fraction(0)) / c) ** 0.5

    def __add__(self, other: "Integral") -> "Integral":
        """Join two adjacent ranges of the same integral (exact)."""
        if other.spec != self.spec:
            raise ValueError("Integral: the two estimates are of different integrals")
        a, b = (self, other) if self.first <= other.first else (other, self)
        if a.first + a.count != b.first:
            raise ValueError(f"Integral: ranges [{a.first}, {a.first + a.count}) and "
                             f"[{b.first}, {b.first + b.count}) are not adjacent")
        return Integral(self.spec, a.first, a.count + b.count, a.sum + b.sum, a.sum_sq + b.sum_sq)


def _preset(name: str) -> Preset:
    for p in _presets():
        if p.name == name.split("+")[0] or p.name == name:
            return p
    raise ValueError(f"udm1.integrate: unknown sampler '{name}' (udm1.presets() lists them)")


@functools.lru_cache(maxsize=1)
def _presets() -> tuple[Preset, ...]:
    return tuple(presets())  # the library's table does not change while it is loaded


def integrate_range(f, spec: IntegralSpec, first: int, count: int, chunk: int = 1 << 16) -> Integral:
    """f over sample indices [first, first + count) of spec's sequence, in chunks of `chunk` points.
    f takes an (m, d) float64 array and returns m finite values."""
    return replicate_ranges(f, [spec], first, count, chunk)[0]


def integrate(f, sampler: str, d: int, n: int | None = None, *, seed: int = 0, randomize=True, stream: int = 0,
              chunk: int = 1 << 16, abs_tol: float | None = None, rel_tol: float | None = None,
              n_max: int = 1 << 24, n_init: int = 1 << 8, replications: int = 16, confidence: float = 0.99,
              transform: str | None = None, criterion: str | None = None, strict: bool = True):
    """The integral of f over [0, 1)^d with `sampler`, in one process.

    With n: the estimate from samples [0, n), an `Integral` (udm1.distributed.integrate gives the same
    bit for bit from a cluster).

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
    estimate (met False); strict=False returns that result instead."""
    if abs_tol is not None or rel_tol is not None:
        if n is not None:
            raise ValueError("udm1.integrate: give n, or a tolerance (abs_tol, rel_tol), not both")
        return integrate_to_tolerance(f, sampler, d, abs_tol=abs_tol, rel_tol=rel_tol, n_max=n_max, n_init=n_init,
                                      replications=replications, confidence=confidence, transform=transform,
                                      criterion=criterion, seed=seed, randomize=randomize, chunk=chunk,
                                      strict=strict)
    if n is None:
        raise ValueError("udm1.integrate: give n (the sample count) or a tolerance (abs_tol, rel_tol)")
    n = integer(n, "n", 1)
    sampler, g = _transformed(f, str(sampler), transform, randomize)
    spec = IntegralSpec(sampler, u32(d, "d"), n, u64(seed, "seed"), randomize, u64(stream, "stream"))
    _preset(spec.sampler)
    return integrate_range(g, spec, 0, spec.n, chunk)


def replicate_ranges(f, specs, first: int, count: int, chunk: int = 1 << 16) -> list[Integral]:
    """integrate_range of [first, first + count) for each spec. Specs that differ only in their stream
    (replicates) share one sequence and one call of f per chunk (f sees their points stacked): the same
    Integrals, bit for bit, at a fraction of the calls."""
    base = specs[0]
    if any((s.sampler, s.d, s.n, s.seed, s.randomize) != (base.sampler, base.d, base.n, base.seed, base.randomize)
           for s in specs):
        return [replicate_ranges(f, [s], first, count, chunk)[0] for s in specs]
    if not (0 <= first and 0 <= count and first + count <= base.n):
        raise ValueError(f"udm1.integrate: range [{first}, {first + count}) is not inside [0, {base.n})")
    seq = base.sequence()
    sums = [(ExactSum(), ExactSum()) for _ in specs]
    step = max(1, chunk // len(specs))
    for start in range(first, first + count, step):
        m = min(step, first + count - start)
        if len(specs) > 1:  # the replicates' points stacked, each written in place
            x = np.empty((len(specs) * m, base.d))
            for r, s in enumerate(specs):
                seq.points(m, start, stream=s.stream, out=x[r * m:(r + 1) * m])
        else:
            x = seq.points(m, start, stream=base.stream)
        y = _checked(f, x, start, m, [s.stream for s in specs] if len(specs) > 1 else None)
        for r, (total, total_sq) in enumerate(sums):
            yr = y[r * m:(r + 1) * m]
            total.add(yr)
            total_sq.add(yr * yr)
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


def _transformed(f, sampler: str, transform: str | None, randomize=True) -> tuple[str, object]:
    """(sampler, integrand) with the transform applied: the tent (baker's) of a randomized sampler by
    the library, on the points' 0.64 fixed point values (the sampler NAME+tent: one bit more than the
    double's and no pass over the points in Python), the others, and the tent of an unrandomized
    sampler, by periodized (the fixed point tent takes x = 1/2 to 0, not 1: a randomized value is never
    exactly 1/2)."""
    if transform in ("tent", "baker") and "+" not in sampler and randomize not in (False, None, "none"):
        return sampler + "+tent", f
    return sampler, (periodized(f, transform) if transform else f)


def periodized(f, transform: str):
    """f composed with a periodizing transform of every coordinate, times its Jacobian: the same
    integral over [0, 1)^d, and a periodic integrand (tent: continuous; c0, c1, c2: with 0, 1 or 2
    derivatives vanishing at the ends too)."""
    if transform not in TRANSFORMS:
        raise ValueError(f"udm1.integrate: transform {transform!r} is not one of {', '.join(TRANSFORMS)}")
    phi, dphi = TRANSFORMS[transform]

    def g(x):
        y = np.asarray(f(phi(x)), dtype=np.float64)
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


def _tolerance(abs_tol, rel_tol, estimate: float) -> float:
    return max(abs_tol or 0.0, (rel_tol or 0.0) * abs(estimate))


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
        n = y.size
        self.m = n.bit_length() - 1
        if n != 1 << self.m or self.m <= FOURIER_LAG:
            raise ValueError(f"udm1.integrate: the lattice criterion needs a power of two above 2^{FOURIER_LAG} "
                             f"points, not {n}")
        capacity = min(int(capacity), FOURIER_BUFFER)
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
    seq = seq or spec.sequence()
    if count <= chunk:
        y = _checked(f, seq.points(count, first, stream=spec.stream), first) if count else np.empty(0)
        if copy:
            y = y.copy()
    else:  # chunk by chunk into one array (each copied at once: f may hand back one buffer every time)
        y = np.empty(count)
        for start in range(first, first + count, chunk):
            m = min(chunk, first + count - start)
            y[start - first:start - first + m] = _checked(f, seq.points(m, start, stream=spec.stream), start)
    return y, ExactSum().add(y)


def _checked(f, x: np.ndarray, start: int, rows: int | None = None, streams=None) -> np.ndarray:
    """f(x) as m finite values, x the points of samples start, start + 1, ... (`rows` of them per stream
    of `streams` stacked, when several), or one ValueError naming the sample, its stream and point."""
    y = np.asarray(f(x), dtype=np.float64)
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


def integrate_to_tolerance(f, sampler: str, d: int, *, abs_tol=None, rel_tol=None, n_max: int = 1 << 24,
                           n_init: int = 1 << 8, replications: int = 16, confidence: float = 0.99,
                           transform: str | None = None, criterion: str | None = None, seed: int = 0,
                           randomize=True, chunk: int = 1 << 16, strict: bool = True, ranges=None,
                           values=None) -> ToleranceResult:
    """udm1.integrate with a tolerance (see there). `ranges(f, specs, first, count)`, if given, computes
    the replicates' Integrals of [first, first + count), and `values(f, spec, first, count)` the values
    and their ExactSum of one range for the lattice criterion (udm1.distributed passes a cluster's)."""
    t0 = time.perf_counter()
    for name, tol in (("abs_tol", abs_tol), ("rel_tol", rel_tol)):
        if tol is not None and not (isinstance(tol, (int, float)) and math.isfinite(tol) and tol > 0):
            raise ValueError(f"udm1.integrate: {name} must be a positive finite number, not {tol!r}")
    if abs_tol is None and rel_tol is None:
        raise ValueError("udm1.integrate: give abs_tol or rel_tol")
    if not (isinstance(confidence, float) and 0.5 <= confidence < 1):
        raise ValueError(f"udm1.integrate: confidence must be in [0.5, 1), not {confidence!r}")
    replications = integer(replications, "replications", 2)
    n_init = integer(n_init, "n_init", 2)
    n_max = integer(n_max, "n_max", 1)
    info = _preset(str(sampler))
    lattice_seq = str(sampler).split("+")[0] == "lattice-seq"
    if criterion is None:
        criterion = "lattice" if lattice_seq else "replications"
    if criterion not in CRITERIA:
        raise ValueError(f"udm1.integrate: criterion {criterion!r} is not one of {', '.join(CRITERIA)}")
    d = u32(d, "d")
    spec_name = str(sampler)
    sampler, g = _transformed(f, spec_name, transform, randomize)
    seed = u64(seed, "seed")
    if criterion == "lattice":
        if not lattice_seq:
            raise ValueError(f"udm1.integrate: criterion 'lattice' needs the sampler 'lattice-seq' (a lattice at "
                             f"every power of two), not {spec_name!r}")
        if n_init & (n_init - 1) or n_init <= 1 << FOURIER_LAG:
            raise ValueError(f"udm1.integrate: criterion 'lattice' needs n_init a power of two above "
                             f"{1 << FOURIER_LAG}, not {n_init}")
        if n_init > n_max:
            raise ValueError(f"udm1.integrate: n_max {n_max} is below n_init = {n_init}")
        return _lattice_to_tolerance(g, IntegralSpec(str(sampler), d, n_max, seed, randomize, 0), abs_tol, rel_tol,
                                     n_max, n_init, chunk, strict, values, t0)
    if n_init * replications > n_max:
        raise ValueError(f"udm1.integrate: n_max {n_max} is below the first round's n_init x replications = "
                         f"{n_init * replications}")
    quantile = _t_quantile(0.5 + confidence / 2, replications - 1)

    def specs(n_set):
        return [IntegralSpec(str(sampler), d, n_set, seed, randomize, r) for r in range(replications)]

    if ranges is None:
        def ranges(fn, sp, first, count):
            return replicate_ranges(fn, sp, first, count, chunk)

    n, parts, history = n_init, None, []
    while True:
        if info.point_set:  # a point set of n points: a new set at each n
            parts = ranges(g, specs(n), 0, n)
        else:  # an extensible sequence: the next [n / 2, n) joins the sums of [0, n / 2)
            sp = specs(n_max)
            if parts is None:
                parts = ranges(g, sp, 0, n)
            else:
                more = ranges(g, sp, n // 2, n - n // 2)
                parts = [a + b for a, b in zip(parts, more)]
        means = np.array([p.value for p in parts])
        estimate = float(np.mean(means))
        bound = quantile * float(np.std(means, ddof=1)) / math.sqrt(replications)
        history.append((n, estimate, bound))
        met = bound <= _tolerance(abs_tol, rel_tol, estimate)
        if met or 2 * n * replications > n_max:
            break
        n *= 2
    result = ToleranceResult(estimate, bound, n, n * replications, replications, time.perf_counter() - t0, met,
                             abs_tol, rel_tol, confidence, history=history)
    return _refuse(result, strict, n_max, f"{n} points x {replications} replications")


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
    is within the tolerance. The estimate is the exact mean of every value (split-independent)."""
    if values is None:
        seq = spec.sequence()

        def values(fn, sp, first, count):  # each range's values used before the next call of f
            return values_range(fn, sp, first, count, chunk, seq, copy=False)

    y, total = values(g, spec, 0, n)
    fourier = LatticeFourier(y, capacity=n_max)
    history = []
    try:
        while True:
            estimate, bound = total.mean(n), fourier.bound()
            history.append((n, estimate, bound))
            met = bound <= _tolerance(abs_tol, rel_tol, estimate)
            if met or 2 * n > n_max:
                break
            y, more = values(g, spec, n, n)
            fourier.double(y)
            total = total + more
            n *= 2
    finally:
        fourier.release()
    result = ToleranceResult(estimate, bound, n, n, 1, time.perf_counter() - t0, met, abs_tol, rel_tol, None,
                             criterion="lattice", history=history)
    return _refuse(result, strict, n_max, f"{n} lattice points")
