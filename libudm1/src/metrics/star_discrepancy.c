/* star_discrepancy.c - the exact star discrepancy of a 2D point set.
 *
 * D* = sup over anchored boxes [0,x) x [0,y) of |A/n - xy|. The supremum is
 * reached at box corners made of point coordinates (or 1): with closed boxes
 * for the excess A/n - xy and open boxes for the deficit xy - A/n. Sweeping x
 * over the sorted distinct x values while keeping a count per y rank gives
 * every such box in O(n^2) (in the spirit of Bundschuh and Zhu 1993).
 */
#include "core/internal.h"

#include <math.h>
#include <stdlib.h>

typedef struct pt { double x, y; uint32_t yrank; } pt;

static int by_x(const void *a, const void *b)
{
    double u = ((const pt *)a)->x, v = ((const pt *)b)->x;
    return (u > v) - (u < v);
}

static int by_double(const void *a, const void *b)
{
    double u = *(const double *)a, v = *(const double *)b;
    return (u > v) - (u < v);
}

udm1_status udm1_star_discrepancy_2d(const double *points, size_t n, size_t stride, double *out)
{
    static const char fn[] = "udm1_star_discrepancy_2d";
    if (!points || !out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, points ? "out" : "points");
    if (n == 0 || n > 16384) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: n = %zu is outside 1..16384", fn, n);
    if (stride < 2) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: stride %zu < 2", fn, stride);
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 2; ++k) {
            double v = points[i * stride + k];
            if (!(v >= 0.0 && v <= 1.0))
                return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: point %zu coordinate %d = %g is outside [0, 1]", fn,
                                 i, k, v);
        }
    pt *p = malloc(sizeof(pt) * n);
    double *ys = malloc(sizeof(double) * (n + 1));
    uint32_t *count = calloc(2 * (n + 1), sizeof(uint32_t)); /* points swept so far, per y rank */
    if (!p || !ys || !count) {
        free(p);
        free(ys);
        free(count);
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory", fn);
    }
    for (size_t i = 0; i < n; ++i) {
        p[i].x = points[i * stride];
        p[i].y = points[i * stride + 1];
        ys[i] = p[i].y;
    }
    qsort(ys, n, sizeof *ys, by_double);
    size_t m = 0; /* distinct y values */
    for (size_t i = 0; i < n; ++i)
        if (m == 0 || ys[i] != ys[m - 1]) ys[m++] = ys[i];
    for (size_t i = 0; i < n; ++i) { /* rank of each point's y */
        size_t lo = 0, hi = m;
        while (hi - lo > 1) {
            size_t mid = (lo + hi) / 2;
            if (ys[mid] <= p[i].y) lo = mid; else hi = mid;
        }
        p[i].yrank = (uint32_t)lo;
    }
    size_t top = m; /* the y thresholds: the distinct y values, and 1 */
    if (ys[m - 1] < 1.0) ys[top++] = 1.0;
    qsort(p, n, sizeof *p, by_x);
    uint32_t *group = count + (n + 1); /* second half: the current x group */
    double worst = 0.0, inv_n = 1.0 / (double)n;
    size_t i = 0;
    for (;;) {
        /* the next x threshold: a group of points with equal x, or 1 after them */
        double x = i < n ? p[i].x : 1.0;
        size_t j = i;
        while (j < n && p[j].x == x) ++j;
        for (size_t k = i; k < j; ++k) ++group[p[k].yrank];
        /* closed boxes [0,x] x [0,y] hold the swept points and the group with y <= ys[r];
         * open boxes [0,x) x [0,y) hold the swept points with y < ys[r] */
        uint64_t swept = 0, grouped = 0;
        for (size_t r = 0; r < top; ++r) {
            uint64_t open = swept;
            if (r < m) {
                swept += count[r];
                grouped += group[r];
            }
            double vol = x * ys[r];
            double excess = (double)(swept + grouped) * inv_n - vol, deficit = vol - (double)open * inv_n;
            if (excess > worst) worst = excess;
            if (deficit > worst) worst = deficit;
        }
        for (size_t k = i; k < j; ++k) {
            ++count[p[k].yrank];
            group[p[k].yrank] = 0;
        }
        i = j;
        if (x >= 1.0) break; /* the threshold 1 has been seen */
    }
    free(p);
    free(ys);
    free(count);
    *out = worst;
    return UDM1_OK;
}
