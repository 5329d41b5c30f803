/* seq.c - udm1_seq: validation of a descriptor, creation from presets or generators, destruction,
 * queries, and random access to single values. */
#include "seq/value.h"
#include "weyl/screen.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Size of the first (1.0) layout of udm1_seq_desc, a constant: later layouts only append. */
#define DESC_V1_SIZE (offsetof(udm1_seq_desc, screen_spp) + sizeof(uint32_t))

void udm1_seq_desc_init(udm1_seq_desc *desc)
{
    if (!desc) return;
    memset(desc, 0, sizeof *desc);
    desc->struct_size = (uint32_t)sizeof *desc;
    desc->randomize = UDM1_RANDOMIZE_DEFAULT;
}

/* floor(frac(v) * 2^128) of a finite double. */
static void double_fraction(double v, uint64_t *hi, uint64_t *lo)
{
    double a = fabs(v);
    double f = a - floor(a);    /* exact for a >= 0 */
    double scaled = f * 0x1p64; /* exact: power-of-two scale, < 2^64 */
    uint64_t h = (uint64_t)scaled;
    double rest = (scaled - (double)h) * 0x1p64; /* exact */
    uint64_t l = (uint64_t)rest;
    if (v < 0) { /* frac(-x) = 1 - frac(x): floor of it is -ceil(frac(x) 2^128) mod 2^128 */
        if ((double)l != rest && ++l == 0) ++h;
        h = ~h;
        l = ~l + 1;
        if (l == 0) ++h;
    }
    *hi = h;
    *lo = l;
}

/* Resolve one user generator. `check` mode reports rational ones instead of failing. */
udm1_status udm1_user_generator(const char *fn, uint32_t j, const udm1_alpha *a, udm1_generator *g, int check)
{
    if (a->reserved != 0)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: alphas[%u].reserved must be 0", fn, j);
    memset(g, 0, sizeof *g);
    switch (a->kind) {
    case UDM1_ALPHA_SQRT:
        if (udm1_gen_sqrt(a->k, g)) return UDM1_OK;
        if (check) {
            g->nature = UDM1_NATURE_RATIONAL;
            return UDM1_OK;
        }
        return udm1_fail(UDM1_ERROR_RATIONAL_ALPHA, "%s: alphas[%u] = sqrt(%llu) is rational", fn, j,
                         (unsigned long long)a->k);
    case UDM1_ALPHA_FIXED:
        g->hi = a->fixed_hi;
        g->lo = a->fixed_lo;
        break;
    case UDM1_ALPHA_DOUBLE:
        if (!isfinite(a->value))
            return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: alphas[%u].value is not finite", fn, j);
        double_fraction(a->value, &g->hi, &g->lo);
        break;
    default:
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: alphas[%u].kind %u is not a udm1_alpha_kind", fn, j,
                         a->kind);
    }
    g->nature = UDM1_NATURE_UNKNOWN;
    if ((g->hi | g->lo) == 0) {
        g->nature = UDM1_NATURE_RATIONAL;
        if (!check)
            return udm1_fail(UDM1_ERROR_RATIONAL_ALPHA, "%s: alphas[%u] has a zero fractional part", fn, j);
    }
    return UDM1_OK;
}

/* UDM1_RANDOMIZE_SCREEN: Weyl sequences (not point sets); screen_spp N >= 1 fixes the samples per pixel
 * (weyl/weyl.h), 0 is progressive (weyl/screen.h). */
static udm1_status screen_init(const char *fn, udm1_seq *seq, uint32_t spp)
{
    if (!seq->gen || seq->point_count)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT,
                         "%s: UDM1_RANDOMIZE_SCREEN applies to Weyl sequences (not point sets), not '%s'", fn, seq->name);
    seq->screen_spp = spp;
    return spp ? UDM1_OK : udm1_screen_generators(fn, seq);
}

udm1_status udm1_seq_create_desc(const udm1_seq_desc *caller_desc, udm1_seq **out)
{
    static const char fn[] = "udm1_seq_create";
    if (out) *out = NULL;
    if (!caller_desc) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: desc is NULL", fn);
    if (!out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: out is NULL", fn);
    udm1_seq_desc copy; /* only the caller's struct_size bytes are read */
    udm1_status read = udm1_read_struct(fn, "desc", "udm1_seq_desc_init", caller_desc, DESC_V1_SIZE, &copy, sizeof copy);
    if (read != UDM1_OK) return read;
    const udm1_seq_desc *desc = &copy;
    if (desc->screen_spp != 0 && desc->randomize != UDM1_RANDOMIZE_SCREEN)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: desc.screen_spp %u is for UDM1_RANDOMIZE_SCREEN only", fn,
                         desc->screen_spp);
    if (desc->randomize > UDM1_RANDOMIZE_SCREEN)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: desc.randomize %u is not a udm1_randomize", fn,
                         desc->randomize);
    uint32_t dims = desc->dimensions;
    if (dims == 0) return udm1_fail(UDM1_ERROR_DIMENSION, "%s: dimensions is 0", fn);
    if (dims > UDM1_MAX_DIMENSIONS)
        return udm1_fail(UDM1_ERROR_DIMENSION, "%s: dimensions %u exceeds the maximum %u", fn, dims,
                         UDM1_MAX_DIMENSIONS);

    const udm1_preset *preset = NULL;
    if (desc->preset) {
        preset = udm1_preset_lookup(desc->preset);
        if (!preset) return udm1_fail(UDM1_ERROR_UNKNOWN_PRESET, "%s: unknown preset '%.64s'", fn, desc->preset);
        if (dims > preset->max_dimensions)
            return udm1_fail(UDM1_ERROR_DIMENSION, "%s: preset '%s' has at most %u dimensions, %u asked", fn,
                             preset->name, preset->max_dimensions, dims);
        int point_set = (preset->flags & UDM1_PRESET_POINT_SET) != 0;
        if (point_set && (desc->point_count == 0 || desc->point_count > UDM1_MAX_POINT_COUNT))
            return udm1_fail(UDM1_ERROR_POINT_COUNT, "%s: preset '%s' needs a point count K in 1..%u, got %llu",
                             fn, preset->name, UDM1_MAX_POINT_COUNT, (unsigned long long)desc->point_count);
        if (!point_set && desc->point_count != 0)
            return udm1_fail(UDM1_ERROR_POINT_COUNT, "%s: preset '%s' is a sequence; point count must be 0, got %llu",
                             fn, preset->name, (unsigned long long)desc->point_count);
    } else {
        if (!desc->alphas) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: desc.preset and desc.alphas are both NULL", fn);
        if (desc->point_count != 0)
            return udm1_fail(UDM1_ERROR_POINT_COUNT, "%s: a sequence from alphas takes point count 0, got %llu", fn,
                             (unsigned long long)desc->point_count);
    }

    udm1_seq *seq = calloc(1, sizeof *seq);
    if (seq) {
        seq->offset = calloc(dims, sizeof(uint64_t));
        seq->dim_key = malloc(sizeof(uint64_t) * dims);
    }
    if (!seq || !seq->offset || !seq->dim_key) {
        udm1_seq_destroy(seq);
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory for %u dimensions", fn, dims);
    }
    seq->dims = dims;
    seq->randomize = desc->randomize;
    seq->seed = desc->seed;
    seq->point_count = desc->point_count;
    seq->seed_key = udm1_seed_key(desc->seed);
    for (uint32_t j = 0; j < dims; ++j) {
        if (desc->offsets) seq->offset[j] = desc->offsets[j];
        seq->dim_key[j] = udm1_dim_key(seq->seed_key, j);
    }
    static const uint32_t modes[] = {UDM1_MODE_NONE, 0, UDM1_MODE_SHIFT, UDM1_MODE_PERMUTE, UDM1_MODE_OWEN,
                                     UDM1_MODE_SCREEN};
    uint32_t default_mode = preset ? preset->default_mode : UDM1_MODE_SHIFT;
    seq->mode = desc->randomize == UDM1_RANDOMIZE_DEFAULT ? default_mode : modes[desc->randomize];

    udm1_status st = UDM1_OK;
    if (preset) {
        seq->name = preset->name;
        seq->kind = preset->kind;
        st = preset->init(seq);
    } else {
        seq->name = "custom";
        seq->kind = &udm1_weyl_kind;
        seq->gen = malloc(sizeof(udm1_generator) * dims);
        if (!seq->gen) st = udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory for %u dimensions", fn, dims);
        for (uint32_t j = 0; j < dims && st == UDM1_OK; ++j)
            st = udm1_user_generator(fn, j, &desc->alphas[j], &seq->gen[j], 0);
    }
    if (st == UDM1_OK && seq->mode == UDM1_MODE_SCREEN) st = screen_init(fn, seq, desc->screen_spp);
    if (st != UDM1_OK) {
        udm1_seq_destroy(seq);
        return st;
    }
    /* Weyl sequences take the inline path for no randomization, shifts and screen shifts */
    if (seq->kind == &udm1_weyl_kind && seq->mode != UDM1_MODE_NONE && seq->mode != UDM1_MODE_SHIFT &&
        seq->mode != UDM1_MODE_SCREEN)
        seq->kind = &udm1_weyl_scrambled_kind;
    if (preset && udm1_preset_is_tent(desc->preset)) {  /* every value through the tent: the generic paths */
        size_t len = strlen(preset->name) + 6;
        seq->owned_name = malloc(len);
        if (!seq->owned_name) {
            udm1_seq_destroy(seq);
            return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory", fn);
        }
        snprintf(seq->owned_name, len, "%s+tent", preset->name);
        seq->name = seq->owned_name;
        seq->inner = seq->kind;
        seq->kind = &udm1_tent_kind;
    }
    *out = seq;
    return UDM1_OK;
}

udm1_status udm1_seq_create(const char *preset, uint32_t dimensions, uint64_t point_count, uint64_t seed,
                            udm1_seq **out)
{
    if (out) *out = NULL;
    if (!preset) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_seq_create: preset is NULL");
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    desc.preset = preset;
    desc.dimensions = dimensions;
    desc.point_count = point_count;
    desc.seed = seed;
    return udm1_seq_create_desc(&desc, out);
}

void udm1_seq_destroy(udm1_seq *seq)
{
    if (!seq) return;
    free(seq->gen);
    free(seq->data);
    free(seq->offset);
    free(seq->dim_key);
    free(seq->screen_gen);
    free(seq->owned_name);
    free(seq);
}

/* The queries: 0 or NULL for a NULL handle, with a message (core.h's rule for status-less functions). */
#define QUERY(fn, value, neutral) (seq ? (value) : (udm1_fail(UDM1_ERROR_NULL_ARGUMENT, fn ": seq is NULL"), (neutral)))
uint32_t udm1_seq_dimensions(const udm1_seq *seq) { return QUERY("udm1_seq_dimensions", seq->dims, 0u); }
const char *udm1_seq_name(const udm1_seq *seq) { return QUERY("udm1_seq_name", seq->name, (const char *)NULL); }
uint64_t udm1_seq_point_count(const udm1_seq *seq) { return QUERY("udm1_seq_point_count", seq->point_count, 0u); }
uint64_t udm1_seq_seed(const udm1_seq *seq) { return QUERY("udm1_seq_seed", seq->seed, 0u); }
uint32_t udm1_seq_randomize(const udm1_seq *seq) { return QUERY("udm1_seq_randomize", seq->randomize, 0u); }

uint32_t udm1_seq_randomization(const udm1_seq *seq)
{
    static const uint32_t asked[] = {UDM1_RANDOMIZE_NONE, UDM1_RANDOMIZE_SHIFT, UDM1_RANDOMIZE_PERMUTE,
                                     UDM1_RANDOMIZE_OWEN, UDM1_RANDOMIZE_DEFAULT, UDM1_RANDOMIZE_SCREEN};
    return QUERY("udm1_seq_randomization", asked[seq->mode], 0u);
}

uint32_t udm1_seq_flags(const udm1_seq *seq)
{
    if (!seq) return QUERY("udm1_seq_flags", 0u, 0u);
    if (!seq->name) return 0;
    const udm1_preset *p = udm1_preset_lookup(seq->name);
    return p ? p->flags : 0;
}

udm1_status udm1_seq_alpha(const udm1_seq *seq, uint32_t dim, uint64_t *hi, uint64_t *lo)
{
    if (!seq || !hi || !lo) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_seq_alpha: a pointer argument is NULL");
    if (dim >= seq->dims)
        return udm1_fail(UDM1_ERROR_DIMENSION, "udm1_seq_alpha: dimension %u of a %u-dimensional sequence", dim,
                         seq->dims);
    if (!seq->gen)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "udm1_seq_alpha: '%s' is not a Weyl sequence", seq->name);
    *hi = seq->gen[dim].hi;
    *lo = seq->gen[dim].lo;
    return UDM1_OK;
}

udm1_status udm1_seq_offset(const udm1_seq *seq, uint64_t stream, uint32_t dim, uint64_t *offset)
{
    if (!seq || !offset) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_seq_offset: a pointer argument is NULL");
    if (dim >= seq->dims)
        return udm1_fail(UDM1_ERROR_DIMENSION, "udm1_seq_offset: dimension %u of a %u-dimensional sequence", dim,
                         seq->dims);
    uint64_t o = seq->offset[dim];
    if (seq->mode == UDM1_MODE_SCREEN)
        o += udm1_weyl_shift(seq, udm1_seq_stream_key(seq, stream), dim);
    else if (seq->mode != UDM1_MODE_NONE)
        o += udm1_shift(udm1_stream_key(seq->seed_key, stream), seq->dim_key[dim]);
    *offset = o;
    return UDM1_OK;
}

static udm1_status sample_raw(const char *fn, const udm1_seq *seq, uint64_t stream, uint64_t index, uint32_t dim,
                              const void *out, uint64_t *raw)
{
    if (!seq || !out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, seq ? "out" : "seq");
    if (dim >= seq->dims)
        return udm1_fail(UDM1_ERROR_DIMENSION, "%s: dimension %u of a %u-dimensional sequence", fn, dim, seq->dims);
    if (seq->point_count && index >= seq->point_count)
        return udm1_fail(UDM1_ERROR_INDEX_RANGE, "%s: index %llu of a %llu-point set", fn,
                         (unsigned long long)index, (unsigned long long)seq->point_count);
    *raw = udm1_value_of(seq, udm1_seq_stream_key(seq, stream), index, dim);
    return UDM1_OK;
}

udm1_status udm1_seq_sample_u64(const udm1_seq *seq, uint64_t stream, uint64_t index, uint32_t dim, uint64_t *out)
{
    uint64_t raw = 0;
    udm1_status st = sample_raw("udm1_seq_sample_u64", seq, stream, index, dim, out, &raw);
    if (st == UDM1_OK) *out = raw;
    return st;
}

udm1_status udm1_seq_sample_f64(const udm1_seq *seq, uint64_t stream, uint64_t index, uint32_t dim, double *out)
{
    uint64_t raw = 0;
    udm1_status st = sample_raw("udm1_seq_sample_f64", seq, stream, index, dim, out, &raw);
    if (st == UDM1_OK) *out = udm1_to_f64(raw);
    return st;
}

udm1_status udm1_seq_sample_f32(const udm1_seq *seq, uint64_t stream, uint64_t index, uint32_t dim, float *out)
{
    uint64_t raw = 0;
    udm1_status st = sample_raw("udm1_seq_sample_f32", seq, stream, index, dim, out, &raw);
    if (st == UDM1_OK) *out = udm1_to_f32(raw);
    return st;
}
