/* noise/side_check.h - a batch's coordinates checked for NaN and infinities while a vector kernel
 * evaluates other points (udm1_side_check, noise/noise_tables.h). The kernel's loop takes one step per
 * iteration: the next few 64-byte vectors of each run still to check, accumulated as x * 0 + acc (0 for
 * a finite x, NaN for a NaN or an infinity, and NaN stays; with 256-bit vectors the bits of x - x,
 * ORed). Those loads depend on nothing the evaluation computes, so the processor overlaps their cache
 * misses with it: the input is checked for a few instructions per iteration instead of a pass over
 * memory before the evaluation, which the batches (noise/batch.c) would otherwise need so that they
 * write nothing until every coordinate is known to be finite. Not a public header; include it after
 * <immintrin.h> where UDM1_HAVE_ISA_KERNELS is defined. */
#ifndef UDM1_NOISE_SIDE_CHECK_H
#define UDM1_NOISE_SIDE_CHECK_H

#include "noise/noise_tables.h"

#define UDM1_SIDE512 __attribute__((target("avx512f")))
#define UDM1_SIDE256 __attribute__((target("avx2")))

UDM1_SIDE512 static inline __m512 udm1_side_step512_ps(udm1_side_check *s, __m512 acc)
{
    if (s->steps) {
        --s->steps;
        for (unsigned r = 0; r < s->runs; ++r) {
            const char *p = s->at[r];
            for (unsigned v = 0; v < s->vectors; ++v)
                acc = _mm512_fmadd_ps(_mm512_loadu_ps((const float *)(const void *)(p + 64 * v)), _mm512_setzero_ps(),
                                      acc);
            s->at[r] = p + 64 * (size_t)s->vectors;
        }
    }
    return acc;
}

UDM1_SIDE512 static inline __m512d udm1_side_step512_pd(udm1_side_check *s, __m512d acc)
{
    if (s->steps) {
        --s->steps;
        for (unsigned r = 0; r < s->runs; ++r) {
            const char *p = s->at[r];
            for (unsigned v = 0; v < s->vectors; ++v)
                acc = _mm512_fmadd_pd(_mm512_loadu_pd((const double *)(const void *)(p + 64 * v)), _mm512_setzero_pd(),
                                      acc);
            s->at[r] = p + 64 * (size_t)s->vectors;
        }
    }
    return acc;
}

UDM1_SIDE256 static inline __m256 udm1_side_step256_ps(udm1_side_check *s, __m256 acc)
{
    if (s->steps) {
        --s->steps;
        for (unsigned r = 0; r < s->runs; ++r) {
            const char *p = s->at[r];
            for (unsigned v = 0; v < 2 * s->vectors; ++v)
            {
                __m256 x = _mm256_loadu_ps((const float *)(const void *)(p + 32 * v));
                acc = _mm256_or_ps(acc, _mm256_sub_ps(x, x));
            }
            s->at[r] = p + 64 * (size_t)s->vectors;
        }
    }
    return acc;
}

UDM1_SIDE256 static inline __m256d udm1_side_step256_pd(udm1_side_check *s, __m256d acc)
{
    if (s->steps) {
        --s->steps;
        for (unsigned r = 0; r < s->runs; ++r) {
            const char *p = s->at[r];
            for (unsigned v = 0; v < 2 * s->vectors; ++v)
            {
                __m256d x = _mm256_loadu_pd((const double *)(const void *)(p + 32 * v));
                acc = _mm256_or_pd(acc, _mm256_sub_pd(x, x));
            }
            s->at[r] = p + 64 * (size_t)s->vectors;
        }
    }
    return acc;
}

/* The kernel's last word: whether its accumulator saw a NaN or an infinity. */
UDM1_SIDE512 static inline void udm1_side_end512_ps(udm1_side_check *s, __m512 acc)
{
    s->bad |= _mm512_cmp_ps_mask(acc, acc, _CMP_UNORD_Q) != 0;
}
UDM1_SIDE512 static inline void udm1_side_end512_pd(udm1_side_check *s, __m512d acc)
{
    s->bad |= _mm512_cmp_pd_mask(acc, acc, _CMP_UNORD_Q) != 0;
}
UDM1_SIDE256 static inline void udm1_side_end256_ps(udm1_side_check *s, __m256 acc)
{
    s->bad |= !_mm256_testz_si256(_mm256_castps_si256(acc), _mm256_castps_si256(acc));
}
UDM1_SIDE256 static inline void udm1_side_end256_pd(udm1_side_check *s, __m256d acc)
{
    s->bad |= !_mm256_testz_si256(_mm256_castpd_si256(acc), _mm256_castpd_si256(acc));
}

#endif /* UDM1_NOISE_SIDE_CHECK_H */
