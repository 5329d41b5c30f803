/* stream.c - udm1_stream (udm1/stream.h): a stream's per-dimension words for the inline draws, and the
 * library's own draw for every case they do not cover. */

/* udm1_stream.flags, private: offset[] holds the randomization words of a base-2 kind; or a_lo[], offset[]
 * and a_hi[] the words of a kind's pin (seq/seq.h) */
#define STREAM_WORDS 0x100u
#define STREAM_PINNED 0x200u
#include "samplers/samplers.h"
#include "seq/scramble.h"
#include "seq/value.h"
#include "weyl/screen.h"

#include <string.h>

/* The child domains of keys 0 and 1 of each block of four dimensions held on the root's chain (a vertex's
 * decorrelated extras: udm1-pt's lobe and roulette, its first medium piece; the README's example), where
 * they fit in the entries past `held` (udm1/stream.h, UDM1_STREAM_CHILDREN): their keys and their
 * dimensions' words, so that their draws hash nothing. Keys and words as udm1/domain.h derives them. Each
 * costs five hashes per stream, what one draw of it costs without the cache. */
static void stream_children(udm1_stream *s)
{
    if (!(s->flags & (UDM1_STREAM_INLINE | UDM1_STREAM_PMJ02 | UDM1_STREAM_SOBOL)) || s->held == 0) return;
    uint32_t blocks = udm1_stream_child_blocks_(s), room = (UDM1_STREAM_DIMS - s->held) / 4;
    uint32_t kinds = 2 * room / blocks < 2 ? 2 * room / blocks : 2;
    for (uint32_t c = 0; c < kinds; ++c)
        for (uint32_t b = 0; b < blocks; ++b) {
            uint32_t slot = c * blocks + b;
            uint64_t key = udm1_domain_child(udm1_domain_next(udm1_domain_root(s, 0), b), c).key;
            /* (the stream's own spare entries, written where udm1/stream.h's readers find them) */
            udm1_mix64x4(key, s->dim_key, (uint64_t *)udm1_stream_child_words_(s, slot));
            s->dim_key[UDM1_STREAM_DIMS - 1 - slot] = key;
        }
    s->flags |= kinds * UDM1_STREAM_CHILDREN;
}

/* A base-2 kind's randomization words of dimensions first .. first + n - 1 for the stream key skey (0 without
 * randomization), udm1_word four at a time */
static void stream_words(const udm1_seq *seq, uint64_t skey, uint32_t first, uint32_t n, uint64_t *words)
{
    if (seq->mode == UDM1_MODE_NONE || seq->mode == UDM1_MODE_STREAMS)
        memset(words, 0, sizeof(uint64_t) * n);
    else
        udm1_mix64_many(seq->dim_key + first, skey, words, n);
}

udm1_status udm1_stream_init(udm1_stream *st, const udm1_seq *seq, uint64_t stream, uint32_t first, uint32_t count)
{
    static const char fn[] = "udm1_stream_init";
    if (!st || !seq) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, st ? "seq" : "st");
    if (count == 0 || count > UDM1_STREAM_DIMS)
        return udm1_fail(UDM1_ERROR_DIMENSION, "%s: count %u is outside 1..%u (UDM1_STREAM_DIMS)", fn, count,
                         UDM1_STREAM_DIMS);
    if (first >= UDM1_DIMENSION_INDEX_LIMIT || count > UDM1_DIMENSION_INDEX_LIMIT - first)
        return udm1_fail(UDM1_ERROR_DIMENSION, "%s: first_dimension %u + count %u passes the dimension index limit",
                         fn, first, count);
    udm1_stream *s = st; /* filled in place: every error is found above */
    memset(s, 0, sizeof *s);
    s->struct_size = (uint32_t)sizeof *s;
    s->seq = seq;
    s->stream = stream;
    /* the domains' root key: the stream's hashed key; in screen mode one key for every pixel, so that a
     * child domain of neighbouring pixels is consecutive segments of one sequence too (udm1/domain.h) */
    s->key = udm1_stream_key(seq->seed_key, seq->mode == UDM1_MODE_SCREEN ? UINT64_MAX : stream);
    s->point_count = seq->point_count;
    s->first = first;
    s->count = count;
    s->dimensions = seq->dims;
    uint64_t skey = udm1_seq_stream_key(seq, stream);
    uint32_t own = first >= seq->dims ? 0 : seq->dims - first < count ? seq->dims - first : count;
    if (seq->kind == &udm1_weyl_kind) { /* modes none, shift, screen: the inline arithmetic */
        s->flags = UDM1_STREAM_INLINE;
        s->index_base = udm1_screen_index(seq, skey, 0);
        s->held = own;
        if (seq->mode == UDM1_MODE_SHIFT) /* the shifts mix64(T + K_j), four at a time */
            udm1_mix64_many(seq->dim_key + first, skey, s->offset, own);
        for (uint32_t j = 0; j < s->held; ++j) {
            uint32_t dim = first + j;
            s->a_hi[j] = seq->gen[dim].hi;
            s->a_lo[j] = seq->gen[dim].lo;
            s->offset[j] = seq->offset[dim] + (seq->mode == UDM1_MODE_SHIFT ? s->offset[j] : udm1_weyl_shift(seq, skey, dim));
        }
    } else if (seq->kind->base2 || seq->kind == &udm1_weyl_scrambled_kind) {
        /* a base-2 randomization on top of the kind's value: the stream's words found once */
        s->flags = STREAM_WORDS;
        s->held = own;
        stream_words(seq, skey, first, own, s->offset);
        /* pmj02 and Sobol without base offsets, unrandomized or digitally shifted (Sobol also Owen-scrambled):
         * drawn inline from their tables */
        int zero = 1;
        for (uint32_t j = 0; zero && j < s->held; ++j) zero = seq->offset[first + j] == 0;
        uint32_t mode = seq->mode == UDM1_MODE_NONE ? 0 : seq->mode == UDM1_MODE_PERMUTE ? 1 : seq->mode == UDM1_MODE_OWEN ? 2 : 3;
        uint32_t byte_dims = 0;
        const void *sobol = udm1_sobol_stream_table(seq, mode == 2, &byte_dims);
        if (zero && mode <= 1 && (s->table = udm1_pmj02_stream_table(seq, &s->table_bits)) != NULL) {
            s->flags |= UDM1_STREAM_PMJ02;
            s->table_mode = mode;
        } else if (zero && mode <= 2 && sobol && first + s->held <= byte_dims) {
            s->flags |= UDM1_STREAM_SOBOL;
            s->table = sobol;
            s->table_bits = byte_dims;
            s->table_mode = mode;
        }
    } else if (seq->kind->pin) { /* words per dimension for the library's draws */
        uint64_t key = seq->mode == UDM1_MODE_SCREEN ? stream : s->key; /* (the key the draws use) */
        int pinned = 1;
        for (uint32_t j = 0; pinned && j < own; ++j)
            pinned = seq->kind->pin(seq, key, first + j, &s->a_lo[j], &s->offset[j], &s->a_hi[j]);
        if (pinned && own) {
            s->flags = STREAM_PINNED;
            s->held = own;
        } else {
            memset(s->a_lo, 0, sizeof s->a_lo);
            memset(s->offset, 0, sizeof s->offset);
            memset(s->a_hi, 0, sizeof s->a_hi);
        }
    }
    for (uint32_t j = 0; j < own; ++j) { /* progressive screen mode: the pixel's shift is part of the base */
        s->base[j] = seq->offset[first + j] + (seq->screen_gen ? udm1_screen_pixel_shift(seq, stream, first + j) : 0);
        s->dim_key[j] = seq->dim_key[first + j];
    }
    stream_children(s);
    return UDM1_OK;
}

/* The checks of a draw of dimensions [first + dim, first + dim + n) at index into out: the status of the
 * first bad input, with a message naming fn. */
static udm1_status stream_check(const char *fn, const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n,
                                const void *out, const char *out_name)
{
    if (!st || !st->seq || !out)
        return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, !st ? "st" : !out ? out_name : "st->seq");
    const udm1_seq *seq = st->seq;
    if (seq->point_count && index >= seq->point_count)
        return udm1_fail(UDM1_ERROR_INDEX_RANGE, "%s: index %llu of a %llu-point set", fn, (unsigned long long)index,
                         (unsigned long long)seq->point_count);
    uint64_t d0 = (uint64_t)st->first + dim;
    if (d0 + n > UDM1_DIMENSION_INDEX_LIMIT)
        return udm1_fail(UDM1_ERROR_DIMENSION, "%s: dimensions from %llu, %u of them, pass the dimension index limit",
                         fn, (unsigned long long)d0, n);
    return UDM1_OK;
}

/* The raw values of a draw; with low_half 0 a base-2 Owen-scrambled kind may leave the low 32 bits 0
 * (a float reads the top 24). */
udm1_status udm1_stream_fill(const char *fn, const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n,
                             uint64_t *raw, int low_half)
{
    udm1_status checked = stream_check(fn, st, index, dim, n, raw, "raw");
    if (checked != UDM1_OK || n == 0) return checked;
    const udm1_seq *seq = st->seq;
    uint64_t d0 = (uint64_t)st->first + dim;
    uint64_t found[64];
    const uint64_t *words = NULL; /* base-2 kinds: the randomization words of the draw's dimensions */
    if ((st->flags & STREAM_WORDS) && dim < st->held && n <= st->held - dim)
        words = st->offset + dim; /* found by udm1_stream_init */
    else if ((st->flags & STREAM_WORDS) && n <= 64 && d0 + n <= seq->dims) { /* past them: as the init finds them */
        stream_words(seq, seq->mode == UDM1_MODE_SCREEN ? st->stream : st->key, (uint32_t)d0, n, found);
        words = found;
    }
    if (words) {
        uint64_t skey = st->key;
        if (seq->kind == &udm1_weyl_scrambled_kind) {
            for (uint32_t j = 0; j < n; ++j) {
                uint32_t d = st->first + dim + j;
                raw[j] = udm1_randomize_base2(seq->mode, udm1_weyl_raw(&seq->gen[d], seq->offset[d], index), words[j]);
            }
        } else {
            if (seq->kind->base2_point)
                seq->kind->base2_point(seq, skey, index, st->first + dim, n, raw);
            else
                for (uint32_t j = 0; j < n; ++j) raw[j] = seq->kind->base2(seq, skey, index, st->first + dim + j);
            if (seq->mode == UDM1_MODE_OWEN)
                udm1_owen64_many(raw, words, raw, n, low_half);
            else
                for (uint32_t j = 0; j < n; ++j) raw[j] = udm1_randomize_base2(seq->mode, raw[j], words[j]);
        }
        return UDM1_OK;
    }
    if ((st->flags & STREAM_PINNED) && dim < st->held && n <= st->held - dim) {
        for (uint32_t j = 0; j < n; ++j)
            raw[j] = seq->kind->pinned(seq, index, st->first + dim + j, st->a_lo[dim + j], st->offset[dim + j],
                                       st->a_hi[dim + j]);
        return UDM1_OK;
    }
    uint64_t key = seq->mode == UDM1_MODE_SCREEN ? st->stream : st->key; /* udm1_seq_stream_key, without the hash */
    udm1_cursor c;
    udm1_cursor_init(&c, seq, st->stream, index, (uint32_t)d0, key);
    udm1_cursor_raw(&c, n, raw);
    return UDM1_OK;
}

udm1_status udm1_stream_fill_raw(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n, uint64_t *raw)
{
    return udm1_stream_fill("udm1_stream_fill_raw", st, index, dim, n, raw, 1);
}

udm1_status udm1_stream_fill_f32(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n, float *out)
{
    static const char fn[] = "udm1_stream_fill_f32";
    uint64_t raw[64];
    if (n <= 4) { /* the common draw (n 0: the checks only) */
        udm1_status s = out ? udm1_stream_fill(fn, st, index, dim, n, raw, 0) : stream_check(fn, st, index, dim, n, out, "out");
        for (uint32_t j = 0; s == UDM1_OK && j < n; ++j) out[j] = udm1_to_f32(raw[j]);
        return s;
    }
    /* the whole range checked before the first chunk is written: no chunk can fail after it */
    udm1_status checked = stream_check(fn, st, index, dim, n, out, "out");
    if (checked != UDM1_OK) return checked;
    for (uint32_t done = 0; done < n;) {
        uint32_t m = n - done < 64 ? n - done : 64;
        udm1_stream_fill(fn, st, index, dim + done, m, raw, 0);
        for (uint32_t j = 0; j < m; ++j) out[done + j] = udm1_to_f32(raw[j]);
        done += m;
    }
    return UDM1_OK;
}
