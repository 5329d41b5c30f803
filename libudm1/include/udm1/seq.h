/*
 * udm1/seq.h - sequences and point sets: presets, creation, random access, bulk fills, the renderer
 * cursor and the check of a generator set.
 * Part of libudm1's public interface; udm1/udm1.h includes every part.
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
 * written to the caller's output (udm1/core.h; the creators set *out to NULL),
 * and udm1_last_error() returns a one-line message, on the calling thread,
 * naming the function and the bad input.
 */
#ifndef UDM1_SEQ_H
#define UDM1_SEQ_H

#include "udm1/core.h"

/* The most dimensions a sequence may have (WR: square roots of the first
 * 65536 primes; R_d: d up to this). Presets with a fixed list have fewer. */
#define UDM1_MAX_DIMENSIONS 65536u

/* Dimension indices are below this limit, 2^32 - 1, everywhere: the fills, the many-points call and
 * the cursor (which hands out dimensions up to UDM1_DIMENSION_INDEX_LIMIT - 1 and is then exhausted).
 * A range of dimensions that would reach it is refused (UDM1_ERROR_DIMENSION); no counter wraps to
 * dimension 0. (1.6) */
#define UDM1_DIMENSION_INDEX_LIMIT 4294967295u

/* The largest point count K of a point set: 2^32 - 1 (pmj02: 2^20). */
#define UDM1_MAX_POINT_COUNT 4294967295u

/* Dimensions of the Sobol presets: the Joe-Kuo new-joe-kuo-6.21201 set. */
#define UDM1_SOBOL_MAX_DIMENSIONS 21201u

#ifdef __cplusplus
extern "C" {
#endif

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
 * lattice-seq embedded rank-1 lattice {phi_2(n) z}, phi_2   random shift            1..64
 *             the base-2 radical inverse (1.9): a sequence whose first 2^m
 *             points are the lattice {k z / 2^m} for every m; raw values
 *             exactly reverse64(n) z_j mod 2^64; z from tools/lattice_search.py
 *             (embedded component-by-component search over 2^6 .. 2^20)
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
    UDM1_RANDOMIZE_SCREEN = 5   /* Weyl sequences: screen-space decorrelation, pixel (x, y) as stream
                                   ((uint64_t)y << 32) | x; its error image is blue noise (its low screen
                                   frequencies damped) and each pixel stays unbiased over seeds.
                                   desc.screen_spp = 0 (1.8), progressive: point n of the pixel is
                                   point n of the sequence shifted by u_j(seed) + x G_j + y H_j, G and
                                   H screen generators chosen from the sequence's generators: blue at
                                   every sample count, so a render may stop or continue anywhere
                                   (creating one searches G and H: about 1 ms per dimension pair).
                                   desc.screen_spp = N >= 1 (1.4), fixed: point n of the pixel is point
                                   m*N + n (mod 2^64) of one sequence shifted by u_j(seed), m the
                                   pixel's Morton index: blue at N samples per pixel.
                                   docs/screen-space.md has both constructions */
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
    uint32_t struct_size;      /* sizeof(udm1_seq_desc) of the caller's header; set by udm1_seq_desc_init.
                                  The library reads only that many bytes: a caller built against an
                                  older 1.x header (a shorter layout) gets the later fields' defaults
                                  (zero); one built against a newer header is accepted when the fields
                                  this library does not know are zero, and refused (INVALID_ARGUMENT)
                                  otherwise. Below the 1.0 layout's size: INVALID_ARGUMENT. */
    uint32_t dimensions;       /* D >= 1 */
    const char *preset;        /* a preset name, or NULL to use `alphas` */
    const udm1_alpha *alphas;  /* D generators when preset is NULL */
    const uint64_t *offsets;   /* optional: D base offsets o_j in 0.64 fixed point; NULL = 0 */
    uint64_t point_count;      /* K for a point-set preset (1..UDM1_MAX_POINT_COUNT); else 0 */
    uint64_t seed;             /* key of the random shifts */
    uint32_t randomize;        /* udm1_randomize; PRNGs and "pattern" presets (cmj, grps) take an
                                  independent stream per stream id unless NONE, and then
                                  apply SHIFT/PERMUTE/OWEN on top if asked */
    uint32_t screen_spp;       /* UDM1_RANDOMIZE_SCREEN: 0 progressive, or the samples per pixel N of
                                  the fixed scheme (1.4; the field was `reserved`, 0, before); else 0 */
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
 *
 * The draws return no status. A draw they cannot make gives NaN (never a value
 * in [0, 1) that would be wrong) and sets udm1_last_error(): a NULL cursor, one
 * never started (zeroed), and every draw after dimension
 * UDM1_DIMENSION_INDEX_LIMIT - 1 (the cursor is then exhausted; dimension
 * counters do not wrap). A NULL output array is ignored.
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
 * Errors: NULL_ARGUMENT, INDEX_RANGE (index >= K for a point set), DIMENSION
 * (first_dimension >= UDM1_DIMENSION_INDEX_LIMIT).
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
 * Errors: NULL arguments with n > 0, an index outside a point set (naming k; every index is checked
 * before out is written), DIMENSION (n_dims 0, or first_dimension + n_dims past
 * UDM1_DIMENSION_INDEX_LIMIT; checked also when n is 0). Since 1.5. */
UDM1_API udm1_status udm1_seq_fill_points_f64(const udm1_seq *seq, size_t n, const uint64_t *streams,
                                              const uint64_t *indices, uint32_t first_dimension,
                                              uint32_t n_dims, double *out);

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
 * Errors (the report left unchanged): NULL_ARGUMENT, INVALID_ARGUMENT (n, work
 * limit, not a Weyl sequence), OUT_OF_MEMORY. */
UDM1_API udm1_status udm1_seq_check(const udm1_seq *seq, uint64_t n, udm1_alpha_report *report);
/* Check user generators before creating a sequence; unlike creation, a
 * rational generator is reported, not refused. Errors: NULL_ARGUMENT,
 * INVALID_ARGUMENT (n, count 0 or above UDM1_MAX_DIMENSIONS, a bad alpha). */
UDM1_API udm1_status udm1_alpha_check(const udm1_alpha *alphas, uint32_t count, uint64_t n,
                                      udm1_alpha_report *report);

#ifdef __cplusplus
}
#endif

#endif /* UDM1_SEQ_H */
