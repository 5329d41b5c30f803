/* finite.c - see finite.h. A contiguous run is searched as a whole: x - x is +0 for a finite x and NaN for
 * a NaN or an infinity, so the OR of the bits of x - x over the run is 0 exactly when all are finite (AVX-512
 * classifies instead). Only when a run holds one is the first bad point looked for, point by point. */
#include "core/finite.h"
#include "core/isa.h"

#include <math.h>
#include <string.h>

static int run_bad_f64(const double *p, size_t len)
{
    uint64_t acc = 0;
    for (size_t i = 0; i < len; ++i) {
        double d = p[i] - p[i];
        uint64_t bits;
        memcpy(&bits, &d, sizeof bits);
        acc |= bits;
    }
    return acc != 0;
}

static int run_bad_f32(const float *p, size_t len)
{
    uint32_t acc = 0;
    for (size_t i = 0; i < len; ++i) {
        float d = p[i] - p[i];
        uint32_t bits;
        memcpy(&bits, &d, sizeof bits);
        acc |= bits;
    }
    return acc != 0;
}

#if defined(UDM1_HAVE_ISA_KERNELS)
#include <immintrin.h>

#define AVX2 __attribute__((target("avx2")))
#define AVX512 __attribute__((target("avx2,avx512f,avx512dq")))
#define NOT_FINITE 0x99 /* vfpclass: quiet NaN, +infinity, -infinity, signalling NaN */

AVX2 static int run_bad_f64_avx2(const double *p, size_t len)
{
    __m256d acc = _mm256_setzero_pd();
    size_t i = 0;
    for (; i + 16 <= len; i += 16) {
        __m256d a = _mm256_loadu_pd(p + i), b = _mm256_loadu_pd(p + i + 4);
        __m256d c = _mm256_loadu_pd(p + i + 8), d = _mm256_loadu_pd(p + i + 12);
        acc = _mm256_or_pd(acc, _mm256_or_pd(_mm256_or_pd(_mm256_sub_pd(a, a), _mm256_sub_pd(b, b)),
                                             _mm256_or_pd(_mm256_sub_pd(c, c), _mm256_sub_pd(d, d))));
    }
    for (; i + 4 <= len; i += 4) {
        __m256d a = _mm256_loadu_pd(p + i);
        acc = _mm256_or_pd(acc, _mm256_sub_pd(a, a));
    }
    __m256i bits = _mm256_castpd_si256(acc);
    return !_mm256_testz_si256(bits, bits) || run_bad_f64(p + i, len - i);
}

AVX2 static int run_bad_f32_avx2(const float *p, size_t len)
{
    __m256 acc = _mm256_setzero_ps();
    size_t i = 0;
    for (; i + 32 <= len; i += 32) {
        __m256 a = _mm256_loadu_ps(p + i), b = _mm256_loadu_ps(p + i + 8);
        __m256 c = _mm256_loadu_ps(p + i + 16), d = _mm256_loadu_ps(p + i + 24);
        acc = _mm256_or_ps(acc, _mm256_or_ps(_mm256_or_ps(_mm256_sub_ps(a, a), _mm256_sub_ps(b, b)),
                                             _mm256_or_ps(_mm256_sub_ps(c, c), _mm256_sub_ps(d, d))));
    }
    for (; i + 8 <= len; i += 8) {
        __m256 a = _mm256_loadu_ps(p + i);
        acc = _mm256_or_ps(acc, _mm256_sub_ps(a, a));
    }
    __m256i bits = _mm256_castps_si256(acc);
    return !_mm256_testz_si256(bits, bits) || run_bad_f32(p + i, len - i);
}

AVX512 static int run_bad_f64_avx512(const double *p, size_t len)
{
    __mmask8 bad = 0;
    size_t i = 0;
    for (; i + 32 <= len; i += 32)
        bad |= _mm512_fpclass_pd_mask(_mm512_loadu_pd(p + i), NOT_FINITE) |
               _mm512_fpclass_pd_mask(_mm512_loadu_pd(p + i + 8), NOT_FINITE) |
               _mm512_fpclass_pd_mask(_mm512_loadu_pd(p + i + 16), NOT_FINITE) |
               _mm512_fpclass_pd_mask(_mm512_loadu_pd(p + i + 24), NOT_FINITE);
    for (; i + 8 <= len; i += 8) bad |= _mm512_fpclass_pd_mask(_mm512_loadu_pd(p + i), NOT_FINITE);
    if (i < len) {
        __mmask8 tail = (__mmask8)((1u << (len - i)) - 1u);
        bad |= _mm512_mask_fpclass_pd_mask(tail, _mm512_maskz_loadu_pd(tail, p + i), NOT_FINITE);
    }
    return bad != 0;
}

AVX512 static int run_bad_f32_avx512(const float *p, size_t len)
{
    __mmask16 bad = 0;
    size_t i = 0;
    for (; i + 64 <= len; i += 64)
        bad |= _mm512_fpclass_ps_mask(_mm512_loadu_ps(p + i), NOT_FINITE) |
               _mm512_fpclass_ps_mask(_mm512_loadu_ps(p + i + 16), NOT_FINITE) |
               _mm512_fpclass_ps_mask(_mm512_loadu_ps(p + i + 32), NOT_FINITE) |
               _mm512_fpclass_ps_mask(_mm512_loadu_ps(p + i + 48), NOT_FINITE);
    for (; i + 16 <= len; i += 16) bad |= _mm512_fpclass_ps_mask(_mm512_loadu_ps(p + i), NOT_FINITE);
    if (i < len) {
        __mmask16 tail = (__mmask16)((1u << (len - i)) - 1u);
        bad |= _mm512_mask_fpclass_ps_mask(tail, _mm512_maskz_loadu_ps(tail, p + i), NOT_FINITE);
    }
    return bad != 0;
}

static int (*run_f64(void))(const double *, size_t)
{
    int level = udm1_isa_level();
    return level == UDM1_ISA_AVX512 ? run_bad_f64_avx512 : level == UDM1_ISA_AVX2 ? run_bad_f64_avx2 : run_bad_f64;
}

static int (*run_f32(void))(const float *, size_t)
{
    int level = udm1_isa_level();
    return level == UDM1_ISA_AVX512 ? run_bad_f32_avx512 : level == UDM1_ISA_AVX2 ? run_bad_f32_avx2 : run_bad_f32;
}
#else
static int (*run_f64(void))(const double *, size_t) { return run_bad_f64; }
static int (*run_f32(void))(const float *, size_t) { return run_bad_f32; }
#endif

/* The runs that hold the coordinates: one per layout (see finite.h), or 0 where they are read point by
 * point (strides above 4 per coordinate: a run would read mostly other data). Both types alike. */
#define FIRST_NONFINITE(T, run)                                                                                        \
    if (count == 0 || dims == 0) return count;                                                                         \
    int (*bad_in)(const T *, size_t) = run();                                                                          \
    size_t span = (count - 1) * stride; /* the last point's offset */                                                  \
    int packed = stride >= dims;                                                                                       \
    for (uint32_t c = 1; packed && c < dims; ++c) packed = axes[c] == axes[0] + c;                                     \
    int found = 1;                                                                                                     \
    if (packed && stride <= 4 * (size_t)dims) {                                                                        \
        found = bad_in(axes[0], span + dims);                                                                          \
    } else if (stride <= 4) {                                                                                          \
        found = 0;                                                                                                     \
        for (uint32_t c = 0; !found && c < dims; ++c) found = bad_in(axes[c], span + 1);                               \
    }                                                                                                                  \
    if (!found) return count;                                                                                          \
    for (size_t i = 0; i < count; ++i) /* (a run may also hold values between the coordinates) */                      \
        for (uint32_t c = 0; c < dims; ++c)                                                                            \
            if (!isfinite(axes[c][i * stride])) {                                                                      \
                if (axis) *axis = c;                                                                                   \
                return i;                                                                                              \
            }                                                                                                          \
    return count;

int udm1_any_nonfinite_f64(const double *p, size_t len) { return run_f64()(p, len); }
int udm1_any_nonfinite_f32(const float *p, size_t len) { return run_f32()(p, len); }

size_t udm1_first_nonfinite_f64(uint32_t dims, const double *const *axes, size_t stride, size_t count, uint32_t *axis)
{
    FIRST_NONFINITE(double, run_f64)
}

size_t udm1_first_nonfinite_f32(uint32_t dims, const float *const *axes, size_t stride, size_t count, uint32_t *axis)
{
    FIRST_NONFINITE(float, run_f32)
}
