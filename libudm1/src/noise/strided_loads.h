/* strided_loads.h - the coordinates of 16 floats' or 8 doubles' points into a vector register, for the
 * AVX-512 noise kernels. One array per axis (stride 1) is a plain load. Points in rows of 2 to 4 numbers
 * (stride 2..4: numpy's (n, 2), (n, 3) and (n, 4) arrays) are read by four masked contiguous loads of
 * the span they cover and two permutations across register pairs: a gather of 16 lanes costs several
 * times that on the processors measured. Larger strides use a gather. The masks stop the loads at the
 * last point's coordinate, so nothing past the caller's array is read. Not a public header; include
 * it after <immintrin.h> where UDM1_HAVE_ISA_KERNELS is defined. */
#ifndef UDM1_NOISE_STRIDED_LOADS_H
#define UDM1_NOISE_STRIDED_LOADS_H

#include <stddef.h>
#include <stdint.h>

#define UDM1_STRIDED_TARGET __attribute__((target("avx512f,avx512vl,avx512dq,avx512bw")))

typedef struct {
    size_t stride;
    __m512i index;   /* lane k: k * stride (32-bit lanes for floats, 64-bit for doubles) */
    __mmask16 m[4];  /* which elements of each of the four loads lie in the span */
    __mmask16 upper; /* lanes whose element lies in the third or fourth load */
} strided_loads;

/* lanes: 16 (floats) or 8 (doubles); stride at most 2^26 (the callers' condition: 32-bit gather offsets) */
UDM1_STRIDED_TARGET static inline strided_loads strided_loads_init(size_t stride, unsigned lanes)
{
    strided_loads s;
    s.stride = stride;
    if (lanes == 16)
        s.index = _mm512_mullo_epi32(_mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
                                     _mm512_set1_epi32((int)stride));
    else
        s.index = _mm512_mullo_epi64(_mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7),
                                     _mm512_set1_epi64((long long)stride));
    size_t span = (lanes - 1) * stride + 1; /* elements from the first point's to the last's */
    s.upper = 0;
    for (unsigned j = 0; j < 4; ++j) {
        uint32_t m = 0;
        for (unsigned e = 0; e < lanes; ++e)
            if (j * lanes + e < span) m |= 1u << e;
        s.m[j] = (__mmask16)m;
    }
    for (unsigned k = 0; k < lanes; ++k)
        if (k * stride >= 2 * lanes) s.upper |= (__mmask16)(1u << k);
    return s;
}

/* the permutations read the low 5 (floats) or 4 (doubles) bits of a lane's index: k * stride picks
 * within a pair of registers, and the pair by whether it is past 2 * lanes */
UDM1_STRIDED_TARGET static inline __m512 strided_load16(const strided_loads *s, const float *p)
{
    if (s->stride == 1) return _mm512_loadu_ps(p);
    if (s->stride > 4) return _mm512_i32gather_ps(s->index, p, 4);
    __m512 a = _mm512_maskz_loadu_ps(s->m[0], p), b = _mm512_maskz_loadu_ps(s->m[1], p + 16);
    __m512 c = _mm512_maskz_loadu_ps(s->m[2], p + 32), d = _mm512_maskz_loadu_ps(s->m[3], p + 48);
    return _mm512_mask_blend_ps(s->upper, _mm512_permutex2var_ps(a, s->index, b),
                                _mm512_permutex2var_ps(c, s->index, d));
}

UDM1_STRIDED_TARGET static inline __m512d strided_load8(const strided_loads *s, const double *p)
{
    if (s->stride == 1) return _mm512_loadu_pd(p);
    if (s->stride > 4) return _mm512_i64gather_pd(s->index, p, 8);
    __m512d a = _mm512_maskz_loadu_pd((__mmask8)s->m[0], p), b = _mm512_maskz_loadu_pd((__mmask8)s->m[1], p + 8);
    __m512d c = _mm512_maskz_loadu_pd((__mmask8)s->m[2], p + 16), d = _mm512_maskz_loadu_pd((__mmask8)s->m[3], p + 24);
    return _mm512_mask_blend_pd((__mmask8)s->upper, _mm512_permutex2var_pd(a, s->index, b),
                                _mm512_permutex2var_pd(c, s->index, d));
}

#endif
