/*
 * udm1/noise.h - lattice gradient noise (Perlin's and from any udm1 sequence), POV-Ray's patterns
 * and colour maps.
 * Part of libudm1's public interface; udm1/udm1.h includes every part.
 */
#ifndef UDM1_NOISE_H
#define UDM1_NOISE_H

#include "udm1/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* Noise and procedural patterns (1.2)                                       */
/* ------------------------------------------------------------------------ */
/*
 * A udm1_noise holds a lattice noise's tables: a permutation of 0..255 and 256
 * unit gradients. Where they come from (desc.table):
 *  NULL or "perlin"  Ken Perlin's reference permutation (Improved Noise, 2002);
 *                    with UDM1_NOISE_IMPROVED, udm1_noise_3d equals his
 *                    reference implementation (noise(3.14, 42, 7) =
 *                    0.13691995878400012). Gradients: his 16 edge directions.
 *  "drand48"         the paper's baseline: srand48(seed), 256 gradients
 *                    (theta = acos(2u - 1), phi = 2 pi v from two drand48()),
 *                    then the swap shuffle p[i] <-> p[floor(256 drand48())], i = 0..255.
 *  any preset name   from that udm1 sequence (seed, default randomization,
 *                    stream 0; point sets with K = 256). Ranking sequence values
 *                    gives an almost arithmetic permutation (three-distance
 *                    theorem) and lattice artifacts, so the values x_k of
 *                    dimension 0 are whitened by the shuffled nested Weyl
 *                    transform of Holian et al. (1994), u_k = {G {(k+1) x_k} + 1/2}
 *                    with G = 2^64/phi, computed in 64-bit integers, and drive a
 *                    Fisher-Yates shuffle (i = 255..1: j = floor((i+1) u_{255-i})).
 *                    Gradients: the sequence's points in dimensions (1, 2) (or
 *                    the whitened values of dimension 0 at indices 256.. for
 *                    sets with fewer dimensions) mapped to the sphere as above.
 * Kinds (desc.kind):
 *  UDM1_NOISE_IMPROVED  Perlin 2002: quintic fade 6t^5 - 15t^4 + 10t^3, the
 *                       gradient of a corner chosen by its hash among 16 edge
 *                       directions; 2D and 1D use the gradient sets of
 *                       Gustavson's noise1234 (+-u +-2v; +-(1..8)x).
 *  UDM1_NOISE_CLASSIC   Perlin 1985 gradient noise: the gradient table, cubic
 *                       fade 3t^2 - 2t^3 (the paper's noise pictures).
 * Periods (desc.period[3], 0 = none): the lattice wraps every period[i] units
 * on that axis, any integer, so a texture covering [0, period) is seamless.
 * Coordinates are doubles and stay correct far from the origin: the lattice
 * cell is found with exact floating-point floor and fmod (no int overflow,
 * |x| up to the largest double); past 2^52 every double is a lattice point
 * and the noise is 0. A NaN or infinite coordinate gives NaN from the scalar
 * functions and UDM1_ERROR_INVALID_ARGUMENT from the batch ones, which check
 * every point before they write and so leave their outputs unchanged.
 * A udm1_noise is immutable and may be shared by threads.
 */
typedef struct udm1_noise udm1_noise;

typedef enum udm1_noise_kind { UDM1_NOISE_IMPROVED = 0, UDM1_NOISE_CLASSIC = 1 } udm1_noise_kind;

typedef struct udm1_noise_desc {
    uint32_t struct_size; /* sizeof(udm1_noise_desc); set by udm1_noise_desc_init; read as udm1_seq_desc's */
    uint32_t kind;        /* udm1_noise_kind */
    const char *table;    /* NULL/"perlin", "drand48" or a preset name */
    uint64_t seed;
    uint32_t period[3];   /* 0: not periodic on that axis */
    uint32_t reserved;    /* set to 0 */
    /* (1.7) */
    uint32_t period_w;    /* the fourth axis' period (4D noise); 0: not periodic */
    uint32_t reserved_w;  /* set to 0 */
} udm1_noise_desc;

UDM1_API void udm1_noise_desc_init(udm1_noise_desc *desc);
/* Errors: NULL_ARGUMENT, INVALID_ARGUMENT (struct_size, kind, reserved, a period
 * above 2^30), UNKNOWN_PRESET (table), OUT_OF_MEMORY. On failure *out is set to
 * NULL (if out is not NULL). */
UDM1_API udm1_status udm1_noise_create(const udm1_noise_desc *desc, udm1_noise **out);
UDM1_API void udm1_noise_destroy(udm1_noise *noise);
/* The permutation (256 entries) and gradients (256 x 3) of a noise, copied out.
 * Either pointer may be NULL. Errors: NULL_ARGUMENT (noise). */
UDM1_API udm1_status udm1_noise_tables(const udm1_noise *noise, uint8_t *perm, double *gradients);

/* Noise values, about in [-1, 1] (not bounded by 1: |n| up to ~1.04). NaN for a NaN or infinite
 * coordinate, and for a NULL noise (with a message; core.h). */
UDM1_API double udm1_noise_1d(const udm1_noise *noise, double x);
UDM1_API double udm1_noise_2d(const udm1_noise *noise, double x, double y);
UDM1_API double udm1_noise_3d(const udm1_noise *noise, double x, double y, double z);

/* (1.7) 4D improved noise: the hash perm[perm[perm[perm[X] + Y] + Z] + W] of each of the cell's 16
 * corners, Perlin's 4D gradient set (the midpoints of the 32 edges of the 4D cube, as his simplex noise
 * reference and Gustavson's noise1234 use them; three components +-1, one 0: u = x (h < 24) or y,
 * v = y (h < 16) or z, w = z (h < 8) or t by h = hash & 31, +-u +-v +-w), the quintic fade, scaled by
 * 0.87 to about [-1, 1]; periodic on the axes with a period (desc.period, desc.period_w): a texture
 * that loops in time over the fourth. Classic noise has no 4D: NaN with INVALID_ARGUMENT. NaN for a
 * non-finite coordinate and a NULL noise, as the others. */
UDM1_API double udm1_noise_4d(const udm1_noise *noise, double x, double y, double z, double w);

/* (1.7) Noise values and their gradients at n points of `dims` (1..4) coordinates, in double or in float:
 * coordinate c of point i is axes[c][i * stride] - packed points: axes = {p, p + 1, p + 2} and stride 3;
 * one array per axis: stride 1. value[i] is the noise (value may be NULL); gradient[i * dims + c] its
 * derivative along axis c (gradient may be NULL; not both): the derivative of the same interpolation,
 * analytic, whose value is value[i] bit for bit.
 *  - double: udm1_noise_1d..4d's values, bit for bit, in every kernel.
 *  - float: float coordinates and float arithmetic, the same operations as the double code, so as
 *    accurate as a float can be: the lattice cell and the offset in it are exact for every finite
 *    float (far from the origin the offset keeps a float's precision, as the double path keeps a
 *    double's), and every kernel (AVX-512 with 16 lanes, AVX2 with 8, the scalar code) gives the same
 *    bits.
 * Errors (value and gradient left unchanged): NULL_ARGUMENT (noise, axes or an axis, value and gradient
 * both), INVALID_ARGUMENT (dims, stride 0, 4D classic noise, a non-finite coordinate: the message names
 * the first such point). */
UDM1_API udm1_status udm1_noise_eval(const udm1_noise *noise, uint32_t dims, const double *const axes[], size_t stride,
                                     size_t n, double *value, double *gradient);
UDM1_API udm1_status udm1_noise_eval_f32(const udm1_noise *noise, uint32_t dims, const float *const axes[],
                                         size_t stride, size_t n, float *value, float *gradient);

/* Noise values at n points of `dims` (1, 2 or 3) coordinates, point i at
 * xyz[i * stride]. Errors (out left unchanged): NULL_ARGUMENT, INVALID_ARGUMENT
 * (dims, stride < dims, a non-finite coordinate: the message names the first
 * such point). */
UDM1_API udm1_status udm1_noise_points(const udm1_noise *noise, uint32_t dims, const double *xyz, size_t n,
                                       size_t stride, double *out);

/* Patterns: a value at a 3D point. UDM1_PATTERN_NOISE, FBM, TURBULENCE and
 * RIDGED are the raw noise sums; the others follow POV-Ray 3.7's definitions
 * over N(P) = clamp((1 + noise_3d(P)) / 2, 0, 1) in the place of POV's Noise
 * (so shapes and ranges match POV-Ray's, not its pixels):
 *  FBM          sum_{i<octaves} omega^i noise(lambda^i P)
 *  TURBULENCE   POV's Turbulence: g1(N(P)) + sum_{i=1}^{octaves-1} omega^i (2 N(lambda^i P) - 1/2),
 *               g1(n) = clamp(2n - 1/2, 0, 1)
 *  RIDGED       sum_{i<octaves} omega^i (1 - |noise(lambda^i P)|)^2
 *  BOZO, BUMPS  N(P) (they differ only in POV's default colour maps)
 *  GRANITE      sum_{i<6} min(|1 - 2 N(4 2^i P)|, 1/2) / 2^i
 *  AGATE        n = (cyc(1.3 agate_turb T(P) + 1.1 z) + 1) / 2, value max(n, 0)^0.77
 *  MARBLE       x + turbulence.x T(P), triangle wave by default
 *  WOOD         |(x + cyc((x + D.x) turbulence.x), y + cyc((y + D.y) turbulence.y))| with
 *               D = DTurbulence(P) (|(x, y)| without turbulence), triangle wave by default
 *  WRINKLES     (sum_{i<10} 0.5^i g1(N(2^i P))) / 2
 *  LEOPARD      ((sin x + sin y + sin z) / 3)^2
 *  ONION        fmod(|P|, 1)
 *  RIPPLES      (1 + mean_i cyc(|P - s_i| frequency + phase)) / 2
 *  WAVES        (2.5 + mean_i cyc(|P - s_i| frequency f_i + phase) / f_i) / 5
 *  CRACKLE      clamp(form . (F1, F2, F3), 0, 1) with Fi = (Fi^m + offset^m)^(1/m) (offset^m: offset
 *               itself for m = 1, as POV-Ray) over udm1's cellular noise (udm1/cellular.h) with jitter 1
 *               and the Minkowski metric of exponent m = crackle_metric (2: Euclidean), its three
 *               nearest feature points found exactly (POV-Ray looks in 81 cells around the point);
 *               solid: clamp(N(q), 0, 1) at the nearest feature point q
 * with cyc(v) = sin(2 pi frac(v)), T = TURBULENCE, DTurbulence the same sum
 * of the vector noise DNoise(P) = (noise(P), noise(P + o1), noise(P + o2)),
 * o1 = (31.416, -47.853, 12.793), o2 = (-101.234, 67.125, -23.478), the 10
 * wave sources s_i = DNoise((i, 0, 0)) normalized, and f_i from POV's wave
 * generator (r <- r 1812433253 + 12345 from r = -560851967, f_i =
 * ((r >> 16) & 0x7FFF) / 32767 + 0.01). A non-zero `turbulence` vector also
 * displaces P by DTurbulence(P) * turbulence before every pattern but marble
 * and wood (POV's turbulence warp). After the pattern, POV's wave shaping:
 * v = fmod(v frequency + phase, 1.00001) (if frequency != 0), wrapped into
 * [0, 1), then the wave function. The POV patterns give values in [0, 1]. */
typedef enum udm1_pattern {
    UDM1_PATTERN_NOISE = 1,
    UDM1_PATTERN_FBM = 2,
    UDM1_PATTERN_TURBULENCE = 3,
    UDM1_PATTERN_RIDGED = 4,
    UDM1_PATTERN_BOZO = 5,
    UDM1_PATTERN_BUMPS = 6,
    UDM1_PATTERN_GRANITE = 7,
    UDM1_PATTERN_AGATE = 8,
    UDM1_PATTERN_MARBLE = 9,
    UDM1_PATTERN_WOOD = 10,
    UDM1_PATTERN_WRINKLES = 11,
    UDM1_PATTERN_LEOPARD = 12,
    UDM1_PATTERN_ONION = 13,
    UDM1_PATTERN_RIPPLES = 14,
    UDM1_PATTERN_WAVES = 15,
    UDM1_PATTERN_CRACKLE = 16 /* (1.7) */
} udm1_pattern;

typedef enum udm1_wave {
    UDM1_WAVE_DEFAULT = 0,  /* triangle for marble and wood, ramp for the others */
    UDM1_WAVE_RAMP = 1,
    UDM1_WAVE_TRIANGLE = 2,
    UDM1_WAVE_SINE = 3,     /* (1 + cyc(v)) / 2 */
    UDM1_WAVE_SCALLOP = 4,  /* |cyc(v / 2)| */
    UDM1_WAVE_CUBIC = 5,    /* 3v^2 - 2v^3 */
    UDM1_WAVE_POLY = 6      /* v^exponent */
} udm1_wave;

typedef struct udm1_pattern_params {
    uint32_t struct_size;  /* set by udm1_pattern_params_init */
    uint32_t pattern;      /* udm1_pattern */
    uint32_t octaves;      /* 1..10; POV default 6 */
    uint32_t wave;         /* udm1_wave */
    double omega;          /* POV default 0.5 */
    double lambda;         /* POV default 2 */
    double turbulence[3];  /* POV's turbulence vector; default 0 */
    double frequency;      /* wave frequency; default 1 (0: no wave shaping) */
    double phase;          /* default 0 */
    double exponent;       /* poly wave; default 1 */
    double agate_turb;     /* default 1 */
    /* (1.7) crackle; a caller of an older layout (a smaller struct_size) gets the defaults */
    double crackle_form[3]; /* the weights of F1, F2, F3; default (-1, 1, 0); all 0: the default */
    double crackle_metric;  /* the Minkowski exponent, 1..64; default 2; 0: 2 */
    double crackle_offset;  /* default 0 */
    uint32_t crackle_solid; /* 1: each cell one value, the noise at its feature point; default 0 */
    uint32_t reserved;      /* set to 0 */
} udm1_pattern_params;

/* POV-Ray's defaults for `pattern`. Does nothing if params is NULL. */
UDM1_API void udm1_pattern_params_init(udm1_pattern_params *params, uint32_t pattern);
/* The name ("marble") of a pattern, NULL if unknown; and the pattern of a name, 0 if unknown. */
UDM1_API const char *udm1_pattern_name(uint32_t pattern);
UDM1_API uint32_t udm1_pattern_from_name(const char *name);
/* The value of a pattern at (x, y, z). NaN for non-finite coordinates, and for a NULL noise or
 * params or a params that udm1_pattern_grid would refuse (with the same message; core.h). */
UDM1_API double udm1_pattern_eval(const udm1_noise *noise, const udm1_pattern_params *params, double x, double y,
                                  double z);
/* Rows [row0, row0 + rows) of a width x height grid into out (row-major, the
 * first given row first): pixel (i, j) is the pattern at
 * origin + (i + 1/2) * step_x + (j + 1/2) * step_y (3-vectors). Rows can be
 * computed by different threads into their own part of an image.
 * Errors (out left unchanged): NULL_ARGUMENT, INVALID_ARGUMENT (sizes 0 or
 * above 65536, rows past height, a bad params field: struct_size, pattern,
 * octaves outside 1..10, non-finite numbers, origin/steps not finite; a pattern
 * that is not a number at some pixel because an octave's scale or sum
 * overflows a double: the message names the pixel), OUT_OF_MEMORY (where a
 * pixel could be NaN - parameters or coordinates near the double range, and
 * every pattern whose bounds are not worked out, POV-Ray's - the rows are
 * computed into a scratch image, copied to out when every pixel is a number). */
UDM1_API udm1_status udm1_pattern_grid(const udm1_noise *noise, const udm1_pattern_params *params, uint32_t width,
                                       uint32_t height, uint32_t row0, uint32_t rows, const double origin[3],
                                       const double step_x[3], const double step_y[3], float *out);
/* The pattern at n points (point i at xyz[i * stride], 3 coordinates).
 * Errors: as udm1_pattern_grid (naming the point; the scratch buffer, where one is needed, holds the n
 * values), and INVALID_ARGUMENT for a non-finite point; out left unchanged. */
UDM1_API udm1_status udm1_pattern_points(const udm1_noise *noise, const udm1_pattern_params *params,
                                         const double *xyz, size_t n, size_t stride, double *out);

/* (1.7) The raw noise patterns (NOISE, FBM, TURBULENCE, RIDGED) and their analytic gradients at n points
 * (point i at xyz[i * stride], 3 coordinates): value[i] (value may be NULL) is udm1_pattern_points' value
 * bit for bit, gradient[3 i + c] its derivative along axis c: each octave's noise gradient (as
 * udm1_noise_eval's) times its scale lambda^i and weight, through the pattern's function (RIDGED:
 * 2 (1 - |n|) sign(n); TURBULENCE: the clamps' slopes, 0 outside (0, 1) and at the kinks).
 * Errors: as udm1_pattern_points (value and gradient left unchanged), and INVALID_ARGUMENT for another
 * pattern (POV-Ray's patterns warp, clamp and wave-shape: no gradient is defined for them here). */
UDM1_API udm1_status udm1_pattern_gradient(const udm1_noise *noise, const udm1_pattern_params *params,
                                           const double *xyz, size_t n, size_t stride, double *value,
                                           double *gradient);

/* Colour maps with POV-Ray's lookup: entries sorted by value; below the first
 * or above the last, their colour; between two, linear interpolation; equal
 * values make a hard edge. */
typedef struct udm1_color_entry {
    double value;
    float rgb[3];
} udm1_color_entry;
/* Errors: NULL_ARGUMENT, INVALID_ARGUMENT (count 0, entries not sorted, a NaN value). */
UDM1_API udm1_status udm1_color_map_eval(const udm1_color_entry *entries, size_t count, double value, float rgb[3]);
/* POV-Ray's default colour map of a pattern (bozo, marble, wood, agate have
 * their own; the others black to white): *entries points to static storage.
 * Errors: NULL_ARGUMENT, INVALID_ARGUMENT (unknown pattern). */
UDM1_API udm1_status udm1_pattern_default_colors(uint32_t pattern, const udm1_color_entry **entries, size_t *count);

#ifdef __cplusplus
}
#endif

#endif /* UDM1_NOISE_H */
