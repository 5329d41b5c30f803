/* generators.c - exact 0.128 fixed-point generators: square roots, quadratic
 * irrationals, R_d roots, primes and square-free parts.
 *
 * Square roots are exact: A = round(frac(alpha) * 2^128) is obtained from an
 * integer square root with remainder, so the rounding is decided exactly.
 * R_d roots are found by bisection in 0.256 fixed point (error far below
 * 2^-200) and then rounded to 128 bits. tests/python/test_exact.py checks
 * every generator bit for bit against mpmath / math.isqrt.
 */
#include "weyl/generators.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- small unsigned big integers, little-endian 64-bit limbs ---- */

#define MP_LIMBS 6 /* 384 bits: enough for b^2 k 4^128 with k < 2^64, b < 2^32 */

typedef struct mp { uint64_t w[MP_LIMBS]; } mp;

static int mp_cmp(const mp *a, const mp *b)
{
    for (int i = MP_LIMBS - 1; i >= 0; --i)
        if (a->w[i] != b->w[i]) return a->w[i] < b->w[i] ? -1 : 1;
    return 0;
}

static void mp_add(mp *a, const mp *b)
{
    uint64_t carry = 0;
    for (int i = 0; i < MP_LIMBS; ++i) {
        uint64_t s = a->w[i] + b->w[i];
        uint64_t c1 = s < a->w[i];
        uint64_t t = s + carry;
        carry = c1 | (t < s);
        a->w[i] = t;
    }
}

static void mp_sub(mp *a, const mp *b)
{
    uint64_t borrow = 0;
    for (int i = 0; i < MP_LIMBS; ++i) {
        uint64_t d = a->w[i] - b->w[i];
        uint64_t b1 = a->w[i] < b->w[i];
        uint64_t t = d - borrow;
        borrow = b1 | (d < borrow);
        a->w[i] = t;
    }
}

static void mp_shr(mp *a, unsigned s) /* 0 < s < 64 */
{
    for (int i = 0; i < MP_LIMBS; ++i) {
        uint64_t next = i + 1 < MP_LIMBS ? a->w[i + 1] : 0;
        a->w[i] = (a->w[i] >> s) | (next << (64 - s));
    }
}

static int mp_is_zero(const mp *a)
{
    for (int i = 0; i < MP_LIMBS; ++i)
        if (a->w[i]) return 0;
    return 1;
}

/* a *= m (single limb); the product must fit. */
static void mp_mul1(mp *a, uint64_t m)
{
    uint64_t carry = 0;
    for (int i = 0; i < MP_LIMBS; ++i) {
        uint64_t hi, lo;
        udm1_mul64(a->w[i], m, &hi, &lo);
        lo += carry;
        hi += lo < carry;
        a->w[i] = lo;
        carry = hi;
    }
}

static int mp_bits(const mp *a)
{
    for (int i = MP_LIMBS - 1; i >= 0; --i)
        if (a->w[i]) {
            int b = 64;
            uint64_t v = a->w[i];
            while (!(v >> 63)) { v <<= 1; --b; }
            return i * 64 + b;
        }
    return 0;
}

/* q = round-to-nearest(sqrt(n)); returns 1 if n is a perfect square. */
static int mp_isqrt_round(const mp *n, mp *q)
{
    mp rem = *n, res, bit, t;
    memset(&res, 0, sizeof res);
    memset(&bit, 0, sizeof bit);
    int top = mp_bits(n);
    if (top == 0) { *q = res; return 1; }
    int pos = (top - 1) & ~1; /* highest even bit position <= msb */
    bit.w[pos / 64] = 1ull << (pos % 64);
    while (!mp_is_zero(&bit)) {
        t = res;
        mp_add(&t, &bit);
        if (mp_cmp(&rem, &t) >= 0) {
            mp_sub(&rem, &t);
            mp_shr(&res, 1);
            mp_add(&res, &bit);
        } else {
            mp_shr(&res, 1);
        }
        mp_shr(&bit, 2);
    }
    int exact = mp_is_zero(&rem);
    /* sqrt(n) >= res + 1/2  <=>  n - res^2 >= res + 1/4  <=>  rem > res */
    if (mp_cmp(&rem, &res) > 0) {
        mp one;
        memset(&one, 0, sizeof one);
        one.w[0] = 1;
        mp_add(&res, &one);
    }
    *q = res;
    return exact;
}

static uint64_t isqrt64(uint64_t k)
{
    uint64_t r = 0, bit = 1ull << 62;
    while (bit > k) bit >>= 2;
    while (bit) {
        if (k >= r + bit) {
            k -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    return r;
}

int udm1_gen_quadratic(int64_t a, uint64_t b, uint64_t k, uint64_t c, udm1_generator *g)
{
    /* value = (a + b sqrt(k)) / c, c = 2^e. round(frac(value) * 2^128)
     *       = (a 2^(128-e) + round(sqrt(b^2 k 4^(128-e)))) mod 2^128. */
    unsigned e = 0;
    while ((1ull << e) < c) ++e;
    if (c == 0 || (1ull << e) != c || e > 2 || b == 0 || b > 0xFFFFFFFFull) return 0;
    uint64_t r = isqrt64(k);
    if (r * r == k) return 0; /* rational */
    mp n, q;
    memset(&n, 0, sizeof n);
    n.w[0] = k;
    mp_mul1(&n, b);
    mp_mul1(&n, b);
    /* shift left by 2 (128 - e) bits = whole limbs plus a remainder */
    unsigned sh = 2 * (128 - e);
    mp s;
    memset(&s, 0, sizeof s);
    for (int i = 0; i < MP_LIMBS; ++i) {
        int dst = i + (int)(sh / 64);
        if (dst < MP_LIMBS) s.w[dst] |= n.w[i] << (sh % 64);
        if (sh % 64 && dst + 1 < MP_LIMBS) s.w[dst + 1] |= n.w[i] >> (64 - sh % 64);
    }
    mp_isqrt_round(&s, &q);
    uint64_t lo = q.w[0], hi = q.w[1];
    /* add a * 2^(128-e) modulo 2^128 (two's complement for negative a) */
    if (e == 0) {
        /* a * 2^128 = 0 mod 2^128 */
    } else {
        uint64_t add_hi = (uint64_t)a << (64 - e);
        hi += add_hi;
    }
    g->hi = hi;
    g->lo = lo;
    g->nature = UDM1_NATURE_QUADRATIC;
    g->radical = udm1_squarefree_part(k);
    return 1;
}

int udm1_gen_sqrt(uint64_t k, udm1_generator *g)
{
    if (k < 2) return 0;
    return udm1_gen_quadratic(0, 1, k, 1, g);
}

uint64_t udm1_squarefree_part(uint64_t k)
{
    if (k == 0) return 0;
    uint64_t m = 1, rest = k, p = 2;
    for (; p * p * p <= rest; p += (p == 2 ? 1 : 2)) {
        unsigned mult = 0;
        while (rest % p == 0) { rest /= p; ++mult; }
        if (mult & 1) m *= p;
    }
    /* rest has no prime factor below p > cbrt(rest): it is 1, q, q r or q^2 */
    uint64_t r = isqrt64(rest);
    if (r * r == rest) return m;
    return m * rest;
}

int udm1_first_primes(uint32_t count, uint64_t *out)
{
    if (count == 0) return 1;
    /* p_n < n (ln n + ln ln n) for n >= 6 */
    double n = count < 6 ? 6.0 : (double)count;
    size_t limit = (size_t)(n * (log(n) + log(log(n)))) + 16;
    unsigned char *composite = calloc(limit + 1, 1);
    if (!composite) return 0;
    uint32_t found = 0;
    for (size_t i = 2; i <= limit && found < count; ++i) {
        if (composite[i]) continue;
        out[found++] = i;
        for (size_t j = i * i; j <= limit; j += i) composite[j] = 1;
    }
    free(composite);
    return found == count;
}

/* ---- R_d: 0.256 fixed-point fractions ---- */

typedef struct frac256 { uint64_t w[4]; } frac256; /* value = w / 2^256 */

static frac256 frac_mul(const frac256 *a, const frac256 *b)
{
    uint64_t prod[8] = {0};
    for (int i = 0; i < 4; ++i) {
        uint64_t carry = 0;
        for (int j = 0; j < 4; ++j) {
            uint64_t hi, lo;
            udm1_mul64(a->w[i], b->w[j], &hi, &lo);
            lo += carry;
            hi += lo < carry;
            uint64_t s = prod[i + j] + lo;
            hi += s < lo;
            prod[i + j] = s;
            carry = hi;
        }
        prod[i + 4] = carry;
    }
    frac256 r;
    for (int i = 0; i < 4; ++i) r.w[i] = prod[i + 4];
    return r;
}

static frac256 frac_pow(const frac256 *g, uint32_t e) /* e >= 1 */
{
    frac256 result = *g, base = *g;
    int have = 0;
    while (e) {
        if (e & 1) {
            result = have ? frac_mul(&result, &base) : base;
            have = 1;
        }
        e >>= 1;
        if (e) base = frac_mul(&base, &base);
    }
    return result;
}

/* Returns 1 if p + p*g >= 1 (as a 257-bit sum), i.e. g^d (1 + g) >= 1. */
static int rd_at_or_above(const frac256 *g, uint32_t d)
{
    frac256 p = frac_pow(g, d);
    frac256 pg = frac_mul(&p, g);
    uint64_t carry = 0;
    for (int i = 0; i < 4; ++i) {
        uint64_t s = p.w[i] + pg.w[i];
        uint64_t c1 = s < p.w[i];
        uint64_t t = s + carry;
        carry = c1 | (t < s);
    }
    return carry != 0;
}

static void round_to_128(const frac256 *f, udm1_generator *g)
{
    uint64_t lo = f->w[2], hi = f->w[3];
    if (f->w[1] >> 63) { /* round half up; ties cannot occur for irrationals */
        ++lo;
        if (lo == 0) ++hi;
    }
    g->hi = hi;
    g->lo = lo;
}

int udm1_gen_rd(uint32_t d, udm1_generator *out)
{
    /* g = 1/phi_d is the root in (1/2, 1) of g^d (1 + g) = 1. Bisection, bit by bit. */
    frac256 g;
    memset(&g, 0, sizeof g);
    for (int bit = 255; bit >= 0; --bit) {
        frac256 t = g;
        t.w[bit / 64] |= 1ull << (bit % 64);
        if (!rd_at_or_above(&t, d)) g = t;
    }
    frac256 power = g;
    for (uint32_t j = 0; j < d; ++j) {
        round_to_128(&power, &out[j]);
        out[j].nature = UDM1_NATURE_INDEPENDENT;
        out[j].radical = 0;
        if (j + 1 < d) power = frac_mul(&power, &g);
    }
    return 1;
}
