"""udm1.integrate's lattice criterion: one shifted embedded lattice ("lattice-seq"), doubled until the
bound read from its Fourier coefficients is within the tolerance.

- The transform: kept across doublings, it equals the direct DFT of the values in lattice order, its
  coefficient 0 is the mean, and for a trigonometric polynomial it is exactly f's coefficients aliased
  mod the lattice (the structure the bound relies on).
- Coverage: under the criterion's assumption (f's Fourier coefficients decay steadily, true of smooth
  integrands periodized by Baker's transform) the bound holds for every shift, not at a confidence.
  Over 300 shifts, from 32 points doubled to the tolerance, the test checks the bound at every doubling
  (11-13 per run) and asks for 99 % of them to hold the integral; measured: all of them (3900 of 3900
  and 3300 of 3300; the error at most 0.42 of the bound). The same runs with the constant 5 2^-m
  lowered to 2^-m hold it in 91 % (2995 of 3300) on the oscillatory integrand, and to 0.2 2^-m in 58 %:
  a bound read at the wrong wavenumbers or scaled too low fails the test.
- A tolerance not met within n_max is refused with the partial estimate; bad arguments in one line.
- The estimate is the exact mean of every value: independent of the chunks.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import udm1
from udm1.integrate import LatticeFourier, _bit_reversal

A = np.array([0.9, 0.6, 1.3])


def oscillatory(x):  # Genz's oscillatory family, d = 3
    return np.cos(2 * np.pi * 0.2 + x @ A)


OSC_EXACT = (np.exp(1j * 2 * np.pi * 0.2) * np.prod((np.exp(1j * A) - 1) / (1j * A))).real


def product_peak(x):  # Genz's product peak, d = 2
    c, w = np.array([2.0, 3.0]), np.array([0.3, 0.6])
    return np.prod(1 / (c ** -2.0 + (x - w) ** 2), axis=1)


PEAK_EXACT = math.prod(c * (math.atan(c * (1 - w)) + math.atan(c * w)) for c, w in ((2.0, 0.3), (3.0, 0.6)))


def test_transform_kept_across_doublings_is_the_direct_dft():
    rng = np.random.default_rng(1)
    y = rng.standard_normal(1 << 12)
    fourier = LatticeFourier(y[:1 << 8])
    for m in range(8, 12):
        fourier.double(y[1 << m:2 << m])
        n = 2 << m
        direct = np.fft.fft(y[:n][_bit_reversal(m + 1)]) / n
        assert np.allclose(fourier.y, direct, rtol=0, atol=1e-12)
        assert abs(fourier.y[0] - y[:n].mean()) < 1e-12
        assert sorted(fourier.order) == list(range(n))  # a permutation of the wavenumbers, 0 first
        assert fourier.order[0] == 0


def _reference_order(y: np.ndarray, order: list[int] | None, top: int, bottom: int) -> list[int]:
    """The wavenumber order by its definition, one pair at a time: at each level, in every block of
    2 half positions, p (1 <= p mod 2 half < half) and p + half swap when the magnitude of the class at
    p + half in the first block exceeds that at p."""
    n = y.size
    order = list(range(n)) if order is None else order + [k + n // 2 for k in order]
    mag = np.abs(y)
    for level in range(top, bottom, -1):
        half = 1 << level
        for q in range(1, half):
            if mag[order[q + half]] > mag[order[q]]:
                for b in range(0, n, 2 * half):
                    order[b + q], order[b + q + half] = order[b + q + half], order[b + q]
    return order


@pytest.mark.parametrize("capacity", [0, 1 << 9, 1 << 12])
def test_order_is_the_definition(capacity):
    # the buffered, vectorised order against the definition, through doublings that grow the buffers
    # (capacity 0 and 2^9) or not (2^12); values with ties (rounded) and without
    rng = np.random.default_rng(5)
    for y in (rng.standard_normal(1 << 11), np.round(rng.standard_normal(1 << 11), 1)):
        fourier = LatticeFourier(y[:1 << 6], capacity=capacity)
        expect = _reference_order(fourier.y, None, 5, 0)
        assert fourier.order.tolist() == expect
        for m in range(6, 11):
            fourier.double(y[1 << m:2 << m])
            expect = _reference_order(fourier.y, expect, m, m - 4)
            assert fourier.order.tolist() == expect, m


def test_transform_is_the_aliased_fourier_coefficients():
    # f = cos(2 pi h.x) = (e(h.x) + e(-h.x)) / 2: on the n-point lattice {k z / n} its transform is 1/2 at
    # l = h.z and l = -h.z (mod n), times the shift's phase, and 0 everywhere else
    d, m = 3, 10
    n = 1 << m
    z = [int(udm1.Sequence("lattice-seq", d, randomize=False).sample(1 << 63, j, dtype=np.uint64)) for j in range(d)]
    seq = udm1.Sequence("lattice-seq", d, seed=7)
    x = seq.points(n)
    for h in ([1, 0, 0], [3, -2, 5], [0, 7, 1]):
        fourier = LatticeFourier(np.cos(2 * np.pi * x @ np.array(h)))
        hz = sum(a * b for a, b in zip(h, z)) % n
        mag = np.abs(fourier.y)
        expect = np.zeros(n)
        expect[hz] += 0.5
        expect[-hz % n] += 0.5
        assert np.allclose(mag, expect, atol=1e-9), h


@pytest.mark.release_only("a coverage check over many seeds; the other tests of this file run its code under the sanitizers")
@pytest.mark.parametrize("f,d,exact,tol", [(oscillatory, 3, OSC_EXACT, 1e-6), (product_peak, 2, PEAK_EXACT, 1e-4)])
def test_bound_covers_the_integral(f, d, exact, tol):
    covers = checks = 0
    for seed in range(300):
        r = udm1.integrate(f, "lattice-seq", d, abs_tol=tol, seed=seed, transform="baker", n_init=32)
        assert r.met and r.criterion == "lattice" and r.replications == 1 and r.n_total == r.n
        assert r.error_bound <= tol and r.confidence is None and r.history[-1][1:] == (r.estimate, r.error_bound)
        for _, estimate, bound in r.history:  # the bound at every doubling, not only the last
            checks += 1
            covers += abs(estimate - exact) <= bound
    assert covers >= 0.99 * checks, f"the bound held the integral at {covers} of {checks} doublings"


def test_doubles_from_n_init_and_keeps_the_points():
    r = udm1.integrate(oscillatory, "lattice-seq", 3, abs_tol=1e-7, seed=2, transform="baker", n_init=64)
    ns = [h[0] for h in r.history]
    assert ns == [64 * 2 ** k for k in range(len(ns))] and ns[-1] == r.n
    whole = udm1.integrate(oscillatory, "lattice-seq", 3, n=r.n, seed=2, transform="baker")
    assert r.estimate == whole.value  # the exact mean of the first n points: nothing dropped on doubling


def test_result_does_not_depend_on_the_chunks():
    a = udm1.integrate(product_peak, "lattice-seq", 2, abs_tol=1e-5, seed=5, transform="baker")
    b = udm1.integrate(product_peak, "lattice-seq", 2, abs_tol=1e-5, seed=5, transform="baker", chunk=1000)
    assert (a.estimate, a.error_bound, a.n) == (b.estimate, b.error_bound, b.n)


def test_an_integrand_that_reuses_its_output_buffer():
    # f hands back the same array every call: each chunk's values are taken before the next call
    buffer = np.empty(1 << 16)

    def reusing(x):
        out = buffer[:x.shape[0]]
        out[:] = product_peak(x)
        return out

    a = udm1.integrate(product_peak, "lattice-seq", 2, abs_tol=1e-5, seed=5, transform="baker", chunk=1000)
    b = udm1.integrate(reusing, "lattice-seq", 2, abs_tol=1e-5, seed=5, transform="baker", chunk=1000)
    assert (a.estimate, a.error_bound, a.n) == (b.estimate, b.error_bound, b.n)


def test_a_range_of_values_is_its_own_array():
    # values_range hands back its own array (udm1.distributed keeps it), even when f reuses one buffer
    from udm1.integrate import IntegralSpec, values_range

    buffer = np.empty(4096)

    def reusing(x):
        out = buffer[:x.shape[0]]
        out[:] = product_peak(x)
        return out

    spec = IntegralSpec("lattice-seq", 2, 1 << 20, 3, True, 0)
    first, _ = values_range(reusing, spec, 0, 1024)
    kept = first.copy()
    values_range(reusing, spec, 1024, 1024)
    assert np.array_equal(first, kept)


def test_the_tent_by_the_library_or_by_numpy():
    # randomized: the library's fixed point tent (sampler NAME+tent); unrandomized: numpy's, which takes
    # x = 1/2 (point 1 of the unshifted lattice) to 1, as Baker's transform does
    from udm1.integrate import periodized

    a = udm1.integrate(product_peak, "lattice-seq", 2, n=1024, seed=3, transform="baker")
    b = udm1.integrate(product_peak, "lattice-seq+tent", 2, n=1024, seed=3)
    assert a.value == b.value
    c = udm1.integrate(product_peak, "lattice-seq", 2, n=1024, randomize=False, transform="baker")
    d = udm1.integrate(periodized(product_peak, "baker"), "lattice-seq", 2, n=1024, randomize=False)
    e = udm1.integrate(product_peak, "lattice-seq+tent", 2, n=1024, randomize=False)
    assert c.value == d.value and c.value != e.value


def test_values_near_the_double_range_and_non_finite_ones():
    # finite values whose float sum overflows pass the check (without a warning); an infinity or a NaN
    # is refused by name
    from udm1.integrate import _checked

    x = np.zeros((64, 2))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.all(_checked(lambda p: np.full(p.shape[0], 1.5e308), x, 0) == 1.5e308)
    for bad, words in ((np.inf, "f is inf at sample 37 "), (np.nan, "f is nan at sample 37 ")):
        with pytest.raises(ValueError, match=words):
            udm1.integrate(lambda p: np.where(np.arange(p.shape[0]) == 37, bad, 1e300), "lattice-seq", 2,
                           abs_tol=1e-3, transform="baker")


def test_tolerance_not_met_is_refused_with_the_partial_estimate():
    with pytest.raises(udm1.ToleranceNotMet, match=r"not met within n_max = 4096 evaluations .* 4096 lattice points"
                       ) as e:
        udm1.integrate(product_peak, "lattice-seq", 2, abs_tol=1e-12, n_max=4096, transform="baker")
    r = e.value.result
    assert not r.met and r.n == 4096 and r.error_bound > 1e-12
    assert abs(r.estimate - PEAK_EXACT) < 1e-2 * PEAK_EXACT


def test_replications_on_the_lattice_sequence_too():
    r = udm1.integrate(oscillatory, "lattice-seq", 3, abs_tol=1e-5, criterion="replications", transform="baker")
    assert r.criterion == "replications" and r.replications == 16 and abs(r.estimate - OSC_EXACT) < 1e-4


@pytest.mark.parametrize("sampler,kwargs,words", [
    ("wr", {"criterion": "lattice"}, "criterion 'lattice' needs the sampler 'lattice-seq'"),
    ("lattice-seq", {"criterion": "fourier"}, "criterion 'fourier' is not one of"),
    ("lattice-seq", {"n_init": 100}, "n_init a power of two above 16, not 100"),
    ("lattice-seq", {"n_init": 16}, "n_init a power of two above 16, not 16"),
    ("lattice-seq", {"n_max": 128}, "n_max 128 is below n_init = 256"),
])
def test_bad_arguments(sampler, kwargs, words):
    with pytest.raises(ValueError, match=words):
        udm1.integrate(oscillatory, sampler, 3, abs_tol=1e-3, **kwargs)
