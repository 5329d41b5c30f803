/* lattice.c - the rank-1 lattice point set ("lattice"): the fixed-N counterpart of a Kronecker sequence.
 *
 *   x_n = { n z / K + shift },   n = 0 .. K-1,   z = (z_0, ..., z_{D-1}) integers coprime to K
 *
 * z is built component by component (CBC): z_0 = 1, and each next z_j is, among candidate units mod K
 * not used yet, the one that minimizes the wrap-around L2 discrepancy of the first j + 1 dimensions.
 * For a lattice that discrepancy is exact in O(K) per candidate, because the differences of lattice
 * points are lattice points:  WD^2 = -(4/3)^d + (1/K) sum_n prod_j g({n z_j / K}),
 * g(t) = 3/2 - t (1 - t). Every unit is a candidate while K * units <= 2^24; above that a spread subset
 * (golden-ratio steps) keeps the work per dimension near 2^24 operations. When every unit is used (D
 * above phi(K)), units repeat: a K-point lattice has at most phi(K) distinct coordinates.
 *
 * Values: z_j / K in 0.128 fixed point rounded up, so that the raw value of point n is exactly
 * floor(2^64 {n z_j / K}) for every K < 2^32 (the error n * 2^-128 never reaches the top 64 bits:
 * the lower bits of n z_j 2^128 / K are multiples of 2^64 / K). */
#include "weyl/weyl.h"

#include <stdlib.h>

#define LATTICE_WORK_PER_DIM (1u << 24)
#define UDM1_LATTICE_MAX_POINTS (1u << 24)

static uint64_t gcd64(uint64_t a, uint64_t b)
{
    while (b) {
        uint64_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* ceil(z 2^128 / K) by binary long division (z < K < 2^32). */
static void rational_generator(uint64_t z, uint64_t k, udm1_generator *g)
{
    uint64_t r = z % k, hi = 0, lo = 0;
    for (int i = 0; i < 128; ++i) {
        r <<= 1;
        uint64_t bit = r >= k;
        if (bit) r -= k;
        hi = (hi << 1) | (lo >> 63);
        lo = (lo << 1) | bit;
    }
    if (r && ++lo == 0) ++hi;
    g->hi = hi;
    g->lo = lo;
    g->nature = UDM1_NATURE_POINT_SET;
    g->radical = 0;
}

udm1_status udm1_init_lattice(udm1_seq_t *seq)
{
    static const char fn[] = "udm1_seq_create";
    uint64_t k = seq->point_count;
    if (k > UDM1_LATTICE_MAX_POINTS) /* the search keeps two arrays of K doubles and reads them once per dimension */
        return udm1_fail(UDM1_ERROR_POINT_COUNT, "%s: a lattice has at most %u points, %llu asked", fn,
                         UDM1_LATTICE_MAX_POINTS, (unsigned long long)k);
    uint32_t d = seq->dims;
    seq->gen = malloc(sizeof(udm1_generator) * d);
    double *prod = malloc(sizeof(double) * k), *g = malloc(sizeof(double) * k);
    uint64_t *cand = malloc(sizeof(uint64_t) * k); /* the units mod K: at most K - 1 */
    char *used = calloc(k, 1);
    if (!seq->gen || !prod || !g || !cand || !used) {
        free(prod), free(g), free(cand), free(used);
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory for a %llu-point lattice", fn,
                         (unsigned long long)k);
    }
    for (uint64_t n = 0; n < k; ++n) {
        double t = (double)n / (double)k;
        g[n] = 1.5 - t * (1.0 - t);
        prod[n] = 1.0;
    }
    size_t nc = 0;
    for (uint64_t c = 1; c < k; ++c)
        if (gcd64(c, k) == 1) cand[nc++] = c;
    size_t units = nc;
    /* the candidate subset when every unit would cost too much */
    size_t limit = k * (uint64_t)nc <= LATTICE_WORK_PER_DIM ? nc : (size_t)(LATTICE_WORK_PER_DIM / k);
    if (limit < 1) limit = 1;
    for (uint32_t j = 0; j < d; ++j) {
        uint64_t best = 1;
        if (j > 0 && k > 2) {
            double best_sum = 0.0;
            int found = 0;
            for (size_t i = 0; i < limit; ++i) {
                size_t at = i; /* all units, or a golden-ratio spread of them */
                if (limit < nc) {
                    double step = (double)i * 0.6180339887498949;
                    at = (size_t)((step - (double)(uint64_t)step) * (double)nc);
                }
                uint64_t c = cand[at < nc ? at : nc - 1];
                if (used[c] && units > j) continue; /* distinct coordinates while units last */
                double s = 0.0;
                uint64_t m = 0;
                for (uint64_t n = 0; n < k; ++n) {
                    s += prod[n] * g[m];
                    m += c;
                    if (m >= k) m -= k;
                }
                if (!found || s < best_sum) best_sum = s, best = c, found = 1;
            }
        }
        uint64_t z = best % k; /* the coordinate z_j of the generating vector */
        used[z] = 1;
        uint64_t m = 0;
        for (uint64_t n = 0; n < k; ++n) {
            prod[n] *= g[m];
            m += z;
            if (m >= k) m -= k;
        }
        if (k == 1) {
            seq->gen[j].hi = seq->gen[j].lo = 0;
            seq->gen[j].nature = UDM1_NATURE_POINT_SET;
            seq->gen[j].radical = 0;
        } else {
            rational_generator(z, k, &seq->gen[j]);
        }
    }
    free(used), free(prod), free(g), free(cand);
    return UDM1_OK;
}
