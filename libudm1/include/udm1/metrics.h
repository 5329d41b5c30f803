/*
 * udm1/metrics.h - quality metrics of point sets and samplers: discrepancies, distances, test integrands,
 * integration error, spectra and the zone plate.
 * Part of libudm1's public interface; udm1/udm1.h includes every part.
 */
#ifndef UDM1_METRICS_H
#define UDM1_METRICS_H

#include "udm1/seq.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* Quality metrics                                                           */
/* ------------------------------------------------------------------------ */
/* A metric that fails writes nothing into its outputs (udm1/core.h): each checks all of its arguments
 * (every point of a set) before it writes, and the spectrum sums its periodograms in memory of its own. */

typedef enum udm1_discrepancy_kind {
    UDM1_DISCREPANCY_L2_STAR = 1,      /* L2-star, square-rooted (as scipy.stats.qmc) */
    UDM1_DISCREPANCY_CENTERED = 2,     /* centered L2, squared (as scipy "CD") */
    UDM1_DISCREPANCY_WRAP_AROUND = 3,  /* wrap-around L2, squared (as scipy "WD") */
    UDM1_DISCREPANCY_MIXTURE = 4       /* mixture L2, squared (as scipy "MD") */
} udm1_discrepancy_kind;

/* Discrepancy of n points in [0,1]^d, point i at points[i * stride + j].
 * The definitions and normalisations are those of scipy.stats.qmc.discrepancy.
 * O(n^2 d) time, no allocation. At any d the value is the true one rounded to a
 * double, +inf where it exceeds the double range (the constant and product terms
 * grow like 1.5^d and are carried with a separate exponent past d = 512), never NaN. Errors: NULL_ARGUMENT, INVALID_ARGUMENT (n == 0,
 * d == 0, stride < d, unknown kind, a coordinate outside [0,1] or NaN). */
UDM1_API udm1_status udm1_discrepancy(const double *points, size_t n, uint32_t d, size_t stride,
                                      uint32_t kind, double *out);

/* The discrepancy of n independent uniform points in d dimensions, the
 * "random" line: E[D^2] for the squared kinds, sqrt(E[D^2]) for L2-star
 * (+inf where it exceeds the double range, never NaN).
 * Errors: NULL_ARGUMENT, INVALID_ARGUMENT (n or d 0, unknown kind). */
UDM1_API udm1_status udm1_discrepancy_random(size_t n, uint32_t d, uint32_t kind, double *out);

/* Exact star discrepancy D*_n = sup over boxes [0,x) x [0,y) of |A/n - xy| of n
 * points in [0,1)^2 (point i at points[i * stride], points[i * stride + 1]),
 * over the closed and open boxes through the points' coordinates; O(n^2).
 * Errors: NULL_ARGUMENT, INVALID_ARGUMENT (n 0 or above 16384, stride < 2,
 * a coordinate outside [0,1] or NaN), OUT_OF_MEMORY. (1.1) */
UDM1_API udm1_status udm1_star_discrepancy_2d(const double *points, size_t n, size_t stride, double *out);

/* Smallest distance between two of n points in [0,1]^d (Euclidean; with
 * toroidal != 0 on the unit torus). Multiply by sqrt(n) for the usual
 * normalised figure. O(n^2 d). Errors: NULL_ARGUMENT, INVALID_ARGUMENT (n < 2,
 * d 0, stride < d, a coordinate not finite). (1.1) */
UDM1_API udm1_status udm1_min_distance(const double *points, size_t n, uint32_t d, size_t stride, int toroidal,
                                       double *out);

/* Test integrands on [0,1]^d with closed-form integrals. Parameters are fixed
 * and documented: u_i = frac(0.1 + i (sqrt5 - 1) / 2), i = 0..d-1.
 *  2D (d must be 2):
 *   GAUSSIAN      exp(-((x-.5)^2 + (y-.5)^2) / (2 0.15^2))          smooth
 *   PRODUCT_PEAK  prod 1 / (0.1^2 + (x_i - 0.5)^2)  / 100           smooth
 *   BILINEAR      x y                                                smooth
 *   DISK          1 inside the disk of centre (.5, .5), area 1/2     discontinuous
 *   TRIANGLE      1 inside (0.1,0.1), (0.9,0.2), (0.3,0.8), area .27 discontinuous
 *   HALFPLANE     1 where y < 0.2 + 0.6 x, area 1/2                  discontinuous
 *   STEP          1 where x < 1/sqrt2                                discontinuous
 *  Any d (Genz 1984 families):
 *   GENZ_OSCILLATORY   cos(2 pi u_0 + sum a x_i), a = 9/d
 *   GENZ_PRODUCT_PEAK  prod (a^-2 + (x_i - u_i)^2)^-1, a = 7/sqrt(d)
 *   GENZ_CORNER_PEAK   (1 + sum a x_i)^-(d+1), a = 2/d; d <= 20
 *   GENZ_GAUSSIAN      exp(-sum a^2 (x_i - u_i)^2), a = 7/sqrt(d)
 *   GENZ_CONTINUOUS    exp(-sum a |x_i - u_i|), a = 4/sqrt(d)
 *   GENZ_DISCONTINUOUS 0 if x_0 > u_0 or x_1 > u_1, else exp(sum a x_i), a = 2/d; d >= 2 */
typedef enum udm1_integrand {
    UDM1_INTEGRAND_GAUSSIAN = 1,
    UDM1_INTEGRAND_PRODUCT_PEAK = 2,
    UDM1_INTEGRAND_BILINEAR = 3,
    UDM1_INTEGRAND_DISK = 4,
    UDM1_INTEGRAND_TRIANGLE = 5,
    UDM1_INTEGRAND_HALFPLANE = 6,
    UDM1_INTEGRAND_STEP = 7,
    UDM1_INTEGRAND_GENZ_OSCILLATORY = 8,
    UDM1_INTEGRAND_GENZ_PRODUCT_PEAK = 9,
    UDM1_INTEGRAND_GENZ_CORNER_PEAK = 10,
    UDM1_INTEGRAND_GENZ_GAUSSIAN = 11,
    UDM1_INTEGRAND_GENZ_CONTINUOUS = 12,
    UDM1_INTEGRAND_GENZ_DISCONTINUOUS = 13
} udm1_integrand;

/* Name ("disk", "genz-gaussian", ...) of an integrand; NULL if unknown. (1.1) */
UDM1_API const char *udm1_integrand_name(uint32_t integrand);
/* Values of the integrand at n points (point i at points[i * stride]) into out[i].
 * Errors: NULL_ARGUMENT, INVALID_ARGUMENT (unknown integrand, d not allowed for
 * it, stride < d, a coordinate not finite: the message names the point). (1.1) */
UDM1_API udm1_status udm1_integrand_eval(uint32_t integrand, uint32_t d, const double *points, size_t n,
                                         size_t stride, double *out);
/* Its exact integral over [0,1]^d. Errors: INVALID_ARGUMENT, NULL_ARGUMENT. (1.1) */
UDM1_API udm1_status udm1_integrand_exact(uint32_t integrand, uint32_t d, double *out);

/* Work limits. The metrics below whose cost grows with their parameters rather than with an input
 * already in memory refuse (INVALID_ARGUMENT, the message naming the limit) a call above about a
 * minute of work on one core (2026 x86-64), as udm1_seq_check does:
 *   UDM1_WORK_LIMIT_INTEGRATION  n x randomizations x d values (udm1_integration_error)
 *   UDM1_WORK_LIMIT_SPECTRUM     n x randomizations x size^2 terms (udm1_spectrum_2d)
 *   UDM1_WORK_LIMIT_ZONEPLATE    width x height x spp samples (udm1_zoneplate)
 * (1.6) */
#define UDM1_WORK_LIMIT_INTEGRATION (1ull << 35)
#define UDM1_WORK_LIMIT_SPECTRUM (1ull << 37)
#define UDM1_WORK_LIMIT_ZONEPLATE (1ull << 32)

/* Integration error of a sampler: for streams r = 0..R-1 the estimate is the
 * mean of the integrand over points [0, n) of stream r, dimensions [0, d);
 * rmse = sqrt(mean over r of (estimate - exact)^2), bias = the mean error.
 * A point set uses its first n points (give it K = n). Errors: NULL_ARGUMENT
 * (seq, rmse), DIMENSION (d > D), INVALID_ARGUMENT (n or R 0, integrand/d, the
 * work limit), INDEX_RANGE (n > K). bias may be NULL. (1.1) */
UDM1_API udm1_status udm1_integration_error(const udm1_seq *seq, uint32_t integrand, uint32_t d, uint64_t n,
                                            uint32_t randomizations, double *rmse, double *bias);

/* Power spectrum of points [0, n) of dimensions (dim0, dim0+1): the periodogram
 * P(k) = |sum_j exp(-2 pi i k . x_j)|^2 / n averaged over streams 0..R-1, at
 * the integer frequencies k in [-size/2, size/2)^2, written row by row with
 * k = (0, 0) at (size/2, size/2). Random points give P ~ 1. O(R n size^2).
 * Errors: NULL_ARGUMENT, DIMENSION, INVALID_ARGUMENT (n or R 0, size 0, odd or
 * above 1024, the work limit), INDEX_RANGE. (1.1) */
UDM1_API udm1_status udm1_spectrum_2d(const udm1_seq *seq, uint32_t dim0, uint64_t n, uint32_t randomizations,
                                      uint32_t size, double *out);

/* Zone plate test: a width x height image of the pixel averages of
 * z(x, y) = (1 + cos(pi (x^2 + y^2) / width)) / 2 (x, y in pixels from the
 * top-left corner, so the frequency reaches 1 cycle per pixel, twice Nyquist,
 * at distance `width`), each pixel estimated with spp points of stream
 * ((uint64_t)y << 32 | x), dimensions (dim0, dim0+1) as the offset in the
 * pixel. Aliasing shows as false rings. Errors: NULL_ARGUMENT, DIMENSION,
 * INVALID_ARGUMENT (0 or above 16384 sizes, spp 0, the work limit), INDEX_RANGE. (1.1) */
UDM1_API udm1_status udm1_zoneplate(const udm1_seq *seq, uint32_t dim0, uint32_t width, uint32_t height,
                                    uint32_t spp, float *out);

#ifdef __cplusplus
}
#endif

#endif /* UDM1_METRICS_H */
