/* noise_simd.c - the improved noise on 4 points at a time with AVX2, for the
 * batch calls. It performs the scalar code's operations in the same order on
 * the same doubles (floor, fade, Perlin's +-u +-v gradients as blends and sign
 * flips, the lerps), so its results equal udm1_noise_3d / udm1_noise_2d bit
 * for bit; tests/c/test_noise.c checks it. The permutation is read through
 * the combined tables hash4 and pair (internal.h): the same hashes in 2 loads
 * per 3D point instead of 14, 1 per 2D point instead of 6, as scalar loads
 * (AVX2 gathers measured slower here). Groups of four with a coordinate
 * at or past 2^31 go to the scalar code, and so do periodic and classic
 * noise. Chosen at run time when the processor has AVX2. */
#include "internal.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

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

AVX2 static inline int in_range(__m256d x) /* all lanes finite and |x| < 2^31 */
{
    __m256d ax = _mm256_andnot_pd(_mm256_set1_pd(-0.0), x);
    return _mm256_movemask_pd(_mm256_cmp_pd(ax, _mm256_set1_pd(0x1p31), _CMP_LT_OQ)) == 0xF;
}

/* Points go in blocks of BLOCK groups of four, in passes: the cells and their column hashes
 * (hash4) of every group, then the corner hashes (pair), then the gradients and lerps. Each
 * pass is a short loop whose loads do not depend on each other across groups, so the
 * processor overlaps their cache misses (the tables are 256 KiB); one long loop per group
 * stalled on them (perf: a third of the time on the two dependent loads). */
#define BLOCK 16

AVX2 static size_t noise3_avx2(const udm1_noise *n, const double *xyz, size_t count, size_t stride, double *out)
{
    size_t i = 0;
    while (i + 4 <= count) {
        size_t groups = (count - i) / 4 < BLOCK ? (count - i) / 4 : BLOCK;
        __m256d fx[BLOCK], fy[BLOCK], fz[BLOCK];
        __m128i z0[BLOCK];
        int32_t ci[BLOCK * 4], qi[BLOCK * 16];
        uint32_t c4[BLOCK * 4];
        __m128i q[BLOCK][4];
        unsigned scalar = 0; /* groups with a coordinate at or past 2^31: the scalar code */
        for (size_t g = 0; g < groups; ++g) {
            const double *p = xyz + (i + 4 * g) * stride;
            __m256d x = _mm256_set_pd(p[3 * stride], p[2 * stride], p[stride], p[0]);
            __m256d y = _mm256_set_pd(p[3 * stride + 1], p[2 * stride + 1], p[stride + 1], p[1]);
            __m256d z = _mm256_set_pd(p[3 * stride + 2], p[2 * stride + 2], p[stride + 2], p[2]);
            if (!(in_range(x) && in_range(y) && in_range(z))) {
                scalar |= 1u << g;
                x = y = z = _mm256_setzero_pd();
            }
            __m128i X0, X1, Y0, Y1, Z1;
            fx[g] = axis(x, &X0, &X1);
            fy[g] = axis(y, &Y0, &Y1);
            fz[g] = axis(z, &z0[g], &Z1);
            _mm_storeu_si128((__m128i *)(ci + 4 * g), _mm_or_si128(_mm_slli_epi32(X0, 8), Y0));
        }
        /* the four column hashes perm[perm[x] + y] of each cell in one load (hash4) */
        for (size_t k = 0; k < 4 * groups; ++k) c4[k] = n->hash4[ci[k]];
        __m128i m = _mm_set1_epi32(255);
        for (size_t g = 0; g < groups; ++g) { /* each column's hashes at z and z + 1 in one load (pair) */
            __m128i c = _mm_loadu_si128((const __m128i *)(c4 + 4 * g)), Z0 = z0[g];
            _mm_storeu_si128((__m128i *)(qi + 16 * g), _mm_add_epi32(_mm_and_si128(c, m), Z0));
            _mm_storeu_si128((__m128i *)(qi + 16 * g + 4), _mm_add_epi32(_mm_and_si128(_mm_srli_epi32(c, 16), m), Z0));
            _mm_storeu_si128((__m128i *)(qi + 16 * g + 8), _mm_add_epi32(_mm_and_si128(_mm_srli_epi32(c, 8), m), Z0));
            _mm_storeu_si128((__m128i *)(qi + 16 * g + 12), _mm_add_epi32(_mm_srli_epi32(c, 24), Z0));
        }
        int32_t *qv = (int32_t *)q;
        for (size_t k = 0; k < 16 * groups; ++k) qv[k] = n->pair[qi[k]];
        for (size_t g = 0; g < groups; ++g, i += 4) {
            if (scalar >> g & 1u) {
                for (size_t k = 0; k < 4; ++k) {
                    const double *p = xyz + (i + k) * stride;
                    out[i + k] = udm1_noise_3d(n, p[0], p[1], p[2]);
                }
                continue;
            }
            __m256d x = fx[g], y = fy[g], z = fz[g];
            __m256d u = fade(x), v = fade(y), w = fade(z);
            __m256d one = _mm256_set1_pd(1.0), x1 = _mm256_sub_pd(x, one), y1 = _mm256_sub_pd(y, one),
                    z1 = _mm256_sub_pd(z, one);
            __m128i qA = q[g][0], qB = q[g][1], qA1 = q[g][2], qB1 = q[g][3];
            __m256d g000 = grad3(qA, x, y, z);
            __m256d g100 = grad3(qB, x1, y, z);
            __m256d g010 = grad3(qA1, x, y1, z);
            __m256d g110 = grad3(qB1, x1, y1, z);
            __m256d g001 = grad3(_mm_srli_epi32(qA, 8), x, y, z1);
            __m256d g101 = grad3(_mm_srli_epi32(qB, 8), x1, y, z1);
            __m256d g011 = grad3(_mm_srli_epi32(qA1, 8), x, y1, z1);
            __m256d g111 = grad3(_mm_srli_epi32(qB1, 8), x1, y1, z1);
            __m256d r = lerp(w, lerp(v, lerp(u, g000, g100), lerp(u, g010, g110)),
                             lerp(v, lerp(u, g001, g101), lerp(u, g011, g111)));
            _mm256_storeu_pd(out + i, r);
        }
    }
    return i;
}

AVX2 static size_t noise2_avx2(const udm1_noise *n, const double *xyz, size_t count, size_t stride, double *out)
{
    size_t i = 0;
    while (i + 4 <= count) {
        size_t groups = (count - i) / 4 < BLOCK ? (count - i) / 4 : BLOCK;
        __m256d fx[BLOCK], fy[BLOCK];
        int32_t ci[BLOCK * 4];
        uint32_t c4[BLOCK * 4];
        unsigned scalar = 0;
        for (size_t g = 0; g < groups; ++g) {
            const double *p = xyz + (i + 4 * g) * stride;
            __m256d x = _mm256_set_pd(p[3 * stride], p[2 * stride], p[stride], p[0]);
            __m256d y = _mm256_set_pd(p[3 * stride + 1], p[2 * stride + 1], p[stride + 1], p[1]);
            if (!(in_range(x) && in_range(y))) {
                scalar |= 1u << g;
                x = y = _mm256_setzero_pd();
            }
            __m128i X0, X1, Y0, Y1;
            fx[g] = axis(x, &X0, &X1);
            fy[g] = axis(y, &Y0, &Y1);
            _mm_storeu_si128((__m128i *)(ci + 4 * g), _mm_or_si128(_mm_slli_epi32(X0, 8), Y0));
        }
        /* the cell's four corner hashes perm[perm[x] + y] in one load (hash4) */
        for (size_t k = 0; k < 4 * groups; ++k) c4[k] = n->hash4[ci[k]];
        for (size_t g = 0; g < groups; ++g, i += 4) {
            if (scalar >> g & 1u) {
                for (size_t k = 0; k < 4; ++k) {
                    const double *p = xyz + (i + k) * stride;
                    out[i + k] = udm1_noise_2d(n, p[0], p[1]);
                }
                continue;
            }
            __m256d x = fx[g], y = fy[g];
            __m256d u = fade(x), v = fade(y);
            __m256d one = _mm256_set1_pd(1.0), x1 = _mm256_sub_pd(x, one), y1 = _mm256_sub_pd(y, one);
            __m128i c = _mm_loadu_si128((const __m128i *)(c4 + 4 * g));
            __m256d g00 = grad2(c, x, y);
            __m256d g10 = grad2(_mm_srli_epi32(c, 16), x1, y);
            __m256d g01 = grad2(_mm_srli_epi32(c, 8), x, y1);
            __m256d g11 = grad2(_mm_srli_epi32(c, 24), x1, y1);
            __m256d r = lerp(v, lerp(u, g00, g10), lerp(u, g01, g11));
            _mm256_storeu_pd(out + i, _mm256_mul_pd(_mm256_set1_pd(0.507), r)); /* noise1234's scale */
        }
    }
    return i;
}

size_t udm1_noise_points_fast(const udm1_noise *n, uint32_t dims, const double *xyz, size_t count, size_t stride,
                              double *out)
{
    if (n->kind != UDM1_NOISE_IMPROVED || n->period[0] || n->period[1] || n->period[2]) return 0;
    if (dims < 2 || dims > 3) return 0;
    /* an AVX-512 version with 8 lanes measured 0.7x this one on the benchmark machine (gathers): not kept */
    if (__builtin_cpu_supports("avx2"))
        return dims == 3 ? noise3_avx2(n, xyz, count, stride, out) : noise2_avx2(n, xyz, count, stride, out);
    return 0;
}

#else
size_t udm1_noise_points_fast(const udm1_noise *n, uint32_t dims, const double *xyz, size_t count, size_t stride,
                              double *out)
{
    (void)n, (void)dims, (void)xyz, (void)count, (void)stride, (void)out;
    return 0;
}
#endif
