/* screen_shift.h - the shift a Weyl sequence adds for a stream, and the screen-space index scheme.
 *
 * UDM1_RANDOMIZE_SHIFT:  point n of stream s is {o_j + r_j(seed, s) + n alpha_j}, r_j a hash (hash.h).
 * UDM1_RANDOMIZE_SCREEN: stream s = (y << 32) | x names pixel (x, y); with N = desc.screen_spp, point
 *   n of that pixel is point m N + n of one randomly shifted sequence:
 *       {o_j + u_j(seed) + (m N + n) alpha_j},   u_j = mix(S + K_j),
 *   m the pixel's Morton (Z-order) index (the bits of x and y interleaved, x in the even bits) and the
 *   index m N + n taken modulo 2^64. Pixels close on screen are close in Morton order, so a block of
 *   neighbouring pixels holds consecutive segments of one low-discrepancy sequence: together they are
 *   a well-spread set, their errors cancel locally and the error image is blue noise (the Z-order
 *   scheme of Ahmed and Wonka 2020, pbrt-v4's ZSobol, here exact for Kronecker sequences at any
 *   index). Over seeds u_j is uniform, so every pixel's estimate stays unbiased.
 * Like hash.h, every step here is part of the ABI. */
#ifndef UDM1_SCREEN_SHIFT_H
#define UDM1_SCREEN_SHIFT_H

#include "hash.h"
#include "internal.h"

/* Spread the low 32 bits of v to the even bits. */
static inline uint64_t udm1_spread_bits(uint64_t v)
{
    v &= 0xFFFFFFFFull;
    v = (v | (v << 16)) & 0x0000FFFF0000FFFFull;
    v = (v | (v << 8)) & 0x00FF00FF00FF00FFull;
    v = (v | (v << 4)) & 0x0F0F0F0F0F0F0F0Full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    v = (v | (v << 1)) & 0x5555555555555555ull;
    return v;
}

/* Morton index of stream = (y << 32) | x. */
static inline uint64_t udm1_morton(uint64_t stream)
{
    return udm1_spread_bits(stream) | (udm1_spread_bits(stream >> 32) << 1);
}

/* The per-stream key a sequence derives from a stream id: a hash, or in screen mode the stream itself
 * (its index segment is a function of the pixel's position; padding still hashes it). */
static inline uint64_t udm1_seq_stream_key(const udm1_seq_t *seq, uint64_t stream)
{
    return seq->mode == UDM1_MODE_SCREEN ? stream : udm1_stream_key(seq->seed_key, stream);
}

/* The shift of dimension dim for a stream key (0 without randomization). Weyl sequences only. */
static inline uint64_t udm1_weyl_shift(const udm1_seq_t *seq, uint64_t skey, uint32_t dim)
{
    if (seq->mode == UDM1_MODE_SHIFT) return udm1_shift(skey, seq->dim_key[dim]);
    if (seq->mode == UDM1_MODE_SCREEN) return udm1_shift(seq->seed_key, seq->dim_key[dim]);
    return 0;
}

/* The sequence index of point n of a stream: n, or in screen mode m N + n (mod 2^64). */
static inline uint64_t udm1_screen_index(const udm1_seq_t *seq, uint64_t skey, uint64_t n)
{
    return seq->mode == UDM1_MODE_SCREEN ? n + udm1_morton(skey) * seq->screen_spp : n;
}

/* Raw value of a Weyl sequence in mode NONE, SHIFT or SCREEN: base offset, shift and index as above. */
static inline uint64_t udm1_weyl_shifted_raw(const udm1_seq_t *seq, uint64_t skey, uint64_t n, uint32_t dim)
{
    return udm1_weyl_raw(&seq->gen[dim], seq->offset[dim] + udm1_weyl_shift(seq, skey, dim),
                         udm1_screen_index(seq, skey, n));
}

#endif
