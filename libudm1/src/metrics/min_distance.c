/* min_distance.c - the smallest distance between two points of a set. */
#include "core/internal.h"

#include <math.h>

udm1_status udm1_min_distance(const double *points, size_t n, uint32_t d, size_t stride, int toroidal, double *out)
{
    static const char fn[] = "udm1_min_distance";
    if (!points || !out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, points ? "out" : "points");
    if (n < 2 || d == 0) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: needs n >= 2 and d >= 1", fn);
    if (stride < d) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: stride %zu < d %u", fn, stride, d);
    for (size_t i = 0; i < n; ++i)
        for (uint32_t k = 0; k < d; ++k)
            if (!isfinite(points[i * stride + k]))
                return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: point %zu coordinate %u is not finite", fn, i, k);
    double best = INFINITY;
    for (size_t i = 0; i < n; ++i) {
        const double *a = points + i * stride;
        for (size_t j = i + 1; j < n; ++j) {
            const double *b = points + j * stride;
            double s = 0.0;
            for (uint32_t k = 0; k < d && s < best; ++k) {
                double t = fabs(a[k] - b[k]);
                if (toroidal && t > 0.5) t = 1.0 - t;
                s += t * t;
            }
            if (s < best) best = s;
        }
    }
    *out = sqrt(best);
    return UDM1_OK;
}
