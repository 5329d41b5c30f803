/* seq/seq.h - the udm1_seq object and the sampler-kind interface.
 *
 * A sequence is made from a preset (seq/presets.c) or from user generators. The preset's init fills
 * the kind's tables (seq->gen for Weyl sets, seq->data for the others); seq->kind then answers every
 * value through one const operations table per sampler kind:
 *
 *   value        required: the raw 0.64 value of (stream key, index, dimension), randomized
 *   fill         optional: rows [first, first + count) x dims [dim0, dim0 + nd), row-major (the
 *                generic code calls value() per entry without it)
 *   base2        optional: for kinds whose value is udm1_randomize_base2(mode, base2(...), word),
 *                the value before randomization (fills of many points find a stream's words once)
 *   base2_point  optional, with base2: base2 of dimensions dim0 .. dim0 + m - 1 of one point at once
 *   pin, pinned  optional: words per (stream key, dimension) that make its values cheaper to find, and
 *                the value from them (udm1_stream_init keeps three per dimension for its draws: the
 *                dimension's randomization word and two of the kind's); pin returns 0 where they would
 *                not help (then only value is used)
 *   seek, step   optional, for generators whose values follow one another (the PRNGs: value (n, j) is
 *                output n D + j): seek gives the state at (index, dim), step the value there and the
 *                state advanced to the next dimension, so a cursor draws one step at a time instead of
 *                seeking again for every value
 *
 * The Weyl kind (weyl/weyl.c) is the one the generic code also knows inline: its values and bulk fills
 * are the integer arithmetic of weyl/weyl.h, with no call through the table. Transforms of a kind (the
 * tent, seq/tent.c) are kinds of their own that wrap seq->inner.
 *
 * Adding a sampler: a file in samplers/ with an init (tables into seq->data, freed with free()) and a
 * `const udm1_kind`, both declared in samplers/samplers.h, and a row in the preset table. */
#ifndef UDM1_SEQ_INTERNAL_H
#define UDM1_SEQ_INTERNAL_H

#include "core/internal.h"
#include "weyl/generators.h"

/* The randomization a sequence applies, with UDM1_RANDOMIZE_DEFAULT resolved. */
enum udm1_mode {
    UDM1_MODE_NONE = 0,
    UDM1_MODE_SHIFT = 1,   /* add r_j modulo 1 (Cranley-Patterson) */
    UDM1_MODE_PERMUTE = 2, /* base 2: XOR with r_j; base b: a random permutation per digit */
    UDM1_MODE_OWEN = 3,    /* nested uniform (Owen) scrambling by hashing */
    UDM1_MODE_STREAMS = 4, /* PRNGs: an independent stream per stream id, no transform */
    UDM1_MODE_SCREEN = 5   /* Weyl: screen-space shifts (weyl/weyl.h, weyl/screen.h) */
};

typedef struct udm1_seq udm1_seq_t;
/* Raw 0.64 value of (stream key, index, dimension < D), randomization applied. */
typedef uint64_t (*udm1_value_fn)(const udm1_seq_t *seq, uint64_t stream_key, uint64_t index, uint32_t dim);
/* Raw values of rows [first, first+count) x dims [dim0, dim0+nd), row-major. */
typedef void (*udm1_fill_fn)(const udm1_seq_t *seq, uint64_t stream_key, uint64_t first, size_t count, uint32_t dim0,
                             uint32_t nd, uint64_t *raw);
/* Values of dimensions dim0 .. dim0 + m - 1 (all < dims) of one point into raw[0 .. m). */
typedef void (*udm1_point_fn)(const udm1_seq_t *seq, uint64_t stream_key, uint64_t index, uint32_t dim0, uint32_t m,
                              uint64_t *raw);
/* A stream's words of dimension dim < dims (0: none that help): r its randomization word (udm1_word), w0 and
 * w1 the kind's; and the value of index from them. */
typedef int (*udm1_pin_fn)(const udm1_seq_t *seq, uint64_t stream_key, uint32_t dim, uint64_t *r, uint64_t *w0,
                           uint64_t *w1);
typedef uint64_t (*udm1_pinned_fn)(const udm1_seq_t *seq, uint64_t index, uint32_t dim, uint64_t r, uint64_t w0,
                                   uint64_t w1);
/* The generator's state at (index, dim < dims). */
typedef uint64_t (*udm1_seek_fn)(const udm1_seq_t *seq, uint64_t stream_key, uint64_t index, uint32_t dim);
/* The value at the state's position (dimension dim, randomization applied); the state advanced by one.
 * The stream key may be 0 where the mode is none (no kind uses it then). */
typedef uint64_t (*udm1_step_fn)(const udm1_seq_t *seq, uint64_t stream_key, uint64_t *state, uint32_t dim);

/* The operations of one sampler kind (see the top of this file). */
typedef struct udm1_kind {
    const char *name;          /* for messages and debugging: "weyl", "sobol", ... */
    udm1_value_fn value;       /* required */
    udm1_fill_fn fill;         /* optional */
    udm1_value_fn base2;       /* optional */
    udm1_point_fn base2_point; /* optional, with base2 */
    udm1_pin_fn pin;           /* optional */
    udm1_pinned_fn pinned;     /* with pin */
    udm1_seek_fn seek;         /* optional, with step */
    udm1_step_fn step;
} udm1_kind;

struct udm1_seq {
    uint32_t dims;
    uint32_t randomize;    /* as asked (udm1_randomize) */
    uint32_t mode;         /* effective (enum udm1_mode) */
    uint64_t seed;
    uint64_t point_count;  /* 0: sequence */
    uint64_t seed_key;     /* derived from seed, see core/hash.h */
    const char *name;      /* static storage, or owned_name */
    const udm1_kind *kind; /* how values are made */
    const udm1_kind *inner;/* a transform's wrapped kind (the tent); NULL otherwise */
    udm1_generator *gen;   /* Weyl: dims generators */
    uint64_t *offset;      /* dims base offsets o_j (0.64) */
    uint64_t *dim_key;     /* dims per-dimension hash keys K_j */
    void *data;            /* other kinds: their tables (freed with free()) */
    uint64_t screen_spp;   /* UDM1_MODE_SCREEN: samples per pixel N (weyl/weyl.h), 0: progressive */
    uint64_t *screen_gen;  /* progressive UDM1_MODE_SCREEN: G_j, H_j of every dimension (weyl/screen.h) */
    char *owned_name;      /* with tent: "NAME+tent" (name points here) */
};

/* ---- presets (presets.c) ---- */
typedef udm1_status (*udm1_init_fn)(udm1_seq_t *seq);
typedef struct udm1_preset {
    const char *name;
    const char *description;
    uint32_t max_dimensions;
    uint32_t flags;
    uint32_t default_mode;  /* enum udm1_mode of UDM1_RANDOMIZE_DEFAULT */
    udm1_init_fn init;      /* fills gen (Weyl) or data; dims, K, seed, mode are set */
    const udm1_kind *kind;  /* the operations of its values */
} udm1_preset;
UDM1_HIDDEN const udm1_preset *udm1_preset_lookup(const char *name);
UDM1_HIDDEN int udm1_preset_is_tent(const char *name);

/* ---- the cursor (cursor.c) ---- */
/* Its private key: the stream key, or for a kind with seek/step the generator's state while the cursor
 * is below the sequence's dimensions (the stream key is then computed again where it is needed). */
UDM1_HIDDEN void udm1_cursor_init(udm1_cursor *c, const udm1_seq_t *seq, uint64_t stream, uint64_t index,
                                  uint32_t dim, uint64_t stream_key);
/* The next n raw values of a started cursor (its dimensions stay below the index limit: the caller
 * checks): the sequence's values over its own dimensions, padding past them. */
UDM1_HIDDEN void udm1_cursor_raw(udm1_cursor *c, uint32_t n, uint64_t *raw);

/* ---- streams (stream.c) ---- */
/* udm1_stream_fill_raw, naming fn in its messages; with low_half 0 an Owen-scrambled base-2 kind may
 * leave the low 32 bits 0 (a float reads only the top 24). */
UDM1_HIDDEN udm1_status udm1_stream_fill(const char *fn, const udm1_stream *st, uint64_t index, uint32_t dim,
                                         uint32_t n, uint64_t *raw, int low_half);

/* ---- transforms of a kind (tent.c) ---- */
/* The tent (baker's) transform 1 - |2x - 1| on a raw 0.64 value, exact: 2x below 1/2, 2 - 2x above. */
static inline uint64_t udm1_tent(uint64_t x)
{
    uint64_t top = 0 - (x >> 63); /* all ones above 1/2: then -x, else x (no branch: the bit is random) */
    return ((x ^ top) - top) << 1;
}
/* The kind of "NAME+tent": the tent of seq->inner's every value. */
UDM1_HIDDEN extern const udm1_kind udm1_tent_kind;

#endif /* UDM1_SEQ_INTERNAL_H */
