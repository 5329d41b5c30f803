/* alpha_check.c - is a set of generators fit for sampling? Rationality,
 * rational dependence, and the worst 2D projection at n points. */
#include "weyl/weyl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Work limit of the projection scan, in kernel evaluations: pairs x (n^2 / 2 + 256),
 * the 256 standing for the fixed cost of a pair. About a minute at the limit. */
#define PROJECTION_BUDGET (1ull << 36)
#define PAIR_OVERHEAD 256u
/* Work limit of the numeric relation scan, in pairs (561 relations each): ~1 s. */
#define RELATION_BUDGET (1ull << 20)
#define RELATION_MAX_COEF 16
#define RELATION_TOLERANCE (1ull << 24) /* 2^-40 in 0.64 fixed point */

typedef struct radical_dim { uint64_t radical; uint32_t dim; } radical_dim;

static int by_radical(const void *a, const void *b)
{
    const radical_dim *x = a, *y = b;
    if (x->radical != y->radical) return x->radical < y->radical ? -1 : 1;
    return x->dim < y->dim ? -1 : (x->dim > y->dim);
}

static int near_zero(uint64_t v) { return v < RELATION_TOLERANCE || v > (uint64_t)0 - RELATION_TOLERANCE; }

/* Is l1 a1 + l2 a2 = 0 mod 1 (to 2^-40) for some small (l1, l2) != 0? */
static int numeric_relation(uint64_t a1, uint64_t a2)
{
    for (int64_t l1 = 0; l1 <= RELATION_MAX_COEF; ++l1)
        for (int64_t l2 = -RELATION_MAX_COEF; l2 <= RELATION_MAX_COEF; ++l2) {
            if (l1 == 0 && l2 <= 0) continue; /* (l1, l2) and -(l1, l2) are the same relation */
            if (near_zero((uint64_t)l1 * a1 + (uint64_t)l2 * a2)) return 1;
        }
    return 0;
}

static int numeric_rational(uint64_t a)
{
    for (uint64_t l = 1; l <= RELATION_MAX_COEF; ++l)
        if (near_zero(l * a)) return 1;
    return 0;
}

static void set_dependent(udm1_alpha_report *r, uint32_t a, uint32_t b, int exact)
{
    if (r->dependent && (r->dependent_dims[0] < a || (r->dependent_dims[0] == a && r->dependent_dims[1] <= b))) return;
    r->dependent = 1;
    r->dependent_exact = (uint32_t)exact;
    r->dependent_dims[0] = a;
    r->dependent_dims[1] = b;
}

/* Returns 0, or 1 when the numeric scan was skipped for its cost. */
static udm1_status check_dependence(const char *fn, const udm1_generator *gen, uint32_t dims, udm1_alpha_report *r,
                                    int *skipped)
{
    /* rational generators */
    for (uint32_t j = 0; j < dims; ++j) {
        int rational = gen[j].nature == UDM1_NATURE_RATIONAL ||
                       (gen[j].nature == UDM1_NATURE_UNKNOWN && numeric_rational(gen[j].hi));
        if (rational && !r->rational) {
            r->rational = 1;
            r->rational_dim = j;
        }
    }
    /* exact: quadratic irrationals with the same square-free part */
    radical_dim *q = malloc(sizeof(radical_dim) * dims);
    if (!q) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory", fn);
    uint32_t nq = 0;
    for (uint32_t j = 0; j < dims; ++j)
        if (gen[j].nature == UDM1_NATURE_QUADRATIC) q[nq++] = (radical_dim){gen[j].radical, j};
    qsort(q, nq, sizeof *q, by_radical);
    for (uint32_t i = 0; i + 1 < nq; ++i)
        if (q[i].radical == q[i + 1].radical) set_dependent(r, q[i].dim, q[i + 1].dim, 1);
    free(q);
    /* numeric: pairs that involve a generator of unknown nature */
    uint64_t unknown = 0;
    for (uint32_t j = 0; j < dims; ++j) unknown += gen[j].nature == UDM1_NATURE_UNKNOWN;
    *skipped = unknown > 0 && unknown * dims > RELATION_BUDGET;
    if (!*skipped) {
        for (uint32_t a = 0; a < dims; ++a)
            for (uint32_t b = a + 1; b < dims; ++b) {
                if (gen[a].nature != UDM1_NATURE_UNKNOWN && gen[b].nature != UDM1_NATURE_UNKNOWN) continue;
                if (numeric_relation(gen[a].hi, gen[b].hi)) set_dependent(r, a, b, 0);
            }
    }
    return UDM1_OK;
}

udm1_status udm1_check_generators(const char *fn, const udm1_generator *gen, uint32_t dims, uint64_t n,
                                  udm1_alpha_report *report)
{
    udm1_alpha_report local, *r = &local; /* the caller's report is written once, at the end */
    memset(r, 0, sizeof *r);
    uint64_t pairs = dims > 1 ? (uint64_t)dims * (dims - 1) / 2 : 1;
    if (n < 2 || n > 65536)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: n = %llu is outside 2..65536", fn, (unsigned long long)n);
    if (pairs > PROJECTION_BUDGET / (n * n / 2 + PAIR_OVERHEAD))
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT,
                         "%s: %u dimensions at n = %llu is over the work limit (pairs x (n^2/2 + 256) <= 2^36)", fn,
                         dims,
                         (unsigned long long)n);
    int skipped = 0;
    udm1_status st = check_dependence(fn, gen, dims, r, &skipped);
    if (st != UDM1_OK) return st;

    uint32_t pd = dims > 1 ? 2 : 1;
    double *col = malloc(sizeof(double) * dims * n);
    double *pts = malloc(sizeof(double) * 2 * n);
    if (!col || !pts) {
        free(col);
        free(pts);
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory", fn);
    }
    for (uint32_t j = 0; j < dims; ++j)
        for (uint64_t i = 0; i < n; ++i) col[(size_t)j * n + i] = udm1_to_f64(udm1_weyl_raw(&gen[j], 0, i));
    r->worst_l2_star = -1.0;
    for (uint32_t a = 0; a < dims; ++a)
        for (uint32_t b = dims > 1 ? a + 1 : a; b < dims; ++b) {
            for (uint64_t i = 0; i < n; ++i) {
                pts[2 * i] = col[(size_t)a * n + i];
                pts[2 * i + 1] = col[(size_t)b * n + i];
            }
            double l2;
            udm1_discrepancy(dims > 1 ? pts : col, n, pd, pd, UDM1_DISCREPANCY_L2_STAR, &l2);
            if (l2 > r->worst_l2_star) {
                r->worst_l2_star = l2;
                r->worst_dims[0] = a;
                r->worst_dims[1] = b;
            }
            if (dims == 1) break;
        }
    uint32_t a = r->worst_dims[0], b = r->worst_dims[1];
    for (uint64_t i = 0; i < n; ++i) {
        pts[2 * i] = col[(size_t)a * n + i];
        pts[2 * i + 1] = col[(size_t)b * n + i];
    }
    udm1_discrepancy(dims > 1 ? pts : col, n, pd, pd, UDM1_DISCREPANCY_WRAP_AROUND, &r->worst_wrap_around);
    udm1_discrepancy_random(n, pd, UDM1_DISCREPANCY_L2_STAR, &r->random_l2_star);
    udm1_discrepancy_random(n, pd, UDM1_DISCREPANCY_WRAP_AROUND, &r->random_wrap_around);
    free(col);
    free(pts);

    char dep[112];
    if (r->dependent)
        snprintf(dep, sizeof dep, "dimensions %u and %u are rationally dependent%s", r->dependent_dims[0],
                 r->dependent_dims[1], r->dependent_exact ? "" : " (numerically)");
    else if (skipped)
        snprintf(dep, sizeof dep, "no exact dependence; numeric dependence not checked (too many generators)");
    else
        snprintf(dep, sizeof dep, "no rational dependence found");
    snprintf(r->message, sizeof r->message,
             "%u generators: %s%s; worst %uD projection (%u, %u) at n = %llu: L2-star %.3g = %.2fx random", dims,
             r->rational ? "a rational generator; " : "", dep, pd, a, b, (unsigned long long)n, r->worst_l2_star,
             r->worst_l2_star / r->random_l2_star);
    *report = local;
    return UDM1_OK;
}

udm1_status udm1_seq_check(const udm1_seq *seq, uint64_t n, udm1_alpha_report *report)
{
    if (!seq || !report)
        return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_seq_check: %s is NULL", seq ? "report" : "seq");
    if (!seq->gen)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "udm1_seq_check: '%s' is not a Weyl sequence", seq->name);
    return udm1_check_generators("udm1_seq_check", seq->gen, seq->dims, n, report);
}

udm1_status udm1_alpha_check(const udm1_alpha *alphas, uint32_t count, uint64_t n, udm1_alpha_report *report)
{
    static const char fn[] = "udm1_alpha_check";
    if (!alphas || !report) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, alphas ? "report" : "alphas");
    if (count == 0 || count > UDM1_MAX_DIMENSIONS)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: count %u is outside 1..%u", fn, count, UDM1_MAX_DIMENSIONS);
    udm1_generator *gen = malloc(sizeof(udm1_generator) * count);
    if (!gen) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory", fn);
    udm1_status st = UDM1_OK;
    for (uint32_t j = 0; j < count && st == UDM1_OK; ++j) st = udm1_user_generator(fn, j, &alphas[j], &gen[j], 1);
    if (st == UDM1_OK) st = udm1_check_generators(fn, gen, count, n, report);
    free(gen);
    return st;
}
