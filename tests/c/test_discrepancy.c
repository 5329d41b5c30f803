/* test_discrepancy.c - discrepancy formulas against closed forms and against
 * their expectation for random points (the scipy comparison is in Python). */
#include "check.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdint.h>

static uint64_t rng_state = 12345;
static double uniform(void) /* SplitMix64, top 53 bits */
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1p-53;
}

int main(void)
{
    /* one point x in 1D, closed forms:
     * L2*^2 = 1/3 - (1 - x^2) + (1 - x);  WD^2 = -4/3 + 3/2 */
    for (int i = 0; i <= 10; ++i) {
        double x = i / 10.0, v;
        CHECK_STATUS(udm1_discrepancy(&x, 1, 1, 1, UDM1_DISCREPANCY_L2_STAR, &v), UDM1_OK);
        double l2 = sqrt(1.0 / 3.0 - (1.0 - x * x) + (1.0 - x));
        CHECKF(fabs(v - l2) < 1e-15, "x=%g: %g vs %g", x, v, l2);
        CHECK_STATUS(udm1_discrepancy(&x, 1, 1, 1, UDM1_DISCREPANCY_WRAP_AROUND, &v), UDM1_OK);
        CHECK(fabs(v - (1.5 - 4.0 / 3.0)) < 1e-15);
        double c = fabs(x - 0.5);
        double cd = 13.0 / 12.0 - 2.0 * (1.0 + 0.5 * c - 0.5 * c * c) + (1.0 + c);
        CHECK_STATUS(udm1_discrepancy(&x, 1, 1, 1, UDM1_DISCREPANCY_CENTERED, &v), UDM1_OK);
        CHECK(fabs(v - cd) < 1e-15);
    }
    /* the regular grid (i + 1/2)/n in 1D has L2*^2 = 1 / (12 n^2) */
    double grid[100];
    for (int i = 0; i < 100; ++i) grid[i] = (i + 0.5) / 100.0;
    double v;
    CHECK_STATUS(udm1_discrepancy(grid, 100, 1, 1, UDM1_DISCREPANCY_L2_STAR, &v), UDM1_OK);
    CHECKF(fabs(v - sqrt(1.0 / (12.0 * 100 * 100))) < 1e-12, "grid %g", v);

    /* random points: the average of D^2 over many sets matches the expectation */
    for (uint32_t kind = UDM1_DISCREPANCY_L2_STAR; kind <= UDM1_DISCREPANCY_MIXTURE; ++kind)
        for (uint32_t d = 1; d <= 3; ++d) {
            enum { N = 32, SETS = 4000 };
            double pts[N * 3], sum = 0.0, sum2 = 0.0;
            for (int s = 0; s < SETS; ++s) {
                for (int i = 0; i < N * 3; ++i) pts[i] = uniform();
                CHECK_STATUS(udm1_discrepancy(pts, N, d, 3, kind, &v), UDM1_OK);
                double sq = kind == UDM1_DISCREPANCY_L2_STAR ? v * v : v;
                sum += sq;
                sum2 += sq * sq;
            }
            double mean = sum / SETS, sd = sqrt((sum2 / SETS - mean * mean) / SETS), expect;
            CHECK_STATUS(udm1_discrepancy_random(N, d, kind, &expect), UDM1_OK);
            if (kind == UDM1_DISCREPANCY_L2_STAR) expect *= expect;
            CHECKF(fabs(mean - expect) < 5.0 * sd, "kind %u d %u: mean %g expected %g (sd %g)", kind, d, mean, expect,
                   sd);
        }
    CHECK_DONE();
}
