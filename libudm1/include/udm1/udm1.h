/*
 * udm1.h - public C interface of libudm1.
 *
 * libudm1 generates uniformly-distributed-modulo-1 (Weyl/Kronecker) sample
 * sequences for computer graphics, exactly, at any index, behind a stable C ABI.
 *
 * This header compiles as C99 and C++. Everything it declares is prefixed udm1_
 * or UDM1_. Nothing else is exported from the shared library.
 *
 * ---------------------------------------------------------------------------
 * THE SEQUENCE CONTRACT (part of the ABI; it will not change within major 1)
 * ---------------------------------------------------------------------------
 * A sequence has D dimensions. Point n (the "index") of stream s has
 * coordinates
 *
 *     x[n][j] = { o_j + r_j(seed, s) + n * alpha_j }        0 <= j < D
 *
 * where {.} is the fractional part, alpha_j the dimension's generator, o_j the
 * base offset of the descriptor (0 unless given) and r_j the per-stream random
 * shift (0 when randomization is UDM1_RANDOMIZE_NONE).
 *
 *  - Indices start at 0, and point 0 equals the offset:  x[0][j] = {o_j + r_j}.
 *    Unrandomized presets have o_j = 0, so their point 0 is the origin. (The
 *    paper counts n = 1, 2, ...; pass first = 1 to reproduce its points.)
 *  - Every index 0 <= n < 2^64 is valid for a sequence. A point set (EPIS,
 *    EPISWR) has a fixed number of points K and valid indices 0 <= n < K.
 *  - Arithmetic is integer. alpha_j is held as its fractional part in 0.128
 *    fixed point, A_j = round(frac(alpha_j) * 2^128). The raw value is the top
 *    64 bits of (O_j * 2^64 + n * A_j) mod 2^128, with O_j = (o_j + r_j) in 0.64
 *    fixed point. Its error against the real number {o_j + r_j + n alpha_j} is
 *    below 2^-63 for every n < 2^64 (2^-64 from truncation, n * 2^-129 from A_j).
 *  - Conversions: u64 is that raw 0.64 value; double is (u64 >> 11) * 2^-53;
 *    float is (u64 >> 40) * 2^-24. Both lie in [0, 1) and are never 1.0.
 *  - The same inputs give bit-identical outputs everywhere: per-sample and bulk
 *    calls, any split of an index range, any thread, any run.
 *
 * Randomization (UDM1_RANDOMIZE_DEFAULT for the Weyl presets = SHIFT, the paper's "unique random start for
 * each pixel"): a Cranley-Patterson rotation done in integers. The 64-bit shift
 * r_j is a counter-based hash of (seed, stream, j): no state per pixel, any
 * pixel's points can be computed in any order on any thread. Use one stream id
 * per pixel (for example ((uint64_t)y << 32) | x) or per independent estimate.
 *
 * Thread safety: a udm1_seq is immutable after creation. Every function that
 * takes a `const udm1_seq *` may be called from any number of threads at once
 * on the same handle. udm1_seq_destroy must not race with other uses of that
 * handle. A udm1_cursor belongs to one thread at a time.
 *
 * Errors: functions that can fail return a udm1_status. On failure nothing is
 * written to the caller's output, and udm1_last_error() returns a one-line
 * message, on the calling thread, naming the function and the bad input.
 */
#ifndef UDM1_UDM1_H
#define UDM1_UDM1_H

#include <stddef.h>
#include <stdint.h>

#define UDM1_VERSION_MAJOR 1
#define UDM1_VERSION_MINOR 5
#define UDM1_VERSION_PATCH 1
/* MAJOR * 10000 + MINOR * 100 + PATCH, as returned by udm1_version(). */
#define UDM1_VERSION (UDM1_VERSION_MAJOR * 10000 + UDM1_VERSION_MINOR * 100 + UDM1_VERSION_PATCH)

/* The most dimensions a sequence may have (WR: square roots of the first
 * 65536 primes; R_d: d up to this). Presets with a fixed list have fewer. */
#define UDM1_MAX_DIMENSIONS 65536u

/* The largest point count K of a point set: 2^32 - 1 (pmj02: 2^20). */
#define UDM1_MAX_POINT_COUNT 4294967295u

/* Dimensions of the Sobol presets: the Joe-Kuo new-joe-kuo-6.21201 set. */
#define UDM1_SOBOL_MAX_DIMENSIONS 21201u

#if defined(UDM1_STATIC_DEFINE)
#  define UDM1_API
#elif defined(_WIN32)
#  if defined(UDM1_BUILDING)
#    define UDM1_API __declspec(dllexport)
#  else
#    define UDM1_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__) && defined(UDM1_BUILDING)
#  define UDM1_API __attribute__((visibility("default")))
#else
#  define UDM1_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* Status codes and version                                                  */
/* ------------------------------------------------------------------------ */

typedef enum udm1_status {
    UDM1_OK = 0,
    UDM1_ERROR_NULL_ARGUMENT = 1,    /* a required pointer argument was NULL */
    UDM1_ERROR_INVALID_ARGUMENT = 2, /* a value outside its documented range */
    UDM1_ERROR_DIMENSION = 3,        /* 0 dimensions, too many, or a dimension index out of range */
    UDM1_ERROR_UNKNOWN_PRESET = 4,   /* no preset has that name */
    UDM1_ERROR_RATIONAL_ALPHA = 5,   /* a generator is rational (e.g. sqrt of a perfect square) */
    UDM1_ERROR_POINT_COUNT = 6,      /* a point set without a valid point count K, or K given to a sequence */
    UDM1_ERROR_INDEX_RANGE = 7,      /* index past the point count, or first + count past 2^64 */
    UDM1_ERROR_OUT_OF_MEMORY = 8
} udm1_status;

/* Version of the library actually loaded: UDM1_VERSION of its build. */
UDM1_API uint32_t udm1_version(void);
/* "1.0.0". Static storage; never NULL. */
UDM1_API const char *udm1_version_string(void);
/* A short fixed English text for a status ("invalid argument"). Static
 * storage; never NULL, also for unknown codes. */
UDM1_API const char *udm1_status_string(udm1_status status);
/* The one-line message of the last failing udm1 call on this thread, such as
 * "udm1_seq_create: unknown preset 'wrr'". Empty if none failed yet.
 * Valid until the next failing udm1 call on this thread. */
UDM1_API const char *udm1_last_error(void);

/* ------------------------------------------------------------------------ */
/* Presets                                                                   */
/* ------------------------------------------------------------------------ */
/*
 * The paper's Weyl/Kronecker sets (x_n = {s + n alpha}, exact in integers):
 * name      generators alpha_j (paper section)                     dimensions
 * wr        sqrt of the primes 2, 3, 5, 7, 11, ... (5.1, Richtmyer)  1..65536
 * wr-ao     sqrt2, sqrt13: the paper's AO pair WR (4.2.1)            1..2
 * we        e, e^2 (4.2.1)                                           1..2
 * wgr       (1+sqrt5)/2, (1+sqrt3)/2 (4.2.1)                         1..2
 * wmmr      the 22 square roots of section 5.1, in its order         1..22
 * hwmmr     the 22 values of section 5.1, in its order               1..22
 * rd        R_d: phi_d^-1, ..., phi_d^-D with phi_d the real root    1..65536
 *           of x^(D+1) = x + 1 (Roberts 2018). The set depends on D.
 * golden    the golden ratio (1+sqrt5)/2: 1D Weyl sequence (= R_1)   1
 * epis      EPIS point set x_n = {n/K + u} (4.2.2); needs K          1
 * episwr    EPISWR = (EPIS, Weyl sqrt137) (4.2.2); needs K           1..2
 * Their default randomization is the random shift (UDM1_RANDOMIZE_SHIFT).
 *
 * The baselines the paper compares with, and today's production samplers:
 * name        what                                      default randomization   dims
 * pcg32       PCG32 XSH-RR (O'Neill), value (n, j) is   a stream per stream id  1..65536
 *             output number n*D + j of the stream; 32 random bits per value
 * drand48     the C library's drand48, same layout;     a stream per stream id  1..65536
 *             with UDM1_RANDOMIZE_NONE and stream 0 it is bit-identical to
 *             srand48(seed) then drand48(), drand48(), ...
 * halton      radical inverse of n in base p_j (the     random digit            1..65536
 *             j-th prime), exact                        permutations (PERMUTE)
 * halton-owen the same                                  Owen scrambling (OWEN)  1..65536
 * sobol       Sobol, Joe-Kuo new-joe-kuo-6.21201        random digital shift    1..21201
 *             direction numbers, 64-bit; point n is     (PERMUTE: XOR)
 *             that of scipy's Sobol (Gray-code order): with UDM1_RANDOMIZE_NONE
 *             its doubles equal scipy.stats.qmc.Sobol(d, scramble=False, bits=53)
 * sobol-owen  the same                                  Owen scrambling by      1..21201
 *                                                       hashing (Burley 2020)
 * hammersley  (n/K, radical inverses in bases 2, 3,     random digital shift    1..65536
 *             5, ...); needs K
 * lp          Larcher-Pillichshammer (n/K, LP(n));      random digital shift    pairs
 *             needs K
 * cmj         correlated multi-jittered (Kensler        a pattern per stream    pairs
 *             2013); needs K
 * grps        golden ratio point set (Schretter,        a pattern per stream    pairs
 *             Kobbelt, Dehaye 2012); needs K
 * pmj02       progressive multi-jittered (0,2)          random digital shift    pairs, 1..64
 *             (Christensen et al. 2018, Pharr 2019);    (keeps the (0,2)
 *             tables built at creation; K <= 2^20       stratification)
 *
 *
 * Beyond the paper (version 1.4):
 * wopt        64 square roots of primes chosen by a    random shift            1..64
 *             greedy search (tools/alpha_search.py) so that the worst 2D
 *             projection stays near random-shift quality for N = 32..4096;
 *             at d = 32 and 64 its worst pair is 2-4x better than wr's and rd's
 * lattice     rank-1 lattice {n z / K}, z built         random shift            1..64
 *             component by component on the exact wrap-around L2 discrepancy;
 *             needs K (1..2^24); with "+tent" (below) error ~ K^-2 on smooth
 *             integrands
 *
 * Transform (1.4): "NAME+tent" is any preset NAME with the tent (baker's) transform
 * x -> 1 - |2x - 1| applied to every value, exactly in the 0.64 fixed point (2x below 1/2,
 * 2 - 2x above). It periodizes smooth integrands: the randomly shifted Weyl sets then
 * integrate smooth non-periodic functions with a smaller error (see README, "Beyond the
 * paper"). udm1_seq_name returns "NAME+tent"; udm1_preset_find("NAME+tent") gives NAME's info.
 *
 * "pairs" (UDM1_PRESET_PAIRS): a 2D construction. Dimensions 2k and 2k+1 form
 * pair k; every pair is its own pattern (keyed by the seed and k) and pairs
 * k >= 1 visit the points in their own order (a hashed permutation of the K
 * indices), so pairs are decorrelated. An odd D uses the first coordinate of
 * the last pair. Halton's and Sobol's digit structure reaches 2^64 indices;
 * Owen scrambling covers the top 32 digits and fills the rest uniformly.
 * Preset names are matched exactly (lower case).
 */

/* Preset flag: the preset is a point set and needs a point count K >= 1. */
#define UDM1_PRESET_POINT_SET 1u
/* Preset flag: a 2D construction used in pairs of dimensions (see above). */
#define UDM1_PRESET_PAIRS 2u

typedef struct udm1_preset_info {
    const char *name;         /* static storage */
    const char *description;  /* static storage, one line */
    uint32_t max_dimensions;  /* dimensions accepted: 1..max_dimensions */
    uint32_t flags;           /* UDM1_PRESET_* */
} udm1_preset_info;

/* Number of presets. */
UDM1_API size_t udm1_preset_count(void);
/* Information on preset i, 0 <= i < udm1_preset_count().
 * Errors: NULL_ARGUMENT (info), INVALID_ARGUMENT (i out of range). */
UDM1_API udm1_status udm1_preset_get(size_t i, udm1_preset_info *info);
/* Information on the preset called name. Errors: NULL_ARGUMENT, UNKNOWN_PRESET. */
UDM1_API udm1_status udm1_preset_find(const char *name, udm1_preset_info *info);

/* ------------------------------------------------------------------------ */
/* Creating sequences                                                        */
/* ------------------------------------------------------------------------ */

typedef struct udm1_seq udm1_seq;

typedef enum udm1_randomize {
    UDM1_RANDOMIZE_NONE = 0,    /* the deterministic sequence; every stream gives the same points */
    UDM1_RANDOMIZE_DEFAULT = 1, /* the preset's own randomization (see the preset table) */
    UDM1_RANDOMIZE_SHIFT = 2,   /* random shift r_j = hash(seed, stream, j), added modulo 1 */
    UDM1_RANDOMIZE_PERMUTE = 3, /* random digital shift: base 2, XOR with r_j; base b (Halton,
                                   Hammersley), a random permutation of the digits at each position */
    UDM1_RANDOMIZE_OWEN = 4,    /* nested uniform (Owen) scrambling by hashing, keyed by r_j */
    UDM1_RANDOMIZE_SCREEN = 5   /* Weyl sequences (1.4): screen-space decorrelation (Z-order). With
                                   stream = ((uint64_t)y << 32) | x for pixel (x, y) and N =
                                   desc.screen_spp, point n of the pixel is point m*N + n (mod 2^64)
                                   of one sequence shifted by u_j(seed), m the pixel's Morton index:
                                   neighbouring pixels hold consecutive segments of one low-
                                   discrepancy sequence, so their errors cancel locally and the error
                                   image is blue noise; each pixel stays unbiased over seeds */
} udm1_randomize;

typedef enum udm1_alpha_kind {
    UDM1_ALPHA_SQRT = 1,     /* alpha = sqrt(k) for an integer k >= 2 that is not a perfect
                                square; computed exactly by integer square root */
    UDM1_ALPHA_FIXED = 2,    /* frac(alpha) = (fixed_hi * 2^64 + fixed_lo) / 2^128, taken as is */
    UDM1_ALPHA_DOUBLE = 3    /* frac(alpha) of a finite double. Only its 53 bits are good: the
                                sequence drifts from the real number you meant by about
                                n * 2^-53; prefer SQRT or FIXED */
} udm1_alpha_kind;

/* One user generator. Unused fields are ignored. */
typedef struct udm1_alpha {
    uint32_t kind;      /* udm1_alpha_kind */
    uint32_t reserved;  /* set to 0 */
    uint64_t k;         /* UDM1_ALPHA_SQRT */
    uint64_t fixed_hi;  /* UDM1_ALPHA_FIXED */
    uint64_t fixed_lo;  /* UDM1_ALPHA_FIXED */
    double value;       /* UDM1_ALPHA_DOUBLE */
} udm1_alpha;

/* Full description of a sequence. Always start from udm1_seq_desc_init(). */
typedef struct udm1_seq_desc {
    uint32_t struct_size;      /* sizeof(udm1_seq_desc); set by udm1_seq_desc_init */
    uint32_t dimensions;       /* D >= 1 */
    const char *preset;        /* a preset name, or NULL to use `alphas` */
    const udm1_alpha *alphas;  /* D generators when preset is NULL */
    const uint64_t *offsets;   /* optional: D base offsets o_j in 0.64 fixed point; NULL = 0 */
    uint64_t point_count;      /* K for a point-set preset (1..UDM1_MAX_POINT_COUNT); else 0 */
    uint64_t seed;             /* key of the random shifts */
    uint32_t randomize;        /* udm1_randomize; PRNGs and "pattern" presets (cmj, grps) take an
                                  independent stream per stream id unless NONE, and then
                                  apply SHIFT/PERMUTE/OWEN on top if asked */
    uint32_t screen_spp;       /* UDM1_RANDOMIZE_SCREEN only: the samples per pixel N (1.4; the field
                                  was `reserved`, 0, before); else 0 */
} udm1_seq_desc;

/* Fill desc with defaults: struct_size set, dimensions 0, preset NULL,
 * alphas NULL, offsets NULL, point_count 0, seed 0, UDM1_RANDOMIZE_DEFAULT.
 * Does nothing if desc is NULL. */
UDM1_API void udm1_seq_desc_init(udm1_seq_desc *desc);

/* Create a sequence from a descriptor. On success *out holds a new handle to
 * release with udm1_seq_destroy; on failure *out is set to NULL (if out is not
 * NULL). Errors: NULL_ARGUMENT, INVALID_ARGUMENT (struct_size, randomize or a
 * reserved field, an unknown alpha kind, a non-finite double), DIMENSION
 * (0 or more than the preset's or library's maximum), UNKNOWN_PRESET,
 * RATIONAL_ALPHA (sqrt of a perfect square, k < 2), POINT_COUNT (K missing or
 * out of range for a point set, or K != 0 for a sequence), OUT_OF_MEMORY. */
UDM1_API udm1_status udm1_seq_create_desc(const udm1_seq_desc *desc, udm1_seq **out);

/* Shorthand: a preset with D dimensions, point count K (0 for sequences) and
 * its default per-stream randomization keyed by seed (UDM1_RANDOMIZE_DEFAULT).
 * For an unrandomized sequence use udm1_seq_create_desc. Errors as above. */
UDM1_API udm1_status udm1_seq_create(const char *preset, uint32_t dimensions,
                                     uint64_t point_count, uint64_t seed, udm1_seq **out);

/* Release a sequence. NULL is accepted and ignored. */
UDM1_API void udm1_seq_destroy(udm1_seq *seq);

/* ------------------------------------------------------------------------ */
/* Queries (0 or NULL for a NULL handle)                                     */
/* ------------------------------------------------------------------------ */

UDM1_API uint32_t udm1_seq_dimensions(const udm1_seq *seq);
/* The preset name, or "custom" for a sequence made from alphas. */
UDM1_API const char *udm1_seq_name(const udm1_seq *seq);
/* K for a point set; 0 for a sequence (all 2^64 indices valid). */
UDM1_API uint64_t udm1_seq_point_count(const udm1_seq *seq);
UDM1_API uint64_t udm1_seq_seed(const udm1_seq *seq);
/* The randomization asked for (desc.randomize). */
UDM1_API uint32_t udm1_seq_randomize(const udm1_seq *seq);
/* The randomization applied: UDM1_RANDOMIZE_NONE, SHIFT, PERMUTE or OWEN, with
 * DEFAULT resolved; DEFAULT itself for a PRNG's or pattern's plain streams. (1.1) */
UDM1_API uint32_t udm1_seq_randomization(const udm1_seq *seq);
/* Preset flags (UDM1_PRESET_*) of the sequence; 0 for "custom". (1.1) */
UDM1_API uint32_t udm1_seq_flags(const udm1_seq *seq);
/* The generator of dimension dim as its 0.128 fixed-point fraction A_j.
 * Errors: NULL_ARGUMENT, DIMENSION, INVALID_ARGUMENT (not a Weyl sequence). */
UDM1_API udm1_status udm1_seq_alpha(const udm1_seq *seq, uint32_t dim, uint64_t *hi, uint64_t *lo);
/* The base offset plus the dimension's random word, O_j = o_j + r_j(seed, stream)
 * (r_j = 0 without randomization), in 0.64 fixed point. For a Weyl sequence
 * with no randomization or a shift it is the raw value of point 0.
 * Errors: NULL_ARGUMENT, DIMENSION. */
UDM1_API udm1_status udm1_seq_offset(const udm1_seq *seq, uint64_t stream, uint32_t dim, uint64_t *offset);

/* ------------------------------------------------------------------------ */
/* Random access: one value                                                  */
/* ------------------------------------------------------------------------ */
/* Value of (stream, index, dim). Errors: NULL_ARGUMENT, DIMENSION
 * (dim >= D), INDEX_RANGE (index >= K for a point set). */
UDM1_API udm1_status udm1_seq_sample_u64(const udm1_seq *seq, uint64_t stream, uint64_t index,
                                         uint32_t dim, uint64_t *out);
UDM1_API udm1_status udm1_seq_sample_f64(const udm1_seq *seq, uint64_t stream, uint64_t index,
                                         uint32_t dim, double *out);
UDM1_API udm1_status udm1_seq_sample_f32(const udm1_seq *seq, uint64_t stream, uint64_t index,
                                         uint32_t dim, float *out);

/* ------------------------------------------------------------------------ */
/* Bulk fill                                                                 */
/* ------------------------------------------------------------------------ */
/* Write indices [first, first + count) by dimensions [dim0, dim0 + ndims) of
 * one stream: value (first + i, dim0 + j) goes to out[i * stride + j].
 * stride >= ndims (elements, not bytes). count == 0 writes nothing and
 * succeeds (after the other checks). Errors: NULL_ARGUMENT (seq, or out
 * when count > 0), DIMENSION (ndims == 0 or dim0 + ndims > D),
 * INVALID_ARGUMENT (stride < ndims, or count * stride overflows size_t),
 * INDEX_RANGE (first + count > 2^64, or > K for a point set).
 * The result equals the per-sample calls bit for bit. */
UDM1_API udm1_status udm1_seq_fill_u64(const udm1_seq *seq, uint64_t stream, uint64_t first, size_t count,
                                       uint32_t dim0, uint32_t ndims, uint64_t *out, size_t stride);
UDM1_API udm1_status udm1_seq_fill_f64(const udm1_seq *seq, uint64_t stream, uint64_t first, size_t count,
                                       uint32_t dim0, uint32_t ndims, double *out, size_t stride);
UDM1_API udm1_status udm1_seq_fill_f32(const udm1_seq *seq, uint64_t stream, uint64_t first, size_t count,
                                       uint32_t dim0, uint32_t ndims, float *out, size_t stride);

/* ------------------------------------------------------------------------ */
/* Renderer cursor: pbrt-v4 Sampler shape (StartPixelSample, Get1D, Get2D)   */
/* ------------------------------------------------------------------------ */
/*
 * For one (stream, index) the cursor hands out dimensions in order, starting
 * at first_dimension: each 1D draw takes the next dimension, each 2D draw the
 * next two. It is a small caller-owned struct: no allocation, no cleanup.
 *
 *   udm1_cursor c;
 *   udm1_cursor_start(&c, seq, pixel_id, sample_index, 0);
 *   float lens[2];  udm1_cursor_2d(&c, lens);      // dimensions 0, 1
 *   float u = udm1_cursor_1d(&c);                  // dimension 2
 *
 * Draws past the sequence's dimension count D (padding rule, fixed by the
 * ABI): dimension j >= D returns an independent uniform value, a counter-based
 * hash of (seed, stream, index, j) converted like the sequence's values, so a
 * path may be longer than the set without reusing its dimensions. Such draws
 * are random, not low-discrepancy; choose D to cover the dimensions that
 * matter. udm1_cursor_padded() tells how many draws were padded.
 */
typedef struct udm1_cursor {
    const udm1_seq *seq;
    uint64_t stream;
    uint64_t index;
    uint64_t key;        /* private: derived from the seed and the stream */
    uint32_t dimension;  /* next dimension to hand out */
    uint32_t padded;     /* number of values drawn past D so far */
} udm1_cursor;

/* Start a cursor at (stream, index), next dimension first_dimension.
 * Errors: NULL_ARGUMENT, INDEX_RANGE (index >= K for a point set).
 * On error the cursor is left unchanged. */
UDM1_API udm1_status udm1_cursor_start(udm1_cursor *cursor, const udm1_seq *seq, uint64_t stream,
                                       uint64_t index, uint32_t first_dimension);
/* Next dimension as a float in [0, 1). The cursor must have been started. */
UDM1_API float udm1_cursor_1d(udm1_cursor *cursor);
/* Next two dimensions into out[0], out[1]. */
UDM1_API void udm1_cursor_2d(udm1_cursor *cursor, float out[2]);
/* Double-precision variants of the two draws above. */
UDM1_API double udm1_cursor_1d_f64(udm1_cursor *cursor);
UDM1_API void udm1_cursor_2d_f64(udm1_cursor *cursor, double out[2]);
/* The next n dimensions into out[0..n-1]: equal, bit for bit, to n successive
 * 1D draws, but one sequential evaluation (one seek for the PRNGs). Since 1.3. */
UDM1_API void udm1_cursor_fill(udm1_cursor *cursor, uint32_t n, float *out);
UDM1_API void udm1_cursor_fill_f64(udm1_cursor *cursor, uint32_t n, double *out);
/* Number of draws so far that fell past the sequence's dimension count. */
UDM1_API uint32_t udm1_cursor_padded(const udm1_cursor *cursor);

/* Many points at once, for renderers that trace many paths together (a wavefront): point k is
 * (streams[k], indices[k]); its dimensions [first_dimension, first_dimension + n_dims) go to
 * out[k * n_dims + j] as doubles in [0, 1). Equal, bit for bit, to a cursor started at
 * (streams[k], indices[k], first_dimension) and filled with n_dims values (padding included).
 * Consecutive points of one stream share its per-stream randomization: keep them together
 * (sorted by stream) and a Weyl sequence's shifts are computed once per stream, not per point.
 * Errors: NULL arguments with n > 0, an index outside a point set (naming k). Since 1.5. */
UDM1_API udm1_status udm1_seq_fill_points_f64(const udm1_seq *seq, size_t n, const uint64_t *streams,
                                              const uint64_t *indices, uint32_t first_dimension,
                                              uint32_t n_dims, double *out);

/* ------------------------------------------------------------------------ */
/* Quality metrics                                                           */
/* ------------------------------------------------------------------------ */

typedef enum udm1_discrepancy_kind {
    UDM1_DISCREPANCY_L2_STAR = 1,      /* L2-star, square-rooted (as scipy.stats.qmc) */
    UDM1_DISCREPANCY_CENTERED = 2,     /* centered L2, squared (as scipy "CD") */
    UDM1_DISCREPANCY_WRAP_AROUND = 3,  /* wrap-around L2, squared (as scipy "WD") */
    UDM1_DISCREPANCY_MIXTURE = 4       /* mixture L2, squared (as scipy "MD") */
} udm1_discrepancy_kind;

/* Discrepancy of n points in [0,1]^d, point i at points[i * stride + j].
 * The definitions and normalisations are those of scipy.stats.qmc.discrepancy.
 * O(n^2 d) time, no allocation. Errors: NULL_ARGUMENT, INVALID_ARGUMENT (n == 0,
 * d == 0, stride < d, unknown kind, a coordinate outside [0,1] or NaN). */
UDM1_API udm1_status udm1_discrepancy(const double *points, size_t n, uint32_t d, size_t stride,
                                      uint32_t kind, double *out);

/* The discrepancy of n independent uniform points in d dimensions, the
 * "random" line: E[D^2] for the squared kinds, sqrt(E[D^2]) for L2-star.
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
 * it, stride < d). (1.1) */
UDM1_API udm1_status udm1_integrand_eval(uint32_t integrand, uint32_t d, const double *points, size_t n,
                                         size_t stride, double *out);
/* Its exact integral over [0,1]^d. Errors: INVALID_ARGUMENT, NULL_ARGUMENT. (1.1) */
UDM1_API udm1_status udm1_integrand_exact(uint32_t integrand, uint32_t d, double *out);

/* Integration error of a sampler: for streams r = 0..R-1 the estimate is the
 * mean of the integrand over points [0, n) of stream r, dimensions [0, d);
 * rmse = sqrt(mean over r of (estimate - exact)^2), bias = the mean error.
 * A point set uses its first n points (give it K = n). Errors: NULL_ARGUMENT
 * (seq, rmse), DIMENSION (d > D), INVALID_ARGUMENT (n or R 0, integrand/d),
 * INDEX_RANGE (n > K). bias may be NULL. (1.1) */
UDM1_API udm1_status udm1_integration_error(const udm1_seq *seq, uint32_t integrand, uint32_t d, uint64_t n,
                                            uint32_t randomizations, double *rmse, double *bias);

/* Power spectrum of points [0, n) of dimensions (dim0, dim0+1): the periodogram
 * P(k) = |sum_j exp(-2 pi i k . x_j)|^2 / n averaged over streams 0..R-1, at
 * the integer frequencies k in [-size/2, size/2)^2, written row by row with
 * k = (0, 0) at (size/2, size/2). Random points give P ~ 1. O(R n size^2).
 * Errors: NULL_ARGUMENT, DIMENSION, INVALID_ARGUMENT (n or R 0, size 0, odd or
 * above 1024), INDEX_RANGE. (1.1) */
UDM1_API udm1_status udm1_spectrum_2d(const udm1_seq *seq, uint32_t dim0, uint64_t n, uint32_t randomizations,
                                      uint32_t size, double *out);

/* Zone plate test: a width x height image of the pixel averages of
 * z(x, y) = (1 + cos(pi (x^2 + y^2) / width)) / 2 (x, y in pixels from the
 * top-left corner, so the frequency reaches 1 cycle per pixel, twice Nyquist,
 * at distance `width`), each pixel estimated with spp points of stream
 * ((uint64_t)y << 32 | x), dimensions (dim0, dim0+1) as the offset in the
 * pixel. Aliasing shows as false rings. Errors: NULL_ARGUMENT, DIMENSION,
 * INVALID_ARGUMENT (0 or above 16384 sizes, spp 0), INDEX_RANGE. (1.1) */
UDM1_API udm1_status udm1_zoneplate(const udm1_seq *seq, uint32_t dim0, uint32_t width, uint32_t height,
                                    uint32_t spp, float *out);

/* ------------------------------------------------------------------------ */
/* Constant-set check                                                        */
/* ------------------------------------------------------------------------ */
/*
 * Reports whether a set of generators can make a good sequence:
 *  - rational: a generator is rational (sqrt of a perfect square, a zero
 *    fixed-point fraction);
 *  - dependent: two generators are rationally dependent together with 1. For
 *    quadratic irrationals (a + b sqrt(m)) this is decided exactly: same
 *    square-free part m. Otherwise a pair is reported when an integer relation
 *    l1 a1 + l2 a2 = 0 mod 1 with |l1|, |l2| <= 16 holds to 2^-40 (numerically
 *    dependent, e.g. repeated values); skipped, and said in the message, when
 *    (generators of unknown nature) x D exceeds 2^20;
 *  - the worst 2D projection: over all pairs of dimensions, the one whose first
 *    n unrandomized points (indices 0..n-1) have the largest L2-star
 *    discrepancy, with its wrap-around discrepancy, beside the expectation for
 *    n random points. (The paper's pair (sqrt487, sqrt237173) is no better than
 *    random at n = 256.) With D == 1 the "projection" is the 1D set itself,
 *    worst_dims is {0, 0} and the random values are those of d = 1.
 *    Cost O(D^2 n^2): refused (INVALID_ARGUMENT) above D(D-1)/2 * (n^2/2 + 256)
 *    = 2^36 kernel evaluations (about a minute).
 */
typedef struct udm1_alpha_report {
    uint32_t rational;           /* 1 if some generator is rational */
    uint32_t rational_dim;       /* the first such dimension */
    uint32_t dependent;          /* 1 if some pair is rationally dependent */
    uint32_t dependent_exact;    /* 1 if that was decided exactly (quadratic irrationals) */
    uint32_t dependent_dims[2];  /* the first such pair */
    uint32_t worst_dims[2];      /* worst 2D projection (both 0 when D == 1) */
    double worst_l2_star;        /* its L2-star discrepancy */
    double worst_wrap_around;    /* its wrap-around discrepancy (squared, as scipy) */
    double random_l2_star;       /* expected L2-star of n random points: sqrt(5 / (36 n)) */
    double random_wrap_around;   /* expected wrap-around of n random points: 17 / (36 n) */
    char message[256];           /* one-line summary */
} udm1_alpha_report;

/* Check the generators of a Weyl sequence at n points (2 <= n <= 65536).
 * Errors: NULL_ARGUMENT, INVALID_ARGUMENT (n, work limit, not a Weyl
 * sequence), OUT_OF_MEMORY. */
UDM1_API udm1_status udm1_seq_check(const udm1_seq *seq, uint64_t n, udm1_alpha_report *report);
/* Check user generators before creating a sequence; unlike creation, a
 * rational generator is reported, not refused. Errors: NULL_ARGUMENT,
 * INVALID_ARGUMENT (n, count 0 or above UDM1_MAX_DIMENSIONS, a bad alpha). */
UDM1_API udm1_status udm1_alpha_check(const udm1_alpha *alphas, uint32_t count, uint64_t n,
                                      udm1_alpha_report *report);

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
 * functions and UDM1_ERROR_INVALID_ARGUMENT from the batch ones.
 * A udm1_noise is immutable and may be shared by threads.
 */
typedef struct udm1_noise udm1_noise;

typedef enum udm1_noise_kind { UDM1_NOISE_IMPROVED = 0, UDM1_NOISE_CLASSIC = 1 } udm1_noise_kind;

typedef struct udm1_noise_desc {
    uint32_t struct_size; /* sizeof(udm1_noise_desc); set by udm1_noise_desc_init */
    uint32_t kind;        /* udm1_noise_kind */
    const char *table;    /* NULL/"perlin", "drand48" or a preset name */
    uint64_t seed;
    uint32_t period[3];   /* 0: not periodic on that axis */
    uint32_t reserved;    /* set to 0 */
} udm1_noise_desc;

UDM1_API void udm1_noise_desc_init(udm1_noise_desc *desc);
/* Errors: NULL_ARGUMENT, INVALID_ARGUMENT (struct_size, kind, reserved, a period
 * above 2^30), UNKNOWN_PRESET (table), OUT_OF_MEMORY. */
UDM1_API udm1_status udm1_noise_create(const udm1_noise_desc *desc, udm1_noise **out);
UDM1_API void udm1_noise_destroy(udm1_noise *noise);
/* The permutation (256 entries) and gradients (256 x 3) of a noise, copied out.
 * Either pointer may be NULL. Errors: NULL_ARGUMENT (noise). */
UDM1_API udm1_status udm1_noise_tables(const udm1_noise *noise, uint8_t *perm, double *gradients);

/* Noise values, about in [-1, 1] (not bounded by 1: |n| up to ~1.04). */
UDM1_API double udm1_noise_1d(const udm1_noise *noise, double x);
UDM1_API double udm1_noise_2d(const udm1_noise *noise, double x, double y);
UDM1_API double udm1_noise_3d(const udm1_noise *noise, double x, double y, double z);

/* Noise values at n points of `dims` (1, 2 or 3) coordinates, point i at
 * xyz[i * stride]. Errors: NULL_ARGUMENT, INVALID_ARGUMENT (dims, stride < dims,
 * a non-finite coordinate: the message names the point; out's values are then
 * unspecified). */
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
    UDM1_PATTERN_WAVES = 15
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
} udm1_pattern_params;

/* POV-Ray's defaults for `pattern`. Does nothing if params is NULL. */
UDM1_API void udm1_pattern_params_init(udm1_pattern_params *params, uint32_t pattern);
/* The name ("marble") of a pattern, NULL if unknown; and the pattern of a name, 0 if unknown. */
UDM1_API const char *udm1_pattern_name(uint32_t pattern);
UDM1_API uint32_t udm1_pattern_from_name(const char *name);
/* The value of a pattern at (x, y, z). params is not checked here (see
 * udm1_pattern_grid); non-finite coordinates give NaN. */
UDM1_API double udm1_pattern_eval(const udm1_noise *noise, const udm1_pattern_params *params, double x, double y,
                                  double z);
/* Rows [row0, row0 + rows) of a width x height grid into out (row-major, the
 * first given row first): pixel (i, j) is the pattern at
 * origin + (i + 1/2) * step_x + (j + 1/2) * step_y (3-vectors). Rows can be
 * computed by different threads into their own part of an image.
 * Errors: NULL_ARGUMENT, INVALID_ARGUMENT (sizes 0 or above 65536, rows past
 * height, a bad params field: struct_size, pattern, octaves outside 1..10,
 * non-finite numbers, origin/steps not finite). */
UDM1_API udm1_status udm1_pattern_grid(const udm1_noise *noise, const udm1_pattern_params *params, uint32_t width,
                                       uint32_t height, uint32_t row0, uint32_t rows, const double origin[3],
                                       const double step_x[3], const double step_y[3], float *out);
/* The pattern at n points (point i at xyz[i * stride], 3 coordinates).
 * Errors: as udm1_pattern_grid, and INVALID_ARGUMENT for a non-finite point. */
UDM1_API udm1_status udm1_pattern_points(const udm1_noise *noise, const udm1_pattern_params *params,
                                         const double *xyz, size_t n, size_t stride, double *out);

/* Colour maps with POV-Ray's lookup: entries sorted by value; below the first
 * or above the last, their colour; between two, linear interpolation; equal
 * values make a hard edge. */
typedef struct udm1_color_entry {
    double value;
    float rgb[3];
} udm1_color_entry;
/* Errors: NULL_ARGUMENT, INVALID_ARGUMENT (count 0, entries not sorted). */
UDM1_API udm1_status udm1_color_map_eval(const udm1_color_entry *entries, size_t count, double value, float rgb[3]);
/* POV-Ray's default colour map of a pattern (bozo, marble, wood, agate have
 * their own; the others black to white): *entries points to static storage.
 * Errors: NULL_ARGUMENT, INVALID_ARGUMENT (unknown pattern). */
UDM1_API udm1_status udm1_pattern_default_colors(uint32_t pattern, const udm1_color_entry **entries, size_t *count);

#ifdef __cplusplus
}
#endif

#endif /* UDM1_UDM1_H */
