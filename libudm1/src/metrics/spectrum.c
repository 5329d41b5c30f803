/* spectrum.c - the power spectrum (periodogram) of a 2D projection, averaged
 * over randomizations: the standard picture of a sampler's structure (flat
 * for random points, a dark centre for blue noise, peaks for lattices). */
#include "core/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TWO_PI 6.28318530717958647692

udm1_status udm1_spectrum_2d(const udm1_seq *seq, uint32_t dim0, uint64_t n, uint32_t randomizations, uint32_t size,
                             double *out)
{
    static const char fn[] = "udm1_spectrum_2d";
    if (!seq || !out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, seq ? "out" : "seq");
    if (udm1_seq_dimensions(seq) < 2 || dim0 > udm1_seq_dimensions(seq) - 2)
        return udm1_fail(UDM1_ERROR_DIMENSION, "%s: dimensions (%u, %u) of a %u-dimensional sequence", fn, dim0,
                         dim0 + 1, udm1_seq_dimensions(seq));
    if (n == 0 || randomizations == 0 || size == 0 || size % 2 || size > 1024)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT,
                         "%s: needs n, randomizations >= 1 and an even size in 2..1024 (n %llu, R %u, size %u)", fn,
                         (unsigned long long)n, randomizations, size);
    if (udm1_work_above(n, randomizations, (uint64_t)size * size, UDM1_WORK_LIMIT_SPECTRUM))
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT,
                         "%s: n %llu x randomizations %u x size^2 %u^2 is above the work limit 2^37 "
                         "(UDM1_WORK_LIMIT_SPECTRUM, about a minute)", fn, (unsigned long long)n, randomizations, size);
    if (udm1_seq_point_count(seq) && n > udm1_seq_point_count(seq))
        return udm1_fail(UDM1_ERROR_INDEX_RANGE, "%s: n = %llu of a %llu-point set", fn, (unsigned long long)n,
                         (unsigned long long)udm1_seq_point_count(seq));
    size_t S = size, cells = S * S;
    /* the periodograms summed in sum, written to out only when every point was drawn */
    double *fre = malloc(sizeof(double) * cells), *fim = malloc(sizeof(double) * cells);
    double *ex = malloc(sizeof(double) * 4 * S), *pts = malloc(sizeof(double) * 2 * 1024);
    double *sum = calloc(cells, sizeof(double));
    if (!fre || !fim || !ex || !pts || !sum) {
        free(fre);
        free(fim);
        free(ex);
        free(pts);
        free(sum);
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory", fn);
    }
    double *exr = ex, *exi = ex + S, *eyr = ex + 2 * S, *eyi = ex + 3 * S;
    udm1_status st = UDM1_OK;
    for (uint32_t r = 0; r < randomizations && st == UDM1_OK; ++r) {
        memset(fre, 0, sizeof(double) * cells);
        memset(fim, 0, sizeof(double) * cells);
        for (uint64_t i0 = 0; i0 < n && st == UDM1_OK; i0 += 1024) {
            size_t c = n - i0 < 1024 ? (size_t)(n - i0) : 1024;
            st = udm1_seq_fill_f64(seq, r, i0, c, dim0, 2, pts, 2);
            for (size_t j = 0; j < c && st == UDM1_OK; ++j) {
                /* e^{-2 pi i k x} for k = -S/2 .. S/2-1, one sin/cos per frequency */
                for (size_t k = 0; k < S; ++k) {
                    double f = (double)((long)k - (long)(S / 2));
                    exr[k] = cos(TWO_PI * f * pts[2 * j]);
                    exi[k] = -sin(TWO_PI * f * pts[2 * j]);
                    eyr[k] = cos(TWO_PI * f * pts[2 * j + 1]);
                    eyi[k] = -sin(TWO_PI * f * pts[2 * j + 1]);
                }
                for (size_t ky = 0; ky < S; ++ky) {
                    double ar = eyr[ky], ai = eyi[ky];
                    double *rowr = fre + ky * S, *rowi = fim + ky * S;
                    for (size_t kx = 0; kx < S; ++kx) {
                        rowr[kx] += ar * exr[kx] - ai * exi[kx];
                        rowi[kx] += ar * exi[kx] + ai * exr[kx];
                    }
                }
            }
        }
        for (size_t k = 0; k < cells; ++k) sum[k] += (fre[k] * fre[k] + fim[k] * fim[k]) / (double)n;
    }
    if (st == UDM1_OK)
        for (size_t k = 0; k < cells; ++k) out[k] = sum[k] / randomizations;
    free(fre);
    free(fim);
    free(ex);
    free(pts);
    free(sum);
    return st;
}
