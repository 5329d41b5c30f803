/* cmj.c - correlated multi-jittered sampling (Kensler, "Correlated
 * Multi-Jittered Sampling", Pixar Technical Memo 13-01, 2013), the final
 * version of the memo (aspect 1, shuffled order), in integer arithmetic:
 *
 *   m = floor(sqrt(K)), n = ceil(K / m), p = the pattern key
 *   s  = permute(i, K, p * 0x51633e2d)
 *   sx = permute(s mod m, m, p * 0x68bc21eb),  sy = permute(s div m, n, p * 0x02e5be93)
 *   jx = hash(s, p * 0x967a889b),  jy = hash(s, p * 0x368cc8b7)       (32 bits)
 *   x  = (sx + (sy + jx 2^-32) / n) / m,  y = (s + jy 2^-32) / K
 *
 * Each of the m x n strata and each of the K rows (1/K in y) holds one point;
 * when K = m n, each of the K columns as well. Used in pairs: pair k has its own
 * pattern key, from (seed, k) and, when randomized, the stream.
 */
#include "samplers/samplers.h"
#include "seq/scramble.h"

/* Kensler's randfloat, kept as its 32-bit integer */
static uint32_t jitter(uint32_t i, uint32_t p)
{
    i ^= p;
    i ^= i >> 17;
    i ^= i >> 10;
    i *= 0xb36534e5u;
    i ^= i >> 12;
    i ^= i >> 21;
    i *= 0x93fc4795u;
    i ^= 0xdf6e307fu;
    i ^= i >> 17;
    i *= 1u | p >> 18;
    return i;
}

static uint64_t isqrt64(uint64_t k)
{
    uint64_t r = 0, bit = 1ull << 62;
    while (bit > k) bit >>= 2;
    for (; bit; bit >>= 2) {
        if (k >= r + bit) {
            k -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
    }
    return r;
}

static uint64_t cmj_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    uint32_t pair = dim / 2, N = (uint32_t)seq->point_count;
    uint32_t p = udm1_key32(seq->mode == UDM1_MODE_NONE ? seq->seed_key : skey, 0x434D4Au, pair);
    uint32_t m = (uint32_t)isqrt64(N), n = (uint32_t)(((uint64_t)N + m - 1) / m); /* 64-bit: N + m wraps near 2^32 */
    uint32_t s = udm1_permute((uint32_t)index, N, p * 0x51633e2du);
    uint64_t v;
    if ((dim & 1) == 0) {
        uint32_t sx = udm1_permute(s % m, m, p * 0x68bc21ebu);
        uint32_t sy = udm1_permute(s / m, n, p * 0x02e5be93u);
        uint32_t jx = jitter(s, p * 0x967a889bu);
        udm1_u128 num = udm1_u128_or64(udm1_u128_shl(udm1_u128_make(0, (uint64_t)sx * n + sy), 32), jx);
        v = udm1_frac64(num, udm1_u128_shl(udm1_u128_make(0, (uint64_t)m * n), 32));
    } else {
        uint32_t jy = jitter(s, p * 0x368cc8b7u);
        v = udm1_frac64(udm1_u128_make(0, (uint64_t)s << 32 | jy), udm1_u128_make(0, (uint64_t)N << 32));
    }
    return udm1_randomize_base2(seq->mode, v + seq->offset[dim], udm1_word(seq, skey, dim));
}

udm1_status udm1_init_cmj(udm1_seq_t *seq)
{
    (void)seq; /* no tables: a value is computed from its index alone */
    return UDM1_OK;
}

const udm1_kind udm1_cmj_kind = {.name = "cmj", .value = cmj_value};
