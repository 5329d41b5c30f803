"""udm1's discrepancies equal scipy.stats.qmc.discrepancy (1e-12 relative),
and the paper's 2D sets have lower discrepancy than random points."""

import math
from fractions import Fraction

import numpy as np
import pytest
from scipy.stats import qmc

import udm1

METHODS = ["L2-star", "CD", "WD", "MD"]


def exact_squared(sample, method) -> Fraction:
    """The squared discrepancy in exact rational arithmetic (doubles are rationals)."""
    x = [[Fraction(v) for v in row] for row in sample]
    n, d = len(x), len(x[0])
    h = Fraction(1, 2)
    if method == "L2-star":
        c, f, k = Fraction(1, 3) ** d, lambda v: (1 - v * v) / 2, lambda a, b: 1 - max(a, b)
    elif method == "CD":
        c = Fraction(13, 12) ** d
        f = lambda v: 1 + h * abs(v - h) - h * (v - h) ** 2
        k = lambda a, b: 1 + h * abs(a - h) + h * abs(b - h) - h * abs(a - b)
    elif method == "WD":
        c, f = Fraction(4, 3) ** d, None
        k = lambda a, b: Fraction(3, 2) - abs(a - b) * (1 - abs(a - b))
    else:
        c = Fraction(19, 12) ** d
        f = lambda v: Fraction(5, 3) - abs(v - h) / 4 - (v - h) ** 2 / 4
        k = lambda a, b: Fraction(15, 8) - abs(a - h) / 4 - abs(b - h) / 4 - 3 * abs(a - b) / 4 + (a - b) ** 2 / 2
    single = -2 * c if f is None else -Fraction(2, n) * sum(math.prod(f(v) for v in r) for r in x)
    pairs = sum(math.prod(k(a, b) for a, b in zip(r, q)) for r in x for q in x)
    return c + single + pairs / n**2


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("d", [1, 2, 3, 5])
@pytest.mark.parametrize("n", [1, 7, 40])
def test_equals_scipy_and_exact(method, d, n):
    """The squared value within 1e-14 x the size of its terms ((19/12)^d) of the
    exact value; a difference from scipy beyond 1e-12 relative is scipy's own
    rounding error. (Both sum O(1) terms to an O(1/n) result: relative errors
    of ~1e-13 are the floor of double arithmetic here.)"""
    rng = np.random.default_rng(n * 10 + d)
    for sample in (rng.random((n, d)), udm1.Sequence("wr", d, seed=n).points(n)):
        ex2 = exact_squared(sample, method)
        ex = math.sqrt(ex2) if method == "L2-star" else float(ex2)
        ours = udm1.discrepancy(sample, method)
        theirs = qmc.discrepancy(sample, method=method)
        sq = (lambda v: v * v) if method == "L2-star" else (lambda v: v)
        assert abs(sq(ours) - float(ex2)) <= 1e-14 * (19 / 12) ** d, (method, d, n, ours, ex)
        assert abs(ours - theirs) <= 1e-12 * abs(ex) + abs(theirs - ex), (method, d, n, ours, theirs, ex)


@pytest.mark.parametrize("method", METHODS)
def test_close_to_scipy_at_larger_n(method):
    # scipy's plain sums lose about 1e-10 relative at n = 1000 (measured against exact
    # rational arithmetic: ours 1.4e-12, scipy 6e-10 at n = 500); agree to 1e-8 here
    sample = np.random.default_rng(9).random((1000, 3))
    assert udm1.discrepancy(sample, method) == pytest.approx(qmc.discrepancy(sample, method=method), rel=1e-8)


def test_random_expectation_matches_scipy_average():
    rng = np.random.default_rng(5)
    for method in METHODS:
        vals = [qmc.discrepancy(rng.random((50, 2)), method=method) for _ in range(400)]
        vals = np.square(vals) if method == "L2-star" else np.array(vals)
        expect = udm1.discrepancy_random(50, 2, method)
        expect = expect**2 if method == "L2-star" else expect
        assert abs(vals.mean() - expect) < 5 * vals.std() / np.sqrt(len(vals))


TWO_D = [("wr-ao", {}), ("we", {}), ("wgr", {}), ("wr", {}), ("rd", {}), ("episwr", {"point_count": None})]


@pytest.mark.parametrize("name,extra", TWO_D)
@pytest.mark.parametrize("n", [64, 256, 1024])
def test_2d_sets_beat_random(name, extra, n):
    kw = {"point_count": n} if "point_count" in extra else {}
    rng = np.random.default_rng(n)
    for method in METHODS:
        random_avg = np.mean([qmc.discrepancy(rng.random((n, 2)), method=method) for _ in range(8)])
        for seed in range(4):  # randomly shifted sets, several seeds: each must beat random
            pts = udm1.Sequence(name, 2, seed=seed, **kw).points(n)
            ours = qmc.discrepancy(pts, method=method)
            assert ours < random_avg, (name, n, method, seed, ours, random_avg)
            assert ours < udm1.discrepancy_random(n, 2, method)
