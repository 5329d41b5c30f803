/* test_check.c - the constant-set check finds what it must: rational and
 * dependent generators, and poor 2D projections (values from the paper's sets
 * and from the field's measurements). */
#include "check.h"

#include <udm1/udm1.h>

#include <string.h>

static udm1_alpha sq(uint64_t k)
{
    udm1_alpha a;
    memset(&a, 0, sizeof a);
    a.kind = UDM1_ALPHA_SQRT;
    a.k = k;
    return a;
}

int main(void)
{
    udm1_alpha_report r;

    /* sqrt2, sqrt3: independent, far better than random at n = 256 */
    udm1_alpha good[2] = {sq(2), sq(3)};
    CHECK_STATUS(udm1_alpha_check(good, 2, 256, &r), UDM1_OK);
    CHECK(!r.rational && !r.dependent);
    CHECK(r.worst_dims[0] == 0 && r.worst_dims[1] == 1);
    CHECKF(r.worst_l2_star < 0.5 * r.random_l2_star, "L2* %g vs random %g", r.worst_l2_star, r.random_l2_star);
    CHECK(strchr(r.message, '\n') == NULL && strlen(r.message) > 10);

    /* the paper's pair (sqrt487, sqrt237173) is no better than random at n = 256 */
    udm1_alpha poor[2] = {sq(487), sq(237173)};
    CHECK_STATUS(udm1_alpha_check(poor, 2, 256, &r), UDM1_OK);
    CHECK(!r.dependent);
    CHECKF(r.worst_l2_star > 0.7 * r.random_l2_star, "L2* %g vs random %g", r.worst_l2_star, r.random_l2_star);

    /* sqrt8 = 2 sqrt2: exactly dependent; sqrt(49) rational; 1/3 numerically rational */
    udm1_alpha dep[4] = {sq(2), sq(5), sq(8), sq(49)};
    CHECK_STATUS(udm1_alpha_check(dep, 4, 64, &r), UDM1_OK);
    CHECK(r.dependent && r.dependent_exact && r.dependent_dims[0] == 0 && r.dependent_dims[1] == 2);
    CHECK(r.rational && r.rational_dim == 3);
    udm1_alpha num[3] = {sq(2), sq(3), sq(2)};
    num[2].kind = UDM1_ALPHA_DOUBLE;
    num[2].value = 3.0 * 1.4142135623730951; /* 3 sqrt2 as a double: numerically dependent on dim 0 */
    CHECK_STATUS(udm1_alpha_check(num, 3, 64, &r), UDM1_OK);
    CHECK(r.dependent && !r.dependent_exact && r.dependent_dims[0] == 0 && r.dependent_dims[1] == 2);
    udm1_alpha rep2[2];
    memset(rep2, 0, sizeof rep2);
    rep2[0].kind = rep2[1].kind = UDM1_ALPHA_FIXED; /* a repeated value */
    rep2[0].fixed_hi = rep2[1].fixed_hi = 0x9E3779B97F4A7C15ull;
    CHECK_STATUS(udm1_alpha_check(rep2, 2, 64, &r), UDM1_OK);
    CHECK(r.dependent && !r.dependent_exact);
    num[2].value = 1.0 / 3.0;
    CHECK_STATUS(udm1_alpha_check(num, 3, 64, &r), UDM1_OK);
    CHECK(r.rational && r.rational_dim == 2);
    num[2].value = 0.7182818284590452; /* e - 2: nothing to report */
    CHECK_STATUS(udm1_alpha_check(num, 3, 64, &r), UDM1_OK);
    CHECK(!r.rational && !r.dependent);

    /* presets: all independent; WMMR's worst projection at n = 1024 is several times
     * worse than random, WR's is close to random, R_d's is in between */
    udm1_seq *s = NULL;
    double wr_worst = 0, wmmr_worst = 0, hw_worst = 0;
    CHECK_STATUS(udm1_seq_create("wr", 22, 0, 0, &s), UDM1_OK);
    CHECK_STATUS(udm1_seq_check(s, 1024, &r), UDM1_OK);
    CHECK(!r.rational && !r.dependent);
    wr_worst = r.worst_l2_star;
    udm1_seq_destroy(s);
    CHECK_STATUS(udm1_seq_create("wmmr", 22, 0, 0, &s), UDM1_OK);
    CHECK_STATUS(udm1_seq_check(s, 1024, &r), UDM1_OK);
    CHECK(!r.rational && !r.dependent);
    wmmr_worst = r.worst_l2_star;
    CHECKF(wmmr_worst > 3.0 * r.random_l2_star, "wmmr worst %g random %g", wmmr_worst, r.random_l2_star);
    udm1_seq_destroy(s);
    CHECK_STATUS(udm1_seq_create("hwmmr", 22, 0, 0, &s), UDM1_OK);
    CHECK_STATUS(udm1_seq_check(s, 1024, &r), UDM1_OK);
    CHECK(!r.rational && !r.dependent);
    hw_worst = r.worst_l2_star;
    udm1_seq_destroy(s);
    CHECK(wr_worst < hw_worst && hw_worst < wmmr_worst);

    /* D == 1: the 1D set itself */
    CHECK_STATUS(udm1_seq_create("golden", 1, 0, 0, &s), UDM1_OK);
    CHECK_STATUS(udm1_seq_check(s, 100, &r), UDM1_OK);
    CHECK(r.worst_dims[0] == 0 && r.worst_dims[1] == 0 && r.worst_l2_star < r.random_l2_star);
    udm1_seq_destroy(s);
    CHECK_DONE();
}
