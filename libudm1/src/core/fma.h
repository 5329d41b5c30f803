/* core/fma.h - a b + c rounded once (a fused multiply-add), in double and float, whatever the platform's C
 * library: udm1_fma and udm1_fmaf, the library's only calls of a fused multiply-add (cellular noise).
 *
 *  - The C library's fma and fmaf (a single instruction where the compiler targets FMA: every AArch64,
 *    x86-64 with FMA), on platforms whose C library rounds them once: glibc, Apple's, the BSDs'.
 *  - An exact emulation on Windows without FMA targeted (and wherever UDM1_FMA_EMULATED is defined, so that
 *    tests/c/test_fma.c checks it everywhere): MinGW-w64's fma and fmaf are not rounded once (measured under
 *    Wine with Debian's MinGW-w64 10: 22 % of doubles and 27 % of floats with operands in (-1, 1) differ
 *    from the FMA instruction's), and the values of a Windows build must equal every other build's. The emulation is
 *    integer arithmetic: the operands' significands as integers, the product's 106 bits and the addend
 *    aligned in 128 bits (bits shifted out kept as a sticky bit), one rounding to nearest-even at the
 *    result's precision - normal or subnormal, overflow to infinity; infinities and NaN as a b + c gives
 *    them. Not installed. */
#ifndef UDM1_FMA_H
#define UDM1_FMA_H

#include "core/bits.h"
#include "core/u128.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#if defined(_WIN32) && !defined(__FMA__) && !defined(__AVX2__) && !defined(UDM1_FMA_EMULATED)
#  define UDM1_FMA_EMULATED 1
#endif

#if defined(UDM1_FMA_EMULATED)
/* x = m 2^e with m a whole number below 2^53 (subnormals included); x finite and not 0 */
static inline uint64_t udm1_fma_split_(double x, int *e)
{
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    int be = (int)((b >> 52) & 0x7FF);
    uint64_t m = b & ((1ull << 52) - 1);
    if (be) m |= 1ull << 52;
    *e = (be ? be : 1) - 1075;
    return m;
}

/* The index of the leading bit of the 128-bit word (hi, lo), not 0. */
static inline int udm1_fma_top_(uint64_t hi, uint64_t lo)
{
    uint64_t x = hi ? hi : lo;
    int n = udm1_top_bit64(x);
    return hi ? 64 + n : n;
}

/* (hi, lo) shifted left by s bits, 0 <= s < 128 */
static inline void udm1_fma_shl_(uint64_t *hi, uint64_t *lo, int s)
{
    if (s >= 64) *hi = *lo << (s - 64), *lo = 0;
    else if (s > 0) *hi = (*hi << s) | (*lo >> (64 - s)), *lo <<= s;
}

/* (hi, lo) shifted right by s >= 0 bits, any bit shifted out ORed into bit 0 (sticky) */
static inline void udm1_fma_shr_sticky_(uint64_t *hi, uint64_t *lo, int s)
{
    uint64_t h = *hi, l = *lo, lost;
    if (s <= 0) return;
    if (s >= 128) {
        lost = h | l, h = 0, l = 0;
    } else if (s >= 64) {
        lost = l | (s > 64 ? h << (128 - s) : 0);
        l = s == 64 ? h : h >> (s - 64), h = 0;
    } else {
        lost = l << (64 - s);
        l = (l >> s) | (h << (64 - s)), h >>= s;
    }
    *hi = h, *lo = l | (lost != 0);
}

/* a b + c (finite, none 0) rounded once to nearest-even in a binary format of p significant bits whose
 * smallest subnormal is 2^emin and whose finite values are below 2^(emax + 1): double (53, -1074, 1023),
 * float (24, -149, 127; the operands floats widened to double, exactly). The product (below 2^106) and the
 * addend are each moved up to a leading bit 124; the one of smaller exponent is moved down to the other's,
 * the bits it loses kept as a sticky bit 0 (it loses some only when moved more than 19 places, and then
 * the sum keeps its leading bit at 123 or above, so the sticky bit lies far below the rounding). */
static inline double udm1_fma_round_(double a, double b, double c, int p, int emin, int emax)
{
    int ea, eb, ec;
    uint64_t ma = udm1_fma_split_(a, &ea), mb = udm1_fma_split_(b, &eb), mc = udm1_fma_split_(c, &ec);
    int sp = (a < 0) != (b < 0), sc = c < 0;
    uint64_t xh, xl, yh = 0, yl = mc;
    udm1_mul64(ma, mb, &xh, &xl);
    int sx = 124 - udm1_fma_top_(xh, xl), sy = 124 - udm1_fma_top_(yh, yl);
    udm1_fma_shl_(&xh, &xl, sx);
    udm1_fma_shl_(&yh, &yl, sy);
    int ex = ea + eb - sx, ey = ec - sy, e;
    if (ex >= ey) {
        udm1_fma_shr_sticky_(&yh, &yl, ex - ey);
        e = ex;
    } else {
        udm1_fma_shr_sticky_(&xh, &xl, ey - ex);
        e = ey;
    }
    uint64_t zh, zl;
    int sz;
    if (sp == sc) {
        zl = xl + yl, zh = xh + yh + (zl < xl), sz = sp;
    } else if (xh > yh || (xh == yh && xl >= yl)) {
        zl = xl - yl, zh = xh - yh - (xl < yl), sz = sp;
    } else {
        zl = yl - xl, zh = yh - xh - (yl < xl), sz = sc;
    }
    if (!(zh | zl)) return 0.0; /* an exact 0 of a sum of opposite signs: +0 when rounding to nearest */
    /* z 2^e: its leading bit L; the lowest bit kept, q: p bits from L down, or the one of 2^emin */
    int L = udm1_fma_top_(zh, zl);
    if (L + e > emax) return sz ? -INFINITY : INFINITY;
    int q = L - (p - 1) > emin - e ? L - (p - 1) : emin - e;
    double r;
    if (q <= 0) { /* exact: below 2^p, no bit under 2^emin */
        r = ldexp((double)zl, e);
    } else {
        /* m = z >> q (below 2^p), and z's bits below bit q (rh, rl) against half of bit q (hh, hl) */
        uint64_t m = q >= 64 ? zh >> (q - 64) : (zl >> q) | (zh << (64 - q)), rh = zh, rl = zl;
        if (q < 64) rh = 0, rl &= (1ull << q) - 1;
        else if (q < 128) rh &= (1ull << (q - 64)) - 1;
        uint64_t hh = q > 64 ? 1ull << (q - 65) : 0, hl = q > 64 ? 0 : 1ull << (q - 1);
        int up = rh > hh || (rh == hh && rl > hl) || (rh == hh && rl == hl && (m & 1));
        r = ldexp((double)(m + (uint64_t)up), e + q); /* exact: at most 2^p, no bit under 2^emin */
    }
    return sz ? -r : r;
}
#endif

static inline double udm1_fma(double a, double b, double c)
{
#if defined(UDM1_FMA_EMULATED)
    if (isfinite(a) && isfinite(b) && !isfinite(c)) return c; /* (the exact product is finite) */
    if (!isfinite(a) || !isfinite(b)) return a * b + c;        /* infinities, NaN */
    if (a == 0 || b == 0) return a * b + c; /* an exact product of 0: the sum as IEEE 754 adds */
    if (c == 0) return a * b;                /* the product rounded once, its sign kept */
    return udm1_fma_round_(a, b, c, 53, -1074, 1023);
#else
    return fma(a, b, c);
#endif
}

static inline float udm1_fmaf(float a, float b, float c)
{
#if defined(UDM1_FMA_EMULATED)
    if (isfinite(a) && isfinite(b) && !isfinite(c)) return c;
    if (!isfinite(a) || !isfinite(b) || a == 0 || b == 0) return a * b + c;
    if (c == 0) return (float)((double)a * b); /* exact in double, rounded once to float */
    return (float)udm1_fma_round_(a, b, c, 24, -149, 127); /* (exact: a float's value in double) */
#else
    return fmaf(a, b, c);
#endif
}

#endif /* UDM1_FMA_H */
