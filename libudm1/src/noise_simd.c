/* noise_simd.c - the improved noise on 4 points at a time with AVX2, for the
 * batch calls. It performs the scalar code's operations in the same order on
 * the same doubles (floor, fade, Perlin's +-u +-v gradients as blends and sign
 * flips, the lerps), so its results equal udm1_noise_3d / udm1_noise_2d bit
 * for bit; tests/c/test_noise.c checks it. Groups of four with a coordinate
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

#define GATHER(base, idx) _mm_i32gather_epi32((const int *)(base), (idx), 4)

AVX2 static size_t noise3_avx2(const udm1_noise *n, const double *xyz, size_t count, size_t stride, double *out)
{
    const int32_t *p = n->perm32;
    size_t i = 0;
    for (; i + 4 <= count; i += 4) {
        const double *q = xyz + i * stride;
        __m256d x = _mm256_set_pd(q[3 * stride], q[2 * stride], q[stride], q[0]);
        __m256d y = _mm256_set_pd(q[3 * stride + 1], q[2 * stride + 1], q[stride + 1], q[1]);
        __m256d z = _mm256_set_pd(q[3 * stride + 2], q[2 * stride + 2], q[stride + 2], q[2]);
        if (!(in_range(x) && in_range(y) && in_range(z))) { /* the scalar code for these four */
            for (size_t k = 0; k < 4; ++k)
                out[i + k] = udm1_noise_3d(n, q[k * stride], q[k * stride + 1], q[k * stride + 2]);
            continue;
        }
        __m128i X0, X1, Y0, Y1, Z0, Z1;
        x = axis(x, &X0, &X1);
        y = axis(y, &Y0, &Y1);
        z = axis(z, &Z0, &Z1);
        __m256d u = fade(x), v = fade(y), w = fade(z);
        __m128i pX0 = GATHER(p, X0), pX1 = GATHER(p, X1);
        __m128i pA = GATHER(p, _mm_add_epi32(pX0, Y0)), pB = GATHER(p, _mm_add_epi32(pX1, Y0));
        __m128i pA1 = GATHER(p, _mm_add_epi32(pX0, Y1)), pB1 = GATHER(p, _mm_add_epi32(pX1, Y1));
        __m256d one = _mm256_set1_pd(1.0), x1 = _mm256_sub_pd(x, one), y1 = _mm256_sub_pd(y, one),
                z1 = _mm256_sub_pd(z, one);
        __m256d g000 = grad3(GATHER(p, _mm_add_epi32(pA, Z0)), x, y, z);
        __m256d g100 = grad3(GATHER(p, _mm_add_epi32(pB, Z0)), x1, y, z);
        __m256d g010 = grad3(GATHER(p, _mm_add_epi32(pA1, Z0)), x, y1, z);
        __m256d g110 = grad3(GATHER(p, _mm_add_epi32(pB1, Z0)), x1, y1, z);
        __m256d g001 = grad3(GATHER(p, _mm_add_epi32(pA, Z1)), x, y, z1);
        __m256d g101 = grad3(GATHER(p, _mm_add_epi32(pB, Z1)), x1, y, z1);
        __m256d g011 = grad3(GATHER(p, _mm_add_epi32(pA1, Z1)), x, y1, z1);
        __m256d g111 = grad3(GATHER(p, _mm_add_epi32(pB1, Z1)), x1, y1, z1);
        __m256d r = lerp(w, lerp(v, lerp(u, g000, g100), lerp(u, g010, g110)),
                         lerp(v, lerp(u, g001, g101), lerp(u, g011, g111)));
        _mm256_storeu_pd(out + i, r);
    }
    return i;
}

AVX2 static size_t noise2_avx2(const udm1_noise *n, const double *xyz, size_t count, size_t stride, double *out)
{
    const int32_t *p = n->perm32;
    size_t i = 0;
    for (; i + 4 <= count; i += 4) {
        const double *q = xyz + i * stride;
        __m256d x = _mm256_set_pd(q[3 * stride], q[2 * stride], q[stride], q[0]);
        __m256d y = _mm256_set_pd(q[3 * stride + 1], q[2 * stride + 1], q[stride + 1], q[1]);
        if (!(in_range(x) && in_range(y))) {
            for (size_t k = 0; k < 4; ++k) out[i + k] = udm1_noise_2d(n, q[k * stride], q[k * stride + 1]);
            continue;
        }
        __m128i X0, X1, Y0, Y1;
        x = axis(x, &X0, &X1);
        y = axis(y, &Y0, &Y1);
        __m256d u = fade(x), v = fade(y);
        __m128i pX0 = GATHER(p, X0), pX1 = GATHER(p, X1);
        __m256d one = _mm256_set1_pd(1.0), x1 = _mm256_sub_pd(x, one), y1 = _mm256_sub_pd(y, one);
        __m256d g00 = grad2(GATHER(p, _mm_add_epi32(pX0, Y0)), x, y);
        __m256d g10 = grad2(GATHER(p, _mm_add_epi32(pX1, Y0)), x1, y);
        __m256d g01 = grad2(GATHER(p, _mm_add_epi32(pX0, Y1)), x, y1);
        __m256d g11 = grad2(GATHER(p, _mm_add_epi32(pX1, Y1)), x1, y1);
        __m256d r = lerp(v, lerp(u, g00, g10), lerp(u, g01, g11));
        _mm256_storeu_pd(out + i, _mm256_mul_pd(_mm256_set1_pd(0.507), r)); /* noise1234's scale */
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
