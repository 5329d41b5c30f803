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

/* constant term c = b^d (b the integral of the one-dimensional kernel), and the mean of the kernel on
 * the diagonal, K(x, x), over a uniform x (for the random-points expectation) */
static double kernel_base(uint32_t kind)
{
    switch (kind) {
    case UDM1_DISCREPANCY_L2_STAR: return 1.0 / 3.0;
    case UDM1_DISCREPANCY_CENTERED: return 13.0 / 12.0;
    case UDM1_DISCREPANCY_WRAP_AROUND: return 4.0 / 3.0;
    default: return 19.0 / 12.0;
    }
}

static double diagonal_base(uint32_t kind)
{
    switch (kind) {
    case UDM1_DISCREPANCY_L2_STAR: return 0.5;
    case UDM1_DISCREPANCY_CENTERED: return 1.25;
    case UDM1_DISCREPANCY_WRAP_AROUND: return 1.5;
    default: return 1.75;
    }
}

static double kernel_constant(uint32_t kind, uint32_t d) { return ipow(kernel_base(kind), d); }

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

/* Above PLAIN_MAX_D dimensions a product of d kernel values (each at most 15/8, some as small as 2^-53)
 * or the constant term can leave a double's exponent range while the discrepancy itself does not (or
 * does, and is then honestly +inf or 0). There the sums are kept as m 2^e with a separate exponent. */
#define PLAIN_MAX_D 512u

typedef struct scaled { double m; int64_t e; } scaled; /* m 2^e, m in [0.5, 1) or 0 */

static scaled scaled_of(double v, int64_t e)
{
    int k;
    double m = frexp(v, &k);
    scaled r = {m, m == 0.0 ? 0 : e + k};
    return r;
}

static void scaled_add(scaled *s, scaled t)
{
    if (t.m == 0.0) return;
    if (s->m == 0.0) {
        *s = t;
        return;
    }
    int64_t e = s->e > t.e ? s->e : t.e, ds = s->e - e, dt = t.e - e;
    double v = (ds < -1100 ? 0.0 : ldexp(s->m, (int)ds)) + (dt < -1100 ? 0.0 : ldexp(t.m, (int)dt));
    *s = scaled_of(v, e);
}

/* the product of f(k) for k < d, as m 2^e: renormalized every 16 factors (16 factors of at least
 * 2^-53 or at most 2 stay inside the double range) */
#define SCALED_PRODUCT(result, start, factor)                                                          \
    do {                                                                                               \
        double p_ = (start);                                                                           \
        int64_t e_ = 0;                                                                                \
        for (uint32_t k0_ = 0; k0_ < d && p_ != 0.0; k0_ += 16) {                                      \
            uint32_t k1_ = d - k0_ < 16 ? d : k0_ + 16;                                                \
            for (uint32_t k = k0_; k < k1_; ++k) p_ *= (factor);                                       \
            int x_;                                                                                    \
            p_ = frexp(p_, &x_);                                                                       \
            e_ += x_;                                                                                  \
        }                                                                                              \
        (result) = scaled_of(p_, e_);                                                                  \
    } while (0)

/* b^d as m 2^e */
static scaled scaled_pow(double b, uint32_t d)
{
    scaled r = {0.5, 1}, x = scaled_of(b, 0);
    while (d) {
        if (d & 1) r = scaled_of(r.m * x.m, r.e + x.e);
        x = scaled_of(x.m * x.m, 2 * x.e);
        d >>= 1;
    }
    return r;
}

static double discrepancy_scaled(const double *points, size_t n, uint32_t d, size_t stride, uint32_t kind)
{
    scaled single = {0, 0}, pairs = {0, 0}, t;
    for (size_t i = 0; i < n; ++i) {
        const double *xi = points + i * stride;
        SCALED_PRODUCT(t, 1.0, single_term(kind, xi[k]));
        scaled_add(&single, t);
        SCALED_PRODUCT(t, 1.0, pair_kernel(kind, xi[k], xi[k]));
        scaled_add(&pairs, t);
        for (size_t j = i + 1; j < n; ++j) {
            const double *xj = points + j * stride;
            SCALED_PRODUCT(t, 2.0, pair_kernel(kind, xi[k], xj[k]));
            scaled_add(&pairs, t);
        }
    }
    scaled c = scaled_pow(kernel_base(kind), d), terms[3];
    double nn = (double)n;
    terms[0] = c;
    /* the wrap-around single term integrates to the constant exactly: c - 2c = -c */
    terms[1] = kind == UDM1_DISCREPANCY_WRAP_AROUND ? scaled_of(-2.0 * c.m, c.e) : scaled_of(-2.0 * single.m / nn, single.e);
    terms[2] = scaled_of(pairs.m / (nn * nn), pairs.e);
    int64_t e = terms[0].e;
    for (int i = 1; i < 3; ++i)
        if (terms[i].m != 0.0 && terms[i].e > e) e = terms[i].e;
    if (kind == UDM1_DISCREPANCY_L2_STAR && (e & 1)) ++e; /* even, for the square root */
    double v = 0.0;
    for (int i = 0; i < 3; ++i)
        if (terms[i].m != 0.0 && terms[i].e - e > -1100) v += ldexp(terms[i].m, (int)(terms[i].e - e));
    if (v <= 0.0) return 0.0;
    if (kind == UDM1_DISCREPANCY_L2_STAR) return ldexp(sqrt(v), (int)(e > 4000 ? 2000 : e < -4000 ? -2000 : e / 2));
    return ldexp(v, (int)(e > 4000 ? 4000 : e < -4000 ? -4000 : e));
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

    if (d > PLAIN_MAX_D) {
        *out = discrepancy_scaled(points, n, d, stride, kind);
        return UDM1_OK;
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
    if (d > PLAIN_MAX_D) { /* in logarithms: b^d (1 - (c / b)^d) / n, +inf past a double's range */
        double b = diagonal_base(kind);
        double lv = d * log(b) + log1p(-exp(d * log(kernel_base(kind) / b))) - log((double)n);
        *out = exp(kind == UDM1_DISCREPANCY_L2_STAR ? lv / 2 : lv);
        return UDM1_OK;
    }
    double diag = ipow(diagonal_base(kind), d);
    double v = (diag - kernel_constant(kind, d)) / (double)n;
    *out = kind == UDM1_DISCREPANCY_L2_STAR ? sqrt(v) : v;
    return UDM1_OK;
}
