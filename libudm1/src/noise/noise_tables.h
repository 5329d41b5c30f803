/* noise/noise_tables.h - a udm1_noise's tables (noise.c builds them; patterns.c and the vector path
 * of noise_simd.c read them). */
#ifndef UDM1_NOISE_TABLES_H
#define UDM1_NOISE_TABLES_H

#include "core/internal.h"
#include "udm1/cellular.h"

/* A noise's tables (noise.c); the patterns (patterns.c) read the wave sources. */
typedef struct udm1_pick { uint8_t iu, iv; double su, sv; } udm1_pick; /* +-c[iu] +-c[iv] */
#define UDM1_NOISE_WAVES 10
struct udm1_noise {
    uint32_t kind;
    uint32_t period[3];
    uint32_t period_w;        /* the fourth axis' */
    uint8_t perm[512];        /* the permutation, twice */
    double grad[256][3];      /* the table's unit gradients */
    int32_t pair[512];        /* perm[k] | perm[k + 1] << 8: a corner's hashes at z and z + 1 in one load */
    uint32_t hash4[256 * 256]; /* by x * 256 + y: the bytes perm[perm[x'] + y'] for (x', y') = (x, y),
                                * (x, y+1), (x+1, y), (x+1, y+1), wrapped to 0..255: a cell's four
                                * column hashes (2D: its corner hashes) in one load */
    double g3[256][3];        /* the gradient the 3D evaluation uses, by corner hash */
    double g2[256][2];        /* ... the 2D one */
    double g1[256];           /* ... the 1D one */
    udm1_pick pick3[256];     /* the improved noise's 3D gradient, as coordinates and signs */
    udm1_pick pick2[256];     /* ... 2D */
    double wave_source[UDM1_NOISE_WAVES][3];
    uint8_t feature[3][256];  /* the cellular noise's feature point offsets by axis, b: (b + 1/2) / 256 (udm1/cellular.h) */
    uint32_t cell4[514];      /* perm[k] | feature[0..2][perm[k]] << 8, 16, 24 (k mod 256): a cell's hash and its
                               * feature point's offsets in one load (the AVX2 cellular kernels; two entries past
                               * 511 for their loads of three neighbours) */
    int32_t triple[512];      /* perm[k] | perm[k + 1] << 8 | perm[k + 2] << 16 (indices mod 256): the hashes of
                               * three neighbouring cells along an axis in one load (the AVX2 cellular kernels) */
};

/* Coordinates a vector kernel checks for NaN and infinities beside its own work (noise/side_check.h has
 * the steps): `runs` contiguous arrays of the kernel's type, `vectors` 64-byte vectors of each per
 * iteration of its loop for `steps` iterations, `at` advanced as they are read; the kernel sets `bad`
 * when one of them is not finite. */
typedef struct udm1_side_check {
    const char *at[4];
    unsigned runs;
    unsigned vectors;
    size_t steps;
    int bad;
} udm1_side_check;

/* The vector path of udm1_noise_points (noise_simd.c): how many leading points it computed, checking side
 * (NULL: nothing) beside them, BLOCK groups of four points per iteration. */
UDM1_HIDDEN size_t udm1_noise_points_fast(const struct udm1_noise *n, uint32_t dims, const double *xyz, size_t count,
                                          size_t stride, double *out, udm1_side_check *side);
/* The vector paths of udm1_noise_eval and udm1_noise_eval_f32 (noise_simd.c, noise_simd_f32.c): how many
 * leading points they computed (they stop before a group with a non-finite coordinate), checking side
 * (NULL: nothing) beside them. The _group functions: the points of one iteration of the path the same
 * arguments take (its steps of side), 0 where no vector path applies. */
UDM1_HIDDEN size_t udm1_noise_eval_fast_f64(const struct udm1_noise *n, uint32_t dims, const double *const *axes,
                                            size_t stride, size_t count, double *value, double *gradient,
                                            udm1_side_check *side);
UDM1_HIDDEN size_t udm1_noise_eval_fast_f32(const struct udm1_noise *n, uint32_t dims, const float *const *axes,
                                            size_t stride, size_t count, float *value, float *gradient,
                                            udm1_side_check *side);
UDM1_HIDDEN size_t udm1_noise_eval_group_f64(const struct udm1_noise *n, uint32_t dims, const double *const *axes,
                                             size_t stride, const double *value, const double *gradient);
UDM1_HIDDEN size_t udm1_noise_eval_group_f32(const struct udm1_noise *n, uint32_t dims, const float *const *axes,
                                             size_t stride, const float *value, const float *gradient);
/* A lattice noise batch, all or nothing (batch.c): every coordinate of points [0, count) checked (before
 * the evaluation, or beside the vector kernel while it writes a first part to memory of its own) before
 * value and gradient are written; INVALID_ARGUMENT naming fn and the first point not finite, OUT_OF_MEMORY,
 * or the values. The arguments otherwise checked. */
UDM1_HIDDEN udm1_status udm1_noise_batch_f64(const char *fn, const struct udm1_noise *n, uint32_t dims,
                                             const double *const *axes, size_t stride, size_t count, double *value,
                                             double *gradient);
UDM1_HIDDEN udm1_status udm1_noise_batch_f32(const char *fn, const struct udm1_noise *n, uint32_t dims,
                                             const float *const *axes, size_t stride, size_t count, float *value,
                                             float *gradient);
/* The scalar references (lattice.c): the noise of dims (1..4) coordinates c, and its gradient into grad
 * (dims values) unless grad is NULL. c must be finite. */
UDM1_HIDDEN double udm1_lattice_f64(const struct udm1_noise *n, uint32_t dims, const double *c, double *grad);
UDM1_HIDDEN float udm1_lattice_f32(const struct udm1_noise *n, uint32_t dims, const float *c, float *grad);

/* The refusal of a batch whose point i has a coordinate c not finite (lattice.c): INVALID_ARGUMENT, the
 * message naming fn, the point and the coordinate. The batches find it (core/finite.h) before they write. */
UDM1_HIDDEN udm1_status udm1_not_finite(const char *fn, size_t i, uint32_t c);

/* Cellular noise (cellular.c): the vector kernels (cellular_simd.c): how many leading points they
 * computed (they stop before a group with a non-finite coordinate); params checked, its metric never
 * MINKOWSKI with exponent 1 or 2. */
UDM1_HIDDEN size_t udm1_cellular_fast_f64(const struct udm1_noise *n, const udm1_cellular_params *params, uint32_t dims,
                                          const double *const *axes, size_t stride, size_t count, double *out);
UDM1_HIDDEN size_t udm1_cellular_fast_f32(const struct udm1_noise *n, const udm1_cellular_params *params, uint32_t dims,
                                          const float *const *axes, size_t stride, size_t count, float *out);
/* POV-Ray's crackle search (patterns.c): the three smallest power sums sum |v_i|^e (e = 2: squares) from
 * the finite 3D point c to the feature points of jitter 1, and the nearest feature point (if not NULL). */
UDM1_HIDDEN void udm1_cellular_nearest3(const struct udm1_noise *n, double e, const double c[3], double F[3],
                                        double nearest[3]);

#endif /* UDM1_NOISE_TABLES_H */
