/* test_lattice_bound.c - udm1_lattice_bound: the spectrum kept across doublings against the direct
 * transform, the wavenumber order against its definition pair by pair, the bound against its formula,
 * the same results whatever the room given up front or after a reset, and its bad inputs. */
#include "check.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define N 1024
#define LAG 4
#define FUDGE 5.0
#define TWO_PI 6.28318530717958647692

static uint64_t rng = 11;
static double uniform(void)
{
    uint64_t z = (rng += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1p-53;
}

static uint64_t bitrev(uint64_t i, int m)
{
    uint64_t r = 0;
    for (int b = 0; b < m; ++b) r |= ((i >> b) & 1) << (m - 1 - b);
    return r;
}

static int log2_of(uint64_t n)
{
    int m = 0;
    while (((uint64_t)1 << m) < n) ++m;
    return m;
}

/* The transform the caller passes: v (n values in sequence order) in lattice order, DFT at l <= n/2 */
static void transform(const double *v, uint64_t n, double *t)
{
    int m = log2_of(n);
    for (uint64_t l = 0; l <= n / 2; ++l) {
        long double re = 0, im = 0;
        for (uint64_t j = 0; j < n; ++j) {
            uint64_t k = bitrev(j, m);
            long double a = -TWO_PI * (long double)((k * l) % n) / (long double)n;
            re += v[j] * cosl(a);
            im += v[j] * sinl(a);
        }
        t[2 * l] = (double)re;
        t[2 * l + 1] = (double)im;
    }
}

/* Y[l] of the first n values directly: (1/n) sum over lattice points k of v[bitrev(k)] e(-kl/n) */
static void direct(const double *v, uint64_t n, uint64_t l, double *re, double *im)
{
    int m = log2_of(n);
    long double a_re = 0, a_im = 0;
    for (uint64_t k = 0; k < n; ++k) {
        long double a = -TWO_PI * (long double)((k * l) % n) / (long double)n;
        a_re += v[bitrev(k, m)] * cosl(a);
        a_im += v[bitrev(k, m)] * sinl(a);
    }
    *re = (double)(a_re / n);
    *im = (double)(a_im / n);
}

/* The order by its definition: at each level, p in [1, half) of every block of 2 half swaps with
 * p + half when |Y| of the class at p + half in the first block exceeds that at p. */
static void reference_order(const double *y, uint64_t n, uint64_t *order, int top, int bottom)
{
    for (int level = top; level > bottom; --level) {
        uint64_t half = (uint64_t)1 << level;
        for (uint64_t q = 1; q < half; ++q) {
            uint64_t a = order[q], c = order[q + half];
            if (hypot(y[2 * c], y[2 * c + 1]) > hypot(y[2 * a], y[2 * a + 1]))
                for (uint64_t b = 0; b < n; b += 2 * half) {
                    uint64_t t = order[b + q];
                    order[b + q] = order[b + q + half];
                    order[b + q + half] = t;
                }
        }
    }
}

static double v[N], t[N + 2], y[2 * N], y2[2 * N];
static uint64_t order[N], order2[N], ref[N];

static void test_doublings(void)
{
    for (int j = 0; j < N; ++j) v[j] = uniform() - 0.25 + (j % 7 == 0 ? 3.0 : 0.0);
    udm1_lattice_bound *b = NULL, *roomy = NULL;
    CHECK_STATUS(udm1_lattice_bound_create(LAG, FUDGE, 0, &b), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_create(LAG, FUDGE, N, &roomy), UDM1_OK);
    CHECK(udm1_lattice_bound_points(b) == 0);
    double bound;
    CHECK_STATUS(udm1_lattice_bound_error(b, &bound), UDM1_ERROR_INVALID_ARGUMENT);
    uint64_t n = 64;
    transform(v, n, t);
    CHECK_STATUS(udm1_lattice_bound_add(b, t, n), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_add(roomy, t, n), UDM1_OK);
    for (;;) {
        int m = log2_of(n);
        CHECK(udm1_lattice_bound_points(b) == n);
        CHECK_STATUS(udm1_lattice_bound_coefficients(b, 0, n, y), UDM1_OK);
        CHECK_STATUS(udm1_lattice_bound_order(b, 0, n, order), UDM1_OK);
        double scale = 0;
        for (uint64_t j = 0; j < n; ++j) scale += fabs(v[j]) / (double)n;
        for (uint64_t l = 0; l < n; ++l) {
            double re, im;
            direct(v, n, l, &re, &im);
            CHECKF(fabs(y[2 * l] - re) <= 1e-13 * scale && fabs(y[2 * l + 1] - im) <= 1e-13 * scale,
                   "n %llu, l %llu: (%.17g, %.17g) against (%.17g, %.17g)", (unsigned long long)n,
                   (unsigned long long)l, y[2 * l], y[2 * l + 1], re, im);
        }
        /* the order: from the start, every level by the definition; after a doubling, the classes of the
         * order before split (l then l + n/2), and the top LAG levels by the definition */
        if (n == 64) {
            for (uint64_t k = 0; k < n; ++k) ref[k] = k;
            reference_order(y, n, ref, m - 1, 0);
        } else {
            for (uint64_t k = 0; k < n / 2; ++k) ref[n / 2 + k] = ref[k] + n / 2;
            reference_order(y, n, ref, m - 1, m - LAG - 1);
        }
        CHECK(memcmp(order, ref, n * sizeof *order) == 0);
        CHECK(order[0] == 0);
        /* the bound: its formula from the coefficients and the order read back */
        double sum = 0;
        for (uint64_t p = n >> (LAG + 1); p < n >> LAG; ++p) sum += hypot(y[2 * order[p]], y[2 * order[p] + 1]);
        CHECK_STATUS(udm1_lattice_bound_error(b, &bound), UDM1_OK);
        CHECKF(fabs(bound - FUDGE * sum / (double)n) <= 1e-12 * bound, "n %llu: %.17g against %.17g",
               (unsigned long long)n, bound, FUDGE * sum / (double)n);
        /* room given up front changes nothing, bit for bit */
        double bound2;
        CHECK_STATUS(udm1_lattice_bound_coefficients(roomy, 0, n, y2), UDM1_OK);
        CHECK_STATUS(udm1_lattice_bound_order(roomy, 0, n, order2), UDM1_OK);
        CHECK_STATUS(udm1_lattice_bound_error(roomy, &bound2), UDM1_OK);
        CHECK(memcmp(y, y2, 2 * n * sizeof *y) == 0 && memcmp(order, order2, n * sizeof *order) == 0);
        CHECK(memcmp(&bound, &bound2, sizeof bound) == 0);
        if (n == N) break;
        transform(v + n, n, t);
        CHECK_STATUS(udm1_lattice_bound_add(b, t, n), UDM1_OK);
        CHECK_STATUS(udm1_lattice_bound_add(roomy, t, n), UDM1_OK);
        n *= 2;
    }
    /* after a reset: the same as new */
    udm1_lattice_bound_reset(b);
    CHECK(udm1_lattice_bound_points(b) == 0);
    transform(v, 64, t);
    CHECK_STATUS(udm1_lattice_bound_add(b, t, 64), UDM1_OK);
    udm1_lattice_bound *fresh = NULL;
    CHECK_STATUS(udm1_lattice_bound_create(LAG, FUDGE, 0, &fresh), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_add(fresh, t, 64), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_coefficients(b, 0, 64, y), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_coefficients(fresh, 0, 64, y2), UDM1_OK);
    CHECK(memcmp(y, y2, 128 * sizeof *y) == 0);
    udm1_lattice_bound_destroy(fresh);
    udm1_lattice_bound_destroy(roomy);
    udm1_lattice_bound_destroy(b);
}

static void test_bad_input(void)
{
    udm1_lattice_bound *b = (udm1_lattice_bound *)&b;
    CHECK_STATUS(udm1_lattice_bound_create(LAG, FUDGE, 0, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_create(0, FUDGE, 0, &b), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(b == NULL);
    CHECK(strstr(udm1_last_error(), "udm1_lattice_bound_create: lag") != NULL);
    CHECK_STATUS(udm1_lattice_bound_create(31, FUDGE, 0, &b), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_create(LAG, 0.0, 0, &b), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_create(LAG, NAN, 0, &b), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_create(LAG, INFINITY, 0, &b), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_create(LAG, FUDGE, ((uint64_t)1 << 32) + 1, &b), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_create(LAG, FUDGE, 0, &b), UDM1_OK);
    for (int j = 0; j < 128; ++j) v[j] = uniform();
    transform(v, 64, t);
    CHECK_STATUS(udm1_lattice_bound_add(NULL, t, 64), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_add(b, NULL, 64), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_add(b, t, 48), UDM1_ERROR_INVALID_ARGUMENT); /* not a power of two */
    CHECK_STATUS(udm1_lattice_bound_add(b, t, 16), UDM1_ERROR_INVALID_ARGUMENT); /* not above 2^lag */
    CHECK(strstr(udm1_last_error(), "not 16") != NULL);
    CHECK(udm1_lattice_bound_points(b) == 0);
    CHECK_STATUS(udm1_lattice_bound_add(b, t, 64), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_coefficients(b, 0, 64, y), UDM1_OK);
    double bound, bound_after;
    CHECK_STATUS(udm1_lattice_bound_error(b, &bound), UDM1_OK);
    transform(v + 64, 64, t);
    CHECK_STATUS(udm1_lattice_bound_add(b, t, 32), UDM1_ERROR_INVALID_ARGUMENT); /* not the points held */
    CHECK(strstr(udm1_last_error(), "64 points held") != NULL);
    t[2 * 5 + 1] = NAN;
    CHECK_STATUS(udm1_lattice_bound_add(b, t, 64), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "coefficient 5 is not finite") != NULL);
    t[2 * 5 + 1] = INFINITY;
    CHECK_STATUS(udm1_lattice_bound_add(b, t, 64), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(udm1_lattice_bound_points(b) == 64); /* nothing changed */
    CHECK_STATUS(udm1_lattice_bound_coefficients(b, 0, 64, y2), UDM1_OK);
    CHECK(memcmp(y, y2, 128 * sizeof *y) == 0);
    CHECK_STATUS(udm1_lattice_bound_error(b, &bound_after), UDM1_OK);
    CHECK(memcmp(&bound, &bound_after, sizeof bound) == 0);
    CHECK_STATUS(udm1_lattice_bound_error(b, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_error(NULL, &bound), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_coefficients(b, 60, 5, y), UDM1_ERROR_INDEX_RANGE);
    CHECK_STATUS(udm1_lattice_bound_coefficients(b, UINT64_MAX, 2, y), UDM1_ERROR_INDEX_RANGE);
    CHECK_STATUS(udm1_lattice_bound_coefficients(b, 0, 4, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_coefficients(b, 64, 0, NULL), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_order(b, 63, 2, order), UDM1_ERROR_INDEX_RANGE);
    CHECK_STATUS(udm1_lattice_bound_order(NULL, 0, 1, order), UDM1_ERROR_NULL_ARGUMENT);
    CHECK(udm1_lattice_bound_points(NULL) == 0);
    CHECK(strstr(udm1_last_error(), "udm1_lattice_bound_points: bound is NULL") != NULL);
    udm1_lattice_bound_reset(NULL);
    CHECK(strstr(udm1_last_error(), "udm1_lattice_bound_reset: bound is NULL") != NULL);
    udm1_lattice_bound_destroy(NULL);
    udm1_lattice_bound_destroy(b);
}

int main(void)
{
    test_doublings();
    test_bad_input();
    CHECK_DONE();
}
