/* core/u128.h - the library's unsigned 128-bit arithmetic, in one place: the type udm1_u128 and the few
 * operations the library needs (products of 64-bit words, shifts, multiply-add by a word, division), in
 * two implementations that give the same bits.
 *
 *  - The compiler's unsigned __int128, where it has one (GCC and Clang on 64-bit targets).
 *  - A portable pair of 64-bit halves elsewhere (MSVC), and wherever UDM1_PORTABLE_INT128 is defined
 *    (the CMake option of that name, so that the code an MSVC build runs is built and tested with GCC
 *    and Clang too). Its 64 x 64 -> 128-bit products are _umul128 on MSVC x64, __umulh on MSVC ARM64,
 *    and four 32 x 32 -> 64-bit products in plain C elsewhere; its division is long division by 32-bit
 *    digits (Knuth's algorithm D, as Hacker's Delight writes it for 64-bit words), in plain C everywhere.
 *
 * tests/c/test_u128.c checks each operation of the portable implementation against unsigned __int128 on
 * edge and random operands; the library's outputs are compared between the two builds by
 * tests/c/test_draw_digest.c. Not installed. */
#ifndef UDM1_U128_H
#define UDM1_U128_H

#include <stdint.h>

#if defined(__SIZEOF_INT128__) && !defined(UDM1_PORTABLE_INT128)
#  define UDM1_U128_NATIVE 1
#endif

#if !defined(UDM1_U128_NATIVE) && defined(_MSC_VER) && (defined(_M_X64) || defined(_M_ARM64))
#  include <intrin.h>
#  if defined(_M_X64)
#    pragma intrinsic(_umul128)
#  else
#    pragma intrinsic(__umulh)
#  endif
#endif

/* ---- 64 x 64 -> 128-bit product, in two words ---- */
static inline void udm1_mul64(uint64_t a, uint64_t b, uint64_t *hi, uint64_t *lo)
{
#if defined(UDM1_U128_NATIVE)
    __extension__ typedef unsigned __int128 u128;
    u128 p = (u128)a * b;
    *hi = (uint64_t)(p >> 64);
    *lo = (uint64_t)p;
#elif defined(_MSC_VER) && defined(_M_X64)
    *lo = _umul128(a, b, hi);
#elif defined(_MSC_VER) && defined(_M_ARM64)
    *hi = __umulh(a, b);
    *lo = a * b;
#else
    uint64_t a0 = a & 0xffffffffu, a1 = a >> 32, b0 = b & 0xffffffffu, b1 = b >> 32;
    uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
    *lo = (mid << 32) | (p00 & 0xffffffffu);
    *hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
#endif
}

#if defined(UDM1_U128_NATIVE)
__extension__ typedef unsigned __int128 udm1_u128;

static inline udm1_u128 udm1_u128_make(uint64_t hi, uint64_t lo) { return ((udm1_u128)hi << 64) | lo; }
static inline uint64_t udm1_u128_hi(udm1_u128 x) { return (uint64_t)(x >> 64); }
static inline uint64_t udm1_u128_lo(udm1_u128 x) { return (uint64_t)x; }
/* x shifted left by s bits, 0 <= s < 128 (bits past 2^128 dropped) */
static inline udm1_u128 udm1_u128_shl(udm1_u128 x, unsigned s) { return x << s; }
/* x OR a word in the low half */
static inline udm1_u128 udm1_u128_or64(udm1_u128 x, uint64_t w) { return x | w; }
/* x b + d modulo 2^128 */
static inline udm1_u128 udm1_u128_muladd64(udm1_u128 x, uint64_t b, uint64_t d) { return x * b + d; }
/* Whether a < b. */
static inline int udm1_u128_lt(udm1_u128 a, udm1_u128 b) { return a < b; }
/* floor(n / d) and n mod d (into *rem), d > 0. */
static inline udm1_u128 udm1_u128_divmod(udm1_u128 n, udm1_u128 d, udm1_u128 *rem)
{
    *rem = n % d;
    return n / d;
}

#else /* the portable pair of halves */
typedef struct udm1_u128 {
    uint64_t hi, lo;
} udm1_u128;

static inline udm1_u128 udm1_u128_make(uint64_t hi, uint64_t lo)
{
    udm1_u128 r;
    r.hi = hi, r.lo = lo;
    return r;
}
static inline uint64_t udm1_u128_hi(udm1_u128 x) { return x.hi; }
static inline uint64_t udm1_u128_lo(udm1_u128 x) { return x.lo; }

static inline udm1_u128 udm1_u128_shl(udm1_u128 x, unsigned s)
{
    if (s == 0) return x;
    if (s >= 64) return udm1_u128_make(x.lo << (s - 64), 0);
    return udm1_u128_make((x.hi << s) | (x.lo >> (64 - s)), x.lo << s);
}

static inline udm1_u128 udm1_u128_or64(udm1_u128 x, uint64_t w) { return udm1_u128_make(x.hi, x.lo | w); }

static inline udm1_u128 udm1_u128_muladd64(udm1_u128 x, uint64_t b, uint64_t d)
{
    uint64_t hi, lo;
    udm1_mul64(x.lo, b, &hi, &lo);
    hi += x.hi * b;
    lo += d;
    hi += lo < d;
    return udm1_u128_make(hi, lo);
}

static inline int udm1_u128_lt(udm1_u128 a, udm1_u128 b) { return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo); }

static inline udm1_u128 udm1_u128_sub_(udm1_u128 a, udm1_u128 b)
{
    return udm1_u128_make(a.hi - b.hi - (a.lo < b.lo), a.lo - b.lo);
}

/* The leading zero bits of x > 0. */
static inline unsigned udm1_nlz64_(uint64_t x)
{
    unsigned n = 0;
    if (!(x >> 32)) n += 32, x <<= 32;
    if (!(x >> 48)) n += 16, x <<= 16;
    if (!(x >> 56)) n += 8, x <<= 8;
    if (!(x >> 60)) n += 4, x <<= 4;
    if (!(x >> 62)) n += 2, x <<= 2;
    if (!(x >> 63)) n += 1;
    return n;
}

/* floor((u1 2^64 + u0) / v) for u1 < v (the quotient fits a word), the remainder into *r: the divisor
 * normalized (its top bit set), then two quotient digits of 32 bits, each estimated from the divisor's
 * top digit and corrected at most twice (Knuth, TAOCP vol. 2, 4.3.1, algorithm D). */
static inline uint64_t udm1_divlu_(uint64_t u1, uint64_t u0, uint64_t v, uint64_t *r)
{
    const uint64_t b = 1ull << 32;
    unsigned s = udm1_nlz64_(v);
    v <<= s;
    uint64_t vn1 = v >> 32, vn0 = v & 0xffffffffu;
    uint64_t un32 = s ? (u1 << s) | (u0 >> (64 - s)) : u1, un10 = u0 << s;
    uint64_t un1 = un10 >> 32, un0 = un10 & 0xffffffffu;
    uint64_t q1 = un32 / vn1, rhat = un32 - q1 * vn1;
    while (q1 >= b || q1 * vn0 > b * rhat + un1) {
        --q1;
        rhat += vn1;
        if (rhat >= b) break;
    }
    uint64_t un21 = un32 * b + un1 - q1 * v; /* (modulo 2^64: the true value is below v) */
    uint64_t q0 = un21 / vn1;
    rhat = un21 - q0 * vn1;
    while (q0 >= b || q0 * vn0 > b * rhat + un0) {
        --q0;
        rhat += vn1;
        if (rhat >= b) break;
    }
    *r = (un21 * b + un0 - q0 * v) >> s;
    return q1 * b + q0;
}

static inline udm1_u128 udm1_u128_divmod(udm1_u128 n, udm1_u128 d, udm1_u128 *rem)
{
    uint64_t r;
    if (d.hi == 0) { /* a one-word divisor: at most two word divisions */
        uint64_t qhi = 0, top = n.hi;
        if (top >= d.lo) qhi = top / d.lo, top %= d.lo;
        uint64_t qlo = udm1_divlu_(top, n.lo, d.lo, &r);
        *rem = udm1_u128_make(0, r);
        return udm1_u128_make(qhi, qlo);
    }
    /* a two-word divisor: the quotient fits a word. Its estimate from the divisor's top 64 bits (normalized)
     * and n / 2 is the quotient or one above it after one decrement (Hacker's Delight, 9-5). */
    unsigned s = udm1_nlz64_(d.hi);
    uint64_t v1 = udm1_u128_shl(d, s).hi;
    uint64_t q = udm1_divlu_(n.hi >> 1, (n.hi << 63) | (n.lo >> 1), v1, &r) >> (63 - s);
    if (q) --q;
    uint64_t phi, plo;
    udm1_mul64(q, d.lo, &phi, &plo);
    udm1_u128 left = udm1_u128_sub_(n, udm1_u128_make(q * d.hi + phi, plo)); /* n - q d */
    if (!udm1_u128_lt(left, d)) {
        ++q;
        left = udm1_u128_sub_(left, d);
    }
    *rem = left;
    return udm1_u128_make(0, q);
}
#endif

/* floor(n / d), d > 0 */
static inline udm1_u128 udm1_u128_div(udm1_u128 n, udm1_u128 d)
{
    udm1_u128 rem;
    return udm1_u128_divmod(n, d, &rem);
}

#endif /* UDM1_U128_H */
