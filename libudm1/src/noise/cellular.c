/* cellular.c - cellular (Worley) noise: udm1_cellular_eval and udm1_cellular_eval_f32 (udm1/cellular.h),
 * the scalar search of noise/cellular_impl.h in both precisions, and the vector kernels' entry. */
#include "core/finite.h"
#include "noise/noise_tables.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define REAL double
#define R(f) f##_f64
#define RT(f) f##_f64
#define RF(fn) fn
#include "noise/cellular_impl.h"
#undef REAL
#undef R
#undef RT
#undef RF

#define REAL float
#define R(f) f##_f32
#define RT(f) f##_f32
#define RF(fn) fn##f
#include "noise/cellular_impl.h"
#undef REAL
#undef R
#undef RT
#undef RF

/* The same search compiled for processors with FMA (every AVX2 one): the same operations, fma() in one
 * instruction instead of a library call, so the same values, several times faster. */
#if defined(UDM1_HAVE_ISA_KERNELS)
#pragma GCC push_options
#pragma GCC target("avx2,fma")
#define CELLULAR_REUSE_TYPES
#define CELLULAR_FMA_INSTRUCTION
#define REAL double
#define R(f) f##_f64_fma
#define RT(f) f##_f64
#define RF(fn) fn
#include "noise/cellular_impl.h"
#undef REAL
#undef R
#undef RT
#undef RF
#define REAL float
#define R(f) f##_f32_fma
#define RT(f) f##_f32
#define RF(fn) fn##f
#include "noise/cellular_impl.h"
#undef REAL
#undef R
#undef RT
#undef RF
#undef CELLULAR_REUSE_TYPES
#undef CELLULAR_FMA_INSTRUCTION
#pragma GCC pop_options
#include "core/isa.h"
/* (the AVX2 and AVX-512 levels imply AVX2 and FMA: core/isa.c) */
#define SEARCH(P, n, u, c, s)                                                                                     \
    (udm1_isa_level() >= UDM1_ISA_AVX2 ? cellular_search_##P##_fma(n, u, c, s) : cellular_search_##P(n, u, c, s))
#else
#define SEARCH(P, n, u, c, s) cellular_search_##P(n, u, c, s)
#endif

void udm1_cellular_params_init(udm1_cellular_params *params)
{
    if (!params) return;
    memset(params, 0, sizeof *params);
    params->struct_size = (uint32_t)sizeof *params;
    params->metric = UDM1_CELLULAR_EUCLIDEAN;
    params->output = UDM1_CELLULAR_F1;
    params->jitter = 1.0;
    params->exponent = 2.0;
}

/* The caller's params (or the defaults), checked; the metric with MINKOWSKI of exponent 2 or 1 made
 * EUCLIDEAN or MANHATTAN (the same values, bit for bit, by the same operations). */
static udm1_status load(const char *fn, const udm1_cellular_params *caller, udm1_cellular_params *p)
{
    udm1_cellular_params_init(p);
    if (caller) {
        udm1_status st = udm1_read_struct(fn, "params", "udm1_cellular_params_init", caller, sizeof *p, p, sizeof *p);
        if (st != UDM1_OK) return st;
    }
    if (p->metric > UDM1_CELLULAR_MINKOWSKI)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: params.metric %u is not a udm1_cellular_metric", fn, p->metric);
    if (p->output > UDM1_CELLULAR_CELL)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: params.output %u is not a udm1_cellular_output", fn, p->output);
    if (p->reserved) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: params.reserved is not 0", fn);
    if (!(p->jitter >= 0.0 && p->jitter <= 1.0))
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: params.jitter %g is outside [0, 1]", fn, p->jitter);
    if (!(p->exponent >= 1.0 && p->exponent <= 64.0))
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: params.exponent %g is outside [1, 64]", fn, p->exponent);
    if (p->metric == UDM1_CELLULAR_MINKOWSKI && p->exponent == 2.0) p->metric = UDM1_CELLULAR_EUCLIDEAN;
    if (p->metric == UDM1_CELLULAR_MINKOWSKI && p->exponent == 1.0) p->metric = UDM1_CELLULAR_MANHATTAN;
    return UDM1_OK;
}

static uint32_t needed(uint32_t output) /* how many nearest distances an output needs */
{
    return output == UDM1_CELLULAR_F3 ? 3 : (output == UDM1_CELLULAR_F2 || output == UDM1_CELLULAR_F2_MINUS_F1) ? 2 : 1;
}

static udm1_status check_call(const char *fn, const udm1_noise *n, uint32_t dims, const void *axes0,
                              const void *const *axes, size_t stride, const void *out)
{
    if (!n || !axes || !out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: a pointer argument is NULL", fn);
    if (dims < 2 || dims > 3) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: dims %u is not 2 or 3", fn, dims);
    for (uint32_t c = 0; c < dims; ++c)
        if (!axes[c]) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: axes[%u] is NULL", fn, c);
    if (stride == 0) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: stride is 0", fn);
    (void)axes0;
    return UDM1_OK;
}

udm1_status udm1_cellular_eval(const udm1_noise *n, const udm1_cellular_params *params, uint32_t dims,
                               const double *const axes[], size_t stride, size_t count, double *out)
{
    static const char fn[] = "udm1_cellular_eval";
    udm1_status st = check_call(fn, n, dims, NULL, (const void *const *)axes, stride, out);
    if (st != UDM1_OK) return st;
    udm1_cellular_params p;
    if ((st = load(fn, params, &p)) != UDM1_OK) return st;
    uint32_t axis = 0;
    size_t bad = udm1_first_nonfinite_f64(dims, axes, stride, count, &axis);
    if (bad < count) return udm1_not_finite(fn, bad, axis);
    cellular_setup_f64 u;
    cellular_setup_init_f64(&u, n, dims, p.metric, needed(p.output), p.jitter, p.exponent);
    size_t i = udm1_cellular_fast_f64(n, &p, dims, axes, stride, count, out);
    for (; i < count; ++i) {
        double c[3] = {0, 0, 0};
        for (uint32_t a = 0; a < dims; ++a) c[a] = axes[a][i * stride];
        nearest3_f64 s;
        SEARCH(f64, n, &u, c, &s);
        out[i] = cellular_output_f64(&s, &u, p.output);
    }
    return UDM1_OK;
}

udm1_status udm1_cellular_eval_f32(const udm1_noise *n, const udm1_cellular_params *params, uint32_t dims,
                                   const float *const axes[], size_t stride, size_t count, float *out)
{
    static const char fn[] = "udm1_cellular_eval_f32";
    udm1_status st = check_call(fn, n, dims, NULL, (const void *const *)axes, stride, out);
    if (st != UDM1_OK) return st;
    udm1_cellular_params p;
    if ((st = load(fn, params, &p)) != UDM1_OK) return st;
    uint32_t axis = 0;
    size_t bad = udm1_first_nonfinite_f32(dims, axes, stride, count, &axis);
    if (bad < count) return udm1_not_finite(fn, bad, axis);
    cellular_setup_f32 u;
    cellular_setup_init_f32(&u, n, dims, p.metric, needed(p.output), p.jitter, p.exponent);
    size_t i = udm1_cellular_fast_f32(n, &p, dims, axes, stride, count, out);
    for (; i < count; ++i) {
        float c[3] = {0, 0, 0};
        for (uint32_t a = 0; a < dims; ++a) c[a] = axes[a][i * stride];
        nearest3_f32 s;
        SEARCH(f32, n, &u, c, &s);
        out[i] = cellular_output_f32(&s, &u, p.output);
    }
    return UDM1_OK;
}

udm1_status udm1_cellular_offsets(const udm1_noise *n, uint8_t *offsets)
{
    if (!n || !offsets) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_cellular_offsets: %s is NULL", n ? "offsets" : "noise");
    for (int h = 0; h < 256; ++h)
        for (int a = 0; a < 3; ++a) offsets[3 * h + a] = n->feature[a][h];
    return UDM1_OK;
}

void udm1_cellular_nearest3(const udm1_noise *n, double e, const double c[3], double F[3], double nearest[3])
{
    uint32_t metric = e == 2.0 ? UDM1_CELLULAR_EUCLIDEAN : e == 1.0 ? UDM1_CELLULAR_MANHATTAN : UDM1_CELLULAR_MINKOWSKI;
    cellular_setup_f64 u;
    cellular_setup_init_f64(&u, n, 3, metric, 3, 1.0, e);
    nearest3_f64 s;
    SEARCH(f64, n, &u, c, &s);
    for (int k = 0; k < 3; ++k) F[k] = s.F[k];
    if (nearest) /* the point's cell + the nearest's offset (exact far from the origin: floor(c) is) */
        for (int a = 0; a < 3; ++a)
            nearest[a] = (floor(c[a]) + s.offset[a]) + (u.c1 * n->feature[a][s.nearest] + u.c0);
}
