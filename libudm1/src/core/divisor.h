/* core/divisor.h - exact division by a divisor fixed in advance, by multiplications: what the radical
 * inverses divide by per digit (the base b) and per value (a power b^s).
 *
 *  udm1_divisor          a 64-bit divisor m >= 1, normalized (m << shift has its top bit set), with its
 *                        reciprocal v = floor((2^128 - 1) / (m << shift)) - 2^64
 *  udm1_divide_by        floor((u1 2^64 + u0) / m) for u1 < m: Moller and Granlund, "Improved division by
 *                        invariant integers" (IEEE Trans. Computers, 2011), algorithm 4: one 64 x 64-bit
 *                        product and at most two corrections
 *  udm1_mod32_magic      ceil(2^64 / d) for 2 <= d < 2^32: x mod d and floor(x / d) of every 32-bit x by
 *                        products (Lemire, Kaser and Kurz, "Faster remainder by direct computation",
 *                        Software: Practice and Experience, 2019)
 *
 * The values are the hardware division's, bit for bit (tests/c/test_radical_inverse.c checks them against
 * it). */
#ifndef UDM1_DIVISOR_H
#define UDM1_DIVISOR_H

#include "core/bits.h"
#include "core/u128.h"

#include <stdint.h>

typedef struct udm1_divisor {
    uint64_t d;     /* m << shift */
    uint64_t v;     /* the reciprocal of d */
    unsigned shift; /* the leading zero bits of m */
} udm1_divisor;

static inline udm1_divisor udm1_divisor_make(uint64_t m)
{
    udm1_divisor dv;
    dv.shift = 63u - (unsigned)udm1_top_bit64(m);
    dv.d = m << dv.shift;
    /* (2^128 - 1 - d 2^64) / d = floor((2^128 - 1) / d) - 2^64, below 2^64 for d >= 2^63 */
    dv.v = udm1_u128_lo(udm1_u128_div(udm1_u128_make(~dv.d, ~0ull), udm1_u128_make(0, dv.d)));
    return dv;
}

/* floor((u1 2^64 + u0) / m), u1 < m */
static inline uint64_t udm1_divide_by(const udm1_divisor *dv, uint64_t u1, uint64_t u0)
{
    uint64_t d = dv->d;
    if (dv->shift) {
        u1 = (u1 << dv->shift) | (u0 >> (64u - dv->shift));
        u0 <<= dv->shift;
    }
    uint64_t q1, q0;
    udm1_mul64(dv->v, u1, &q1, &q0);
    q0 += u0;
    q1 += u1 + 1u + (q0 < u0);
    uint64_t r = u0 - q1 * d;
    if (r > q0) { /* (the estimate one too large) */
        --q1;
        r += d;
    }
    if (r >= d) ++q1; /* (one too small, rarely) */
    return q1;
}

static inline uint64_t udm1_mod32_magic(uint32_t d) { return UINT64_MAX / d + 1u; }

/* x mod d, with magic = udm1_mod32_magic(d) */
static inline uint32_t udm1_mod32(uint32_t x, uint32_t d, uint64_t magic)
{
    uint64_t hi, lo;
    udm1_mul64(magic * x, d, &hi, &lo);
    return (uint32_t)hi;
}

/* floor(x / d), with magic = udm1_mod32_magic(d) */
static inline uint32_t udm1_div32(uint32_t x, uint64_t magic)
{
    uint64_t hi, lo;
    udm1_mul64(magic, x, &hi, &lo);
    return (uint32_t)hi;
}

#endif /* UDM1_DIVISOR_H */
