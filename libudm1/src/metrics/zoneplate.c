/* zoneplate.c - the zone plate test: pixel averages of a chirp whose
 * frequency passes the Nyquist limit, estimated with a sampler. A good sampler
 * shows the rings fading into grey; a poor one, false rings (aliasing). */
#include "core/internal.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846

udm1_status udm1_zoneplate(const udm1_seq *seq, uint32_t dim0, uint32_t width, uint32_t height, uint32_t spp,
                           float *out)
{
    static const char fn[] = "udm1_zoneplate";
    if (!seq || !out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, seq ? "out" : "seq");
    if (udm1_seq_dimensions(seq) < 2 || dim0 > udm1_seq_dimensions(seq) - 2)
        return udm1_fail(UDM1_ERROR_DIMENSION, "%s: dimensions (%u, %u) of a %u-dimensional sequence", fn, dim0,
                         dim0 + 1, udm1_seq_dimensions(seq));
    if (width == 0 || height == 0 || width > 16384 || height > 16384 || spp == 0)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: width %u, height %u (each in 1..16384) or spp %u (>= 1) out "
                         "of range", fn, width, height, spp);
    if (udm1_work_above(width, height, spp, UDM1_WORK_LIMIT_ZONEPLATE))
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT,
                         "%s: width %u x height %u x spp %u samples is above the work limit 2^32 "
                         "(UDM1_WORK_LIMIT_ZONEPLATE, about a minute)", fn, width, height, spp);
    if (udm1_seq_point_count(seq) && spp > udm1_seq_point_count(seq))
        return udm1_fail(UDM1_ERROR_INDEX_RANGE, "%s: spp = %u of a %llu-point set", fn, spp,
                         (unsigned long long)udm1_seq_point_count(seq));
    double *uv = malloc(sizeof(double) * 2 * spp);
    if (!uv) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory", fn);
    double k = PI / (double)width;
    /* the checks above are every pixel's fill's own (the dimensions, spp within a point set), so no fill
     * fails once a pixel is written: the status below is OK (a failure would still be returned) */
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            udm1_status st = udm1_seq_fill_f64(seq, ((uint64_t)y << 32) | x, 0, spp, dim0, 2, uv, 2);
            if (st != UDM1_OK) {
                free(uv);
                return st;
            }
            double sum = 0.0;
            for (uint32_t s = 0; s < spp; ++s) {
                double px = x + uv[2 * s], py = y + uv[2 * s + 1];
                sum += 0.5 + 0.5 * cos(k * (px * px + py * py));
            }
            out[(size_t)y * width + x] = (float)(sum / spp);
        }
    free(uv);
    return UDM1_OK;
}
