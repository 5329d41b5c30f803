/* domain.c - udm1_domain_fill_raw (udm1/domain.h): a domain's values for every sequence kind - the
 * root through its stream, a child as its sequence at (the child's key as stream key, the permuted
 * index); the header's inline draws give the same values for Weyl sequences. */
#include "seq/scramble.h"
#include "seq/value.h"

/* A nested uniform scramble of the k-bit index v (v < 2^k, k <= 32): the bit-reversed value hashed
 * modulo 2^k (each step a bijection) and reversed back; k = 32 is udm1_owen_index32. */
static uint32_t owen_bits(uint32_t v, uint32_t seed, unsigned k)
{
    if (k == 0) return 0;
    uint32_t mask = k == 32 ? 0xFFFFFFFFu : (1u << k) - 1u;
    uint32_t x = udm1_owen_hash32(udm1_reverse32(v) >> (32 - k), seed) & mask;
    return udm1_reverse32(x) >> (32 - k);
}

/* The child's index: the low 32 bits scrambled for a sequence; for a point set of K points a
 * permutation of [0, K): the scramble of ceil(log2 K) bits, cycle-walked back into [0, K). */
static uint64_t permuted_index(uint64_t index, uint64_t K, uint32_t seed)
{
    if (!K) return (index & 0xFFFFFFFF00000000ull) | udm1_owen_index32((uint32_t)index, seed);
    unsigned k = 0;
    while (k < 32 && (1ull << k) < K) ++k;
    uint32_t v = (uint32_t)index;
    do v = owen_bits(v, seed, k);
    while (v >= K);
    return v;
}

/* A draw's raw values; with low_half 0 an Owen-scrambled base-2 kind may leave the low 32 bits 0. */
static udm1_status domain_fill(const char *fn, const udm1_domain *d, uint32_t n, uint64_t *raw, int low_half)
{
    if (!d || !d->stream || !d->stream->seq || !raw)
        return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn,
                         !d ? "d" : !raw ? "raw" : !d->stream ? "d->stream" : "d->stream->seq");
    if (n == 0 || n > 4) return udm1_fail(UDM1_ERROR_DIMENSION, "%s: n = %u is outside 1..4", fn, n);
    const udm1_stream *st = d->stream;
    if (!d->key) return udm1_stream_fill(fn, st, d->index, d->dim, n, raw, low_half); /* the root's chain: the stream */
    const udm1_seq *seq = st->seq;
    if (seq->point_count && d->index >= seq->point_count)
        return udm1_fail(UDM1_ERROR_INDEX_RANGE, "%s: index %llu of a %llu-point set", fn,
                         (unsigned long long)d->index, (unsigned long long)seq->point_count);
    uint64_t first64 = (uint64_t)st->first + d->dim;
    if (first64 + n > UDM1_DIMENSION_INDEX_LIMIT)
        return udm1_fail(UDM1_ERROR_DIMENSION, "%s: dimensions from %llu, %u of them, pass the dimension index limit", fn,
                         (unsigned long long)first64, n);
    uint32_t first = (uint32_t)first64;
    uint64_t key = d->key, m = permuted_index(d->index, seq->point_count, (uint32_t)(key >> 32));
    uint32_t inside = first >= seq->dims ? 0 : seq->dims - first < n ? seq->dims - first : n;
    if (seq->kind == &udm1_weyl_kind) { /* its own shift; in screen mode after the pixel's segment base
                                           (fixed N) or on top of the pixel's shift (progressive) */
        for (uint32_t j = 0; j < inside; ++j) {
            uint32_t dim = first + j;
            uint64_t pixel = seq->screen_gen ? udm1_screen_pixel_shift(seq, st->stream, dim) : 0;
            raw[j] = udm1_weyl_raw(&seq->gen[dim], seq->offset[dim] + pixel + udm1_shift(key, seq->dim_key[dim]),
                                   m + st->index_base);
        }
    } else if (inside && seq->kind->base2) { /* the values, then the domain's words on them */
        uint64_t word[4];
        if (seq->kind->base2_point)
            seq->kind->base2_point(seq, key, m, first, inside, raw);
        else
            for (uint32_t j = 0; j < inside; ++j) raw[j] = seq->kind->base2(seq, key, m, first + j);
        if (seq->mode == UDM1_MODE_NONE || seq->mode == UDM1_MODE_STREAMS)
            for (uint32_t j = 0; j < inside; ++j) word[j] = 0;
        else /* udm1_word of the four dimensions at once */
            udm1_mix64_many(seq->dim_key + first, key, word, inside);
        if (seq->mode == UDM1_MODE_OWEN)
            udm1_owen64_many(raw, word, raw, inside, low_half);
        else
            for (uint32_t j = 0; j < inside; ++j) raw[j] = udm1_randomize_base2(seq->mode, raw[j], word[j]);
    } else if (inside && seq->kind->fill) {
        seq->kind->fill(seq, key, m, 1, first, inside, raw);
    } else {
        for (uint32_t j = 0; j < inside; ++j) raw[j] = udm1_value_of(seq, key, m, first + j);
    }
    for (uint32_t j = inside; j < n; ++j) /* padding: the cursor's rule, the domain's key as the stream's */
        raw[j] = udm1_pad(udm1_shift(key, udm1_dim_key(seq->seed_key, first + j)), d->index);
    return UDM1_OK;
}

udm1_status udm1_domain_fill_raw(const udm1_domain *d, uint32_t n, uint64_t *raw)
{
    return domain_fill("udm1_domain_fill_raw", d, n, raw, 1);
}

udm1_status udm1_domain_fill_f32(const udm1_domain *d, uint32_t n, float *out)
{
    uint64_t raw[4];
    if (!out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_domain_fill_f32: out is NULL");
    udm1_status s = domain_fill("udm1_domain_fill_f32", d, n, raw, 0);
    if (s == UDM1_OK)
        for (uint32_t j = 0; j < n; ++j) out[j] = udm1_to_f32(raw[j]);
    return s;
}
