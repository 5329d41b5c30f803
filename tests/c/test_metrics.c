/* test_metrics.c - the measuring instruments: exact 2D star discrepancy
 * against brute force, minimum distance, integration error against a manual
 * computation, spectra and the zone plate; and their bad inputs. */
#include "check.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdlib.h>

static uint64_t rng = 42;
static double uniform(void)
{
    uint64_t z = (rng += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1p-53;
}

/* O(n^3): every box through point coordinates (and 1), closed and open */
static double brute_star(const double *p, size_t n)
{
    double worst = 0.0;
    for (size_t a = 0; a <= n; ++a)
        for (size_t b = 0; b <= n; ++b) {
            double x = a < n ? p[2 * a] : 1.0, y = b < n ? p[2 * b + 1] : 1.0;
            size_t closed = 0, open = 0;
            for (size_t k = 0; k < n; ++k) {
                closed += p[2 * k] <= x && p[2 * k + 1] <= y;
                open += p[2 * k] < x && p[2 * k + 1] < y;
            }
            double e = (double)closed / n - x * y, f = x * y - (double)open / n;
            if (e > worst) worst = e;
            if (f > worst) worst = f;
        }
    return worst;
}

static void test_star(void)
{
    double p[2 * 80], v;
    for (size_t n = 1; n <= 80; n += 7) {
        for (size_t i = 0; i < 2 * n; ++i) p[i] = uniform();
        if (n > 10) { /* ties in x and in y */
            p[2 * 3] = p[2 * 5];
            p[2 * 4 + 1] = p[2 * 9 + 1];
        }
        CHECK_STATUS(udm1_star_discrepancy_2d(p, n, 2, &v), UDM1_OK);
        double b = brute_star(p, n);
        CHECKF(fabs(v - b) < 1e-15, "n=%zu: %.17g vs brute force %.17g", n, v, b);
    }
    /* one point at (1/2, 1/2) */
    double one[2] = {0.5, 0.5};
    CHECK_STATUS(udm1_star_discrepancy_2d(one, 1, 2, &v), UDM1_OK);
    CHECK(fabs(v - 0.75) < 1e-15); /* the closed box [0,.5]^2 holds the point with volume 1/4 */
    /* a 2D set from a sequence: agrees with brute force too */
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("sobol-owen", 2, 0, 3, &s), UDM1_OK);
    double q[2 * 64];
    CHECK_STATUS(udm1_seq_fill_f64(s, 0, 0, 64, 0, 2, q, 2), UDM1_OK);
    CHECK_STATUS(udm1_star_discrepancy_2d(q, 64, 2, &v), UDM1_OK);
    CHECK(fabs(v - brute_star(q, 64)) < 1e-15);
    udm1_seq_destroy(s);
    CHECK_STATUS(udm1_star_discrepancy_2d(NULL, 1, 2, &v), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_star_discrepancy_2d(p, 0, 2, &v), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_star_discrepancy_2d(p, 16385, 2, &v), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_star_discrepancy_2d(p, 2, 1, &v), UDM1_ERROR_INVALID_ARGUMENT);
    p[1] = NAN;
    CHECK_STATUS(udm1_star_discrepancy_2d(p, 2, 2, &v), UDM1_ERROR_INVALID_ARGUMENT);
}

static void test_min_distance(void)
{
    double p[6] = {0.1, 0.1, 0.9, 0.1, 0.5, 0.6}, v;
    CHECK_STATUS(udm1_min_distance(p, 3, 2, 2, 0, &v), UDM1_OK);
    CHECK(fabs(v - sqrt(0.16 + 0.25)) < 1e-15);
    CHECK_STATUS(udm1_min_distance(p, 3, 2, 2, 1, &v), UDM1_OK); /* across the border: 0.2 */
    CHECK(fabs(v - 0.2) < 1e-15);
    CHECK_STATUS(udm1_min_distance(p, 1, 2, 2, 0, &v), UDM1_ERROR_INVALID_ARGUMENT);
    p[0] = INFINITY;
    CHECK_STATUS(udm1_min_distance(p, 3, 2, 2, 0, &v), UDM1_ERROR_INVALID_ARGUMENT);
}

static void test_integration_error(void)
{
    /* rmse and bias equal the estimates computed here from fills and evaluations */
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("halton", 3, 0, 5, &s), UDM1_OK);
    enum { N = 500, R = 7, D = 3 };
    double pts[N * D], vals[N], exact, sq = 0.0, sum = 0.0;
    CHECK_STATUS(udm1_integrand_exact(UDM1_INTEGRAND_GENZ_GAUSSIAN, D, &exact), UDM1_OK);
    for (uint64_t r = 0; r < R; ++r) {
        udm1_seq_fill_f64(s, r, 0, N, 0, D, pts, D);
        CHECK_STATUS(udm1_integrand_eval(UDM1_INTEGRAND_GENZ_GAUSSIAN, D, pts, N, D, vals), UDM1_OK);
        double m = 0.0;
        for (int i = 0; i < N; ++i) m += vals[i];
        double e = m / N - exact;
        sq += e * e;
        sum += e;
    }
    double rmse, bias;
    CHECK_STATUS(udm1_integration_error(s, UDM1_INTEGRAND_GENZ_GAUSSIAN, D, N, R, &rmse, &bias), UDM1_OK);
    CHECK(fabs(rmse - sqrt(sq / R)) < 1e-12 * (1 + rmse) && fabs(bias - sum / R) < 1e-12);
    CHECK_STATUS(udm1_integration_error(s, UDM1_INTEGRAND_DISK, 3, N, R, &rmse, NULL), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_integration_error(s, UDM1_INTEGRAND_GENZ_GAUSSIAN, 4, N, R, &rmse, NULL), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_integration_error(s, 99, 3, N, R, &rmse, NULL), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_integration_error(s, UDM1_INTEGRAND_GENZ_GAUSSIAN, 3, 0, R, &rmse, NULL), UDM1_ERROR_INVALID_ARGUMENT);
    udm1_seq_destroy(s);
    CHECK_STATUS(udm1_seq_create("cmj", 2, 64, 5, &s), UDM1_OK);
    CHECK_STATUS(udm1_integration_error(s, UDM1_INTEGRAND_DISK, 2, 65, R, &rmse, NULL), UDM1_ERROR_INDEX_RANGE);
    udm1_seq_destroy(s);
    CHECK(udm1_integrand_name(0) == NULL && udm1_integrand_name(14) == NULL);
    CHECK_STATUS(udm1_integrand_exact(UDM1_INTEGRAND_GENZ_CORNER_PEAK, 21, &exact), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_integrand_exact(UDM1_INTEGRAND_GENZ_DISCONTINUOUS, 1, &exact), UDM1_ERROR_INVALID_ARGUMENT);
}

static void test_spectrum_and_zoneplate(void)
{
    enum { S = 32, N = 256 };
    static double sp[S * S];
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("pcg32", 2, 0, 5, &s), UDM1_OK);
    CHECK_STATUS(udm1_spectrum_2d(s, 0, N, 16, S, sp), UDM1_OK);
    double mean = 0.0;
    for (int k = 0; k < S * S; ++k)
        if (k != (S / 2) * S + S / 2) mean += sp[k];
    mean /= S * S - 1;
    CHECK(fabs(sp[(S / 2) * S + S / 2] - N) < 1e-9); /* DC: |n|^2 / n */
    CHECKF(fabs(mean - 1.0) < 0.05, "random points: mean spectrum %g, expected 1", mean);
    udm1_seq_destroy(s);
    /* a stratified sampler has little low-frequency energy */
    CHECK_STATUS(udm1_seq_create("sobol-owen", 2, 0, 5, &s), UDM1_OK);
    CHECK_STATUS(udm1_spectrum_2d(s, 0, N, 16, S, sp), UDM1_OK);
    double low = 0.0;
    for (int ky = -2; ky <= 2; ++ky)
        for (int kx = -2; kx <= 2; ++kx)
            if (kx || ky) low += sp[(ky + S / 2) * S + kx + S / 2];
    CHECKF(low / 24 < 0.1, "sobol-owen low-frequency energy %g", low / 24);
    static float img[64 * 48];
    CHECK_STATUS(udm1_zoneplate(s, 0, 64, 48, 16, img), UDM1_OK);
    int bad = 0;
    for (int i = 0; i < 64 * 48; ++i) bad += !(img[i] >= 0.0f && img[i] <= 1.0f);
    CHECK(bad == 0);
    CHECK(img[0] > 0.9f); /* the centre of the rings, in the top-left corner, is bright */
    CHECK_STATUS(udm1_zoneplate(s, 1, 64, 48, 16, img), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_zoneplate(s, 0, 0, 48, 16, img), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_spectrum_2d(s, 0, N, 16, 31, sp), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_spectrum_2d(s, 0, 0, 16, S, sp), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_spectrum_2d(NULL, 0, N, 16, S, sp), UDM1_ERROR_NULL_ARGUMENT);
    udm1_seq_destroy(s);
}

int main(void)
{
    test_star();
    test_min_distance();
    test_integration_error();
    test_spectrum_and_zoneplate();
    CHECK_DONE();
}
