/* cursor.c - the renderer cursor (pbrt-v4's Sampler shape: start a pixel sample, then draw dimension
 * after dimension), padded past the sequence's dimensions with independent hashed values. A draw the
 * cursor cannot make (NULL, never started, exhausted at the dimension index limit) is NaN. */
#include "seq/value.h"

#include <math.h>

void udm1_cursor_init(udm1_cursor *c, const udm1_seq_t *seq, uint64_t stream, uint64_t index, uint32_t dim,
                      uint64_t stream_key)
{
    c->seq = seq;
    c->stream = stream;
    c->index = index;
    c->key = seq->kind->seek && dim < seq->dims ? seq->kind->seek(seq, stream_key, index, dim) : stream_key;
    c->dimension = dim;
    c->padded = 0;
}

udm1_status udm1_cursor_start(udm1_cursor *cursor, const udm1_seq *seq, uint64_t stream, uint64_t index,
                              uint32_t first_dimension)
{
    if (!cursor || !seq)
        return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_cursor_start: %s is NULL", cursor ? "seq" : "cursor");
    if (seq->point_count && index >= seq->point_count)
        return udm1_fail(UDM1_ERROR_INDEX_RANGE, "udm1_cursor_start: index %llu of a %llu-point set",
                         (unsigned long long)index, (unsigned long long)seq->point_count);
    if (first_dimension >= UDM1_DIMENSION_INDEX_LIMIT)
        return udm1_fail(UDM1_ERROR_DIMENSION, "udm1_cursor_start: first_dimension %u is not below the dimension index "
                         "limit 2^32 - 1", first_dimension);
    udm1_cursor_init(cursor, seq, stream, index, first_dimension, udm1_seq_stream_key(seq, stream));
    return UDM1_OK;
}

/* The stream key: the cursor's key, or for a kind whose cursor holds its state computed again (0 where
 * the mode is none: a stepping kind does not use it then) */
static inline uint64_t stream_key_of(const udm1_cursor *c, int for_padding)
{
    const udm1_seq *seq = c->seq;
    if (!seq->kind->seek) return c->key;
    return seq->mode == UDM1_MODE_NONE && !for_padding ? 0 : udm1_seq_stream_key(seq, c->stream);
}

/* The next value of a cursor inside the sequence's dimensions */
static inline uint64_t inside_next(udm1_cursor *c)
{
    const udm1_seq *seq = c->seq;
    uint32_t dim = c->dimension++;
    if (seq->kind == &udm1_weyl_kind) return udm1_weyl_shifted_raw(seq, c->key, c->index, dim);
    if (seq->kind->step) return seq->kind->step(seq, stream_key_of(c, 0), &c->key, dim); /* a step, no seek */
    return seq->kind->value(seq, c->key, c->index, dim);
}

static inline uint64_t cursor_next(udm1_cursor *c)
{
    const udm1_seq *seq = c->seq;
    if (UDM1_LIKELY(c->dimension < seq->dims)) return inside_next(c);
    uint32_t dim = c->dimension++;
    ++c->padded;
    /* padding: an independent uniform value of (seed, stream, index, dim) */
    return udm1_pad(udm1_shift(stream_key_of(c, 1), udm1_dim_key(seq->seed_key, dim)), c->index);
}

/* The message for udm1_last_error of a draw the cursor cannot make (out of line: the draws stay small) */
static UDM1_NOINLINE_COLD int cannot_draw(const udm1_cursor *c, const char *fn)
{
    if (!c) udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: cursor is NULL", fn);
    else if (!c->seq) udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: the cursor was not started (udm1_cursor_start)", fn);
    else udm1_fail(UDM1_ERROR_DIMENSION, "%s: the cursor is exhausted (dimension index limit 2^32 - 1)", fn);
    return 0;
}

/* Whether the cursor can draw (else the message for udm1_last_error) */
static inline int can_draw(const udm1_cursor *c, const char *fn)
{
    if (UDM1_LIKELY(c && c->seq && c->dimension < UDM1_DIMENSION_INDEX_LIMIT)) return 1;
    return cannot_draw(c, fn);
}

/* Whether the next draw is inside the sequence's dimensions (then it can draw: dims < the index limit) */
static inline int draws_inside(const udm1_cursor *c) { return c && c->seq && c->dimension < c->seq->dims; }

float udm1_cursor_1d(udm1_cursor *cursor)
{
    if (UDM1_LIKELY(draws_inside(cursor))) return udm1_to_f32(inside_next(cursor));
    return can_draw(cursor, "udm1_cursor_1d") ? udm1_to_f32(cursor_next(cursor)) : NAN;
}

double udm1_cursor_1d_f64(udm1_cursor *cursor)
{
    if (UDM1_LIKELY(draws_inside(cursor))) return udm1_to_f64(inside_next(cursor));
    return can_draw(cursor, "udm1_cursor_1d_f64") ? udm1_to_f64(cursor_next(cursor)) : NAN;
}

void udm1_cursor_2d(udm1_cursor *cursor, float out[2])
{
    if (!out) return;
    out[0] = can_draw(cursor, "udm1_cursor_2d") ? udm1_to_f32(cursor_next(cursor)) : NAN;
    out[1] = can_draw(cursor, "udm1_cursor_2d") ? udm1_to_f32(cursor_next(cursor)) : NAN;
}

void udm1_cursor_2d_f64(udm1_cursor *cursor, double out[2])
{
    if (!out) return;
    out[0] = can_draw(cursor, "udm1_cursor_2d_f64") ? udm1_to_f64(cursor_next(cursor)) : NAN;
    out[1] = can_draw(cursor, "udm1_cursor_2d_f64") ? udm1_to_f64(cursor_next(cursor)) : NAN;
}

/* The next n raw values: the sequence's own fill over the dimensions it has (one
 * row of a sequential fill), cursor_next for the padded rest. */
void udm1_cursor_raw(udm1_cursor *c, uint32_t n, uint64_t *raw)
{
    const udm1_seq *seq = c->seq;
    uint32_t k = 0;
    if (seq->kind == &udm1_weyl_kind) { /* the Weyl values in one loop (its bulk kernel costs more for one row) */
        uint32_t inside = c->dimension >= seq->dims ? 0 : seq->dims - c->dimension < n ? seq->dims - c->dimension : n;
        for (; k < inside; ++k) raw[k] = udm1_weyl_shifted_raw(seq, c->key, c->index, c->dimension + k);
        c->dimension += inside;
    } else if (!seq->kind->step && seq->kind->fill && c->dimension < seq->dims) {
        uint32_t inside = seq->dims - c->dimension < n ? seq->dims - c->dimension : n;
        seq->kind->fill(seq, c->key, c->index, 1, c->dimension, inside, raw);
        c->dimension += inside;
        k = inside;
    } else if (seq->kind->step && c->dimension < seq->dims) { /* steps, with the stream key found once */
        uint32_t inside = seq->dims - c->dimension < n ? seq->dims - c->dimension : n;
        uint64_t skey = stream_key_of(c, 0);
        for (; k < inside; ++k) raw[k] = seq->kind->step(seq, skey, &c->key, c->dimension + k);
        c->dimension += inside;
    }
    for (; k < n; ++k) raw[k] = cursor_next(c);
}

/* n draws converted to float (f64 = 0) or double (f64 = 1), in chunks of 32; NaN for the draws past
 * the dimension index limit, or all n if the cursor cannot draw */
static void cursor_fill_as(const char *fn, udm1_cursor *cursor, uint32_t n, void *out, int f64)
{
    if (!out) return;
    uint64_t raw[32];
    for (uint32_t done = 0; done < n;) {
        uint32_t m = n - done < 32 ? n - done : 32, ok = 0;
        if (can_draw(cursor, fn)) {
            ok = UDM1_DIMENSION_INDEX_LIMIT - cursor->dimension < m ? UDM1_DIMENSION_INDEX_LIMIT - cursor->dimension : m;
            udm1_cursor_raw(cursor, ok, raw);
            if (ok < m) can_draw(cursor, fn); /* the message: exhausted */
        }
        for (uint32_t k = 0; k < m; ++k) {
            if (f64) ((double *)out)[done + k] = k < ok ? udm1_to_f64(raw[k]) : NAN;
            else ((float *)out)[done + k] = k < ok ? udm1_to_f32(raw[k]) : NAN;
        }
        done += m;
    }
}

void udm1_cursor_fill(udm1_cursor *cursor, uint32_t n, float *out) { cursor_fill_as("udm1_cursor_fill", cursor, n, out, 0); }
void udm1_cursor_fill_f64(udm1_cursor *cursor, uint32_t n, double *out)
{
    cursor_fill_as("udm1_cursor_fill_f64", cursor, n, out, 1);
}

uint32_t udm1_cursor_padded(const udm1_cursor *cursor) { return cursor ? cursor->padded : 0; }
