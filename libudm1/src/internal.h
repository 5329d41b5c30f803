/* internal.h - definitions shared by libudm1's sources; not installed. */
#ifndef UDM1_INTERNAL_H
#define UDM1_INTERNAL_H

#include "udm1/udm1.h"

#include <stddef.h>
#include <stdint.h>

#if defined(__GNUC__)
#  define UDM1_HIDDEN __attribute__((visibility("hidden")))
#  define UDM1_LIKELY(x) __builtin_expect(!!(x), 1)
#  define UDM1_UNLIKELY(x) __builtin_expect(!!(x), 0)
#else
#  define UDM1_HIDDEN
#  define UDM1_LIKELY(x) (x)
#  define UDM1_UNLIKELY(x) (x)
#endif

/* What is known about a generator's arithmetic nature (for udm1_alpha_check). */
enum udm1_alpha_nature {
    UDM1_NATURE_UNKNOWN = 0,   /* a fixed-point or double value: only numeric checks */
    UDM1_NATURE_RATIONAL = 1,  /* rational: useless as a generator */
    UDM1_NATURE_QUADRATIC = 2, /* a + b sqrt(m), m square-free >= 2, stored in `radical` */
    UDM1_NATURE_INDEPENDENT = 3, /* independent of every other generator of its set and of 1
                                    by construction (e, e^2; R_d) */
    UDM1_NATURE_POINT_SET = 4    /* rational by design: the n/K axis of a point set (EPIS) */
};

/* One dimension's generator: the 0.128 fixed-point fraction and its nature. */
typedef struct udm1_generator {
    uint64_t hi, lo;
    uint32_t nature;   /* enum udm1_alpha_nature */
    uint64_t radical;  /* square-free m for UDM1_NATURE_QUADRATIC */
} udm1_generator;

/* The randomization a sequence applies, with UDM1_RANDOMIZE_DEFAULT resolved. */
enum udm1_mode {
    UDM1_MODE_NONE = 0,
    UDM1_MODE_SHIFT = 1,   /* add r_j modulo 1 (Cranley-Patterson) */
    UDM1_MODE_PERMUTE = 2, /* base 2: XOR with r_j; base b: a random permutation per digit */
    UDM1_MODE_OWEN = 3,    /* nested uniform (Owen) scrambling by hashing */
    UDM1_MODE_STREAMS = 4, /* PRNGs: an independent stream per stream id, no transform */
    UDM1_MODE_SCREEN = 5   /* Weyl: a shift from the pixel's Morton index (screen_shift.h) */
};

typedef struct udm1_seq udm1_seq_t;
/* Raw 0.64 value of (stream key, index, dimension < D), randomization applied. */
typedef uint64_t (*udm1_value_fn)(const udm1_seq_t *seq, uint64_t stream_key, uint64_t index, uint32_t dim);
/* Optional fast path: raw values of rows [first, first+count) x dims [dim0, dim0+nd), row-major. */
typedef void (*udm1_fill_fn)(const udm1_seq_t *seq, uint64_t stream_key, uint64_t first, size_t count, uint32_t dim0,
                             uint32_t nd, uint64_t *raw);

struct udm1_seq {
    uint32_t dims;
    uint32_t randomize;    /* as asked (udm1_randomize) */
    uint32_t mode;         /* effective (enum udm1_mode) */
    uint64_t seed;
    uint64_t point_count;  /* 0: sequence */
    uint64_t seed_key;     /* derived from seed, see hash.h */
    const char *name;      /* static storage */
    udm1_value_fn value;   /* NULL for Weyl sequences: the inline fast path over gen */
    udm1_fill_fn fill;     /* NULL: fills call value() */
    udm1_generator *gen;   /* Weyl: dims generators */
    uint64_t *offset;      /* dims base offsets o_j (0.64) */
    uint64_t *dim_key;     /* dims per-dimension hash keys K_j */
    void *data;            /* other kinds: their tables (freed with free()) */
    uint64_t screen_spp;   /* UDM1_MODE_SCREEN: samples per pixel N (screen_shift.h) */
    int tent;              /* "+tent": every value goes through udm1_tent */
    udm1_value_fn inner_value; /* with tent: the sequence's own value function (NULL: the Weyl path) */
    /* Optional: for presets whose value is udm1_randomize_base2(mode, base2(...), udm1_word(seq, skey, dim)),
     * the value before randomization (udm1_seq_fill_points_f64 then computes a stream's words once) */
    udm1_value_fn base2;
    /* Optional, with base2: base2's values of dimensions dim0 .. dim0 + m - 1 (all < dims) of one point
     * into raw[0 .. m), in one call (Sobol: the index's Gray-code bits found once for all of them) */
    void (*base2_point)(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim0, uint32_t m, uint64_t *raw);
    char *owned_name;      /* with tent: "NAME+tent" (name points here) */
};

/* A noise's tables (noise.c); the patterns (patterns.c) read the wave sources. */
typedef struct udm1_pick { uint8_t iu, iv; double su, sv; } udm1_pick; /* +-c[iu] +-c[iv] */
#define UDM1_NOISE_WAVES 10
struct udm1_noise {
    uint32_t kind;
    uint32_t period[3];
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
};

/* The vector path of udm1_noise_points (noise_simd.c): how many leading points it computed. */
UDM1_HIDDEN size_t udm1_noise_points_fast(const struct udm1_noise *n, uint32_t dims, const double *xyz, size_t count,
                                          size_t stride, double *out);

/* ---- error reporting (status.c) ---- */
/* Record a one-line message for udm1_last_error() and return status. */
UDM1_HIDDEN udm1_status udm1_fail(udm1_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* ---- generators (generators.c) ---- */
/* frac(sqrt(k)) for k >= 2 not a perfect square; returns 0 if k is a square. */
UDM1_HIDDEN int udm1_gen_sqrt(uint64_t k, udm1_generator *g);
/* frac((a + b sqrt(k)) / c), small a, b >= 1, c in {1, 2}; k not a square. */
UDM1_HIDDEN int udm1_gen_quadratic(int64_t a, uint64_t b, uint64_t k, uint64_t c, udm1_generator *g);
/* R_d generators phi_d^-1 .. phi_d^-d into g[0..d-1]; d >= 1. Returns 0 on out of memory. */
UDM1_HIDDEN int udm1_gen_rd(uint32_t d, udm1_generator *g);
/* Square-free part of k (k >= 1). */
UDM1_HIDDEN uint64_t udm1_squarefree_part(uint64_t k);
/* The first `count` primes into out. Returns 0 on out of memory. */
UDM1_HIDDEN int udm1_first_primes(uint32_t count, uint64_t *out);

/* ---- presets (presets.c) ---- */
typedef udm1_status (*udm1_init_fn)(udm1_seq_t *seq);
typedef struct udm1_preset {
    const char *name;
    const char *description;
    uint32_t max_dimensions;
    uint32_t flags;
    uint32_t default_mode; /* enum udm1_mode of UDM1_RANDOMIZE_DEFAULT */
    udm1_init_fn init;     /* fills gen (Weyl) or value + data; dims, K, seed, mode are set */
} udm1_preset;
UDM1_HIDDEN const udm1_preset *udm1_preset_lookup(const char *name);
UDM1_HIDDEN int udm1_preset_is_tent(const char *name);

/* The tent (baker's) transform 1 - |2x - 1| on a raw 0.64 value, exact: 2x below 1/2, 2 - 2x above. */
static inline uint64_t udm1_tent(uint64_t x) { return (x >> 63) ? (0 - x) << 1 : x << 1; }

/* ---- sampler kinds: init functions (one file each) ---- */
UDM1_HIDDEN udm1_status udm1_init_pcg32(udm1_seq_t *seq);
UDM1_HIDDEN udm1_status udm1_init_drand48(udm1_seq_t *seq);
UDM1_HIDDEN udm1_status udm1_init_halton(udm1_seq_t *seq);
UDM1_HIDDEN udm1_status udm1_init_sobol(udm1_seq_t *seq);
UDM1_HIDDEN udm1_status udm1_init_hammersley(udm1_seq_t *seq);
UDM1_HIDDEN udm1_status udm1_init_lattice(udm1_seq_t *seq);
UDM1_HIDDEN udm1_status udm1_init_lp(udm1_seq_t *seq);
UDM1_HIDDEN udm1_status udm1_init_cmj(udm1_seq_t *seq);
UDM1_HIDDEN udm1_status udm1_init_grps(udm1_seq_t *seq);
UDM1_HIDDEN udm1_status udm1_init_pmj02(udm1_seq_t *seq);
/* Weyl sequences with a non-shift randomization go through this value function. */
UDM1_HIDDEN uint64_t udm1_weyl_value(const udm1_seq_t *seq, uint64_t stream_key, uint64_t index, uint32_t dim);

/* Base-b radical inverse of n as 0.64 (floor), exact; digits permuted per mode
 * (r is the dimension's random word). Used by Halton and Hammersley. */
UDM1_HIDDEN uint64_t udm1_radical_inverse(uint64_t n, uint32_t base, uint32_t mode, uint64_t r);

/* ---- user generators (seq.c) ---- */
/* Resolve alphas[j]; with check != 0 a rational one is marked, not refused. */
UDM1_HIDDEN udm1_status udm1_user_generator(const char *fn, uint32_t j, const udm1_alpha *a, udm1_generator *g,
                                            int check);

/* ---- check (alpha_check.c) ---- */
UDM1_HIDDEN udm1_status udm1_check_generators(const udm1_generator *gen, uint32_t dims, uint64_t n,
                                              udm1_alpha_report *report);

/* ---- 64x64 -> 128 multiply ---- */
static inline void udm1_mul64(uint64_t a, uint64_t b, uint64_t *hi, uint64_t *lo)
{
#if defined(__SIZEOF_INT128__)
    __extension__ typedef unsigned __int128 u128;
    u128 p = (u128)a * b;
    *hi = (uint64_t)(p >> 64);
    *lo = (uint64_t)p;
#else
    uint64_t a0 = a & 0xffffffffu, a1 = a >> 32, b0 = b & 0xffffffffu, b1 = b >> 32;
    uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
    *lo = (mid << 32) | (p00 & 0xffffffffu);
    *hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
#endif
}

/* Raw value: top 64 bits of (offset * 2^64 + n * A) mod 2^128. */
static inline uint64_t udm1_weyl_raw(const udm1_generator *g, uint64_t offset, uint64_t n)
{
    uint64_t mhi, mlo;
    udm1_mul64(n, g->lo, &mhi, &mlo);
    (void)mlo;
    return n * g->hi + mhi + offset;
}

/* Conversions of a raw 0.64 value. Both are < 1 for every input. */
static inline double udm1_to_f64(uint64_t u) { return (double)(int64_t)(u >> 11) * 0x1p-53; }
static inline float udm1_to_f32(uint64_t u) { return (float)(int32_t)(u >> 40) * 0x1p-24f; }

#endif /* UDM1_INTERNAL_H */
