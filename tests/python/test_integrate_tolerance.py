"""udm1.integrate to a tolerance: randomized replications with a Student-t interval.

- Coverage: over 300 seeds, the returned interval [estimate - bound, estimate + bound] holds the exact
  integral of closed-form integrands at about the confidence asked (99 %; measured 294-299 of 300 with
  the default 16 replicates, 288 for wr with 8: fewer replicates estimate the spread worse, and stopping
  at the first small estimate favours the runs that underestimated it). The test asks for at least
  285 covers of 300: with a true coverage of 99 % the chance of fewer is below 1e-6 (binomial), while a
  coverage of 95 % or less fails it about half the time or more: it catches an interval that is too
  narrow (a wrong quantile, the standard deviation instead of the standard error, optional stopping
  going unchecked), not chance.
- A tolerance not met within n_max is refused with one message, the partial estimate in the error.
- The periodizing transforms keep the integral and make the integrand periodic.
- Exact sums: the result does not depend on the chunk size.
- Bad arguments: one ValueError naming the argument.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import udm1

A = np.array([0.9, 0.6, 1.3])


def oscillatory(x):  # Genz's oscillatory family, d = 3
    return np.cos(2 * np.pi * 0.2 + x @ A)


OSC_EXACT = (np.exp(1j * 2 * np.pi * 0.2) * np.prod((np.exp(1j * A) - 1) / (1j * A))).real


def product_peak(x):  # Genz's product peak, d = 2: prod 1 / (c^-2 + (x - w)^2)
    c, w = np.array([2.0, 3.0]), np.array([0.3, 0.6])
    return np.prod(1 / (c ** -2.0 + (x - w) ** 2), axis=1)


PEAK_EXACT = math.prod(c * (math.atan(c * (1 - w)) + math.atan(c * w)) for c, w in ((2.0, 0.3), (3.0, 0.6)))


@pytest.mark.release_only("a coverage check over 300 seeds; the other tests of this file run its code under the sanitizers")
@pytest.mark.parametrize("sampler,f,d,exact,tol", [
    ("wr", oscillatory, 3, OSC_EXACT, 2e-4),
    ("sobol-owen", oscillatory, 3, OSC_EXACT, 2e-4),
    ("rd", product_peak, 2, PEAK_EXACT, 1e-3),
])
def test_interval_covers_the_integral(sampler, f, d, exact, tol):
    covers, met = 0, 0
    for seed in range(300):
        r = udm1.integrate(f, sampler, d, abs_tol=tol, seed=seed, n_init=64, confidence=0.99)  # 16 replicates
        met += r.met
        covers += abs(r.estimate - exact) <= r.error_bound
        assert r.error_bound <= tol and r.n_total == r.n * 16
    assert met == 300
    assert covers >= 285, f"{sampler}: the 99 % interval held the integral in {covers} of 300 runs"


def test_tolerance_not_met_is_refused_with_the_partial_estimate():
    with pytest.raises(udm1.ToleranceNotMet, match=r"not met within n_max = 8192 evaluations") as e:
        udm1.integrate(oscillatory, "wr", 3, abs_tol=1e-13, n_max=8192, n_init=256, replications=8)
    r = e.value.result
    assert not r.met and r.n_total <= 8192 and r.error_bound > 1e-13
    assert abs(r.estimate - OSC_EXACT) < 1e-3  # the estimate is there, and a good one
    r2 = udm1.integrate(oscillatory, "wr", 3, abs_tol=1e-13, n_max=8192, n_init=256, replications=8, strict=False)
    assert not r2.met and r2.estimate == r.estimate


def test_rel_tol_and_history():
    r = udm1.integrate(product_peak, "sobol-owen", 2, rel_tol=1e-4, seed=3)
    assert r.met and r.error_bound <= 1e-4 * abs(r.estimate)
    ns = [h[0] for h in r.history]
    assert ns == [256 * 2 ** k for k in range(len(ns))] and ns[-1] == r.n


@pytest.mark.parametrize("name", sorted(udm1.TRANSFORMS))
def test_transforms_keep_the_integral_and_periodize(name):
    from udm1.integrate import periodized

    def f(x):
        return np.exp(x @ np.array([1.0, 0.5]))

    exact = (math.e - 1) * (math.exp(0.5) - 1) / 0.5
    est = udm1.integrate(f, "sobol-owen", 2, n=1 << 16, seed=1, transform=name).value
    assert abs(est - exact) < 2e-3, (name, est, exact)
    g = periodized(f, name)
    edge = g(np.array([[0.0, 0.3], [1.0, 0.3], [0.3, 0.0], [0.3, 1.0]]))
    assert edge[0] == pytest.approx(edge[1], abs=1e-12) and edge[2] == pytest.approx(edge[3], abs=1e-12)


@pytest.mark.release_only("a long run at two chunk sizes; test_integrate_inputs.py runs the chunking under the sanitizers")
def test_result_does_not_depend_on_the_chunks():
    a = udm1.integrate(oscillatory, "wr", 3, abs_tol=1e-5, seed=5)
    b = udm1.integrate(oscillatory, "wr", 3, abs_tol=1e-5, seed=5, chunk=777)
    assert (a.estimate, a.error_bound, a.n) == (b.estimate, b.error_bound, b.n)


@pytest.mark.parametrize("kwargs,words", [
    ({"abs_tol": -1.0}, "abs_tol must be a positive"),
    ({"rel_tol": float("nan")}, "rel_tol must be a positive"),
    ({"abs_tol": 1e-3, "n": 100}, "not both"),
    ({"abs_tol": 1e-3, "transform": "sine"}, "transform 'sine'"),
    ({"abs_tol": 1e-3, "confidence": 1.0}, "confidence"),
    ({"abs_tol": 1e-3, "replications": 1}, "replications"),
    ({"abs_tol": 1e-3, "n_max": 100}, "n_max 100"),
    ({}, "give n"),
])
def test_bad_arguments(kwargs, words):
    with pytest.raises(ValueError, match=words):
        udm1.integrate(oscillatory, "wr", 3, **kwargs)
