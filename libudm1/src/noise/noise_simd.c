/* noise_simd.c - the improved noise on 4 points at a time with AVX2 or AVX-512VL, for the
 * batch calls. It performs the scalar code's operations in the same order on
 * the same doubles (floor, fade, Perlin's +-u +-v gradients as blends and sign
 * flips, the lerps), so its results equal udm1_noise_3d / udm1_noise_2d bit
 * for bit; tests/c/test_noise.c checks it. The permutation is read through
 * the combined tables hash4 and pair (internal.h): the same hashes in 5 loads
 * per 3D point instead of 14, 1 per 2D point instead of 6, as scalar loads
 * (AVX2 gathers measured slower here). Groups of four with a coordinate
 * at or past 2^31 go to the scalar code, and so do periodic and classic
 * noise. Chosen at run time by core/isa.h: AVX-512VL where the processor has it, else AVX2
 * (UDM1_ISA=avx2 or baseline caps the choice). */
#include "core/isa.h"
#include "noise/noise_tables.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#if defined(UDM1_HAVE_ISA_KERNELS)
#include <immintrin.h>

#include "noise/side_check.h"

#define AVX2 __attribute__((target("avx2")))

AVX2 static inline __m256d fade(__m256d t)
{
    /* t * t * t * (t * (t * 6 - 15) + 10), in the scalar order */
    __m256d a = _mm256_mul_pd(_mm256_mul_pd(t, t), t);
    __m256d b = _mm256_sub_pd(_mm256_mul_pd(t, _mm256_set1_pd(6.0)), _mm256_set1_pd(15.0));
    b = _mm256_add_pd(_mm256_mul_pd(t, b), _mm256_set1_pd(10.0));
    return _mm256_mul_pd(a, b);
}

AVX2 static inline __m256d lerp(__m256d t, __m256d a, __m256d b)
{
    return _mm256_add_pd(a, _mm256_mul_pd(t, _mm256_sub_pd(b, a)));
}

AVX2 static inline __m256d flip(__m256d v, __m256i bit) /* negate the lanes whose bit is set */
{
    return _mm256_xor_pd(v, _mm256_castsi256_pd(_mm256_slli_epi64(bit, 63)));
}

/* Perlin's gradient: u = x (h < 8) or y; v = y (h < 4), x (h = 12, 14) or z; +-u +-v */
AVX2 static inline __m256d grad3(__m128i hash, __m256d x, __m256d y, __m256d z)
{
    __m256i h = _mm256_cvtepi32_epi64(_mm_and_si128(hash, _mm_set1_epi32(15)));
    __m256d below8 = _mm256_castsi256_pd(_mm256_cmpgt_epi64(_mm256_set1_epi64x(8), h));
    __m256d below4 = _mm256_castsi256_pd(_mm256_cmpgt_epi64(_mm256_set1_epi64x(4), h));
    __m256d is12or14 = _mm256_castsi256_pd(_mm256_or_si256(_mm256_cmpeq_epi64(h, _mm256_set1_epi64x(12)),
                                                           _mm256_cmpeq_epi64(h, _mm256_set1_epi64x(14))));
    __m256d u = _mm256_blendv_pd(y, x, below8);
    __m256d v = _mm256_blendv_pd(_mm256_blendv_pd(z, x, is12or14), y, below4);
    u = flip(u, _mm256_and_si256(h, _mm256_set1_epi64x(1)));
    v = flip(v, _mm256_srli_epi64(_mm256_and_si256(h, _mm256_set1_epi64x(2)), 1));
    return _mm256_add_pd(u, v);
}

/* noise1234's 2D gradient: u = x (h & 7 < 4) or y, v the other; +-u +-2v */
AVX2 static inline __m256d grad2(__m128i hash, __m256d x, __m256d y)
{
    __m256i h = _mm256_cvtepi32_epi64(_mm_and_si128(hash, _mm_set1_epi32(7)));
    __m256d below4 = _mm256_castsi256_pd(_mm256_cmpgt_epi64(_mm256_set1_epi64x(4), h));
    __m256d u = _mm256_blendv_pd(y, x, below4);
    __m256d v = _mm256_mul_pd(_mm256_set1_pd(2.0), _mm256_blendv_pd(x, y, below4));
    u = flip(u, _mm256_and_si256(h, _mm256_set1_epi64x(1)));
    v = flip(v, _mm256_srli_epi64(_mm256_and_si256(h, _mm256_set1_epi64x(2)), 1));
    return _mm256_add_pd(u, v);
}

/* floor, offset in the cell, and the corner indices (& 255) of one axis */
AVX2 static inline __m256d axis(__m256d x, __m128i *i0, __m128i *i1)
{
    __m256d f = _mm256_floor_pd(x);
    __m128i i = _mm256_cvttpd_epi32(f);
    *i0 = _mm_and_si128(i, _mm_set1_epi32(255));
    *i1 = _mm_and_si128(_mm_add_epi32(i, _mm_set1_epi32(1)), _mm_set1_epi32(255));
    return _mm256_sub_pd(x, f);
}

AVX2 static inline int all_finite(__m256d x) /* all lanes finite */
{
    __m256d ax = _mm256_andnot_pd(_mm256_set1_pd(-0.0), x);
    return _mm256_movemask_pd(_mm256_cmp_pd(ax, _mm256_set1_pd(INFINITY), _CMP_LT_OQ)) == 0xF;
}

AVX2 static inline int in_range(__m256d x) /* all lanes finite and |x| < 2^31 */
{
    __m256d ax = _mm256_andnot_pd(_mm256_set1_pd(-0.0), x);
    return _mm256_movemask_pd(_mm256_cmp_pd(ax, _mm256_set1_pd(0x1p31), _CMP_LT_OQ)) == 0xF;
}

#define BLOCK 16 /* groups of four points per block (noise_simd_kernels.h) */
#define PREFETCH 128 /* points ahead to ask the cache for (a hint: never faults; an address, not a pointer, past the end) */

#define KERNEL_ATTR AVX2
#define NOISE3 noise3_avx2
#define NOISE2 noise2_avx2
#define GRAD3 grad3
#define GRAD2 grad2
#include "noise/noise_simd_kernels.h"
#undef KERNEL_ATTR
#undef NOISE3
#undef NOISE2
#undef GRAD3
#undef GRAD2

/* The same kernels with AVX-512 (VL, DQ) on 256-bit vectors: the gradient's choices as mask
 * registers (tests, masked blends and sign flips: 10 instructions instead of 16) and 32 vector
 * registers. The lanes stay four, the operations and their order the scalar code's. */
#define AVX512 __attribute__((target("avx2,avx512f,avx512vl,avx512dq")))

AVX512 static inline __m256d grad3_avx512(__m128i hash, __m256d x, __m256d y, __m256d z)
{
    __mmask8 below8 = _mm_testn_epi32_mask(hash, _mm_set1_epi32(8));
    __mmask8 below4 = _mm_testn_epi32_mask(hash, _mm_set1_epi32(12));
    __mmask8 is12or14 = _mm_cmpeq_epi32_mask(_mm_and_si128(hash, _mm_set1_epi32(13)), _mm_set1_epi32(12));
    __m256d u = _mm256_mask_blend_pd(below8, y, x);
    __m256d v = _mm256_mask_blend_pd(below4, _mm256_mask_blend_pd(is12or14, z, x), y);
    __m256d sign = _mm256_set1_pd(-0.0);
    u = _mm256_mask_xor_pd(u, _mm_test_epi32_mask(hash, _mm_set1_epi32(1)), u, sign);
    v = _mm256_mask_xor_pd(v, _mm_test_epi32_mask(hash, _mm_set1_epi32(2)), v, sign);
    return _mm256_add_pd(u, v);
}

AVX512 static inline __m256d grad2_avx512(__m128i hash, __m256d x, __m256d y)
{
    __mmask8 below4 = _mm_testn_epi32_mask(hash, _mm_set1_epi32(4));
    __m256d u = _mm256_mask_blend_pd(below4, y, x);
    __m256d v = _mm256_mul_pd(_mm256_set1_pd(2.0), _mm256_mask_blend_pd(below4, x, y));
    __m256d sign = _mm256_set1_pd(-0.0);
    u = _mm256_mask_xor_pd(u, _mm_test_epi32_mask(hash, _mm_set1_epi32(1)), u, sign);
    v = _mm256_mask_xor_pd(v, _mm_test_epi32_mask(hash, _mm_set1_epi32(2)), v, sign);
    return _mm256_add_pd(u, v);
}

#define KERNEL_ATTR AVX512
#define NOISE3 noise3_avx512
#define NOISE2 noise2_avx512
#define GRAD3 grad3_avx512
#define GRAD2 grad2_avx512
#include "noise/noise_simd_kernels.h"
#undef KERNEL_ATTR
#undef NOISE3
#undef NOISE2
#undef GRAD3
#undef GRAD2

size_t udm1_noise_points_fast(const udm1_noise *n, uint32_t dims, const double *xyz, size_t count, size_t stride,
                              double *out, udm1_side_check *side)
{
    if (n->kind != UDM1_NOISE_IMPROVED || n->period[0] || n->period[1] || n->period[2]) return 0;
    if (dims < 2 || dims > 3) return 0;
    udm1_side_check none = {{NULL}, 0, 0, 0, 0};
    if (!side) side = &none;
    /* an AVX-512 version with 8 lanes (gathers) measured 0.7x the AVX2 one on the benchmark machine:
     * the AVX-512 kernels keep 4 lanes */
    switch (udm1_isa_level()) {
    case UDM1_ISA_AVX512:
        return dims == 3 ? noise3_avx512(n, xyz, count, stride, out, side) : noise2_avx512(n, xyz, count, stride, out, side);
    case UDM1_ISA_AVX2:
        return dims == 3 ? noise3_avx2(n, xyz, count, stride, out, side) : noise2_avx2(n, xyz, count, stride, out, side);
    default: break;
    }
    return 0;
}

#else
size_t udm1_noise_points_fast(const udm1_noise *n, uint32_t dims, const double *xyz, size_t count, size_t stride,
                              double *out, udm1_side_check *side)
{
    (void)n, (void)dims, (void)xyz, (void)count, (void)stride, (void)out, (void)side;
    return 0;
}
#endif
