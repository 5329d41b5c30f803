/* weyl/weyl.h - the Weyl/Kronecker value: the raw integer arithmetic, the shift a sequence adds for a
 * stream, and the screen-space index scheme. weyl.c holds the Weyl kinds and the bulk kernels.
 *
 * Raw value:             the top 64 bits of (O_j 2^64 + n A_j) mod 2^128, A_j the generator in 0.128
 *                        fixed point (weyl/generators.h), O_j the base offset plus the shift below.
 *
 * UDM1_RANDOMIZE_SHIFT:  point n of stream s is {o_j + r_j(seed, s) + n alpha_j}, r_j a hash (hash.h).
 * UDM1_RANDOMIZE_SCREEN, progressive (desc.screen_spp = 0): stream s = (y << 32) | x names pixel
 *   (x, y); point n of that pixel is
 *       {o_j + u_j(seed) + x G_j + y H_j + n alpha_j},   u_j = mix(S + K_j),
 *   the screen generators G_j, H_j of weyl/screen.h (x G_j + y H_j taken modulo 2^64). Every pixel keeps
 *   the sequence's own points, shifted; the shifts turn each Fourier mode of the error into a plane wave
 *   of high screen frequency, at every sample count (docs/screen-space.md).
 * UDM1_RANDOMIZE_SCREEN, fixed N = desc.screen_spp >= 1: point n of pixel (x, y) is point m N + n of
 *   one randomly shifted sequence:
 *       {o_j + u_j(seed) + (m N + n) alpha_j},
 *   m the pixel's Morton (Z-order) index (the bits of x and y interleaved, x in the even bits) and the
 *   index m N + n taken modulo 2^64. Pixels close on screen are close in Morton order, so a block of
 *   neighbouring pixels holds consecutive segments of one low-discrepancy sequence: together they are
 *   a well-spread set, their errors cancel locally and the error image is blue noise at N samples (the
 *   Z-order scheme of Ahmed and Wonka 2020, pbrt-v4's ZSobol, here exact for Kronecker sequences at any
 *   index). Over seeds u_j is uniform, so every pixel's estimate stays unbiased in both schemes.
 * Like core/hash.h, every step here is part of the ABI. */
#ifndef UDM1_WEYL_H
#define UDM1_WEYL_H

#include "core/hash.h"
#include "seq/seq.h"
#include "weyl/screen.h"

/* Raw value: top 64 bits of (offset * 2^64 + n * A) mod 2^128. */
static inline uint64_t udm1_weyl_raw(const udm1_generator *g, uint64_t offset, uint64_t n)
{
    uint64_t mhi, mlo;
    udm1_mul64(n, g->lo, &mhi, &mlo);
    (void)mlo;
    return n * g->hi + mhi + offset;
}

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
    if (seq->mode == UDM1_MODE_SCREEN)
        return udm1_shift(seq->seed_key, seq->dim_key[dim]) + (seq->screen_spp ? 0 : udm1_screen_pixel_shift(seq, skey, dim));
    return 0;
}

/* The sequence index of point n of a stream: n, or in fixed-N screen mode m N + n (mod 2^64). */
static inline uint64_t udm1_screen_index(const udm1_seq_t *seq, uint64_t skey, uint64_t n)
{
    return seq->mode == UDM1_MODE_SCREEN && seq->screen_spp ? n + udm1_morton(skey) * seq->screen_spp : n;
}

/* Raw value of a Weyl sequence in mode NONE, SHIFT or SCREEN: base offset, shift and index as above. */
static inline uint64_t udm1_weyl_shifted_raw(const udm1_seq_t *seq, uint64_t skey, uint64_t n, uint32_t dim)
{
    return udm1_weyl_raw(&seq->gen[dim], seq->offset[dim] + udm1_weyl_shift(seq, skey, dim),
                         udm1_screen_index(seq, skey, n));
}

/* The kind of Weyl sequences in modes NONE, SHIFT and SCREEN: udm1_weyl_shifted_raw, which the
 * generic code also calls inline (seq/value.h); its bulk fills are udm1_weyl_fill. */
UDM1_HIDDEN extern const udm1_kind udm1_weyl_kind;
/* ... in modes PERMUTE and OWEN: the raw value, then the base-2 randomization of its digits. */
UDM1_HIDDEN extern const udm1_kind udm1_weyl_scrambled_kind;

/* The rank-1 lattice point set {n z / K} (lattice.c): its generators z_j / K into seq->gen. */
UDM1_HIDDEN udm1_status udm1_init_lattice(udm1_seq_t *seq);

/* Output types of the bulk fills. */
enum udm1_out_kind { UDM1_OUT_U64, UDM1_OUT_F64, UDM1_OUT_F32 };
/* Rows [first, first + count) (count >= 1) x dims [dim0, dim0 + ndims) of a sequence of udm1_weyl_kind
 * into out (udm1_out_kind), row i at out + i * stride: exact 128-bit states advanced by additions,
 * equal bit for bit to udm1_weyl_shifted_raw of every entry. Arguments are checked by the caller. */
UDM1_HIDDEN void udm1_weyl_fill(int out_kind, const udm1_seq_t *seq, uint64_t skey, uint64_t first, size_t count,
                                uint32_t dim0, uint32_t ndims, void *out, size_t stride);

#endif /* UDM1_WEYL_H */
