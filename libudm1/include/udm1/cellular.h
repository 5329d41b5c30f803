/*
 * udm1/cellular.h - cellular (Worley) noise over a udm1_noise's tables: distances to the feature
 * points of a lattice, one point per unit cell.
 * Part of libudm1's public interface; udm1/udm1.h includes every part.
 */
#ifndef UDM1_CELLULAR_H
#define UDM1_CELLULAR_H

#include "udm1/noise.h"

#ifdef __cplusplus
extern "C" {
#endif

/* (1.7) Every unit cell of the integer lattice holds one feature point. The cell (X, Y[, Z]) takes entry
 * h = perm[perm[perm[X'] + Y'] + Z'] (2D: perm[perm[X'] + Y']) of the noise's table of 256 offsets, with X'
 * the cell index wrapped by the noise's period on that axis (desc.period; 0 = 256) and then to 0..255, as
 * the lattice noise hashes its corners; so the pattern is periodic wherever the noise is. Its point is
 * cell + 1/2 + jitter (o - 1/2), o = (b + 1/2) / 256 in (0, 1)^3 from the entry's 8-bit offsets b (the
 * arithmetic: v = c1 b + (c0 - (t - d)) on each axis, t the point's offset in its cell, d the cell's
 * from the point's, c1 = jitter / 256, c0 = 1/2 - 127.5 c1). Where the offsets come from (desc.table):
 *  a preset          that sequence's first 256 points (dimensions 0, 1, 2; a set of fewer dimensions: its
 *                    values whitened as the gradients are; udm1/noise.h), the feature points of a
 *                    neighbourhood then as evenly spread as the sequence's points are;
 *  NULL or "perlin"  a hash: udm1's 64-bit mixer of (the entry, the axis);
 *  "drand48"         drand48 draws after the gradients and the permutation.
 *
 * The value at a point p is a function of the distances d(p, q) to the feature points q, in the metric:
 *  EUCLIDEAN  sqrt(sum v_i^2)   MANHATTAN  sum |v_i|   CHEBYSHEV  max |v_i|
 *  MINKOWSKI  (sum |v_i|^e)^(1/e), e = params.exponent (>= 1; 2 and 1 give the first two, bit for bit)
 * The outputs: F1, F2, F3 (the nearest, second and third distances, in cell units), F2 - F1, and CELL
 * (the nearest feature point's entry h / 255, in [0, 1], constant over its cell; ties: the smaller h).
 * The search is exact: every cell that could hold one of the three nearest points is visited (the
 * 3^d block around p first, then larger shells while a cell of the next shell could be nearer than the
 * current F1..F3 with a margin of 2^-20 for rounding), so the values are those of the nearest points
 * among all cells, whatever the jitter, metric and point, and the same in every kernel.
 *
 * Coordinates far from the origin keep their offset in the cell exact (as the noise's). float: float
 * coordinates and arithmetic; the AVX-512 and AVX2 kernels equal the scalar code bit for bit. */
typedef enum udm1_cellular_metric {
    UDM1_CELLULAR_EUCLIDEAN = 0,
    UDM1_CELLULAR_MANHATTAN = 1,
    UDM1_CELLULAR_CHEBYSHEV = 2,
    UDM1_CELLULAR_MINKOWSKI = 3
} udm1_cellular_metric;

typedef enum udm1_cellular_output {
    UDM1_CELLULAR_F1 = 0,
    UDM1_CELLULAR_F2 = 1,
    UDM1_CELLULAR_F3 = 2,
    UDM1_CELLULAR_F2_MINUS_F1 = 3,
    UDM1_CELLULAR_CELL = 4
} udm1_cellular_output;

typedef struct udm1_cellular_params {
    uint32_t struct_size; /* set by udm1_cellular_params_init */
    uint32_t metric;      /* udm1_cellular_metric; default EUCLIDEAN */
    uint32_t output;      /* udm1_cellular_output; default F1 */
    uint32_t reserved;    /* set to 0 */
    double jitter;        /* 0..1: how far a feature point may stray from its cell's centre; default 1 (Worley) */
    double exponent;      /* MINKOWSKI's e, 1..64; default 2 */
} udm1_cellular_params;

/* The defaults above. Does nothing if params is NULL. */
UDM1_API void udm1_cellular_params_init(udm1_cellular_params *params);

/* Cellular noise at n points of `dims` (2 or 3) coordinates: coordinate c of point i is axes[c][i * stride]
 * (packed points: axes = {p, p + 1, p + 2} and stride 3); out[i] its value. A NULL params takes the
 * defaults. Errors (out left unchanged): NULL_ARGUMENT (noise, axes or an axis, out), INVALID_ARGUMENT
 * (dims, stride 0, a params field: struct_size, metric, output, reserved, jitter outside [0, 1], exponent
 * outside [1, 64]; a non-finite coordinate: the message names the first such point). */
UDM1_API udm1_status udm1_cellular_eval(const udm1_noise *noise, const udm1_cellular_params *params, uint32_t dims,
                                        const double *const axes[], size_t stride, size_t n, double *out);
UDM1_API udm1_status udm1_cellular_eval_f32(const udm1_noise *noise, const udm1_cellular_params *params,
                                            uint32_t dims, const float *const axes[], size_t stride, size_t n,
                                            float *out);

/* The 256 feature point offsets of a noise, offsets[3 h + a] = b_a of entry h (768 bytes), copied out.
 * Errors: NULL_ARGUMENT. */
UDM1_API udm1_status udm1_cellular_offsets(const udm1_noise *noise, uint8_t *offsets);

#ifdef __cplusplus
}
#endif

#endif /* UDM1_CELLULAR_H */
