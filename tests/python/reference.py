"""An independent reference for udm1's sequences, written from the contract in
udm1.h, not from the C sources: generators from math.isqrt and mpmath, the
shift hash from its documented formula, values in exact integer arithmetic.
"""

from __future__ import annotations

import math
from functools import lru_cache

import mpmath

M64 = (1 << 64) - 1
GOLDEN_GAMMA = 0x9E3779B97F4A7C15
SEED_SALT = int.from_bytes(b"udm1SEED", "big")

# Working precision of the "true" generators: fraction * 2^PREC.
PREC = 400

WMMR_RADICANDS = [13, 173, 17, 293, 47, 2213, 67, 4493, 97, 9413, 167, 27893, 193, 37253, 277, 76733, 307, 94253,
                  317, 100493, 487, 237173]


def primes(count: int) -> list[int]:
    out, n = [], 2
    limit = 16
    while len(out) < count:
        limit *= 2
        sieve = bytearray([1]) * (limit + 1)
        sieve[0:2] = b"\x00\x00"
        for i in range(2, math.isqrt(limit) + 1):
            if sieve[i]:
                sieve[i * i::i] = bytearray(len(sieve[i * i::i]))
        out = [i for i in range(limit + 1) if sieve[i]]
    return out[:count]


# ---- generators as exact fractions: value / 2^bits, floored ----

def sqrt_frac(k: int, bits: int = PREC) -> int:
    """floor(frac(sqrt(k)) * 2^bits), exact."""
    r = math.isqrt(k << (2 * bits))
    return r % (1 << bits)


def quad_frac(a: int, k: int, c: int, bits: int = PREC) -> int:
    """floor(frac((a + sqrt(k)) / c) * 2^bits) for c a power of two, exact."""
    r = math.isqrt(k << (2 * bits))  # floor(sqrt(k) 2^bits)
    return ((a << bits) + r) // c % (1 << bits)


def mp_frac(x, bits: int = PREC) -> int:
    with mpmath.workprec(bits + 64):
        return int(mpmath.floor(mpmath.frac(x) * mpmath.mpf(2) ** bits))


@lru_cache(maxsize=None)
def rd_fracs(d: int, bits: int = PREC) -> tuple[int, ...]:
    """R_d generators phi_d^-1..phi_d^-d, phi_d the root of x^(d+1) = x + 1 (mpmath)."""
    with mpmath.workprec(bits + 64):
        f = lambda x: x ** (d + 1) - x - 1
        lo, hi = mpmath.mpf(1), mpmath.mpf(2)
        for _ in range(60):  # bracket the root, then Newton from the middle
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
        phi = mpmath.findroot(f, (lo + hi) / 2, solver="newton")
        assert abs(f(phi)) < mpmath.mpf(2) ** (-bits - 8)
        g = 1 / phi
        out, p = [], mpmath.mpf(1)
        for _ in range(d):
            p *= g
            out.append(int(mpmath.floor(p * mpmath.mpf(2) ** bits)))
        return tuple(out)


def e_frac(bits: int = PREC) -> int:
    with mpmath.workprec(bits + 64):
        return mp_frac(mpmath.e, bits)


def e2_frac(bits: int = PREC) -> int:
    with mpmath.workprec(bits + 64):
        return mp_frac(mpmath.e ** 2, bits)


def preset_fracs(name: str, d: int, k: int = 0, bits: int = PREC) -> list[int]:
    """True generators of a preset, floor(frac * 2^bits); for EPIS, 1/K exactly as a fraction is
    returned as None (handled by the caller)."""
    phi = lambda: quad_frac(1, 5, 2, bits)
    h13 = lambda: quad_frac(1, 3, 2, bits)
    if name == "wr":
        return [sqrt_frac(p, bits) for p in primes(d)]
    if name == "wr-ao":
        return [sqrt_frac(2, bits), sqrt_frac(13, bits)][:d]
    if name == "we":
        return [e_frac(bits), e2_frac(bits)][:d]
    if name == "wgr":
        return [phi(), h13()][:d]
    if name == "wmmr":
        return [sqrt_frac(r, bits) for r in WMMR_RADICANDS][:d]
    if name == "hwmmr":
        return ([phi(), h13(), e_frac(bits), e2_frac(bits)] + [sqrt_frac(r, bits) for r in WMMR_RADICANDS[:18]])[:d]
    if name == "rd":
        return list(rd_fracs(d, bits))
    if name == "golden":
        return [phi()]
    if name in ("epis", "episwr"):
        return [None, sqrt_frac(137, bits)][:d]
    raise KeyError(name)


def round128(frac_bits: int, bits: int = PREC) -> int:
    """round(frac * 2^128) mod 2^128 from a floor(frac * 2^bits) with bits >> 128."""
    return ((frac_bits + (1 << (bits - 129))) >> (bits - 128)) % (1 << 128)


# ---- the documented hash ----

def mix64(z: int) -> int:
    z &= M64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & M64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & M64
    return z ^ (z >> 31)


def seed_key(seed: int) -> int:
    return mix64(seed ^ SEED_SALT)


def dim_key(sk: int, dim: int) -> int:
    return mix64(sk + (dim + 1) * GOLDEN_GAMMA)


def stream_key(sk: int, stream: int) -> int:
    return mix64(sk ^ mix64(stream + GOLDEN_GAMMA))


def shift(seed: int, stream: int, dim: int) -> int:
    sk = seed_key(seed)
    return mix64(stream_key(sk, stream) + dim_key(sk, dim))


def pad(seed: int, stream: int, index: int, dim: int) -> int:
    return mix64(shift(seed, stream, dim) + (index + 1) * GOLDEN_GAMMA)


# ---- values ----

def raw_value(offset64: int, alpha128: int, n: int) -> int:
    """The contract's raw value: top 64 bits of (O 2^64 + n A) mod 2^128."""
    return (((offset64 << 64) + n * alpha128) % (1 << 128)) >> 64


def true_value(offset64: int, frac_bits: int, n: int, bits: int = PREC) -> int:
    """{O/2^64 + n alpha} * 2^bits (floor), with alpha to `bits` bits: error n 2^-bits."""
    return ((offset64 << (bits - 64)) + n * frac_bits) % (1 << bits)


def circular_distance(a: int, b: int, bits: int) -> int:
    d = (a - b) % (1 << bits)
    return min(d, (1 << bits) - d)


def to_f64(u: int) -> float:
    return (u >> 11) * 2.0 ** -53


def to_f32(u: int) -> float:
    return (u >> 40) * 2.0 ** -24


# ---- progressive screen-space randomization (weyl/screen.c), transcribed from its comment ----

SCREEN_R = [0xDB4F0B9175AE2165, 0xBBE0563303A4615F, 0xA0F2EC75A1FE1575, 0x89E182857D9ED688]
SCREEN_COUNTS = [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256]


def _signed64(v: int) -> int:
    v &= M64
    return v - (1 << 64) if v >> 63 else v


def screen_pair(a: int, b: int, single: bool) -> list[int]:
    """The chosen (G_2p, G_2p+1, H_2p, H_2p+1) for the top 64 bits a, b of a pair's generators."""
    import math
    modes, energy = [], []
    for h2 in range(0, 1 if single else 33):
        for h1 in range(-32, 33):
            if h2 == 0 and h1 <= 0:
                continue
            d = abs(_signed64(h1 * a + h2 * b)) >> 32
            r2 = 1 + h1 * h1 + h2 * h2
            w = (1 << 40) // (r2 * math.isqrt(r2))
            row = []
            for n in SCREEN_COUNTS:
                t = (804 * n * d) >> 30
                row.append((w * ((1 << 40) // ((1 << 20) + t * t))) >> 20)
            modes.append((h1, h2))
            energy.append(row)
    total = [sum(col) for col in zip(*energy)]
    r1 = ((1 << 32) // 4) ** 2
    best, chosen = None, None
    for c in range(1, 65):
        g = [((1 << 63) + c * r) & M64 for r in SCREEN_R]
        low, top = [0] * len(SCREEN_COUNTS), [0] * len(SCREEN_COUNTS)
        for (h1, h2), row in zip(modes, energy):
            su = _signed64(h1 * g[0] + h2 * g[1]) >> 32
            sv = _signed64(h1 * g[2] + h2 * g[3]) >> 32
            q = su * su + sv * sv
            if q >= r1:
                continue
            win = ((r1 - q) >> 16) * 65536 // (r1 >> 16)
            for k, e in enumerate(row):
                e = (e >> 16) * win
                low[k] += e
                top[k] = max(top[k], e)
        score = max(float(low[k] + 4 * top[k]) / float(total[k]) for k in range(len(SCREEN_COUNTS)))
        if best is None or score < best:
            best, chosen = score, g
    return chosen


def screen_generators(alpha_his: list[int]) -> list[tuple[int, int]]:
    """(G_j, H_j) of every dimension from the top 64 bits of the generators."""
    out = []
    for j in range(0, len(alpha_his), 2):
        single = j + 1 == len(alpha_his)
        g = screen_pair(alpha_his[j], 0 if single else alpha_his[j + 1], single)
        out.append((g[0], g[2]))
        if not single:
            out.append((g[1], g[3]))
    return out
