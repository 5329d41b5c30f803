/*
 * udm1/stream.h - one stream of a sequence, ready to draw per sample without a library call: a
 * renderer's pixel. Part of libudm1's public interface; udm1/udm1.h includes every part. (1.6)
 *
 * A renderer asks for a few dimensions of one (pixel, sample) at a time. A call into the shared library
 * per value costs more than the value (a Weyl value is two multiplications), so udm1_stream_init fills,
 * once per stream, what each of its dimensions needs - for a Weyl sequence the generator A_j and the
 * stream's offset O_j = o_j + r_j(seed, stream) of the sequence contract (udm1/seq.h) - and the draws
 * below are static inline: the documented integer arithmetic on this struct, in the caller's code,
 * where the compiler can keep it in registers and vectorize it over dimensions.
 *
 *     udm1_stream px;                                      // about 1.7 KB, on the stack or in a tile
 *     udm1_stream_init(&px, seq, ((uint64_t)y << 32) | x, 0, 32);   // once per pixel: dims 0..31
 *     for (uint64_t i = 0; i < spp; ++i) {
 *         float film[2];  udm1_stream_draw_f32(&px, i, 0, 2, film);    // dimensions 0, 1 of sample i
 *         ...
 *     }
 *
 * The values are those of the sequence, bit for bit: udm1_seq_sample_*, the fills, the cursor and
 * udm1_seq_fill_points_f64 give the same (the contract's exactness, conversions and padding included).
 * The inline arithmetic is used where the struct says it applies (flags & UDM1_STREAM_INLINE: a Weyl
 * sequence without a transform, in modes none, shift or screen) and the dimensions asked are among the
 * `held` ones (the sequence's own, not padded); every other case - the other sampler kinds, the tent, digit scrambling, dimensions
 * outside [first, first + count), an index outside a point set - goes through udm1_stream_fill_raw, one
 * library call for the whole draw (for a PRNG one seek for all its values). Those draws are no less
 * exact, only not inline.
 *
 * A udm1_stream refers to its sequence (which must outlive it) and is not changed by drawing: one may be
 * shared by any number of threads. It holds no allocation: no cleanup.
 */
#ifndef UDM1_STREAM_H
#define UDM1_STREAM_H

#include "udm1/seq.h"

#include <math.h>

/* The draws, the domains' derivations and every helper they call are forced inline where the compiler
 * allows it: a call per draw would cost more than the values (measured: a 4D Weyl draw 0.6 ns per
 * dimension inline, 1.1 ns when the compiler chose a call; GCC left a domain draw's helpers as calls in a
 * renderer's loop, 1.7x its time); their library calls are kept out of line (UDM1_COLD_), so that a
 * domain passed by value stays in registers. */
#if defined(__GNUC__) || defined(__clang__)
#define UDM1_DRAW_ static inline __attribute__((always_inline))
#define UDM1_COLD_ static __attribute__((noinline, cold, unused))
#elif defined(_MSC_VER)
#define UDM1_DRAW_ static __forceinline
#define UDM1_COLD_ static __declspec(noinline)
#else
#define UDM1_DRAW_ static inline
#define UDM1_COLD_ static inline
#endif

/* The inline draws use x86 vector instructions where the compiler targets them (SSE2, x86-64's baseline;
 * SSSE3, SSE4.1, AVX2, GFNI, AVX-512 where enabled) and NEON on 64-bit Arm (AArch64's baseline). Defined before
 * udm1/udm1.h is included, UDM1_INLINE_SCALAR gives the portable scalar code instead: the same values (the
 * tests build both). The header compiles as C99 and C++ with GCC, Clang and MSVC. */
#if !defined(UDM1_INLINE_SCALAR) && (defined(__x86_64__) || defined(_M_X64)) && (defined(__SSE2__) || defined(_MSC_VER))
#define UDM1_X86_ 1
#include <immintrin.h>
#if defined(__AVX2__)
#define UDM1_AVX2_ 1
#endif
#elif !defined(UDM1_INLINE_SCALAR) && (defined(__aarch64__) || defined(_M_ARM64)) && !defined(_M_ARM64EC)
#define UDM1_NEON_ 1
#include <arm_neon.h>
#endif

/* The top half of a 64 x 64-bit product: the compiler's unsigned __int128 where it has one, __umulh on
 * MSVC (x64, ARM64), 32-bit halves elsewhere; defined before udm1/udm1.h is included,
 * UDM1_PORTABLE_INT128 gives the code without __int128 (what MSVC compiles) with any compiler. */
#if defined(__SIZEOF_INT128__) && !defined(UDM1_PORTABLE_INT128)
#define UDM1_MULHI_INT128_ 1
#elif defined(_MSC_VER) && (defined(_M_X64) || defined(_M_ARM64))
#define UDM1_MULHI_UMULH_ 1
#include <intrin.h>
#endif

/* The dimensions one udm1_stream holds (more: several streams, or draws through the library). */
#define UDM1_STREAM_DIMS 64u
/* udm1_stream.flags: which inline arithmetic applies to the dimensions it holds. Each flag also names the
 * layout of the data it reads: a later library that changes a layout sets another flag, and code
 * compiled against this header then draws through the library instead.
 *   UDM1_STREAM_INLINE  a Weyl sequence: a_hi, a_lo, offset (the contract's arithmetic)
 *   UDM1_STREAM_PMJ02   pmj02 without randomization or with its digital shift: `table` holds the (0,2)
 *                       coordinates as 32-bit fractions in blocks of four dimensions, [blocks][K][4]
 *                       (blocks = ceil(dimensions / 4); a point's four side by side; each pair in the
 *                       order its indices read it), then XORed with the word in offset
 *   UDM1_STREAM_SOBOL   Sobol (Gray-code order) of the sequence's first table_dims dimensions and indices
 *                       below 2^32: `table` holds [dim][4][256] 64-bit words, the XOR of the direction
 *                       numbers 8k .. 8k + 7 selected by byte k of the Gray code; then the randomization
 *                       table_mode names with the word in offset
 * (table_mode: 0 none, 1 XOR with the word, 2 Owen scrambling keyed by the word, seq/scramble.h's)
 * Two more bits, C = (flags / UDM1_STREAM_CHILDREN) & 3, say that the stream holds the child domains a
 * renderer derives in every sample (udm1/domain.h): for each of the B = ceil(held / 4) blocks b of four
 * dimensions of the root's chain, the children of keys c < C (udm1_domain_child(udm1_domain_next(root, b),
 * c)), in slot s = c B + b, in entries past `held` of the arrays below: the child's key in dim_key[63 - s],
 * the words mix64(key + K_j) of its dimensions 0..3 in the four entries a_hi[60 - 4 s ..] for s < R =
 * (64 - held) / 4, else a_lo[60 - 4 (s - R) ..]. The library fills them with the stream for the three
 * inline kinds, C = min(2, 2 R / B) (keys 0 and 1 where they fit), and the draws of those children compute
 * nothing that they hold. */
#define UDM1_STREAM_INLINE 1u
#define UDM1_STREAM_PMJ02 2u
#define UDM1_STREAM_SOBOL 4u
#define UDM1_STREAM_CHILDREN 8u

#ifdef __cplusplus
extern "C" {
#endif

typedef struct udm1_stream {
    uint32_t struct_size;  /* sizeof(udm1_stream) of the library that filled it */
    uint32_t flags;        /* UDM1_STREAM_* */
    const udm1_seq *seq;
    uint64_t stream;       /* the stream id given to udm1_stream_init */
    uint64_t key;          /* private: the stream's key (core hash of seed and stream) */
    uint64_t index_base;   /* added to every index (screen-space randomization: m N; else 0) */
    uint64_t point_count;  /* K of a point set, else 0 */
    uint32_t first, count; /* the dimensions it stands for: [first, first + count), count <= UDM1_STREAM_DIMS */
    uint32_t held;         /* how many of them, from first, have their words below (the sequence's own) */
    uint32_t dimensions;   /* D of the sequence */
    /* per dimension held: with UDM1_STREAM_INLINE, A_j in 0.128 fixed point and O_j in 0.64; otherwise
     * private data of the library's draws (the stream's randomization words of the base-2 kinds) */
    uint64_t a_hi[UDM1_STREAM_DIMS], a_lo[UDM1_STREAM_DIMS], offset[UDM1_STREAM_DIMS];
    /* for the domains (udm1/domain.h), per dimension held: the base offset o_j and the dimension key K_j */
    uint64_t base[UDM1_STREAM_DIMS], dim_key[UDM1_STREAM_DIMS];
    /* UDM1_STREAM_PMJ02, UDM1_STREAM_SOBOL: the kind's table (layouts above), pmj02's ceil(log2 K) or
     * the dimensions Sobol's table covers, and the randomization */
    const void *table;
    uint32_t table_bits;
    uint32_t table_mode;
} udm1_stream;

/* The child domains a stream holds (UDM1_STREAM_CHILDREN above): how many keys per block, how many blocks,
 * and slot s's key and four words. */
UDM1_DRAW_ uint32_t udm1_stream_child_kinds_(const udm1_stream *st) { return (st->flags / UDM1_STREAM_CHILDREN) & 3u; }
UDM1_DRAW_ uint32_t udm1_stream_child_blocks_(const udm1_stream *st) { return (st->held + 3u) / 4u; }
UDM1_DRAW_ uint64_t udm1_stream_child_key_(const udm1_stream *st, uint32_t s) { return st->dim_key[UDM1_STREAM_DIMS - 1u - s]; }
UDM1_DRAW_ const uint64_t *udm1_stream_child_words_(const udm1_stream *st, uint32_t s)
{
    uint32_t r = (UDM1_STREAM_DIMS - st->held) / 4u; /* the slots in a_hi's spare entries; then a_lo's */
    return s < r ? st->a_hi + UDM1_STREAM_DIMS - 4u - 4u * s : st->a_lo + UDM1_STREAM_DIMS - 4u - 4u * (s - r);
}

/* Fill *st for stream `stream` of seq, dimensions [first_dimension, first_dimension + count).
 * count may exceed D (the rest is padded, as the cursor pads) and is at most UDM1_STREAM_DIMS.
 * Errors: NULL_ARGUMENT, DIMENSION (count 0 or above UDM1_STREAM_DIMS, or the range past the dimension
 * index limit). On error *st is left unchanged. */
UDM1_API udm1_status udm1_stream_init(udm1_stream *st, const udm1_seq *seq, uint64_t stream,
                                      uint32_t first_dimension, uint32_t count);

/* Raw 0.64 values of dimensions [first + dim, first + dim + n) of point `index` into raw[0..n-1]: any
 * dimension (held, or not: the sequence's value or its padding), any kind. The draws below call it where
 * their inline arithmetic does not apply. Errors (raw left unchanged): NULL_ARGUMENT, INDEX_RANGE
 * (index >= K of a point set), DIMENSION (past the dimension index limit). */
UDM1_API udm1_status udm1_stream_fill_raw(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n,
                                          uint64_t *raw);

/* The same values as floats into out[0..n-1] (the conversion of udm1/seq.h); for the kinds whose low
 * bits a float does not read, without computing them. Errors as udm1_stream_fill_raw, NULL out (out left
 * unchanged: the whole range is checked before the first value is written). */
UDM1_API udm1_status udm1_stream_fill_f32(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n,
                                          float *out);

/* ---- inline arithmetic (the sequence contract of udm1/seq.h) -------------------------------------- */

/* The top 64 bits of a * b. */
UDM1_DRAW_ uint64_t udm1_mulhi64(uint64_t a, uint64_t b)
{
#if defined(UDM1_MULHI_INT128_)
    __extension__ typedef unsigned __int128 udm1_u128_;
    return (uint64_t)(((udm1_u128_)a * b) >> 64);
#elif defined(UDM1_MULHI_UMULH_)
    return __umulh(a, b);
#else
    uint64_t a0 = a & 0xFFFFFFFFu, a1 = a >> 32, b0 = b & 0xFFFFFFFFu, b1 = b >> 32;
    uint64_t mid = (a0 * b0 >> 32) + (a1 * b0 & 0xFFFFFFFFu) + (a0 * b1 & 0xFFFFFFFFu);
    return a1 * b1 + (a1 * b0 >> 32) + (a0 * b1 >> 32) + (mid >> 32);
#endif
}

/* The raw value of a Weyl dimension: the top 64 bits of (o 2^64 + n (a_hi 2^64 + a_lo)) mod 2^128. */
UDM1_DRAW_ uint64_t udm1_weyl_value(uint64_t a_hi, uint64_t a_lo, uint64_t o, uint64_t n)
{
    return o + n * a_hi + udm1_mulhi64(n, a_lo);
}

/* The same for n < 2^32 with 32 x 32 -> 64-bit products only, which compilers vectorize (equal bit for
 * bit: with n < 2^32 neither partial sum below reaches 2^64). */
UDM1_DRAW_ uint64_t udm1_weyl_value32(uint64_t a_hi, uint64_t a_lo, uint64_t o, uint32_t n)
{
    uint64_t h0 = (uint64_t)n * (uint32_t)a_hi, h1 = (uint64_t)n * (uint32_t)(a_hi >> 32);
    uint64_t l0 = (uint64_t)n * (uint32_t)a_lo, l1 = (uint64_t)n * (uint32_t)(a_lo >> 32);
    return o + h0 + (h1 << 32) + ((l1 + (l0 >> 32)) >> 32);
}

/* Four dimensions at once for n < 2^32: udm1_weyl_value32 of (a_hi[j], a_lo[j], o[j], n), j < 4, with
 * the 32 x 32 -> 64-bit vector multiply of SSE2 (x86-64's baseline) or AVX2, where the compiler targets
 * them; the same values bit for bit. */
#if defined(UDM1_AVX2_)
UDM1_DRAW_ void udm1_weyl4_32(const uint64_t *a_hi, const uint64_t *a_lo, const uint64_t *o, uint32_t n,
                                 uint64_t *out)
{
    __m256i N = _mm256_set1_epi64x((long long)n);
    __m256i H = _mm256_loadu_si256((const __m256i *)a_hi), L = _mm256_loadu_si256((const __m256i *)a_lo);
    __m256i h0 = _mm256_mul_epu32(N, H), h1 = _mm256_mul_epu32(N, _mm256_srli_epi64(H, 32));
    __m256i l0 = _mm256_mul_epu32(N, L), l1 = _mm256_mul_epu32(N, _mm256_srli_epi64(L, 32));
    __m256i carry = _mm256_srli_epi64(_mm256_add_epi64(l1, _mm256_srli_epi64(l0, 32)), 32);
    __m256i r = _mm256_add_epi64(_mm256_loadu_si256((const __m256i *)o), _mm256_add_epi64(h0, _mm256_slli_epi64(h1, 32)));
    _mm256_storeu_si256((__m256i *)out, _mm256_add_epi64(r, carry));
}
#elif defined(UDM1_X86_)
UDM1_DRAW_ void udm1_weyl4_32(const uint64_t *a_hi, const uint64_t *a_lo, const uint64_t *o, uint32_t n,
                                 uint64_t *out)
{
    __m128i N = _mm_set1_epi64x((long long)n);
    for (int k = 0; k < 4; k += 2) {
        __m128i H = _mm_loadu_si128((const __m128i *)(a_hi + k)), L = _mm_loadu_si128((const __m128i *)(a_lo + k));
        __m128i h0 = _mm_mul_epu32(N, H), h1 = _mm_mul_epu32(N, _mm_srli_epi64(H, 32));
        __m128i l0 = _mm_mul_epu32(N, L), l1 = _mm_mul_epu32(N, _mm_srli_epi64(L, 32));
        __m128i carry = _mm_srli_epi64(_mm_add_epi64(l1, _mm_srli_epi64(l0, 32)), 32);
        __m128i r = _mm_add_epi64(_mm_loadu_si128((const __m128i *)(o + k)), _mm_add_epi64(h0, _mm_slli_epi64(h1, 32)));
        _mm_storeu_si128((__m128i *)(out + k), _mm_add_epi64(r, carry));
    }
}
#elif defined(UDM1_NEON_)
UDM1_DRAW_ uint64x2_t udm1_weyl2_32_neon_(uint32x2_t N, const uint64_t *a_hi, const uint64_t *a_lo, const uint64_t *o)
{
    uint64x2_t H = vld1q_u64(a_hi), L = vld1q_u64(a_lo);
    uint64x2_t h0 = vmull_u32(N, vmovn_u64(H)), h1 = vmull_u32(N, vshrn_n_u64(H, 32));
    uint64x2_t l0 = vmull_u32(N, vmovn_u64(L)), l1 = vmull_u32(N, vshrn_n_u64(L, 32));
    uint64x2_t carry = vshrq_n_u64(vaddq_u64(l1, vshrq_n_u64(l0, 32)), 32);
    return vaddq_u64(vaddq_u64(vld1q_u64(o), vaddq_u64(h0, vshlq_n_u64(h1, 32))), carry);
}

UDM1_DRAW_ void udm1_weyl4_32(const uint64_t *a_hi, const uint64_t *a_lo, const uint64_t *o, uint32_t n,
                                 uint64_t *out)
{
    uint32x2_t N = vdup_n_u32(n);
    vst1q_u64(out, udm1_weyl2_32_neon_(N, a_hi, a_lo, o));
    vst1q_u64(out + 2, udm1_weyl2_32_neon_(N, a_hi + 2, a_lo + 2, o + 2));
}
#else
UDM1_DRAW_ void udm1_weyl4_32(const uint64_t *a_hi, const uint64_t *a_lo, const uint64_t *o, uint32_t n,
                                 uint64_t *out)
{
    for (int j = 0; j < 4; ++j) out[j] = udm1_weyl_value32(a_hi[j], a_lo[j], o[j], n);
}
#endif

/* Two dimensions at once for n < 2^32 (SSE2 on x86-64, NEON on AArch64), as udm1_weyl4_32. */
#if defined(UDM1_X86_)
UDM1_DRAW_ void udm1_weyl2_32(const uint64_t *a_hi, const uint64_t *a_lo, const uint64_t *o, uint32_t n,
                                 uint64_t *out)
{
    __m128i N = _mm_set1_epi64x((long long)n);
    __m128i H = _mm_loadu_si128((const __m128i *)a_hi), L = _mm_loadu_si128((const __m128i *)a_lo);
    __m128i h0 = _mm_mul_epu32(N, H), h1 = _mm_mul_epu32(N, _mm_srli_epi64(H, 32));
    __m128i l0 = _mm_mul_epu32(N, L), l1 = _mm_mul_epu32(N, _mm_srli_epi64(L, 32));
    __m128i carry = _mm_srli_epi64(_mm_add_epi64(l1, _mm_srli_epi64(l0, 32)), 32);
    __m128i r = _mm_add_epi64(_mm_loadu_si128((const __m128i *)o), _mm_add_epi64(h0, _mm_slli_epi64(h1, 32)));
    _mm_storeu_si128((__m128i *)out, _mm_add_epi64(r, carry));
}
#elif defined(UDM1_NEON_)
UDM1_DRAW_ void udm1_weyl2_32(const uint64_t *a_hi, const uint64_t *a_lo, const uint64_t *o, uint32_t n,
                                 uint64_t *out)
{
    vst1q_u64(out, udm1_weyl2_32_neon_(vdup_n_u32(n), a_hi, a_lo, o));
}
#else
UDM1_DRAW_ void udm1_weyl2_32(const uint64_t *a_hi, const uint64_t *a_lo, const uint64_t *o, uint32_t n,
                                 uint64_t *out)
{
    out[0] = udm1_weyl_value32(a_hi[0], a_lo[0], o[0], n);
    out[1] = udm1_weyl_value32(a_hi[1], a_lo[1], o[1], n);
}
#endif

/* Dimensions 0..n-1 of (a_hi, a_lo, o) at n < 2^32: fours, then a two, then a one. */
UDM1_DRAW_ void udm1_weyl_run32(const uint64_t *a_hi, const uint64_t *a_lo, const uint64_t *o, uint32_t n,
                                   uint32_t count, uint64_t *out)
{
    uint32_t j = 0;
    for (; j + 4 <= count; j += 4) udm1_weyl4_32(a_hi + j, a_lo + j, o + j, n, out + j);
    if (j + 2 <= count) udm1_weyl2_32(a_hi + j, a_lo + j, o + j, n, out + j), j += 2;
    if (j < count) out[j] = udm1_weyl_value32(a_hi[j], a_lo[j], o[j], n);
}

/* The documented conversions (udm1/seq.h): float = top 24 bits x 2^-24, double = top 53 bits x 2^-53. */
UDM1_DRAW_ float udm1_raw_to_f32(uint64_t u) { return (float)(int32_t)(u >> 40) * (1.0f / 16777216.0f); }
UDM1_DRAW_ double udm1_raw_to_f64(uint64_t u) { return (double)(int64_t)(u >> 11) * (1.0 / 9007199254740992.0); }

/* The bits of each 32-bit lane of x reversed, in the vector register: GFNI's bit matrix (where the
 * compiler targets GFNI) or two byte shuffles of a nibble table (SSSE3; MSVC: AVX), then the bytes swapped
 * by a shuffle; with SSE2 alone, shifts and masks. */
#if defined(UDM1_X86_) && (defined(__SSSE3__) || defined(__AVX__))
#define UDM1_REVERSE_SHUFFLE_ 1
UDM1_DRAW_ __m128i udm1_reverse32x4_(__m128i x)
{
    const __m128i bswap = _mm_setr_epi8(3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12);
#if defined(__GFNI__)
    return _mm_shuffle_epi8(_mm_gf2p8affine_epi64_epi8(x, _mm_set1_epi64x(0x8040201008040201ll), 0), bswap);
#else
    const __m128i m4 = _mm_set1_epi8(0x0F), nib = _mm_setr_epi8(0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15);
    x = _mm_shuffle_epi8(x, bswap);
    return _mm_or_si128(_mm_slli_epi16(_mm_shuffle_epi8(nib, _mm_and_si128(x, m4)), 4),
                        _mm_shuffle_epi8(nib, _mm_and_si128(_mm_srli_epi16(x, 4), m4)));
#endif
}
#elif defined(UDM1_X86_)
UDM1_DRAW_ __m128i udm1_reverse32x4_(__m128i x)
{
    /* halves exchanged, then bytes, nibbles, pairs and bits (16-bit shifts: the masks keep each in its byte) */
    const __m128i m4 = _mm_set1_epi8(0x0F), m2 = _mm_set1_epi8(0x33), m1 = _mm_set1_epi8(0x55);
    x = _mm_or_si128(_mm_slli_epi32(x, 16), _mm_srli_epi32(x, 16));
    x = _mm_or_si128(_mm_slli_epi16(x, 8), _mm_srli_epi16(x, 8));
    x = _mm_or_si128(_mm_and_si128(_mm_srli_epi16(x, 4), m4), _mm_slli_epi16(_mm_and_si128(x, m4), 4));
    x = _mm_or_si128(_mm_and_si128(_mm_srli_epi16(x, 2), m2), _mm_slli_epi16(_mm_and_si128(x, m2), 2));
    return _mm_or_si128(_mm_and_si128(_mm_srli_epi16(x, 1), m1), _mm_slli_epi16(_mm_and_si128(x, m1), 1));
}
#endif

/* The bits of x in reverse order; a hash of 32 bits in which each output bit depends only on the input
 * bits at or below it, each step a bijection modulo 2^k for every k (Burley 2020, with Vegdahl's
 * constants): applied to bit-reversed digits it is a nested uniform (Owen) scramble. */
UDM1_DRAW_ uint32_t udm1_reverse32(uint32_t x)
{
#if defined(__clang__)
    return __builtin_bitreverse32(x);
#elif defined(UDM1_REVERSE_SHUFFLE_) /* (3 or 4 vector instructions for 16) */
    return (uint32_t)_mm_cvtsi128_si32(udm1_reverse32x4_(_mm_cvtsi32_si128((int)x)));
#else
#if defined(__GNUC__)
    x = __builtin_bswap32(x);
#else
    x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
    x = (x >> 16) | (x << 16);
#endif
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    return ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
#endif
}

UDM1_DRAW_ uint32_t udm1_owen_hash32(uint32_t x, uint32_t seed)
{
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

/* A nested uniform scramble of the k-bit value v (v < 2^k, 1 <= k <= 32): it maps each aligned block of
 * 2^j values onto an aligned block of 2^j. */
UDM1_DRAW_ uint32_t udm1_owen_bits(uint32_t v, uint32_t seed, unsigned k)
{
    uint32_t mask = k >= 32 ? 0xFFFFFFFFu : (1u << k) - 1u;
    return udm1_reverse32(udm1_owen_hash32(udm1_reverse32(v) >> (32 - k), seed) & mask) >> (32 - k);
}

/* The raw pmj02 value (UDM1_STREAM_PMJ02) of dimension first + dim of point index < K, XORed with word. */
UDM1_DRAW_ uint64_t udm1_pmj02_value_(const udm1_stream *st, uint64_t index, uint32_t dim, uint64_t word)
{
    uint32_t d = st->first + dim;
    const uint32_t *xy = (const uint32_t *)st->table;
    return ((uint64_t)xy[((d / 4) * st->point_count + index) * 4 + d % 4] << 32) ^ word;
}

/* The bit-reversed top 32 bits of Sobol dimension d (UDM1_STREAM_SOBOL, table_mode 2) at Gray code g. */
UDM1_DRAW_ uint32_t udm1_sobol_rev_(const udm1_stream *st, uint32_t d, uint32_t g)
{
    const uint32_t(*T)[256] = (const uint32_t(*)[256])st->table + 4 * (size_t)d;
    return T[0][g & 255u] ^ T[1][(g >> 8) & 255u] ^ T[2][(g >> 16) & 255u] ^ T[3][g >> 24];
}

/* The same of n (1..4) dimensions d .. into r: where g < 2^16 (a pixel's sample index, unscrambled) from
 * the tables of its two low bytes only (a zero byte's entry is 0). */
UDM1_DRAW_ void udm1_sobol_rev4_(const udm1_stream *st, uint32_t d, uint32_t g, uint32_t n, uint32_t *r)
{
    const uint32_t(*T)[256] = (const uint32_t(*)[256])st->table + 4 * (size_t)d;
    if (g >> 16)
        for (uint32_t j = 0; j < n && j < 4; ++j) r[j] = udm1_sobol_rev_(st, d + j, g);
    else
        for (uint32_t j = 0; j < n && j < 4; ++j) r[j] = T[4 * j][g & 255u] ^ T[4 * j + 1][g >> 8];
}

/* The raw Sobol value (UDM1_STREAM_SOBOL) of dimension first + dim of point index < 2^32, randomized with
 * word: XOR (table_mode 1) or Owen scrambling (2: the top 32 bits scrambled, the low 32 a hash of them, or
 * left 0 with low_half 0 - a float reads only the top 24 bits). */
UDM1_DRAW_ uint64_t udm1_sobol_value_(const udm1_stream *st, uint32_t index, uint32_t dim, uint64_t word, int low_half)
{
    uint32_t g = index ^ (index >> 1), d = st->first + dim;
    if (st->table_mode != 2) {
        const uint64_t(*T)[256] = (const uint64_t(*)[256])st->table + 4 * (size_t)d;
        uint64_t v = T[0][g & 255u] ^ T[1][(g >> 8) & 255u] ^ T[2][(g >> 16) & 255u] ^ T[3][g >> 24];
        return st->table_mode == 1 ? v ^ word : v;
    }
    uint32_t top = udm1_reverse32(udm1_owen_hash32(udm1_sobol_rev_(st, d, g), (uint32_t)word));
    if (!low_half) return (uint64_t)top << 32;
    /* seq/scramble.h's udm1_owen64: the low half a hash of the top one and the word's high half */
    uint64_t z = ((uint64_t)top << 32 | (uint32_t)(word >> 32)) ^ 0x4F57454E00000000ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (uint64_t)top << 32 | (uint32_t)(z ^ (z >> 31));
}

#if defined(UDM1_X86_)
/* The first n (1..4) of four floats in a register into out (all four in one store where n is 4). */
UDM1_DRAW_ void udm1_store_f32_(__m128 f, uint32_t n, float *out)
{
    if (n == 4) {
        _mm_storeu_ps(out, f);
        return;
    }
    float f4[4];
    _mm_storeu_ps(f4, f);
    for (uint32_t j = 0; j < n; ++j) out[j] = f4[j];
}

/* The low (high 0) or high (high 1) 32-bit halves of words[0..3] in one register. Where the compiler
 * targets AVX2 a child's words are hashed four at once and stored so: two wide loads take them; else they
 * are stored one by one, and a wide load would wait for the stores: read one by one. */
UDM1_DRAW_ __m128i udm1_word_halves_(const uint64_t *words, int high)
{
#if defined(UDM1_AVX2_)
    __m128 w0 = _mm_castsi128_ps(_mm_loadu_si128((const __m128i *)words));
    __m128 w1 = _mm_castsi128_ps(_mm_loadu_si128((const __m128i *)(words + 2)));
    return _mm_castps_si128(high ? _mm_shuffle_ps(w0, w1, 0xDD) : _mm_shuffle_ps(w0, w1, 0x88));
#else
    int sh = high ? 32 : 0;
    return _mm_setr_epi32((int)(words[0] >> sh), (int)(words[1] >> sh), (int)(words[2] >> sh), (int)(words[3] >> sh));
#endif
}
#endif

/* Floats of n (1..4) Owen-scrambled Sobol dimensions first + dim .. at Gray code g, the scrambles keyed by
 * the low halves of words[0 .. n - 1] (four readable). On x86-64 and with NEON the four lanes are
 * scrambled, reversed (udm1_reverse32x4_) and converted in one register, the 32-bit products by SSE4.1's
 * (MSVC: AVX) or, with SSE2 alone (x86-64's baseline), by products of lanes 0, 2 and 1, 3 (`pmuludq`); the
 * same values as the scalar code. */
#if defined(UDM1_X86_)
#if defined(__SSE4_1__) || defined(__AVX__)
#define udm1_mullo32x4_(a, b) _mm_mullo_epi32(a, b)
#else
/* the low 32 bits of a * b in each lane: lanes 0 and 2, then 1 and 3, by 32 x 32 -> 64-bit products */
UDM1_DRAW_ __m128i udm1_mullo32x4_(__m128i a, __m128i b)
{
    __m128i even = _mm_mul_epu32(a, b), odd = _mm_mul_epu32(_mm_srli_epi64(a, 32), _mm_srli_epi64(b, 32));
    return _mm_unpacklo_epi32(_mm_shuffle_epi32(even, 0x08), _mm_shuffle_epi32(odd, 0x08));
}
#endif
#endif

UDM1_DRAW_ void udm1_sobol_owen_f32_(const udm1_stream *st, uint32_t g, uint32_t dim, uint32_t n,
                                        const uint64_t *words, float *out)
{
    uint32_t d = st->first + dim;
#if defined(UDM1_X86_)
    uint32_t r[4] = {0, 0, 0, 0};
    udm1_sobol_rev4_(st, d, g, n, r);
    __m128i x = _mm_setr_epi32((int)r[0], (int)r[1], (int)r[2], (int)r[3]); /* (in registers: a wide load of
                                                                              values just stored waits for them) */
    __m128i seed = udm1_word_halves_(words, 0);
    x = _mm_xor_si128(x, udm1_mullo32x4_(x, _mm_set1_epi32(0x3d20adea)));
    x = _mm_add_epi32(x, seed);
    x = udm1_mullo32x4_(x, _mm_or_si128(_mm_srli_epi32(seed, 16), _mm_set1_epi32(1)));
    x = _mm_xor_si128(x, udm1_mullo32x4_(x, _mm_set1_epi32(0x05526c56)));
    x = _mm_xor_si128(x, udm1_mullo32x4_(x, _mm_set1_epi32(0x53a22864)));
    x = udm1_reverse32x4_(x);
    udm1_store_f32_(_mm_mul_ps(_mm_cvtepi32_ps(_mm_srli_epi32(x, 8)), _mm_set1_ps(1.0f / 16777216.0f)), n < 4 ? n : 4, out);
#elif defined(UDM1_NEON_)
    uint32_t r[4] = {0, 0, 0, 0};
    udm1_sobol_rev4_(st, d, g, n, r);
    uint32x4_t x = vld1q_u32(r);
    uint32x4_t seed = vcombine_u32(vmovn_u64(vld1q_u64(words)), vmovn_u64(vld1q_u64(words + 2))); /* low halves */
    x = veorq_u32(x, vmulq_u32(x, vdupq_n_u32(0x3d20adeau)));
    x = vaddq_u32(x, seed);
    x = vmulq_u32(x, vorrq_u32(vshrq_n_u32(seed, 16), vdupq_n_u32(1u)));
    x = veorq_u32(x, vmulq_u32(x, vdupq_n_u32(0x05526c56u)));
    x = veorq_u32(x, vmulq_u32(x, vdupq_n_u32(0x53a22864u)));
    x = vreinterpretq_u32_u8(vrbitq_u8(vrev32q_u8(vreinterpretq_u8_u32(x)))); /* bits reversed in each lane */
    float f[4];
    vst1q_f32(f, vmulq_f32(vcvtq_f32_u32(vshrq_n_u32(x, 8)), vdupq_n_f32(1.0f / 16777216.0f)));
    for (uint32_t j = 0; j < n && j < 4; ++j) out[j] = f[j];
#else
    for (uint32_t j = 0; j < n; ++j)
        out[j] = (float)(udm1_reverse32(udm1_owen_hash32(udm1_sobol_rev_(st, d + j, g), (uint32_t)words[j])) >> 8) *
                 (1.0f / 16777216.0f);
#endif
}

/* Whether dimensions [dim, dim + n) of point index are Sobol values drawn inline. */
UDM1_DRAW_ int udm1_stream_sobol_(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n)
{
    return (st->flags & UDM1_STREAM_SOBOL) && n <= st->held && dim <= st->held - n && index <= 0xFFFFFFFFu;
}

/* ... of dimensions dim .. dim + n - 1, as raw values (out_kind 0), floats (1) or doubles (2), each
 * converted where it is made (a wide load of values just stored one by one would wait for them) */
UDM1_DRAW_ void udm1_pmj02_values_(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n,
                                      const uint64_t *words, int xor_words, int out_kind, void *out)
{
#if defined(UDM1_X86_)
    uint32_t d = st->first + dim;
    if (out_kind == 1 && n <= 4 && d % 4 == 0 && dim <= UDM1_STREAM_DIMS - 4) {
        /* floats of a point's block of four coordinates: one load, the words' high halves, one convert */
        __m128i x = _mm_loadu_si128((const __m128i *)((const uint32_t *)st->table + ((d / 4) * st->point_count + index) * 4));
        if (xor_words) x = _mm_xor_si128(x, udm1_word_halves_(words, 1)); /* the words' high halves */
        udm1_store_f32_(_mm_mul_ps(_mm_cvtepi32_ps(_mm_srli_epi32(x, 8)), _mm_set1_ps(1.0f / 16777216.0f)), n, (float *)out);
        return;
    }
#elif defined(UDM1_NEON_)
    uint32_t d = st->first + dim;
    if (out_kind == 1 && n <= 4 && d % 4 == 0 && dim <= UDM1_STREAM_DIMS - 4) {
        /* floats of a point's block of four coordinates, as above */
        uint32x4_t x = vld1q_u32((const uint32_t *)st->table + ((d / 4) * st->point_count + index) * 4);
        if (xor_words)
            x = veorq_u32(x, vcombine_u32(vshrn_n_u64(vld1q_u64(words), 32), vshrn_n_u64(vld1q_u64(words + 2), 32)));
        float f[4];
        vst1q_f32(f, vmulq_f32(vcvtq_f32_u32(vshrq_n_u32(x, 8)), vdupq_n_f32(1.0f / 16777216.0f)));
        for (uint32_t j = 0; j < n; ++j) ((float *)out)[j] = f[j];
        return;
    }
#endif
    for (uint32_t j = 0; j < n; ++j) {
        uint64_t v = udm1_pmj02_value_(st, index, dim + j, xor_words ? words[j] : 0);
        if (out_kind == 1) ((float *)out)[j] = udm1_raw_to_f32(v);
        else if (out_kind == 2) ((double *)out)[j] = udm1_raw_to_f64(v);
        else ((uint64_t *)out)[j] = v;
    }
}

/* Whether dimensions [dim, dim + n) of point index are drawn inline. */
UDM1_DRAW_ int udm1_stream_inline_(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n)
{
    return (st->flags & UDM1_STREAM_INLINE) && n <= st->held && dim <= st->held - n &&
           (st->point_count == 0 || index < st->point_count);
}

/* Whether dimensions [dim, dim + n) of point index are pmj02 values drawn inline. */
UDM1_DRAW_ int udm1_stream_pmj02_(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n)
{
    return (st->flags & UDM1_STREAM_PMJ02) && n <= st->held && dim <= st->held - n && index < st->point_count;
}

/* Dimensions [first + dim, first + dim + n) of point `index`, as raw 0.64 values, floats or doubles.
 * A draw the library refuses (an index outside a point set, a NULL stream, dimensions past the index
 * limit) gives NaN in each of the n outputs of the float and double draws (0 for raw values) and
 * nothing else, and udm1_last_error() says why (a NULL output array is then left alone). */
UDM1_DRAW_ void udm1_stream_draw_raw(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n,
                                        uint64_t *raw)
{
    if (st && udm1_stream_inline_(st, index, dim, n)) {
        uint64_t m = index + st->index_base;
        if (m <= 0xFFFFFFFFu) {
            udm1_weyl_run32(st->a_hi + dim, st->a_lo + dim, st->offset + dim, (uint32_t)m, n, raw);
        } else {
            for (uint32_t j = 0; j < n; ++j)
                raw[j] = udm1_weyl_value(st->a_hi[dim + j], st->a_lo[dim + j], st->offset[dim + j], m);
        }
        return;
    }
    if (st && udm1_stream_pmj02_(st, index, dim, n)) {
        udm1_pmj02_values_(st, index, dim, n, st->offset + dim, st->table_mode == 1, 0, raw);
        return;
    }
    if (st && udm1_stream_sobol_(st, index, dim, n)) {
        for (uint32_t j = 0; j < n; ++j) raw[j] = udm1_sobol_value_(st, (uint32_t)index, dim + j, st->offset[dim + j], 1);
        return;
    }
    if (udm1_stream_fill_raw(st, index, dim, n, raw) != UDM1_OK && raw)
        for (uint32_t j = 0; j < n; ++j) raw[j] = 0;
}

UDM1_DRAW_ void udm1_stream_draw_f32(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n, float *out)
{
    if (st && udm1_stream_inline_(st, index, dim, n)) {
        uint64_t m = index + st->index_base;
        if (m <= 0xFFFFFFFFu && n <= 4) { /* the common draw: one vector step */
            uint64_t r[4];
            udm1_weyl_run32(st->a_hi + dim, st->a_lo + dim, st->offset + dim, (uint32_t)m, n, r);
            for (uint32_t k = 0; k < n; ++k) out[k] = udm1_raw_to_f32(r[k]);
        } else if (m <= 0xFFFFFFFFu) {
            for (uint32_t j = 0; j < n; j += UDM1_STREAM_DIMS) {
                uint64_t r[UDM1_STREAM_DIMS];
                uint32_t c = n - j < UDM1_STREAM_DIMS ? n - j : UDM1_STREAM_DIMS;
                udm1_weyl_run32(st->a_hi + dim + j, st->a_lo + dim + j, st->offset + dim + j, (uint32_t)m, c, r);
                for (uint32_t k = 0; k < c; ++k) out[j + k] = udm1_raw_to_f32(r[k]);
            }
        } else {
            for (uint32_t j = 0; j < n; ++j)
                out[j] = udm1_raw_to_f32(udm1_weyl_value(st->a_hi[dim + j], st->a_lo[dim + j], st->offset[dim + j], m));
        }
        return;
    }
    if (st && udm1_stream_pmj02_(st, index, dim, n)) {
        udm1_pmj02_values_(st, index, dim, n, st->offset + dim, st->table_mode == 1, 1, out);
        return;
    }
    if (st && udm1_stream_sobol_(st, index, dim, n)) {
        if (st->table_mode == 2 && n <= 4 && dim <= UDM1_STREAM_DIMS - 4) { /* (four lanes in the arrays) */
            udm1_sobol_owen_f32_(st, (uint32_t)index ^ ((uint32_t)index >> 1), dim, n, st->offset + dim, out);
            return;
        }
        for (uint32_t j = 0; j < n; ++j)
            out[j] = udm1_raw_to_f32(udm1_sobol_value_(st, (uint32_t)index, dim + j, st->offset[dim + j], 0));
        return;
    }
    if (udm1_stream_fill_f32(st, index, dim, n, out) != UDM1_OK && out)
        for (uint32_t j = 0; j < n; ++j) out[j] = (float)NAN;
}

UDM1_DRAW_ void udm1_stream_draw_f64(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n, double *out)
{
    if (st && udm1_stream_inline_(st, index, dim, n)) {
        uint64_t m = index + st->index_base;
        if (m <= 0xFFFFFFFFu && n <= 4) { /* the common draw: one vector step */
            uint64_t r[4];
            udm1_weyl_run32(st->a_hi + dim, st->a_lo + dim, st->offset + dim, (uint32_t)m, n, r);
            for (uint32_t k = 0; k < n; ++k) out[k] = udm1_raw_to_f64(r[k]);
        } else if (m <= 0xFFFFFFFFu) {
            for (uint32_t j = 0; j < n; j += UDM1_STREAM_DIMS) {
                uint64_t r[UDM1_STREAM_DIMS];
                uint32_t c = n - j < UDM1_STREAM_DIMS ? n - j : UDM1_STREAM_DIMS;
                udm1_weyl_run32(st->a_hi + dim + j, st->a_lo + dim + j, st->offset + dim + j, (uint32_t)m, c, r);
                for (uint32_t k = 0; k < c; ++k) out[j + k] = udm1_raw_to_f64(r[k]);
            }
        } else {
            for (uint32_t j = 0; j < n; ++j)
                out[j] = udm1_raw_to_f64(udm1_weyl_value(st->a_hi[dim + j], st->a_lo[dim + j], st->offset[dim + j], m));
        }
        return;
    }
    if (st && udm1_stream_pmj02_(st, index, dim, n)) {
        udm1_pmj02_values_(st, index, dim, n, st->offset + dim, st->table_mode == 1, 2, out);
        return;
    }
    if (st && udm1_stream_sobol_(st, index, dim, n)) {
        for (uint32_t j = 0; j < n; ++j)
            out[j] = udm1_raw_to_f64(udm1_sobol_value_(st, (uint32_t)index, dim + j, st->offset[dim + j], 1));
        return;
    }
    uint64_t raw[UDM1_STREAM_DIMS];
    int ok = 1;
    for (uint32_t done = 0; ok && done < n;) {
        uint32_t m = n - done < UDM1_STREAM_DIMS ? n - done : UDM1_STREAM_DIMS;
        ok = udm1_stream_fill_raw(st, index, dim + done, m, out ? raw : NULL) == UDM1_OK;
        for (uint32_t j = 0; ok && j < m; ++j) out[done + j] = udm1_raw_to_f64(raw[j]);
        done += m;
    }
    if (!ok && out) /* a later part refused (dimensions past the limit): the whole draw is */
        for (uint32_t j = 0; j < n; ++j) out[j] = NAN;
}

#ifdef __cplusplus
}
#endif

#endif /* UDM1_STREAM_H */
