"""Monte Carlo and quasi-Monte Carlo integrals over [0, 1)^d with any udm1 sampler,
summed exactly (udm1.exact_sum), so that the estimate of n samples is the same bit for
bit however the index range [0, n) is split: in chunks here, or over a Dask cluster
(udm1.distributed.integrate).

    est = udm1.integrate(lambda x: np.prod(x, axis=1), "wr", d=4, n=1 << 20, seed=1)
    est.value, est.stderr
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._convert import integer, u32, u64
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
    for p in presets():
        if p.name == name.split("+")[0] or p.name == name:
            return p
    raise ValueError(f"udm1.integrate: unknown sampler '{name}' (udm1.presets() lists them)")


def integrate_range(f, spec: IntegralSpec, first: int, count: int, chunk: int = 1 << 16) -> Integral:
    """f over sample indices [first, first + count) of spec's sequence, in chunks of `chunk` points.
    f takes an (m, d) float64 array and returns m finite values."""
    if not (0 <= first and 0 <= count and first + count <= spec.n):
        raise ValueError(f"udm1.integrate: range [{first}, {first + count}) is not inside [0, {spec.n})")
    seq = spec.sequence()
    total, total_sq = ExactSum(), ExactSum()
    for start in range(first, first + count, chunk):
        m = min(chunk, first + count - start)
        x = seq.points(m, start, stream=spec.stream)
        y = np.asarray(f(x), dtype=np.float64)
        if y.shape not in ((m,), (m, 1)):
            raise ValueError(f"udm1.integrate: f returned shape {y.shape} for {m} points (want ({m},))")
        y = y.reshape(m)
        bad = np.flatnonzero(~np.isfinite(y))
        if bad.size:
            k = int(bad[0])
            raise ValueError(f"udm1.integrate: f is {y[k]!r} at sample {start + k} (point {x[k].tolist()})")
        total.add(y)
        total_sq.add(y * y)
    return Integral(spec, first, count, total, total_sq)


def integrate(f, sampler: str, d: int, n: int, *, seed: int = 0, randomize=True, stream: int = 0,
              chunk: int = 1 << 16) -> Integral:
    """The estimate of the integral of f over [0, 1)^d from samples [0, n) of `sampler`, in one
    process. udm1.distributed.integrate gives the same Integral bit for bit from a cluster."""
    n = integer(n, "n", 1)
    spec = IntegralSpec(str(sampler), u32(d, "d"), n, u64(seed, "seed"), randomize, u64(stream, "stream"))
    _preset(spec.sampler)
    return integrate_range(f, spec, 0, spec.n, chunk)
