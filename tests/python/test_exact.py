"""Every preset's values equal an independent high-precision computation.

- Generators: bit-exact against round(frac(alpha) * 2^128) computed with
  math.isqrt (square roots, quadratic irrationals) and mpmath (e, e^2, R_d).
- Values: within 2^-60 of {O + n alpha} computed with 400-bit generators, for
  every preset and every dimension up to 64, at indices 0..1000, 2^32 +- 1,
  2^53, 2^63 and 2^64 - 1; and bit-exact against the contract's integer formula.
- fmod(n * alpha, 1) in double is shown to fail where udm1 does not.
"""

import math

import numpy as np
import pytest

import reference as ref
import udm1

BIG = [2**32 - 1, 2**32, 2**32 + 1, 2**53, 2**63, 2**64 - 1]
WEYL = ["wr", "wr-ao", "we", "wgr", "wmmr", "hwmmr", "rd", "golden", "epis", "episwr"]
PRESETS = [(p.name, min(p.max_dimensions, 64)) for p in udm1.presets() if p.name in WEYL]


def make(name, d, seed=0, randomize=False):
    k = 1000 if name in ("epis", "episwr") else 0
    return udm1.Sequence(name, d, point_count=k, seed=seed, randomize=randomize)


@pytest.mark.parametrize("name,d", PRESETS)
def test_generators_bit_exact(name, d):
    s = make(name, d)
    fr = ref.preset_fracs(name, d, k=1000)
    for j in range(d):
        if fr[j] is None:  # EPIS: ceil(2^128 / K)
            assert s.alpha(j) == -(-(1 << 128) // 1000)
        else:
            assert s.alpha(j) == ref.round128(fr[j]), f"{name} dim {j}"


def test_wr_all_65536_generators_bit_exact():
    s = udm1.Sequence("wr", udm1.presets()[0].max_dimensions, randomize=False)
    assert s.d == 65536
    ps = ref.primes(65536)
    assert ps[1023] == 8161 and ps[-1] == 821641
    for j in range(0, 65536, 1):
        assert s.alpha(j) == ref.round128(ref.sqrt_frac(ps[j], 192), 192), f"sqrt({ps[j]})"


@pytest.mark.parametrize("d", [1, 2, 3, 5, 8, 20, 64, 100, 1000])
def test_rd_generators_bit_exact(d):
    s = udm1.Sequence("rd", d, randomize=False)
    fr = ref.rd_fracs(d)
    for j in range(d):
        assert s.alpha(j) == ref.round128(fr[j]), f"R_{d} dim {j}"


@pytest.mark.parametrize("randomize", [False, True])
@pytest.mark.parametrize("name,d", PRESETS)
def test_values_within_2_pow_minus_60(name, d, randomize):
    s = make(name, d, seed=20261122, randomize=randomize)
    fr = ref.preset_fracs(name, d, k=1000)
    point_set = s.point_count > 0
    small = s.points(1001, dtype=np.uint64) if not point_set else s.points(1000, dtype=np.uint64)
    tol = 1 << (ref.PREC - 60)
    for j in range(d):
        off = s.offset(j, stream=0)
        alpha = s.alpha(j)
        if fr[j] is None:  # EPIS: exactly floor(n 2^64 / K) + u
            for n in range(1000):
                assert int(small[n, j]) == ((n << 64) // 1000 + off) % (1 << 64)
            continue
        idx = list(range(small.shape[0])) + ([] if point_set else BIG)
        for n in idx:
            u = int(small[n, j]) if n < small.shape[0] else int(s.sample(n, j, dtype=np.uint64))
            assert u == ref.raw_value(off, alpha, n), f"{name} dim {j} n {n}: not the contract's formula"
            true = ref.true_value(off, fr[j], n)
            dist = ref.circular_distance(u << (ref.PREC - 64), true, ref.PREC)
            assert dist < tol, f"{name} dim {j} n {n}: off by {dist / 2**ref.PREC:.3g}"


def test_fmod_double_is_not_exact_but_udm1_is():
    # the paper's worst generator: frac(sqrt(237173)) = 0.0041...
    s = udm1.Sequence("wmmr", 22, randomize=False)
    fr = ref.preset_fracs("wmmr", 22)[21]
    n = 2**40
    exact = ref.true_value(0, fr, n) / 2**ref.PREC
    naive = math.fmod(n * math.sqrt(237173), 1.0)
    ours = float(s.sample(n, 21))
    assert abs(naive - exact) > 1e-4  # the field's measurement: 1.6e-3 at 2^40
    assert abs(ours - exact) < 2**-52


def test_point_zero_is_the_offset():
    for name, d in PRESETS:
        s = make(name, d, seed=5, randomize=True)
        for j in range(d):
            assert int(s.sample(0, j, stream=9, dtype=np.uint64)) == s.offset(j, stream=9)
        s0 = make(name, d, randomize=False)
        assert np.all(s0.points(1, dtype=np.uint64) == 0)
