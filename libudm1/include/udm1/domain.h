/*
 * udm1/domain.h - domains: samplers for the sub-problems of a render, derived from keys, so that a
 * renderer never hands out dimension indices. Part of libudm1's public interface; udm1/udm1.h includes
 * every part. (1.6)
 *
 * A domain is a 24-byte value (a stream, a key, a sample index), passed and copied freely. It gives up
 * to four dimensions, drawn together; a sub-problem that needs more takes more domains:
 *
 *     udm1_domain px = udm1_domain_root(&stream, sample);   // the pixel's sample
 *     float film[2];  udm1_domain_draw_f32(px, 2, film);     // the root: the stream's dimensions 0, 1
 *     for (int depth = 0; ...; ++depth) {
 *         udm1_domain v = udm1_domain_child(px, 100 + depth);  // this vertex
 *         float u[4];  udm1_domain_draw_f32(v, 4, u);           // light (u[0], u[1]), BSDF (u[2], u[3])
 *         float rr;    udm1_domain_draw_f32(udm1_domain_child(v, 1), 1, &rr);
 *     }
 *
 * The rules:
 *  - Within a domain, the dimensions drawn together are low-discrepancy jointly, across the samples of
 *    a stream: a domain's 4D pattern is the sequence's first four dimensions (those of its stream, from
 *    `first`), so its 2D projections have the sequence's discrepancy.
 *  - Different keys give decorrelated domains. A child's pattern is the same set randomized by its own
 *    key: a random shift of each dimension (Weyl) or the sequence's randomization keyed by the domain
 *    (the others), and its sample index permuted by a nested uniform (Owen) scramble of the low 32 bits,
 *    so two domains pair their points like two independent stratified sets, not point by point. The
 *    index permutation maps every aligned block of 2^k indices onto an aligned block: the first 2^k
 *    samples of a child domain are 2^k consecutive points of the sequence (for a Kronecker sequence a
 *    shifted copy of its first 2^k points, the same wrap-around discrepancy), and between powers of two
 *    a stratified subset of the next block.
 *  - The root is the stream itself: its draws equal udm1_stream_draw_* of dimensions 0..3 (the cursor's
 *    values), with no permutation: the camera's dimensions keep the sequence's order at every count.
 *  - Keys are any 64-bit numbers; siblings need distinct keys, which may be 0, 1, 2, ... A chain
 *    child(child(d, a), b) is another domain than child(d, b). Equal derivations give equal domains in
 *    every pixel, sample, thread and run.
 *  - udm1_domain_split(d, key, n, i), i < n: the n sub-samples of d's sample (samples d.index * n + i of
 *    the child of key): together over all samples one globally well-distributed pattern of n times the
 *    samples, and for n a power of two each sample's n sub-samples are consecutive points of it.
 *  - udm1_domain_chain(d, key, i): sub-sample i when their number is not fixed: child(child(d, key), i).
 *  - Screen-space randomization (UDM1_RANDOMIZE_SCREEN): the keys do not depend on the pixel, and a
 *    child's index is its permuted sample index after the pixel's segment (m N, udm1/seq.h), so that in
 *    every domain neighbouring pixels take consecutive segments of one shifted sequence: the error stays
 *    blue noise in every dimension, and each pixel stays unbiased over seeds.
 *
 * Draws past the sequence's dimensions are padded with hashed values (the cursor's rule), and a point
 * set's index permutation stays inside its K points. Domains of a sequence other than a Weyl sequence
 * without a transform (see udm1/stream.h) draw through one library call, udm1_domain_fill_raw.
 */
#ifndef UDM1_DOMAIN_H
#define UDM1_DOMAIN_H

#include "udm1/stream.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct udm1_domain {
    const udm1_stream *stream;
    uint64_t key;    /* 0 for the root; else derived from its parent's key and its own (below) */
    uint64_t index;  /* the sample index */
} udm1_domain;

/* The golden-ratio increment and the 64-bit finalizer (Stafford's Mix13) of the library's hashing: the
 * per-stream shifts of udm1/seq.h, the padding and the domains' keys. Part of the ABI. */
#define UDM1_GOLDEN_GAMMA 0x9E3779B97F4A7C15ull

static inline uint64_t udm1_mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* A nested uniform scramble of a 32-bit index: it maps each aligned block of 2^k indices onto an
 * aligned block of 2^k. */
static inline uint32_t udm1_owen_index32(uint32_t x, uint32_t seed)
{
    return udm1_reverse32(udm1_owen_hash32(udm1_reverse32(x), seed));
}

/* The root domain of a stream's sample `index`. */
static inline udm1_domain udm1_domain_root(const udm1_stream *st, uint64_t index)
{
    udm1_domain d;
    d.stream = st, d.key = 0, d.index = index;
    return d;
}

/* The child of key `key`: its key is mix64(K + (key + 1) G), K its parent's key (the stream's own for
 * the root: a hash of the seed and the stream, in screen mode of the seed alone), and never 0 (0 becomes
 * G). */
static inline udm1_domain udm1_domain_child(udm1_domain parent, uint64_t key)
{
    uint64_t base = parent.key ? parent.key : (parent.stream ? parent.stream->key : 0);
    uint64_t k = udm1_mix64(base + (key + 1u) * UDM1_GOLDEN_GAMMA);
    parent.key = k ? k : UDM1_GOLDEN_GAMMA;
    return parent;
}

/* Sub-sample i of n of the child of key (see the rules above): that child at index parent.index * n + i. */
static inline udm1_domain udm1_domain_split(udm1_domain parent, uint64_t key, uint32_t n, uint32_t i)
{
    udm1_domain d = udm1_domain_child(parent, key);
    d.index = parent.index * n + i;
    return d;
}

/* Sub-sample i of an open-ended number: child(child(parent, key), i). */
static inline udm1_domain udm1_domain_chain(udm1_domain parent, uint64_t key, uint64_t i)
{
    return udm1_domain_child(udm1_domain_child(parent, key), i);
}

/* The raw values of the domain's first n dimensions (1..4) into raw: any domain, any sequence kind.
 * Errors (raw left unchanged): NULL_ARGUMENT, DIMENSION (n 0 or above 4). */
UDM1_API udm1_status udm1_domain_fill_raw(const udm1_domain *d, uint32_t n, uint64_t *raw);

/* The same as floats (the conversion of udm1/seq.h), without the low bits a float does not read.
 * Errors as udm1_domain_fill_raw, NULL out. */
UDM1_API udm1_status udm1_domain_fill_f32(const udm1_domain *d, uint32_t n, float *out);

/* Whether the child domain d draws n dimensions inline (a Weyl sequence, no point set, held dims). */
static inline int udm1_domain_inline_(const udm1_domain *d, uint32_t n)
{
    const udm1_stream *st = d->stream;
    return st && d->key && (st->flags & UDM1_STREAM_INLINE) && n <= 4 && n <= st->held && st->point_count == 0;
}

/* udm1_mix64(add + in[j]) of four values at once, where the compiler targets AVX2 (64-bit products from 32-bit ones,
 * or AVX-512's own): the same values. */
#if defined(__AVX2__)
static inline __m256i udm1_mul64x4_(__m256i a, uint64_t c)
{
#if defined(__AVX512DQ__) && defined(__AVX512VL__)
    return _mm256_mullo_epi64(a, _mm256_set1_epi64x((long long)c));
#else
    __m256i lo = _mm256_set1_epi64x((long long)(c & 0xFFFFFFFFu)), hi = _mm256_set1_epi64x((long long)(c >> 32));
    __m256i cross = _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(a, 32), lo), _mm256_mul_epu32(a, hi));
    return _mm256_add_epi64(_mm256_mul_epu32(a, lo), _mm256_slli_epi64(cross, 32));
#endif
}

static inline void udm1_mix64x4(uint64_t add, const uint64_t *in, uint64_t *out)
{
    __m256i z = _mm256_add_epi64(_mm256_set1_epi64x((long long)add), _mm256_loadu_si256((const __m256i *)in));
    z = udm1_mul64x4_(_mm256_xor_si256(z, _mm256_srli_epi64(z, 30)), 0xBF58476D1CE4E5B9ull);
    z = udm1_mul64x4_(_mm256_xor_si256(z, _mm256_srli_epi64(z, 27)), 0x94D049BB133111EBull);
    _mm256_storeu_si256((__m256i *)out, _mm256_xor_si256(z, _mm256_srli_epi64(z, 31)));
}
#else
static inline void udm1_mix64x4(uint64_t add, const uint64_t *in, uint64_t *out)
{
    for (int j = 0; j < 4; ++j) out[j] = udm1_mix64(add + in[j]);
}
#endif

/* A child domain's values of dimensions 0..n-1 (inline case) as raw values (out_kind 0), floats (1) or
 * doubles (2): its index scrambled, its own shifts. Where the compiler targets AVX2 the four shifts and
 * values stay in one register from the key to the conversion (a wide load of values just stored one by
 * one would wait for them). */
static inline void udm1_domain_values_(const udm1_stream *st, uint64_t key, uint64_t index, uint32_t n, int out_kind,
                                       void *out)
{
    uint32_t low = udm1_owen_index32((uint32_t)index, (uint32_t)(key >> 32));
    if (index <= 0xFFFFFFFFu && st->index_base == 0) {
#if defined(__AVX2__)
        __m256i z = _mm256_add_epi64(_mm256_set1_epi64x((long long)key), _mm256_loadu_si256((const __m256i *)st->domain_key));
        z = udm1_mul64x4_(_mm256_xor_si256(z, _mm256_srli_epi64(z, 30)), 0xBF58476D1CE4E5B9ull);
        z = udm1_mul64x4_(_mm256_xor_si256(z, _mm256_srli_epi64(z, 27)), 0x94D049BB133111EBull);
        z = _mm256_xor_si256(z, _mm256_srli_epi64(z, 31));
        __m256i O = _mm256_add_epi64(z, _mm256_loadu_si256((const __m256i *)st->domain_base));
        __m256i N = _mm256_set1_epi64x((long long)low);
        __m256i H = _mm256_loadu_si256((const __m256i *)st->a_hi), L = _mm256_loadu_si256((const __m256i *)st->a_lo);
        __m256i h0 = _mm256_mul_epu32(N, H), h1 = _mm256_mul_epu32(N, _mm256_srli_epi64(H, 32));
        __m256i l0 = _mm256_mul_epu32(N, L), l1 = _mm256_mul_epu32(N, _mm256_srli_epi64(L, 32));
        __m256i carry = _mm256_srli_epi64(_mm256_add_epi64(l1, _mm256_srli_epi64(l0, 32)), 32);
        __m256i v = _mm256_add_epi64(_mm256_add_epi64(O, _mm256_add_epi64(h0, _mm256_slli_epi64(h1, 32))), carry);
        if (out_kind == 1 && n == 4) { /* the top 24 bits of each lane, as floats, in the register */
            __m256i top = _mm256_srli_epi64(v, 40);
            __m128i lo32 = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(top, _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6)));
            _mm_storeu_ps((float *)out, _mm_mul_ps(_mm_cvtepi32_ps(lo32), _mm_set1_ps(1.0f / 16777216.0f)));
            return;
        }
        uint64_t r[4];
        _mm256_storeu_si256((__m256i *)r, v);
#else
        uint64_t r[4];
        for (uint32_t j = 0; j < n; ++j)
            r[j] = udm1_weyl_value32(st->a_hi[j], st->a_lo[j], st->domain_base[j] + udm1_mix64(key + st->domain_key[j]), low);
#endif
        for (uint32_t j = 0; j < n; ++j) {
            if (out_kind == 1) ((float *)out)[j] = udm1_raw_to_f32(r[j]);
            else if (out_kind == 2) ((double *)out)[j] = udm1_raw_to_f64(r[j]);
            else ((uint64_t *)out)[j] = r[j];
        }
        return;
    }
    uint64_t m = ((index & 0xFFFFFFFF00000000ull) | low) + st->index_base; /* (screen mode: the pixel's segment) */
    for (uint32_t j = 0; j < n; ++j) {
        uint64_t r = udm1_weyl_value(st->a_hi[j], st->a_lo[j], st->domain_base[j] + udm1_mix64(key + st->domain_key[j]), m);
        if (out_kind == 1) ((float *)out)[j] = udm1_raw_to_f32(r);
        else if (out_kind == 2) ((double *)out)[j] = udm1_raw_to_f64(r);
        else ((uint64_t *)out)[j] = r;
    }
}

/* Whether the child domain d of a pmj02 stream draws n dimensions inline. */
static inline int udm1_domain_pmj02_(const udm1_domain *d, uint32_t n)
{
    const udm1_stream *st = d->stream;
    return st && d->key && (st->flags & UDM1_STREAM_PMJ02) && n <= 4 && n <= st->held && d->index < st->point_count;
}

/* A pmj02 child domain's values (out_kind as udm1_pmj02_values_): its index permuted inside the K
 * points, its own words. */
static inline void udm1_domain_pmj02_values_(const udm1_domain *d, uint32_t n, int out_kind, void *out)
{
    const udm1_stream *st = d->stream;
    uint64_t K = st->point_count, words[4];
    uint32_t m = (uint32_t)d->index;
    if (st->table_bits) {
        do m = udm1_owen_bits(m, (uint32_t)(d->key >> 32), st->table_bits);
        while (m >= K);
    }
    if (st->table_xor) udm1_mix64x4(d->key, st->domain_key, words);
    udm1_pmj02_values_(st, m, 0, n, words, (int)st->table_xor, out_kind, out);
}

/* The domain's first n dimensions (1..4) as raw values, floats or doubles. A draw the library refuses
 * gives 0 (raw) or NaN, with udm1_last_error() saying why. */
static inline void udm1_domain_draw_raw(udm1_domain d, uint32_t n, uint64_t *raw)
{
    if (!d.key && d.stream) {
        udm1_stream_draw_raw(d.stream, d.index, 0, n <= 4 ? n : 4, raw);
        return;
    }
    if (udm1_domain_inline_(&d, n)) {
        udm1_domain_values_(d.stream, d.key, d.index, n, 0, raw);
        return;
    }
    if (udm1_domain_pmj02_(&d, n)) {
        udm1_domain_pmj02_values_(&d, n, 0, raw);
        return;
    }
    if (udm1_domain_fill_raw(&d, n, raw) != UDM1_OK)
        for (uint32_t j = 0; j < n && j < 4; ++j) raw[j] = 0;
}

static inline void udm1_domain_draw_f32(udm1_domain d, uint32_t n, float *out)
{
    if (d.key && udm1_domain_inline_(&d, n)) {
        udm1_domain_values_(d.stream, d.key, d.index, n, 1, out);
        return;
    }
    if (!d.key && d.stream) {
        udm1_stream_draw_f32(d.stream, d.index, 0, n <= 4 ? n : 4, out);
        return;
    }
    if (udm1_domain_pmj02_(&d, n)) {
        udm1_domain_pmj02_values_(&d, n, 1, out);
        return;
    }
    if (udm1_domain_fill_f32(&d, n, out) != UDM1_OK)
        for (uint32_t j = 0; j < n && j < 4; ++j) out[j] = (float)NAN;
}

static inline void udm1_domain_draw_f64(udm1_domain d, uint32_t n, double *out)
{
    uint64_t raw[4];
    if (d.key && udm1_domain_inline_(&d, n)) {
        udm1_domain_values_(d.stream, d.key, d.index, n, 2, out);
        return;
    }
    if (!d.key && d.stream) {
        udm1_stream_draw_f64(d.stream, d.index, 0, n <= 4 ? n : 4, out);
        return;
    }
    if (udm1_domain_pmj02_(&d, n)) {
        udm1_domain_pmj02_values_(&d, n, 2, out);
        return;
    }
    int ok = udm1_domain_fill_raw(&d, n, raw) == UDM1_OK;
    for (uint32_t j = 0; j < n && j < 4; ++j) out[j] = ok ? udm1_raw_to_f64(raw[j]) : NAN;
}

#ifdef __cplusplus
}
#endif

#endif /* UDM1_DOMAIN_H */
