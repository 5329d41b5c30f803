/* scramble.h - hashed permutations and scramblings shared by the samplers.
 *
 *  udm1_permute(i, l, p)  a pseudo-random permutation of [0, l), keyed by p:
 *                         Kensler's "permute" (Correlated Multi-Jittered
 *                         Sampling, Pixar TM 13-01, 2013), cycle-walking hash.
 *  udm1_owen32(x, seed)   nested uniform (Owen) scrambling of 32 binary digits
 *                         by hashing (Burley, "Practical Hash-based Owen
 *                         Scrambling", JCGT 2020), with the Laine-Karras style
 *                         hash improved by Vegdahl (2021), as pbrt-v4 and
 *                         OpenQMC use it.
 *  udm1_owen64(v, r)      Owen scrambling of a 0.64 value: the top 32 digits
 *                         by udm1_owen32, the lower 32 filled uniformly from a
 *                         hash of the scrambled top (Owen scrambling to full
 *                         depth is uniform below the last distinct digit).
 */
#ifndef UDM1_SCRAMBLE_H
#define UDM1_SCRAMBLE_H

#include "core/hash.h"
#include "seq/seq.h"

#include <stdint.h>

/* udm1_permute's mask of l > 0: l - 1 with every bit below its top bit set */
static inline uint32_t udm1_permute_mask(uint32_t l)
{
    uint32_t w = l - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    return w;
}

/* One step of udm1_permute's cycle walk: a bijection of [0, w] (w its mask) */
static inline uint32_t udm1_permute_step(uint32_t i, uint32_t w, uint32_t p)
{
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
    return i;
}

/* udm1_permute before its final rotation by p: the cycle walk of i's hash below l (w its mask) */
static inline uint32_t udm1_permute_walk(uint32_t i, uint32_t l, uint32_t w, uint32_t p)
{
    do i = udm1_permute_step(i, w, p);
    while (i >= l);
    return i;
}

static inline uint32_t udm1_permute(uint32_t i, uint32_t l, uint32_t p)
{
    return (uint32_t)(((uint64_t)udm1_permute_walk(i, l, udm1_permute_mask(l), p) + p) % l);
}

static inline uint64_t udm1_reverse64(uint64_t x)
{
    return ((uint64_t)udm1_reverse32((uint32_t)x) << 32) | udm1_reverse32((uint32_t)(x >> 32));
}

/* udm1_reverse32, udm1_owen_hash32 and udm1_owen_index32 (an Owen scramble of 32 bits) are public:
 * udm1/domain.h, where the domains' index permutation uses them. */
static inline uint32_t udm1_owen32(uint32_t x, uint32_t seed) { return udm1_owen_index32(x, seed); }

static inline uint64_t udm1_owen64(uint64_t v, uint64_t r)
{
    uint32_t top = udm1_owen32((uint32_t)(v >> 32), (uint32_t)r);
    uint32_t low = (uint32_t)udm1_mix64(((uint64_t)top << 32 | (uint32_t)(r >> 32)) ^ 0x4F57454E00000000ull);
    return (uint64_t)top << 32 | low;
}

/* udm1_owen64 of v[j], r[j] into out[j] for j < n, four at a time where the instruction set allows
 * (owen_simd.c): the same values; with low_half 0 only their top 32 bits (the low half 0), which is
 * all a float conversion reads. */
UDM1_HIDDEN void udm1_owen64_many(const uint64_t *v, const uint64_t *r, uint64_t *out, uint32_t n, int low_half);

/* udm1_mix64(in[j] + add) into out[j] for j < n, four at a time where the instruction set allows: the
 * words udm1_shift(key, K_j) of n dimensions at once (in = their keys K_j, add = the stream key). */
UDM1_HIDDEN void udm1_mix64_many(const uint64_t *in, uint64_t add, uint64_t *out, uint32_t n);

/* Randomize a value whose digits are binary (Weyl, Sobol, i/K, ...). */
static inline uint64_t udm1_randomize_base2(uint32_t mode, uint64_t v, uint64_t r)
{
    switch (mode) {
    case UDM1_MODE_SHIFT: return v + r;
    case UDM1_MODE_PERMUTE: return v ^ r;
    case UDM1_MODE_OWEN: return udm1_owen64(v, r);
    default: return v;
    }
}

/* The random word r_j of a dimension for a stream (0 without randomization). */
static inline uint64_t udm1_word(const udm1_seq_t *seq, uint64_t stream_key, uint32_t dim)
{
    /* (the modes that use no word: none, and the PRNGs' and patterns' plain streams) */
    return seq->mode == UDM1_MODE_NONE || seq->mode == UDM1_MODE_STREAMS ? 0 : udm1_shift(stream_key, seq->dim_key[dim]);
}

/* A 32-bit key of (seed, what, k): patterns and per-pair index permutations. */
static inline uint32_t udm1_key32(uint64_t seed_key, uint64_t what, uint64_t k)
{
    return (uint32_t)udm1_mix64(seed_key ^ udm1_mix64(what * 0x9E3779B97F4A7C15ull + k));
}

/* The point of pair k of a "pairs" point set: pair 0 in order, pairs k >= 1
 * through a hashed permutation of the K indices keyed by (seed, k). */
static inline uint64_t udm1_pair_index(const udm1_seq_t *seq, uint32_t pair, uint64_t index)
{
    if (pair == 0) return index;
    return udm1_permute((uint32_t)index, (uint32_t)seq->point_count, udm1_key32(seq->seed_key, 0x50414952u, pair));
}

/* floor(num 2^64 / den) exactly, for a fraction num / den < 1 with den < 2^96:
 * two long-division steps of 32 bits each, so nothing overflows 128 bits. */
static inline uint64_t udm1_frac64(udm1_u128 num, udm1_u128 den)
{
    udm1_u128 r1;
    udm1_u128 q1 = udm1_u128_divmod(udm1_u128_shl(num, 32), den, &r1);
    udm1_u128 q0 = udm1_u128_div(udm1_u128_shl(r1, 32), den);
    return (udm1_u128_lo(q1) << 32) | udm1_u128_lo(q0);
}

#endif /* UDM1_SCRAMBLE_H */
