/* integrands.c - test integrands with closed-form integrals (the 2D set of the
 * sampling literature and Genz's six families), and the integration error of
 * a sampler over randomizations. Definitions and parameters are in udm1.h. */
#include "core/hash.h"
#include "core/internal.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define INV_GOLDEN 0.6180339887498948482

enum { FIRST = UDM1_INTEGRAND_GAUSSIAN, LAST_2D = UDM1_INTEGRAND_STEP, LAST = UDM1_INTEGRAND_GENZ_DISCONTINUOUS };

static const char *const NAMES[] = {NULL,
                                    "gaussian",
                                    "product-peak",
                                    "bilinear",
                                    "disk",
                                    "triangle",
                                    "halfplane",
                                    "step",
                                    "genz-oscillatory",
                                    "genz-product-peak",
                                    "genz-corner-peak",
                                    "genz-gaussian",
                                    "genz-continuous",
                                    "genz-discontinuous"};

const char *udm1_integrand_name(uint32_t integrand)
{
    return integrand >= FIRST && integrand <= LAST ? NAMES[integrand] : NULL;
}

static double u_param(uint32_t i) { double v = 0.1 + i * INV_GOLDEN; return v - floor(v); }

static double genz_a(uint32_t kind, uint32_t d)
{
    switch (kind) {
    case UDM1_INTEGRAND_GENZ_OSCILLATORY: return 9.0 / d;
    case UDM1_INTEGRAND_GENZ_PRODUCT_PEAK:
    case UDM1_INTEGRAND_GENZ_GAUSSIAN: return 7.0 / sqrt((double)d);
    case UDM1_INTEGRAND_GENZ_CORNER_PEAK: return 2.0 / d;
    case UDM1_INTEGRAND_GENZ_CONTINUOUS: return 4.0 / sqrt((double)d);
    default: return 2.0 / d; /* discontinuous */
    }
}

static udm1_status check_kind(const char *fn, uint32_t kind, uint32_t d)
{
    if (kind < FIRST || kind > LAST) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: unknown integrand %u", fn, kind);
    if (kind <= LAST_2D && d != 2)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: integrand '%s' is 2D, d = %u given", fn, NAMES[kind], d);
    if (d == 0 || d > UDM1_MAX_DIMENSIONS)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: d = %u is outside 1..%u", fn, d, UDM1_MAX_DIMENSIONS);
    if (kind == UDM1_INTEGRAND_GENZ_CORNER_PEAK && d > 20)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: genz-corner-peak takes d <= 20, d = %u given", fn, d);
    if (kind == UDM1_INTEGRAND_GENZ_DISCONTINUOUS && d < 2)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: genz-discontinuous takes d >= 2", fn);
    return UDM1_OK;
}

/* signed area test for the triangle: inside when all edges agree */
static int in_triangle(double x, double y)
{
    static const double P[3][2] = {{0.1, 0.1}, {0.9, 0.2}, {0.3, 0.8}};
    int pos = 0, neg = 0;
    for (int k = 0; k < 3; ++k) {
        const double *a = P[k], *b = P[(k + 1) % 3];
        double c = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
        pos |= c > 0;
        neg |= c < 0;
    }
    return !(pos && neg);
}

static double eval1(uint32_t kind, uint32_t d, const double *x)
{
    switch (kind) {
    case UDM1_INTEGRAND_GAUSSIAN: {
        double dx = x[0] - 0.5, dy = x[1] - 0.5;
        return exp(-(dx * dx + dy * dy) / (2 * 0.15 * 0.15));
    }
    case UDM1_INTEGRAND_PRODUCT_PEAK: {
        double dx = x[0] - 0.5, dy = x[1] - 0.5;
        return 1.0 / ((0.01 + dx * dx) * (0.01 + dy * dy)) / 100.0;
    }
    case UDM1_INTEGRAND_BILINEAR: return x[0] * x[1];
    case UDM1_INTEGRAND_DISK: {
        double dx = x[0] - 0.5, dy = x[1] - 0.5;
        return dx * dx + dy * dy < 0.5 / PI ? 1.0 : 0.0;
    }
    case UDM1_INTEGRAND_TRIANGLE: return in_triangle(x[0], x[1]) ? 1.0 : 0.0;
    case UDM1_INTEGRAND_HALFPLANE: return x[1] < 0.2 + 0.6 * x[0] ? 1.0 : 0.0;
    case UDM1_INTEGRAND_STEP: return x[0] < 0.70710678118654752440 ? 1.0 : 0.0;
    default: break;
    }
    double a = genz_a(kind, d), acc = kind == UDM1_INTEGRAND_GENZ_PRODUCT_PEAK ? 1.0 : 0.0;
    switch (kind) {
    case UDM1_INTEGRAND_GENZ_OSCILLATORY:
        for (uint32_t i = 0; i < d; ++i) acc += x[i];
        return cos(2 * PI * u_param(0) + a * acc);
    case UDM1_INTEGRAND_GENZ_PRODUCT_PEAK:
        for (uint32_t i = 0; i < d; ++i) {
            double t = x[i] - u_param(i);
            acc /= 1.0 / (a * a) + t * t;
        }
        return acc;
    case UDM1_INTEGRAND_GENZ_CORNER_PEAK:
        for (uint32_t i = 0; i < d; ++i) acc += x[i];
        return pow(1.0 + a * acc, -(double)(d + 1));
    case UDM1_INTEGRAND_GENZ_GAUSSIAN:
        for (uint32_t i = 0; i < d; ++i) {
            double t = x[i] - u_param(i);
            acc += t * t;
        }
        return exp(-a * a * acc);
    case UDM1_INTEGRAND_GENZ_CONTINUOUS:
        for (uint32_t i = 0; i < d; ++i) acc += fabs(x[i] - u_param(i));
        return exp(-a * acc);
    default: /* discontinuous */
        if (x[0] > u_param(0) || x[1] > u_param(1)) return 0.0;
        for (uint32_t i = 0; i < d; ++i) acc += x[i];
        return exp(a * acc);
    }
}

udm1_status udm1_integrand_eval(uint32_t integrand, uint32_t d, const double *points, size_t n, size_t stride,
                                double *out)
{
    static const char fn[] = "udm1_integrand_eval";
    if (!points || !out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, points ? "out" : "points");
    udm1_status st = check_kind(fn, integrand, d);
    if (st != UDM1_OK) return st;
    if (stride < d) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: stride %zu < d %u", fn, stride, d);
    for (size_t i = 0; i < n; ++i)
        for (uint32_t k = 0; k < d; ++k)
            if (!isfinite(points[i * stride + k]))
                return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: point %zu coordinate %u is not finite", fn, i, k);
    for (size_t i = 0; i < n; ++i) out[i] = eval1(integrand, d, points + i * stride);
    return UDM1_OK;
}

udm1_status udm1_integrand_exact(uint32_t integrand, uint32_t d, double *out)
{
    static const char fn[] = "udm1_integrand_exact";
    if (!out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: out is NULL", fn);
    udm1_status st = check_kind(fn, integrand, d);
    if (st != UDM1_OK) return st;
    double a = genz_a(integrand, d), v = 1.0;
    switch (integrand) {
    case UDM1_INTEGRAND_GAUSSIAN: {
        double s = 0.15, one = sqrt(2 * PI) * s * erf(0.5 / (sqrt(2.0) * s));
        v = one * one;
        break;
    }
    case UDM1_INTEGRAND_PRODUCT_PEAK: {
        double one = 10.0 * 2.0 * atan(5.0); /* int 1/(0.01 + t^2) over [-1/2, 1/2] */
        v = one * one / 100.0;
        break;
    }
    case UDM1_INTEGRAND_BILINEAR: v = 0.25; break;
    case UDM1_INTEGRAND_DISK: v = 0.5; break;
    case UDM1_INTEGRAND_TRIANGLE: v = 0.27; break;
    case UDM1_INTEGRAND_HALFPLANE: v = 0.5; break;
    case UDM1_INTEGRAND_STEP: v = 0.70710678118654752440; break;
    case UDM1_INTEGRAND_GENZ_OSCILLATORY: {
        /* Re( e^{i 2 pi u0} prod (e^{i a} - 1) / (i a) ) */
        double re = cos(2 * PI * u_param(0)), im = sin(2 * PI * u_param(0));
        double fr = sin(a) / a, fi = (1.0 - cos(a)) / a; /* (e^{ia} - 1)/(ia) */
        for (uint32_t i = 0; i < d; ++i) {
            double nr = re * fr - im * fi, ni = re * fi + im * fr;
            re = nr;
            im = ni;
        }
        v = re;
        break;
    }
    case UDM1_INTEGRAND_GENZ_PRODUCT_PEAK:
        for (uint32_t i = 0; i < d; ++i) v *= a * (atan(a * (1.0 - u_param(i))) + atan(a * u_param(i)));
        break;
    case UDM1_INTEGRAND_GENZ_CORNER_PEAK: {
        /* (1 / (d! a^d)) sum over vertices v of (-1)^|v| (1 + a |v|)^-1 */
        double sum = 0.0, binom = 1.0, fact = 1.0;
        for (uint32_t k = 1; k <= d; ++k) fact *= k;
        for (uint32_t k = 0; k <= d; ++k) {
            sum += ((k & 1) ? -1.0 : 1.0) * binom / (1.0 + a * k);
            binom = binom * (d - k) / (k + 1);
        }
        v = sum / (fact * pow(a, (double)d));
        break;
    }
    case UDM1_INTEGRAND_GENZ_GAUSSIAN:
        for (uint32_t i = 0; i < d; ++i)
            v *= sqrt(PI) / (2 * a) * (erf(a * (1.0 - u_param(i))) + erf(a * u_param(i)));
        break;
    case UDM1_INTEGRAND_GENZ_CONTINUOUS:
        for (uint32_t i = 0; i < d; ++i) v *= (2.0 - exp(-a * u_param(i)) - exp(-a * (1.0 - u_param(i)))) / a;
        break;
    default: /* discontinuous */
        for (uint32_t i = 0; i < d; ++i) v *= (exp(a * (i < 2 ? u_param(i) : 1.0)) - 1.0) / a;
        break;
    }
    *out = v;
    return UDM1_OK;
}

udm1_status udm1_integration_error(const udm1_seq *seq, uint32_t integrand, uint32_t d, uint64_t n,
                                   uint32_t randomizations, double *rmse, double *bias)
{
    static const char fn[] = "udm1_integration_error";
    if (!seq || !rmse) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, seq ? "rmse" : "seq");
    udm1_status st = check_kind(fn, integrand, d);
    if (st != UDM1_OK) return st;
    if (d > udm1_seq_dimensions(seq))
        return udm1_fail(UDM1_ERROR_DIMENSION, "%s: d = %u but the sequence has %u dimensions", fn, d, udm1_seq_dimensions(seq));
    if (n == 0 || randomizations == 0)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: n and randomizations must be at least 1", fn);
    if (udm1_work_above(n, randomizations, d, UDM1_WORK_LIMIT_INTEGRATION))
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT,
                         "%s: n %llu x randomizations %u x d %u values is above the work limit 2^35 "
                         "(UDM1_WORK_LIMIT_INTEGRATION, about a minute)", fn, (unsigned long long)n, randomizations, d);
    if (udm1_seq_point_count(seq) && n > udm1_seq_point_count(seq))
        return udm1_fail(UDM1_ERROR_INDEX_RANGE, "%s: n = %llu of a %llu-point set", fn, (unsigned long long)n,
                         (unsigned long long)udm1_seq_point_count(seq));
    double exact;
    udm1_integrand_exact(integrand, d, &exact);
    enum { CHUNK = 1024 };
    double *pts = malloc(sizeof(double) * CHUNK * d);
    if (!pts) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory", fn);
    double sum_sq = 0.0, sum_err = 0.0;
    for (uint32_t r = 0; r < randomizations; ++r) {
        double sum = 0.0, comp = 0.0;
        for (uint64_t i0 = 0; i0 < n; i0 += CHUNK) {
            size_t c = n - i0 < CHUNK ? (size_t)(n - i0) : CHUNK;
            st = udm1_seq_fill_f64(seq, r, i0, c, 0, d, pts, d);
            if (st != UDM1_OK) break;
            for (size_t i = 0; i < c; ++i) {
                double y = eval1(integrand, d, pts + i * d) - comp; /* Kahan */
                double t = sum + y;
                comp = (t - sum) - y;
                sum = t;
            }
        }
        if (st != UDM1_OK) break;
        double err = sum / (double)n - exact;
        sum_sq += err * err;
        sum_err += err;
    }
    free(pts);
    if (st != UDM1_OK) return st;
    *rmse = sqrt(sum_sq / randomizations);
    if (bias) *bias = sum_err / randomizations;
    return UDM1_OK;
}
