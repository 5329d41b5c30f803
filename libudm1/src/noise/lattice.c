/* noise/lattice.c - the lattice noises' scalar code in double and in float (noise/lattice_impl.h, one
 * source for both), the per-point functions and the batch evaluations with gradients, which hand what
 * they can to the vector kernels (noise_simd.c, noise_simd_f32.c) and the rest to the scalar code. */
#include "noise/noise_tables.h"

#include <math.h>

#define REAL double
#define R(fn) fn##_f64
#define RF(fn) fn
#define ZERO_SIGN
#include "noise/lattice_impl.h"
#undef ZERO_SIGN
#undef REAL
#undef R
#undef RF

#define REAL float
#define R(fn) fn##_f32
#define RF(fn) fn##f
#define ZERO_SIGN +0.0f
#include "noise/lattice_impl.h"
#undef ZERO_SIGN
#undef REAL
#undef R
#undef RF

double udm1_noise_3d(const udm1_noise *n, double x, double y, double z)
{
    /* NaN or infinite; each on its own: a sum of huge finite coordinates would overflow (found by fuzzing) */
    if (UDM1_UNLIKELY(!n)) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_noise_3d: noise is NULL"), NAN;
    if (UDM1_UNLIKELY(!(fabs(x) < INFINITY && fabs(y) < INFINITY && fabs(z) < INFINITY))) return NAN;
    return noise3_f64(n, x, y, z, NULL);
}

double udm1_noise_2d(const udm1_noise *n, double x, double y)
{
    if (UDM1_UNLIKELY(!n)) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_noise_2d: noise is NULL"), NAN;
    if (UDM1_UNLIKELY(!(fabs(x) < INFINITY && fabs(y) < INFINITY))) return NAN;
    return noise2_f64(n, x, y, NULL);
}

double udm1_noise_1d(const udm1_noise *n, double x)
{
    if (UDM1_UNLIKELY(!n)) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_noise_1d: noise is NULL"), NAN;
    if (UDM1_UNLIKELY(!(fabs(x) < INFINITY))) return NAN;
    return noise1_f64(n, x, NULL);
}

double udm1_noise_4d(const udm1_noise *n, double x, double y, double z, double w)
{
    if (UDM1_UNLIKELY(!n)) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_noise_4d: noise is NULL"), NAN;
    if (UDM1_UNLIKELY(n->kind != UDM1_NOISE_IMPROVED))
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "udm1_noise_4d: 4D noise is improved noise only"), NAN;
    if (UDM1_UNLIKELY(!(fabs(x) < INFINITY && fabs(y) < INFINITY && fabs(z) < INFINITY && fabs(w) < INFINITY)))
        return NAN;
    return noise4_f64(n, x, y, z, w, NULL);
}

/* The checks both batch evaluations share; what they say names the function. */
static udm1_status eval_args(const char *fn, const udm1_noise *n, uint32_t dims, const void *const *axes,
                             size_t stride, size_t count, const void *value, const void *gradient)
{
    if (!n || !axes || (!value && !gradient))
        return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn,
                         !n ? "noise" : !axes ? "axes" : "value and gradient are both");
    if (dims < 1 || dims > 4)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: dims %u is not 1, 2, 3 or 4", fn, dims);
    if (dims == 4 && n->kind != UDM1_NOISE_IMPROVED)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: 4D noise is improved noise only", fn);
    if (stride == 0) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: stride is 0", fn);
    for (uint32_t c = 0; c < dims; ++c)
        if (!axes[c] && count) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: axes[%u] is NULL", fn, c);
    return UDM1_OK;
}

/* The message of a batch refused for point i's coordinate c (core/finite.h found it before any output). */
udm1_status udm1_not_finite(const char *fn, size_t i, uint32_t c)
{
    return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: point %zu coordinate %u is not finite", fn, i, c);
}

udm1_status udm1_noise_eval(const udm1_noise *n, uint32_t dims, const double *const axes[], size_t stride,
                            size_t count, double *value, double *gradient)
{
    static const char fn[] = "udm1_noise_eval";
    udm1_status st = eval_args(fn, n, dims, (const void *const *)axes, stride, count, value, gradient);
    if (st != UDM1_OK) return st;
    return udm1_noise_batch_f64(fn, n, dims, axes, stride, count, value, gradient);
}

udm1_status udm1_noise_eval_f32(const udm1_noise *n, uint32_t dims, const float *const axes[], size_t stride,
                                size_t count, float *value, float *gradient)
{
    static const char fn[] = "udm1_noise_eval_f32";
    udm1_status st = eval_args(fn, n, dims, (const void *const *)axes, stride, count, value, gradient);
    if (st != UDM1_OK) return st;
    return udm1_noise_batch_f32(fn, n, dims, axes, stride, count, value, gradient);
}

double udm1_lattice_f64(const udm1_noise *n, uint32_t dims, const double *c, double *grad)
{
    switch (dims) {
    case 1: return noise1_f64(n, c[0], grad);
    case 2: return noise2_f64(n, c[0], c[1], grad);
    case 3: return noise3_f64(n, c[0], c[1], c[2], grad);
    default: return noise4_f64(n, c[0], c[1], c[2], c[3], grad);
    }
}

float udm1_lattice_f32(const udm1_noise *n, uint32_t dims, const float *c, float *grad)
{
    switch (dims) {
    case 1: return noise1_f32(n, c[0], grad);
    case 2: return noise2_f32(n, c[0], c[1], grad);
    case 3: return noise3_f32(n, c[0], c[1], c[2], grad);
    default: return noise4_f32(n, c[0], c[1], c[2], c[3], grad);
    }
}
