"""Statistics at any finite magnitude. The sum of squares behind Integral.stderr is exact (ExactSum.add_squares:
no square overflows past 1.3e154 or underflows below 1.5e-154), so stderr is exact rational arithmetic
rounded once, and scaling f by a power of two scales it exactly; the tolerance rules' statistics are
taken at a power-of-two scale of the values, so they too scale exactly; an exact sum past the double
range is +-inf, and its repr never raises. Before, f of size 1e200 failed ("inf is not finite": its
square overflowed), f of size 1e-200 had its variance underflow to 0 (a tolerance "met" with a bound of
0), and repr(ExactSum) raised OverflowError past 1.8e308."""

import math
import random
from fractions import Fraction

import numpy as np
import pytest

import udm1
from udm1.exact_sum import ExactSum

A = np.array([0.9, 0.6, 1.3])


def oscillatory(x):
    return np.cos(2 * np.pi * 0.2 + x @ A[:x.shape[1]])


def hard_values(rng, n):
    """Values over the whole double range: subnormals, the largest, cancelling pairs, signed zeros."""
    x = rng.standard_normal(n) * 10.0 ** rng.integers(-320, 308, n)
    extra = [5e-324, -5e-324, 2.2250738585072014e-308, 1.7976931348623157e308, -1.7976931348623157e308,
             0.0, -0.0, 1.0, 3e-320, 2.0**-537, 2.0**511, 1.3e154, 1.5e-154, 2.0**400, 2.0**-400, 2.0**401]
    return rng.permutation(np.concatenate([x, -x[: n // 4], extra]))


def exact_squares(x):
    return sum(Fraction(float(v)) ** 2 for v in x)


def test_sums_of_squares_are_exact_over_the_whole_double_range():
    rng = np.random.default_rng(3)
    for trial in range(4):
        x = hard_values(rng, 400)
        s = ExactSum().add_squares(x)
        assert s.fraction() == exact_squares(x) and s.count == x.size
    # the fast path (every |x| in [2^-400, 2^400]) and the banded one agree with the arithmetic too
    for scale in (1.0, 2.0**399, 2.0**-399, 2.0**600, 2.0**-600):
        x = rng.standard_normal(300) * scale
        assert ExactSum().add_squares(x).fraction() == exact_squares(x), scale


def test_sums_of_squares_do_not_depend_on_the_split():
    rng = np.random.default_rng(8)
    x = hard_values(rng, 2000)
    whole = ExactSum().add_squares(x)
    for trial in range(10):
        cuts = sorted(rng.choice(np.arange(1, x.size), size=int(rng.integers(1, 30)), replace=False))
        parts = [ExactSum().add_squares(p) for p in np.split(x, cuts)]
        random.Random(trial).shuffle(parts)
        total = ExactSum()
        for p in parts:
            total = total + p
        assert total == whole


def test_sums_past_the_double_range_are_infinite_and_printable():
    big = ExactSum().add([1e308, 1e308])
    assert big.value() == math.inf and repr(big) == "ExactSum(sum=inf, count=2)"
    assert big.mean() == 1e308 and big.mean(1) == math.inf
    assert big.fraction() == 2 * Fraction(1e308)
    assert ExactSum().add([-1.7e308, -1.7e308, 1e300]).value() == -math.inf
    assert ExactSum().add([1.7e308, 1.7e308, -1.7e308]).value() == 1.7e308  # back inside: exact, not inf
    squares = ExactSum().add_squares([1e200, 1e200])
    assert squares.value() == math.inf and "inf" in repr(squares)
    assert squares.fraction() == 2 * Fraction(1e200) ** 2
    assert ExactSum().add_squares([5e-324]).value() == 0.0 and ExactSum().add_squares([5e-324]).fraction() > 0


def is_rounded_sqrt(r: float, x: Fraction) -> bool:
    """r is sqrt(x) correctly rounded: the true root lies within half an ulp of r."""
    half = Fraction(math.ulp(r)) / 2
    return (Fraction(r) - half) ** 2 <= x <= (Fraction(r) + half) ** 2


def test_sqrt_fraction_is_correctly_rounded():
    from udm1.exact_sum import sqrt_fraction

    rng = np.random.default_rng(5)
    for _ in range(300):
        x = Fraction(int(rng.integers(1, 2**62)), int(rng.integers(1, 2**62)))
        x *= Fraction(2) ** int(rng.integers(-2000, 2000))
        r = sqrt_fraction(x)
        underflow, overflow = r == 0.0 and x < Fraction(2) ** -2148, r == math.inf and x > Fraction(2) ** 2046
        assert underflow or overflow or is_rounded_sqrt(r, x)
    assert sqrt_fraction(Fraction(4)) == 2.0 and sqrt_fraction(Fraction(0)) == 0.0
    assert sqrt_fraction(Fraction(1e308) ** 2 * 3) == math.sqrt(3) * 1e308


def variance_of_mean(y) -> Fraction:
    """sample variance / n of the values, in exact rational arithmetic."""
    n = len(y)
    s = sum(Fraction(float(v)) for v in y)
    q = sum(Fraction(float(v)) ** 2 for v in y)
    return (q - s * s / n) / (n - 1) / n


@pytest.mark.parametrize("k", [-1020, -700, -400, 0, 300, 700, 1000])
def test_stderr_is_exact_and_scales_with_f(k):
    """f times 2^k: the estimate and the standard error are 2^k times f's, bit for bit, and equal the
    definition computed with fractions (1e-307 .. 1e301 here)."""
    scale = 2.0 ** k

    def f(x):
        return oscillatory(x) * scale

    r = udm1.integrate(f, "wr", 3, n=500, seed=2, chunk=64)
    one = udm1.integrate(oscillatory, "wr", 3, n=500, seed=2)
    y = f(udm1.Sequence("wr", 3, seed=2).points(500))
    assert r.value == one.value * scale and r.stderr == one.stderr * scale
    assert is_rounded_sqrt(r.stderr, variance_of_mean(y)) and math.isfinite(r.stderr) and r.stderr > 0


def test_the_reviewers_magnitudes():
    # an integrand of size 1e200 failed with "inf is not finite"
    r = udm1.integrate(lambda x: 1e200 * np.cos(x).prod(axis=1), "wr", 2, n=1000)
    assert math.isfinite(r.stderr) and 1e196 < r.stderr < 1e199 and 1e199 < r.value < 1e200
    # the largest doubles: the sums pass the double range, the mean and stderr do not
    big = udm1.integrate(lambda x: np.where(x[:, 0] < 0.5, 1.7976931348623157e308, -1e308), "wr", 2, n=1001)
    assert math.isfinite(big.value) and math.isfinite(big.stderr) and big.stderr > 1e306
    y = np.where(udm1.Sequence("wr", 2).points(1001)[:, 0] < 0.5, 1.7976931348623157e308, -1e308)
    assert is_rounded_sqrt(big.stderr, variance_of_mean(y))


@pytest.mark.parametrize("k", [-900, -300, 600, 900])
def test_replications_rule_scales_with_f(k):
    """The tolerance rule on 2^k f with the tolerance 2^k tol: the same run, every estimate and bound 2^k
    times the original's, bit for bit (before: the replicates' spread underflowed to 0 at 2^-900 and
    the tolerance was 'met' at once; at 2^900 it overflowed to inf)."""
    scale = 2.0 ** k
    one = udm1.integrate(oscillatory, "wr", 3, abs_tol=1e-4, seed=4, n_init=64)
    r = udm1.integrate(lambda x: oscillatory(x) * scale, "wr", 3, abs_tol=1e-4 * scale, seed=4, n_init=64)
    assert r.met and r.n == one.n
    assert [(n, e, b) for n, e, b in r.history] == [(n, e * scale, b * scale) for n, e, b in one.history]


@pytest.mark.parametrize("k", [-900, -300, 600, 900, 1015])
def test_lattice_rule_scales_with_f(k):
    scale = 2.0 ** k
    one = udm1.integrate(oscillatory, "lattice-seq", 3, abs_tol=1e-7, seed=4, transform="baker")
    r = udm1.integrate(lambda x: oscillatory(x) * scale, "lattice-seq", 3, abs_tol=1e-7 * scale, seed=4,
                       transform="baker")
    assert r.met and r.n == one.n
    assert [(n, e, b) for n, e, b in r.history] == [(n, e * scale, b * scale) for n, e, b in one.history]


def test_a_bound_past_the_double_range_is_inf_and_not_met():
    # 4 replicates of 2 points of f in [-1.7e308, 1.7e308]: the 99.9 % half-width passes the double range
    # (with seed 1: 12.9 standard errors of 1.6e308), so the bound is inf (documented), not NaN or an error
    r = udm1.integrate(lambda x: 1.7e308 * (2 * x[:, 0] - 1), "pcg32", 1, abs_tol=1e300, n_init=2, replications=4,
                       n_max=8, seed=1, confidence=0.999, strict=False)
    assert r.history[0][2] == math.inf and r.error_bound == math.inf and not r.met
    assert math.isfinite(r.estimate)


def test_squares_can_be_left_out():
    """The tolerance rules use the replicates' means only: their Integrals keep no sum of squares (and so
    say, rather than give a standard error of nothing); the sums are the same."""
    from udm1.integrate import IntegralSpec, integrate_range

    spec = IntegralSpec("wr", 2, 1000, 1)
    with_sq, without = integrate_range(oscillatory, spec, 0, 1000), integrate_range(oscillatory, spec, 0, 1000,
                                                                                   squares=False)
    assert with_sq.sum == without.sum and without.sum_sq is None and with_sq.sum_sq.count == 1000
    with pytest.raises(ValueError, match="sum of squares was not kept"):
        without.stderr
    halves = integrate_range(oscillatory, spec, 0, 500, squares=False) + integrate_range(oscillatory, spec, 500, 500)
    assert halves.sum == with_sq.sum and halves.sum_sq is None  # a sum of squares of half the range is none
