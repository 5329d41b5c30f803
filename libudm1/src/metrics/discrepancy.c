/* discrepancy.c - L2-type discrepancies with the definitions of
 * scipy.stats.qmc.discrepancy (Hickernell 1998; Zhou, Fang, Ning 2013).
 *
 * Each is D^2 = c - (2/n) sum_i prod_k f(x_ik) + (1/n^2) sum_ij prod_k K(x_ik, x_jk),
 * evaluated with compensated (Neumaier) sums over the symmetric pairs.
 * scipy returns CD, WD and MD squared and L2-star square-rooted; so do we.
 */
#include "core/internal.h"

#include <math.h>

typedef struct kahan { double sum, comp; } kahan;

static void kahan_add(kahan *k, double v)
{
    double t = k->sum + v;
    if (fabs(k->sum) >= fabs(v))
        k->comp += (k->sum - t) + v;
    else
        k->comp += (v - t) + k->sum;
    k->sum = t;
}

static double kahan_value(const kahan *k) { return k->sum + k->comp; }

static double ipow(double b, uint32_t e)
{
    double r = 1.0;
    while (e) {
        if (e & 1) r *= b;
        b *= b;
        e >>= 1;
    }
    return r;
}

/* constant term c = integral of the kernel, single term f, pair kernel K */
static double kernel_constant(uint32_t kind, uint32_t d)
{
    switch (kind) {
    case UDM1_DISCREPANCY_L2_STAR: return ipow(1.0 / 3.0, d);
    case UDM1_DISCREPANCY_CENTERED: return ipow(13.0 / 12.0, d);
    case UDM1_DISCREPANCY_WRAP_AROUND: return ipow(4.0 / 3.0, d);
    default: return ipow(19.0 / 12.0, d);
    }
}

static double single_term(uint32_t kind, double x)
{
    double c = fabs(x - 0.5);
    switch (kind) {
    case UDM1_DISCREPANCY_L2_STAR: return (1.0 - x * x) * 0.5; /* 2^(1-d) prod (1 - x^2) / 2 */
    case UDM1_DISCREPANCY_CENTERED: return 1.0 + 0.5 * c - 0.5 * c * c;
    case UDM1_DISCREPANCY_WRAP_AROUND: return 0.0; /* no single sum: the kernel integrates to c exactly */
    default: return 5.0 / 3.0 - 0.25 * c - 0.25 * c * c;
    }
}

static double pair_kernel(uint32_t kind, double x, double y)
{
    double dxy = fabs(x - y);
    switch (kind) {
    case UDM1_DISCREPANCY_L2_STAR: return 1.0 - (x > y ? x : y);
    case UDM1_DISCREPANCY_CENTERED: return 1.0 + 0.5 * fabs(x - 0.5) + 0.5 * fabs(y - 0.5) - 0.5 * dxy;
    case UDM1_DISCREPANCY_WRAP_AROUND: return 1.5 - dxy * (1.0 - dxy);
    default: return 15.0 / 8.0 - 0.25 * fabs(x - 0.5) - 0.25 * fabs(y - 0.5) - 0.75 * dxy + 0.5 * dxy * dxy;
    }
}

static int valid_kind(uint32_t kind) { return kind >= UDM1_DISCREPANCY_L2_STAR && kind <= UDM1_DISCREPANCY_MIXTURE; }

udm1_status udm1_discrepancy(const double *points, size_t n, uint32_t d, size_t stride, uint32_t kind, double *out)
{
    static const char fn[] = "udm1_discrepancy";
    if (!points || !out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, points ? "out" : "points");
    if (n == 0 || d == 0) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: n and d must be at least 1", fn);
    if (stride < d) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: stride %zu < d %u", fn, stride, d);
    if (!valid_kind(kind)) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: unknown kind %u", fn, kind);
    for (size_t i = 0; i < n; ++i)
        for (uint32_t k = 0; k < d; ++k) {
            double x = points[i * stride + k];
            if (!(x >= 0.0 && x <= 1.0))
                return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: point %zu coordinate %u = %g is outside [0, 1]", fn,
                                 i, k, x);
        }

    kahan single = {0, 0}, pairs = {0, 0};
    for (size_t i = 0; i < n; ++i) {
        const double *xi = points + i * stride;
        double ps = 1.0, pd = 1.0;
        for (uint32_t k = 0; k < d; ++k) {
            ps *= single_term(kind, xi[k]);
            pd *= pair_kernel(kind, xi[k], xi[k]);
        }
        kahan_add(&single, ps);
        kahan_add(&pairs, pd);
        for (size_t j = i + 1; j < n; ++j) {
            const double *xj = points + j * stride;
            double p = 2.0;
            for (uint32_t k = 0; k < d; ++k) p *= pair_kernel(kind, xi[k], xj[k]);
            kahan_add(&pairs, p);
        }
    }
    double nn = (double)n;
    kahan total = {0, 0};
    kahan_add(&total, kernel_constant(kind, d));
    if (kind == UDM1_DISCREPANCY_WRAP_AROUND)
        kahan_add(&total, -2.0 * kernel_constant(kind, d)); /* its single term integrates exactly */
    else
        kahan_add(&total, -2.0 * kahan_value(&single) / nn);
    kahan_add(&total, kahan_value(&pairs) / (nn * nn));
    double v = kahan_value(&total);
    if (kind == UDM1_DISCREPANCY_L2_STAR) v = sqrt(v > 0.0 ? v : 0.0);
    *out = v;
    return UDM1_OK;
}

udm1_status udm1_discrepancy_random(size_t n, uint32_t d, uint32_t kind, double *out)
{
    static const char fn[] = "udm1_discrepancy_random";
    if (!out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: out is NULL", fn);
    if (n == 0 || d == 0) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: n and d must be at least 1", fn);
    if (!valid_kind(kind)) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: unknown kind %u", fn, kind);
    /* E[D^2] = (E[K(x, x)] - c) / n for independent uniform points */
    double diag;
    switch (kind) {
    case UDM1_DISCREPANCY_L2_STAR: diag = ipow(0.5, d); break;
    case UDM1_DISCREPANCY_CENTERED: diag = ipow(1.25, d); break;
    case UDM1_DISCREPANCY_WRAP_AROUND: diag = ipow(1.5, d); break;
    default: diag = ipow(1.75, d); break;
    }
    double v = (diag - kernel_constant(kind, d)) / (double)n;
    *out = kind == UDM1_DISCREPANCY_L2_STAR ? sqrt(v) : v;
    return UDM1_OK;
}
