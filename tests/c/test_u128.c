/* test_u128.c - the portable 128-bit arithmetic (libudm1/src/core/u128.h with UDM1_PORTABLE_INT128: what
 * MSVC builds) and the portable top half of a product of the inline draws (udm1_mulhi64 of udm1/stream.h)
 * against the compiler's unsigned __int128, on edge operands and on random ones of every bit length:
 * products, shifts, multiply-adds, comparisons, and divisions of every case of the long division (one- and
 * two-word divisors, each normalization shift, quotient digits that need their corrections). The
 * library's own values are compared between the two builds by test_draw_digest.
 *
 * tests/msvc/check_msvc.cmake builds this file again as MSVC's branch (clang with -fms-extensions,
 * _MSC_VER and _M_X64 defined: _umul128 and __umulh), where clang is installed. */
#define UDM1_PORTABLE_INT128 1
#include "core/u128.h"

#include "check.h"

#include <udm1/stream.h>

#include <stdio.h>
#include <stdlib.h>

#if !defined(__SIZEOF_INT128__)
int main(void)
{
    printf("test_u128: no unsigned __int128 to compare with: skipped\n");
    return 77;
}
#else
__extension__ typedef unsigned __int128 ref128;

static uint64_t rng_state = 0x243F6A8885A308D3ull;
static uint64_t next64(void) /* splitmix64 */
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* A random value of `bits` bits (1..128; the top one set), or with some probability a value near a
 * power of two or all ones below it, which the corrections of the long division meet. */
static ref128 operand(unsigned bits)
{
    ref128 top = (ref128)1 << (bits - 1), mask = top | (top - 1), v = ((ref128)next64() << 64) | next64();
    switch (next64() % 8) {
    case 0: v = next64() & 0xF; break;                                     /* just above the power of two */
    case 1: v = mask - (next64() & 0xF); break;                            /* just below the next one */
    case 2: v |= (top - 1) >> (next64() % bits); break;                    /* a long run of ones */
    default: break;
    }
    return (v & mask) | top;
}

static udm1_u128 to_u(ref128 x) { return udm1_u128_make((uint64_t)(x >> 64), (uint64_t)x); }
static int same(udm1_u128 a, ref128 b) { return udm1_u128_hi(a) == (uint64_t)(b >> 64) && udm1_u128_lo(a) == (uint64_t)b; }

static void print128(const char *what, ref128 x)
{
    fprintf(stderr, "  %s = 0x%016llx%016llx\n", what, (unsigned long long)(uint64_t)(x >> 64), (unsigned long long)(uint64_t)x);
}

static int check_division(ref128 n, ref128 d)
{
    udm1_u128 rem, q = udm1_u128_divmod(to_u(n), to_u(d), &rem);
    int ok = same(q, n / d) && same(rem, n % d) && same(udm1_u128_div(to_u(n), to_u(d)), n / d);
    if (!ok) {
        fprintf(stderr, "test_u128: division differs\n");
        print128("n", n), print128("d", d), print128("n / d", n / d), print128("n % d", n % d);
        print128("portable q", ((ref128)udm1_u128_hi(q) << 64) | udm1_u128_lo(q));
        print128("portable r", ((ref128)udm1_u128_hi(rem) << 64) | udm1_u128_lo(rem));
    }
    return ok;
}

static void test_products(void)
{
    static const uint64_t edge[] = {0, 1, 2, 3, 0xFFFFFFFFu, 0x100000000ull, 0x100000001ull, 0x7FFFFFFFFFFFFFFFull,
                                    0x8000000000000000ull, 0xFFFFFFFFFFFFFFFEull, 0xFFFFFFFFFFFFFFFFull,
                                    0x9E3779B97F4A7C15ull, 0xFFFFFFFF00000000ull, 0x00000000FFFFFFFFull};
    int bad = 0;
    for (size_t i = 0; i < sizeof edge / sizeof *edge + 200000; ++i) {
        size_t ne = sizeof edge / sizeof *edge;
        uint64_t a = i < ne * ne ? edge[i % ne] : next64() >> (next64() % 64);
        uint64_t b = i < ne * ne ? edge[i / ne % ne] : next64() >> (next64() % 64);
        ref128 p = (ref128)a * b;
        uint64_t hi, lo;
        udm1_mul64(a, b, &hi, &lo);
        if (hi != (uint64_t)(p >> 64) || lo != (uint64_t)p || udm1_mulhi64(a, b) != (uint64_t)(p >> 64)) {
            if (bad++ < 5)
                fprintf(stderr, "test_u128: %016llx * %016llx gives %016llx %016llx (mulhi64 %016llx)\n",
                        (unsigned long long)a, (unsigned long long)b, (unsigned long long)hi, (unsigned long long)lo,
                        (unsigned long long)udm1_mulhi64(a, b));
        }
        uint32_t d = (uint32_t)next64();
        ref128 x = operand(1 + (unsigned)(next64() % 128));
        if (!same(udm1_u128_muladd64(to_u(x), a, d), x * a + d)) ++bad;
        if (!same(udm1_u128_or64(to_u(x), a), x | a)) ++bad;
    }
    CHECKF(bad == 0, "%d products or multiply-adds differ", bad);
}

static void test_shifts_and_order(void)
{
    int bad = 0;
    for (int i = 0; i < 20000; ++i) {
        ref128 x = operand(1 + (unsigned)(next64() % 128)), y = i % 3 ? operand(1 + (unsigned)(next64() % 128)) : x;
        for (unsigned s = 0; s < 128; s += 1 + (unsigned)(i % 5))
            if (!same(udm1_u128_shl(to_u(x), s), x << s)) ++bad;
        if (udm1_u128_lt(to_u(x), to_u(y)) != (x < y) || udm1_u128_lt(to_u(y), to_u(x)) != (y < x)) ++bad;
        if (udm1_u128_hi(to_u(x)) != (uint64_t)(x >> 64) || udm1_u128_lo(to_u(x)) != (uint64_t)x) ++bad;
    }
    CHECKF(bad == 0, "%d shifts, comparisons or halves differ", bad);
}

static void test_divisions(void)
{
    int bad = 0;
    /* every pair of bit lengths, several operands each: one-word and two-word divisors, each
     * normalization shift, dividends below, equal to and far above the divisor */
    for (unsigned nb = 1; nb <= 128; ++nb)
        for (unsigned db = 1; db <= 128; ++db)
            for (int k = 0; k < 6; ++k) {
                ref128 n = operand(nb), d = operand(db);
                if (!check_division(n, d) && ++bad > 5) goto done;
                if (k == 0 && !check_division(d, d)) ++bad;
                ref128 below = n / d * d; /* the largest dividend of the same quotient */
                if (k == 1 && ~(ref128)0 - below >= d - 1 && !check_division(below + (d - 1), d)) ++bad;
            }
    /* the library's own divisions: 2^128 - 1 by a point count (the lattice's generators), and the fraction
     * steps of udm1_frac64 (cmj, Halton, Hammersley: num < den < 2^96, shifted by 32) */
    for (int i = 0; i < 200000 && bad <= 5; ++i) {
        ref128 k = 1 + (next64() >> (next64() % 64));
        if (!check_division(~(ref128)0, k)) ++bad;
        ref128 den = operand(1 + (unsigned)(next64() % 96)), num = den > 1 ? operand(1 + (unsigned)(next64() % 96)) % den : 0;
        if (!check_division(num << 32, den)) ++bad;
        if (!check_division((num << 32) % den << 32, den)) ++bad;
    }
done:
    CHECKF(bad == 0, "%d divisions differ", bad);
}

int main(void)
{
    test_products();
    test_shifts_and_order();
    test_divisions();
    CHECK_DONE();
}
#endif
