/* test_radical_inverse.c - the radical inverses' fast paths (libudm1/src/samplers/radical_inverse.c,
 * compiled here) against a transcription of their definition, and the divisions by multiplication they
 * use (libudm1/src/core/divisor.h) against the hardware's division:
 *
 *  - udm1_divide_by on edge and random divisors of every bit length and numerators u1 < m;
 *    udm1_mod32 and udm1_div32 on edge and random 32-bit operands;
 *  - udm1_radical_inverse (one value), udm1_radical_fill (a fill split at its last index's digits, Owen's
 *    lanes) and udm1_radical_pin/udm1_radical_pinned (a stream's two splits) against the definition:
 *    the K base-b digits of n reversed, each permuted by Kensler's permute keyed per position (and per
 *    scrambled prefix for Owen), R / b^K floored to 64 bits by long division; in every mode, small and
 *    large bases, indices about each split and power of b, near 2^32 and up to 2^64 - 1. */
#include "samplers/radical_inverse.c"

#include "check.h"

#include <stdio.h>
#include <stdlib.h>

#if !defined(__SIZEOF_INT128__)
int main(void)
{
    printf("test_radical_inverse: no unsigned __int128 in this compiler: skipped\n");
    return 77;
}
#else
__extension__ typedef unsigned __int128 u128;

static uint64_t rng_state = 0x243F6A8885A308D3ull;
static uint64_t next64(void) /* splitmix64 */
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
/* a random value of a random bit length 1..64 */
static uint64_t any64(void)
{
    unsigned bits = 1u + (unsigned)(next64() % 64u);
    uint64_t v = next64();
    return bits == 64 ? v : v & ((1ull << bits) - 1u);
}

/* ---- the definition, written out ---- */

static uint32_t kensler_permute(uint32_t i, uint32_t l, uint32_t p)
{
    uint32_t w = l - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    do {
        i ^= p;
        i *= 0xe170893du;
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i *= 0x0929eb3fu;
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i *= 1u | p >> 27;
        i *= 0x6935fa69u;
        i ^= (i & w) >> 11;
        i *= 0x74dcb303u;
        i ^= (i & w) >> 2;
        i *= 0x9e501cc3u;
        i ^= (i & w) >> 2;
        i *= 0xc860a3dfu;
        i &= w;
        i ^= i >> 5;
    } while (i >= l);
    return (uint32_t)(((uint64_t)i + p) % l);
}

static uint64_t reference(uint64_t n, uint32_t b, uint32_t mode, uint64_t r)
{
    if (b == 2) { /* bit reversal, then the base-2 randomizations (seq/scramble.h) */
        uint64_t v = 0;
        for (int i = 0; i < 64; ++i, n >>= 1) v = v << 1 | (n & 1u);
        return udm1_randomize_base2(mode, v, r);
    }
    u128 R = 0, D = 1;
    uint32_t k = 0;
    for (; D <= UINT64_MAX; ++k) { /* K digits: b^K >= 2^64 */
        uint32_t d = (uint32_t)(n % b);
        n /= b;
        if (mode == UDM1_MODE_PERMUTE || mode == UDM1_MODE_OWEN) {
            uint32_t key = (uint32_t)r + (k + 1u) * 0x9E3779B9u;
            if (mode == UDM1_MODE_OWEN) key ^= (uint32_t)((((uint64_t)R ^ (uint64_t)(R >> 64)) * 0xD6E8FEB86659FD93ull) >> 32);
            d = kensler_permute(d, b, key);
        }
        R = R * b + d;
        D *= b;
    }
    uint64_t q = 0; /* floor(R 2^64 / D), bit by bit (R < D < 2^96) */
    for (int i = 0; i < 64; ++i) {
        R <<= 1;
        q <<= 1;
        if (R >= D) R -= D, q |= 1u;
    }
    return mode == UDM1_MODE_SHIFT ? q + r : q;
}

/* ---- the divisions ---- */

static void test_divisions(void)
{
    int bad = 0;
    for (int t = 0; t < 200000; ++t) {
        uint64_t m = t < 64 ? 1ull << t : t < 128 ? (1ull << (t - 64)) - 1u + (t == 64) : any64();
        if (m == 0) m = 1;
        udm1_divisor dv = udm1_divisor_make(m);
        for (int j = 0; j < 4; ++j) {
            uint64_t u1 = j == 0 ? m - 1u : j == 1 ? 0 : next64() % m, u0 = j == 0 ? UINT64_MAX : next64();
            u128 want = (((u128)u1 << 64) | u0) / m;
            uint64_t got = udm1_divide_by(&dv, u1, u0);
            if (got != (uint64_t)want && bad++ < 5)
                fprintf(stderr, "divide_by %016llx:%016llx / %llu = %016llx, expected %016llx\n", (unsigned long long)u1,
                        (unsigned long long)u0, (unsigned long long)m, (unsigned long long)got,
                        (unsigned long long)want);
        }
    }
    CHECKF(bad == 0, "udm1_divide_by: %d wrong quotients", bad);
    bad = 0;
    for (int t = 0; t < 200000; ++t) {
        uint32_t d = t < 32 ? (uint32_t)(1ull << t) + (t == 0) : t < 64 ? (uint32_t)((1ull << (t - 31)) - 1u) + (t == 32) * 2u
                                                                        : (uint32_t)any64();
        if (d < 2) d = 2 + (uint32_t)(next64() % 1000u);
        uint64_t magic = udm1_mod32_magic(d);
        uint32_t xs[4] = {UINT32_MAX, d - 1u, d, (uint32_t)next64()};
        for (int j = 0; j < 4; ++j) {
            uint32_t x = xs[j];
            if ((udm1_mod32(x, d, magic) != x % d || udm1_div32(x, magic) != x / d) && bad++ < 5)
                fprintf(stderr, "mod32/div32 %u by %u: %u %u, expected %u %u\n", x, d, udm1_mod32(x, d, magic),
                        udm1_div32(x, magic), x % d, x / d);
        }
    }
    CHECKF(bad == 0, "udm1_mod32 / udm1_div32: %d wrong results", bad);
}

/* ---- the radical inverses ---- */

static const uint32_t MODES[] = {UDM1_MODE_NONE, UDM1_MODE_SHIFT, UDM1_MODE_PERMUTE, UDM1_MODE_OWEN};

/* indices worth checking in base b: about each power of b up to 2^64, about 2^32, the largest */
static size_t interesting(uint32_t b, uint64_t *out, size_t cap)
{
    size_t m = 0;
    for (uint64_t p = 1;; p *= b) {
        for (int64_t e = -2; e <= 2; ++e)
            if (m < cap && (e >= 0 || p >= (uint64_t)-e)) out[m++] = p + (uint64_t)e;
        if (p > UINT64_MAX / b) break;
    }
    uint64_t fixed[] = {0, 1, 0xFFFFFFFFull, 0x100000000ull, 0x100000001ull, 1ull << 63, UINT64_MAX - 1u, UINT64_MAX};
    for (size_t i = 0; i < sizeof fixed / sizeof *fixed && m < cap; ++i) out[m++] = fixed[i];
    while (m < cap) out[m++] = any64();
    return m;
}

static int check_value(const char *what, uint64_t got, uint64_t n, uint32_t b, uint32_t mode, uint64_t r, uint64_t add)
{
    static int shown = 0;
    uint64_t want = reference(n, b, mode, r) + add;
    if (got == want) return 0;
    if (shown++ < 10) fprintf(stderr, "%s base %u mode %u r %016llx n %llu: %016llx, expected %016llx\n", what, b, mode,
            (unsigned long long)r, (unsigned long long)n, (unsigned long long)got, (unsigned long long)want);
    return 1;
}

static void test_radical(void)
{
    static const uint32_t bases[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 97, 101, 251, 257, 311, 1021,
                                     1031, 65521, 65537, 821641, 4294967291u};
    int bad = 0;
    for (size_t bi = 0; bi < sizeof bases / sizeof *bases; ++bi) {
        uint32_t b = bases[bi];
        udm1_radix rx;
        udm1_radix_init(&rx, b);
        uint64_t ns[200];
        size_t nn = interesting(b, ns, 200);
        for (size_t mi = 0; mi < 4; ++mi) {
            uint32_t mode = MODES[mi];
            for (int rep = 0; rep < 3; ++rep) {
                uint64_t r = next64(), add = rep == 2 ? next64() : 0, w0, w1;
                udm1_radical_pin(&rx, mode, r, &w0, &w1);
                for (size_t i = 0; i < nn; ++i) {
                    uint64_t n = ns[i];
                    bad += check_value("value", udm1_radical_inverse(n, &rx, mode, r), n, b, mode, r, 0);
                    bad += check_value("pinned", udm1_radical_pinned(n, &rx, mode, r, w0, w1), n, b, mode, r, 0);
                }
                /* fills: ranges from 0, about the splits and the powers of b, at the end of the indices */
                uint64_t firsts[] = {0, 0, rx.limit[0] - 5u, rx.limit[1] - 3u, ns[5 + (size_t)rep], 0xFFFFFFF0ull,
                                     UINT64_MAX - 40u, next64() >> (next64() % 64u)};
                size_t counts[] = {1, 97, 10, 6, 11, 33, 41, 29};
                for (size_t f = 0; f < sizeof firsts / sizeof *firsts; ++f) {
                    uint64_t out[2 * 97];
                    size_t count = counts[f];
                    if (firsts[f] > UINT64_MAX - count) firsts[f] = UINT64_MAX - count;
                    udm1_radical_fill(&rx, mode, r, firsts[f], count, add, out, 2);
                    for (size_t i = 0; i < count; ++i)
                        bad += check_value("fill", out[2 * i], firsts[f] + i, b, mode, r, add);
                }
            }
        }
    }
    CHECKF(bad == 0, "radical inverses: %d values differ from the definition", bad);
}

int main(void)
{
    test_divisions();
    test_radical();
    CHECK_DONE();
}
#endif
