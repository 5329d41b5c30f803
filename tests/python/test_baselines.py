"""The baseline samplers against independent references: scipy's Sobol, exact
rational radical inverses, and Python implementations of Kensler's CMJ and of
the golden ratio point set written from the papers."""

import math
from fractions import Fraction

import numpy as np
import pytest
from scipy.stats import qmc

import reference as ref
import udm1

M32 = 0xFFFFFFFF


@pytest.mark.parametrize("d,n", [(1, 4096), (2, 4096), (8, 4096), (40, 1024), (1024, 64), (21201, 4)])
def test_sobol_equals_scipy_bits53(d, n):
    ours = udm1.Sequence("sobol", d, randomize=False).points(n)
    theirs = qmc.Sobol(d, scramble=False, bits=53).random(n)
    assert np.array_equal(ours, theirs)


def test_sobol_random_access_equals_scipy():
    """Points in shuffled order, one at a time (the table of the first 256 dimensions and the bit loop
    beyond them and past index 255), equal scipy's rows."""
    d, n = 300, 1024
    theirs = qmc.Sobol(d, scramble=False, bits=53).random(n)
    seq = udm1.Sequence("sobol", d, randomize=False)
    order = np.random.default_rng(5).permutation(n)
    ours = seq.points_at(np.zeros(n, dtype=np.uint64), order)
    assert np.array_equal(ours, theirs[order])
    assert np.array_equal(seq.points_at([0, 0], [1023, 3], dims=range(250, 262)), theirs[[1023, 3], 250:262])


def test_sobol_top_30_bits_equal_scipy_default():
    ours = udm1.Sequence("sobol", 16, randomize=False).points(1 << 12, dtype=np.uint64)
    theirs = qmc.Sobol(16, scramble=False).random(1 << 12)  # bits=30
    assert np.array_equal((ours >> np.uint64(34)).astype(np.float64) * 2.0**-30, theirs)


def exact_radical_inverse(n: int, b: int) -> Fraction:
    x, f = Fraction(0), Fraction(1, b)
    while n:
        n, d = divmod(n, b)
        x += d * f
        f /= b
    return x


def test_halton_and_hammersley_exact():
    primes = ref.primes(20)
    h = udm1.Sequence("halton", 20, randomize=False)
    idx = list(range(0, 300)) + [2**32 + 1, 2**53 + 7, 2**63, 2**64 - 1]
    for j, b in enumerate(primes):
        for n in idx:
            want = math.floor(exact_radical_inverse(n, b) * 2**64)
            assert int(h.sample(n, j, dtype=np.uint64)) == want, (b, n)
    K = 1000
    hm = udm1.Sequence("hammersley", 4, point_count=K, randomize=False)
    pts = hm.points(K, dtype=np.uint64)
    for n in range(0, K, 37):
        assert int(pts[n, 0]) == (n << 64) // K
        assert int(pts[n, 3]) == math.floor(exact_radical_inverse(n, 5) * 2**64)


def test_lp_first_values():
    lp = udm1.Sequence("lp", 2, point_count=4, randomize=False).points(4, dtype=np.uint64)
    assert [int(v) >> 32 for v in lp[:, 1]] == [0, 0x80000000, 0xC0000000, 0x40000000]


# ---- Kensler's correlated multi-jittered sampling, from the memo (final version) ----

def permute(i, l, p):
    w = l - 1
    for s in (1, 2, 4, 8, 16):
        w |= w >> s
    while True:
        i ^= p; i = (i * 0xe170893d) & M32; i ^= p >> 16; i ^= (i & w) >> 4; i ^= p >> 8
        i = (i * 0x0929eb3f) & M32; i ^= p >> 23; i ^= (i & w) >> 1; i = (i * (1 | p >> 27)) & M32
        i = (i * 0x6935fa69) & M32; i ^= (i & w) >> 11; i = (i * 0x74dcb303) & M32; i ^= (i & w) >> 2
        i = (i * 0x9e501cc3) & M32; i ^= (i & w) >> 2; i = (i * 0xc860a3df) & M32; i &= w; i ^= i >> 5
        if i < l:
            return (i + p) % l


def randhash(i, p):
    i ^= p; i ^= i >> 17; i ^= i >> 10; i = (i * 0xb36534e5) & M32; i ^= i >> 12; i ^= i >> 21
    i = (i * 0x93fc4795) & M32; i ^= 0xdf6e307f; i ^= i >> 17; i = (i * (1 | p >> 18)) & M32
    return i


def cmj_exact(s, N, p):
    m = math.isqrt(N)
    n = (N + m - 1) // m
    s = permute(s, N, (p * 0x51633e2d) & M32)
    sx = permute(s % m, m, (p * 0x68bc21eb) & M32)
    sy = permute(s // m, n, (p * 0x02e5be93) & M32)
    jx = Fraction(randhash(s, (p * 0x967a889b) & M32), 2**32)
    jy = Fraction(randhash(s, (p * 0x368cc8b7) & M32), 2**32)
    x = (sx + (sy + jx) / n) / m
    y = (s + jy) / N
    return math.floor(x * 2**64), math.floor(y * 2**64)


def key32(seed_key, what, k):
    return ref.mix64(seed_key ^ ref.mix64(what * 0x9E3779B97F4A7C15 + k)) & M32


@pytest.mark.parametrize("K", [1, 7, 16, 100, 1000])
def test_cmj_equals_the_memo(K):
    seed = 12345
    seq = udm1.Sequence("cmj", 4, point_count=K, seed=seed, randomize=False)
    pts = seq.points(K, dtype=np.uint64)
    for pair in (0, 1):
        p = key32(ref.seed_key(seed), 0x434D4A, pair)
        for s in range(K):
            assert (int(pts[s, 2 * pair]), int(pts[s, 2 * pair + 1])) == cmj_exact(s, K, p)


@pytest.mark.parametrize("K", [1, 2, 5, 89, 100, 1000])
def test_grps_equals_sorted_golden_sequence(K):
    seed = 77
    seq = udm1.Sequence("grps", 2, point_count=K, seed=seed, randomize=False)
    pts = seq.points(K, dtype=np.uint64)
    golden = ref.round128(ref.quad_frac(-1, 5, 2))  # frac(1/phi) in 0.128
    sk = ref.seed_key(seed)
    s1 = ref.mix64(sk ^ ref.mix64(0x4752505331))
    s2 = ref.mix64(sk ^ ref.mix64(0x4752505332))
    g = [ref.raw_value(0, golden, i) for i in range(K)]
    xs = sorted((v + s1) % 2**64 for v in g)  # the sorted golden sequence, by sorting
    assert [int(v) for v in pts[:, 0]] == xs
    assert [int(v) for v in pts[:, 1]] == [(ref.raw_value(0, golden, t) + s2) % 2**64 for t in range(K)]


@pytest.mark.parametrize("name", ["pcg32", "drand48", "halton", "halton-owen", "sobol", "sobol-owen"])
def test_sequences_beat_or_match_random_in_the_mean(name):
    # integration of a smooth function: the QMC baselines beat pcg32 by far at n = 4096
    f = lambda x: np.exp(-np.sum((x - 0.5) ** 2, axis=1) * 4)
    exact = (math.sqrt(math.pi / 4) * math.erf(1)) ** 2
    errs = []
    for seed in range(16):
        x = udm1.Sequence(name, 2, seed=seed).points(4096, stream=seed)
        errs.append(f(x).mean() - exact)
    rmse = float(np.sqrt(np.mean(np.square(errs))))
    if name in ("pcg32", "drand48"):
        assert 1e-4 < rmse < 1e-2  # ~ sigma / sqrt(n)
    else:
        assert rmse < 2e-4, (name, rmse)
