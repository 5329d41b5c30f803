/*
 * udm1/domain.h - domains: samplers for the sub-problems of a render, derived from keys, so that a
 * renderer never hands out dimension indices. Part of libudm1's public interface; udm1/udm1.h includes
 * every part. (1.6)
 *
 * A domain is a 32-byte value (a stream, a key, a sample index, a dimension offset), passed and copied
 * freely. It gives up to four dimensions, drawn together; a sub-problem that needs more takes more
 * domains. In a hot loop, derive and draw where the compiler inlines: a domain handed by value to a
 * function it does not inline goes through the stack (above 16 bytes, in the x86-64 and AArch64 ABIs),
 * and its first use waits on a store-forwarding stall; pass the stream pointer and the sample index
 * instead (in udm1-pt's wavefront loop the difference was 7 % of the render time). A path's domains:
 *
 *     udm1_domain px = udm1_domain_root(&stream, sample);     // the pixel's sample: dimensions 0..3
 *     float film[2];  udm1_domain_draw_f32(px, 2, film);
 *     udm1_domain v = px;
 *     for (int depth = 0; ...; ++depth) {
 *         v = udm1_domain_next(v, 1);                           // this vertex: the next four dimensions
 *         float u[4];  udm1_domain_draw_f32(v, 4, u);           // light (u[0], u[1]), BSDF (u[2], u[3])
 *         float rr;    udm1_domain_draw_f32(udm1_domain_child(v, 1), 1, &rr);   // a decorrelated extra
 *     }
 *
 * Two derivations, two rules:
 *  - udm1_domain_next(d, k): the k-th block of four dimensions after d's, with d's index and key. The
 *    domains of one chain of next() are one pattern: their dimensions together are the sequence's jointly
 *    low-discrepancy points (for a Kronecker sequence a point of the whole path, as a cursor would hand
 *    out), up to the stream's count, and padded past the sequence's dimensions (the cursor's rule).
 *  - udm1_domain_child(d, key): a new pattern, decorrelated from its parent and from other keys. A child
 *    draws the sequence's first dimensions again (of its stream, from `first`), randomized by its own
 *    key: a random shift of each dimension (Weyl) or the sequence's randomization keyed by the domain
 *    (the others), and its sample index permuted by a nested uniform (Owen) scramble of the low 32 bits,
 *    so two domains pair their points like two independent stratified sets, not point by point. The
 *    permutation maps every aligned block of 2^k indices onto an aligned block: the first 2^k samples
 *    of a child are 2^k consecutive points of the sequence (for a Kronecker sequence a shifted copy of
 *    its first 2^k points, the same wrap-around discrepancy), and between powers of two a stratified
 *    subset of the next block. Its 2D projections have the sequence's discrepancy.
 *  - The root is the stream itself: udm1_domain_next chains from it draw udm1_stream_draw_* of the same
 *    dimensions (the cursor's values), with no permutation: the camera's dimensions keep the sequence's
 *    order at every count.
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
 * Cost: a child's draw hashes its four dimensions' words (and a child() its key) unless its stream holds
 * them: udm1_stream_init fills, with the stream, the children of keys 0 and 1 of each block of four
 * dimensions on the root's chain - child(next(root, b), 0 or 1), a vertex's decorrelated extras, the same
 * in every sample of the pixel - where they fit (udm1/stream.h, UDM1_STREAM_CHILDREN); their draws are the
 * same values, without the hashes.
 *
 * Which to use: next() along a path keeps a Kronecker sequence's joint structure across the path's
 * decisions (measurably lower error for the Weyl sets than independent domains); child() for what has
 * no place in the chain (optional decisions, splits, other subsystems), so that adding or removing one
 * never shifts the dimensions of another. A point set's index permutation stays inside its K points.
 * Domains of a sequence other than a Weyl sequence without a transform, Sobol or pmj02 (the cases
 * udm1/stream.h draws inline) draw through one library call, udm1_domain_fill_raw.
 */
#ifndef UDM1_DOMAIN_H
#define UDM1_DOMAIN_H

#include "udm1/stream.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct udm1_domain {
    const udm1_stream *stream;
    uint64_t key;      /* 0 for the root's chain; else derived from its parent's key and its own (below) */
    uint64_t index;    /* the sample index */
    uint32_t dim;      /* its first dimension, from the stream's first: 4 per next() */
    uint32_t reserved; /* 0, or a child's slot + 1 in its stream's cache (udm1/stream.h, UDM1_STREAM_CHILDREN): a
                          hint, used only where that slot holds the domain's key */
} udm1_domain;

/* The golden-ratio increment and the 64-bit finalizer (Stafford's Mix13) of the library's hashing: the
 * per-stream shifts of udm1/seq.h, the padding and the domains' keys. Part of the ABI. */
#define UDM1_GOLDEN_GAMMA 0x9E3779B97F4A7C15ull

UDM1_DRAW_ uint64_t udm1_mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* A nested uniform scramble of a 32-bit index: it maps each aligned block of 2^k indices onto an
 * aligned block of 2^k. */
UDM1_DRAW_ uint32_t udm1_owen_index32(uint32_t x, uint32_t seed)
{
    return udm1_reverse32(udm1_owen_hash32(udm1_reverse32(x), seed));
}

/* The root domain of a stream's sample `index`. */
UDM1_DRAW_ udm1_domain udm1_domain_root(const udm1_stream *st, uint64_t index)
{
    udm1_domain d;
    d.stream = st, d.key = 0, d.index = index, d.dim = 0, d.reserved = 0;
    return d;
}

/* The k-th block of four dimensions after d's: same key and index, dim + 4 k (a dim past 2^32 - 1 is
 * kept at the limit: its draws are refused, NaN). */
UDM1_DRAW_ udm1_domain udm1_domain_next(udm1_domain d, uint32_t k)
{
    uint64_t dim = (uint64_t)d.dim + 4u * (uint64_t)k;
    d.dim = dim < 0xFFFFFFFFu ? (uint32_t)dim : 0xFFFFFFFFu;
    return d;
}

/* The child of key `key`: its key is mix64(K + (key + 1) G), K its parent's key (the stream's own for
 * the root's chain: a hash of the seed and the stream, in screen mode of the seed alone) plus its
 * parent's dimension offset, and never 0 (0 becomes G); its dimensions start again at 0. A child the
 * stream holds takes that key from the stream, and its slot as the hint `reserved`. */
UDM1_DRAW_ udm1_domain udm1_domain_child(udm1_domain parent, uint64_t key)
{
    const udm1_stream *st = parent.stream;
    if (!parent.key && st && parent.dim % 4u == 0) { /* a child the stream holds: its key from the stream */
        uint32_t blocks = udm1_stream_child_blocks_(st), b = parent.dim / 4u;
        if (key < udm1_stream_child_kinds_(st) && b < blocks) {
            uint32_t s = (uint32_t)key * blocks + b;
            parent.key = udm1_stream_child_key_(st, s);
            parent.dim = 0;
            parent.reserved = s + 1u;
            return parent;
        }
    }
    uint64_t base = (parent.key ? parent.key : (parent.stream ? parent.stream->key : 0)) + parent.dim;
    uint64_t k = udm1_mix64(base + (key + 1u) * UDM1_GOLDEN_GAMMA);
    parent.key = k ? k : UDM1_GOLDEN_GAMMA;
    parent.dim = 0;
    parent.reserved = 0;
    return parent;
}

/* Sub-sample i of n of the child of key (see the rules above): that child at index parent.index * n + i. */
UDM1_DRAW_ udm1_domain udm1_domain_split(udm1_domain parent, uint64_t key, uint32_t n, uint32_t i)
{
    udm1_domain d = udm1_domain_child(parent, key);
    d.index = parent.index * n + i;
    return d;
}

/* Sub-sample i of an open-ended number: child(child(parent, key), i). */
UDM1_DRAW_ udm1_domain udm1_domain_chain(udm1_domain parent, uint64_t key, uint64_t i)
{
    return udm1_domain_child(udm1_domain_child(parent, key), i);
}

/* The raw values of the domain's first n dimensions (1..4) into raw: any domain, any sequence kind.
 * Errors (raw left unchanged): NULL_ARGUMENT, DIMENSION (n 0 or above 4, a dimension past the index
 * limit), INDEX_RANGE (an index outside a point set). */
UDM1_API udm1_status udm1_domain_fill_raw(const udm1_domain *d, uint32_t n, uint64_t *raw);

/* The same as floats (the conversion of udm1/seq.h), without the low bits a float does not read.
 * Errors as udm1_domain_fill_raw, NULL out (out left unchanged). */
UDM1_API udm1_status udm1_domain_fill_f32(const udm1_domain *d, uint32_t n, float *out);

/* udm1_mix64(add + in[j]) of four values at once, where the compiler targets AVX2 (64-bit products from
 * 32-bit ones, or AVX-512's own): the same values. */
#if defined(UDM1_AVX2_)
UDM1_DRAW_ __m256i udm1_mul64x4_(__m256i a, uint64_t c)
{
#if defined(__AVX512DQ__) && defined(__AVX512VL__)
    return _mm256_mullo_epi64(a, _mm256_set1_epi64x((long long)c));
#else
    __m256i lo = _mm256_set1_epi64x((long long)(c & 0xFFFFFFFFu)), hi = _mm256_set1_epi64x((long long)(c >> 32));
    __m256i cross = _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(a, 32), lo), _mm256_mul_epu32(a, hi));
    return _mm256_add_epi64(_mm256_mul_epu32(a, lo), _mm256_slli_epi64(cross, 32));
#endif
}

UDM1_DRAW_ __m256i udm1_mix64x4_(uint64_t add, const uint64_t *in)
{
    __m256i z = _mm256_add_epi64(_mm256_set1_epi64x((long long)add), _mm256_loadu_si256((const __m256i *)in));
    z = udm1_mul64x4_(_mm256_xor_si256(z, _mm256_srli_epi64(z, 30)), 0xBF58476D1CE4E5B9ull);
    z = udm1_mul64x4_(_mm256_xor_si256(z, _mm256_srli_epi64(z, 27)), 0x94D049BB133111EBull);
    return _mm256_xor_si256(z, _mm256_srli_epi64(z, 31));
}
#endif

UDM1_DRAW_ void udm1_mix64x4(uint64_t add, const uint64_t *in, uint64_t *out)
{
#if defined(UDM1_AVX2_)
    _mm256_storeu_si256((__m256i *)out, udm1_mix64x4_(add, in));
#else
    for (int j = 0; j < 4; ++j) out[j] = udm1_mix64(add + in[j]);
#endif
}

/* Store one of a domain's values as a raw value (out_kind 0), a float (1) or a double (2). */
UDM1_DRAW_ void udm1_put_(int out_kind, void *out, uint32_t j, uint64_t r)
{
    if (out_kind == 1) ((float *)out)[j] = udm1_raw_to_f32(r);
    else if (out_kind == 2) ((double *)out)[j] = udm1_raw_to_f64(r);
    else ((uint64_t *)out)[j] = r;
}

/* Whether a child domain's n dimensions are drawn inline: a Weyl sequence, no point set, dims held. */
UDM1_DRAW_ int udm1_domain_inline_(const udm1_domain *d, uint32_t n)
{
    const udm1_stream *st = d->stream;
    return st && d->key && (st->flags & UDM1_STREAM_INLINE) && n - 1u < 4u && n <= st->held &&
           d->dim <= st->held - n && st->point_count == 0;
}

/* The words mix64(key + K_j), j < 4, of a child domain's dimensions 0..3 where its stream holds them (its
 * hint names a slot that holds its key, udm1/stream.h), else NULL: the draw hashes them. */
UDM1_DRAW_ const uint64_t *udm1_domain_words_(const udm1_domain *d)
{
    const udm1_stream *st = d->stream;
    uint32_t s = d->reserved - 1u;
    if (d->reserved == 0 || d->dim != 0 || s >= udm1_stream_child_kinds_(st) * udm1_stream_child_blocks_(st) ||
        udm1_stream_child_key_(st, s) != d->key)
        return NULL;
    return udm1_stream_child_words_(st, s);
}

/* A child domain's values of dimensions dim .. dim + n - 1 (inline case): its index scrambled, its own
 * shifts. Where the compiler targets AVX2 the four shifts and values stay in one register from the key to
 * the conversion (a wide load of values just stored one by one would wait for them). */
UDM1_DRAW_ void udm1_domain_values_(const udm1_stream *st, uint64_t key, uint64_t index, uint32_t dim, uint32_t n,
                                       const uint64_t *words, int out_kind, void *out)
{
    /* the index scramble (udm1_owen_index32): hashed, then its bits reversed */
    uint32_t hashed = udm1_owen_hash32(udm1_reverse32((uint32_t)index), (uint32_t)(key >> 32)), low = udm1_reverse32(hashed);
    if (index <= 0xFFFFFFFFu && st->index_base == 0 && dim <= UDM1_STREAM_DIMS - 4) { /* (four lanes in the arrays) */
#if defined(UDM1_AVX2_)
        __m256i O = _mm256_add_epi64(words ? _mm256_loadu_si256((const __m256i *)words) : udm1_mix64x4_(key, st->dim_key + dim),
                                     _mm256_loadu_si256((const __m256i *)(st->base + dim)));
        /* the index scramble's final bit reversal in the register that multiplies: the same value, without a
         * trip through a general register */
        __m128i x = udm1_reverse32x4_(_mm_cvtsi32_si128((int)hashed));
        __m256i N = _mm256_broadcastq_epi64(x);
        __m256i H = _mm256_loadu_si256((const __m256i *)(st->a_hi + dim));
        __m256i L = _mm256_loadu_si256((const __m256i *)(st->a_lo + dim));
        __m256i h0 = _mm256_mul_epu32(N, H), h1 = _mm256_mul_epu32(N, _mm256_srli_epi64(H, 32));
        __m256i l0 = _mm256_mul_epu32(N, L), l1 = _mm256_mul_epu32(N, _mm256_srli_epi64(L, 32));
        __m256i carry = _mm256_srli_epi64(_mm256_add_epi64(l1, _mm256_srli_epi64(l0, 32)), 32);
        __m256i v = _mm256_add_epi64(_mm256_add_epi64(O, _mm256_add_epi64(h0, _mm256_slli_epi64(h1, 32))), carry);
        if (out_kind == 1) { /* the top 24 bits of each lane, as floats, in the register */
            __m256i top = _mm256_srli_epi64(v, 40);
            __m128i lo32 = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(top, _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6)));
            __m128 f = _mm_mul_ps(_mm_cvtepi32_ps(lo32), _mm_set1_ps(1.0f / 16777216.0f));
            udm1_store_f32_(f, n, (float *)out);
            return;
        }
        uint64_t r[4];
        _mm256_storeu_si256((__m256i *)r, v);
#elif defined(UDM1_NEON_)
        uint64_t r[4], o[4]; /* the shifts one by one (NEON has no 64-bit product), the values in two vectors */
        for (uint32_t j = 0; j < 4; ++j) o[j] = st->base[dim + j] + (words ? words[j] : udm1_mix64(key + st->dim_key[dim + j]));
        udm1_weyl4_32(st->a_hi + dim, st->a_lo + dim, o, low, r);
#elif defined(UDM1_X86_)
        /* the values in two SSE2 vectors, as above; the shifts from the words held, or hashed one by one and
         * put in the registers (a wide load of values just stored one by one would wait for them) */
        uint64_t r[4];
        __m128i N = _mm_set1_epi64x((long long)low), v[2], O[2];
        if (words) {
            for (int k = 0; k < 2; ++k)
                O[k] = _mm_add_epi64(_mm_loadu_si128((const __m128i *)(words + 2 * k)),
                                     _mm_loadu_si128((const __m128i *)(st->base + dim + 2 * k)));
        } else {
            uint64_t o[4] = {0, 0, 0, 0};
            for (uint32_t j = 0; j < n; ++j) o[j] = st->base[dim + j] + udm1_mix64(key + st->dim_key[dim + j]);
            O[0] = _mm_set_epi64x((long long)o[1], (long long)o[0]), O[1] = _mm_set_epi64x((long long)o[3], (long long)o[2]);
        }
        for (int k = 0; k < 2; ++k) {
            __m128i H = _mm_loadu_si128((const __m128i *)(st->a_hi + dim + 2 * k)), L = _mm_loadu_si128((const __m128i *)(st->a_lo + dim + 2 * k));
            __m128i h0 = _mm_mul_epu32(N, H), h1 = _mm_mul_epu32(N, _mm_srli_epi64(H, 32));
            __m128i l0 = _mm_mul_epu32(N, L), l1 = _mm_mul_epu32(N, _mm_srli_epi64(L, 32));
            __m128i carry = _mm_srli_epi64(_mm_add_epi64(l1, _mm_srli_epi64(l0, 32)), 32);
            v[k] = _mm_add_epi64(_mm_add_epi64(O[k], _mm_add_epi64(h0, _mm_slli_epi64(h1, 32))), carry);
        }
        if (out_kind == 1) { /* the top 24 bits of each lane, as floats, in the register */
            __m128i top = _mm_castps_si128(_mm_shuffle_ps(_mm_castsi128_ps(_mm_srli_epi64(v[0], 40)),
                                                          _mm_castsi128_ps(_mm_srli_epi64(v[1], 40)), 0x88));
            __m128 f = _mm_mul_ps(_mm_cvtepi32_ps(top), _mm_set1_ps(1.0f / 16777216.0f));
            udm1_store_f32_(f, n, (float *)out);
            return;
        }
        _mm_storeu_si128((__m128i *)r, v[0]);
        _mm_storeu_si128((__m128i *)(r + 2), v[1]);
#else
        uint64_t r[4];
        for (uint32_t j = 0; j < n; ++j)
            r[j] = udm1_weyl_value32(st->a_hi[dim + j], st->a_lo[dim + j],
                                     st->base[dim + j] + (words ? words[j] : udm1_mix64(key + st->dim_key[dim + j])), low);
#endif
        for (uint32_t j = 0; j < n; ++j) udm1_put_(out_kind, out, j, r[j]);
        return;
    }
    uint64_t m = ((index & 0xFFFFFFFF00000000ull) | low) + st->index_base; /* (screen mode: the pixel's segment) */
    for (uint32_t j = 0; j < n; ++j)
        udm1_put_(out_kind, out, j,
                  udm1_weyl_value(st->a_hi[dim + j], st->a_lo[dim + j], st->base[dim + j] + udm1_mix64(key + st->dim_key[dim + j]), m));
}

/* Whether the child domain d of a pmj02 stream draws n dimensions inline. */
UDM1_DRAW_ int udm1_domain_pmj02_(const udm1_domain *d, uint32_t n)
{
    const udm1_stream *st = d->stream;
    return st && d->key && (st->flags & UDM1_STREAM_PMJ02) && n - 1u < 4u && n <= st->held &&
           d->dim <= st->held - n && d->index < st->point_count;
}

/* A pmj02 child domain's values (out_kind as udm1_put_): its index permuted inside the K points, its own
 * words. */
UDM1_DRAW_ void udm1_domain_pmj02_values_(const udm1_domain *d, uint32_t n, int out_kind, void *out)
{
    const udm1_stream *st = d->stream;
    uint64_t K = st->point_count, words[4];
    uint32_t m = (uint32_t)d->index;
    if (st->table_bits) {
        do m = udm1_owen_bits(m, (uint32_t)(d->key >> 32), st->table_bits);
        while (m >= K);
    }
    const uint64_t *held = st->table_mode == 1 ? udm1_domain_words_(d) : NULL;
    if (st->table_mode == 1 && !held) udm1_mix64x4(d->key, st->dim_key + d->dim, words);
    udm1_pmj02_values_(st, m, d->dim, n, held ? held : words, st->table_mode == 1, out_kind, out);
}

/* Whether the child domain d of a Sobol stream draws n dimensions inline. */
UDM1_DRAW_ int udm1_domain_sobol_(const udm1_domain *d, uint32_t n)
{
    const udm1_stream *st = d->stream;
    return st && d->key && (st->flags & UDM1_STREAM_SOBOL) && n - 1u < 4u && n <= st->held &&
           d->dim <= st->held - n && d->index <= 0xFFFFFFFFu && d->dim <= UDM1_STREAM_DIMS - 4;
}

/* A Sobol child domain's values (out_kind as udm1_put_): its index scrambled, its own words. */
UDM1_DRAW_ void udm1_domain_sobol_values_(const udm1_domain *d, uint32_t n, int out_kind, void *out)
{
    const udm1_stream *st = d->stream;
    uint32_t m = udm1_owen_index32((uint32_t)d->index, (uint32_t)(d->key >> 32));
    uint64_t own[4] = {0, 0, 0, 0};
    const uint64_t *words = st->table_mode ? udm1_domain_words_(d) : NULL;
    if (!words) {
        if (st->table_mode) udm1_mix64x4(d->key, st->dim_key + d->dim, own);
        words = own;
    }
    if (out_kind == 1 && st->table_mode == 2) udm1_sobol_owen_f32_(st, m ^ (m >> 1), d->dim, n, words, (float *)out);
    else
        for (uint32_t j = 0; j < n; ++j) udm1_put_(out_kind, out, j, udm1_sobol_value_(st, m, d->dim + j, words[j], out_kind != 1));
}

/* A draw through the library (out_kind as udm1_put_), out of line: a refused draw gives 0 (raw) or NaN in
 * its first min(n, 4) outputs. */
UDM1_COLD_ void udm1_domain_library_(udm1_domain d, uint32_t n, int out_kind, void *out)
{
    uint64_t raw[4];
    udm1_status s = out_kind == 1 ? udm1_domain_fill_f32(&d, n, (float *)out) : udm1_domain_fill_raw(&d, n, out ? raw : NULL);
    for (uint32_t j = 0; out && j < n && j < 4; ++j) {
        if (out_kind == 0) ((uint64_t *)out)[j] = s == UDM1_OK ? raw[j] : 0;
        else if (out_kind == 2) ((double *)out)[j] = s == UDM1_OK ? udm1_raw_to_f64(raw[j]) : (double)NAN;
        else if (s != UDM1_OK) ((float *)out)[j] = (float)NAN;
    }
}

/* The domain's first n dimensions (1..4) as raw values, floats or doubles. A draw the library refuses
 * (n outside 1..4 among them) gives 0 (raw) or NaN in its first min(n, 4) outputs and writes nothing else,
 * with udm1_last_error() saying why. */
UDM1_DRAW_ void udm1_domain_draw_raw(udm1_domain d, uint32_t n, uint64_t *raw)
{
    if (!d.key && d.stream && n - 1u < 4u) {
        udm1_stream_draw_raw(d.stream, d.index, d.dim, n, raw);
        return;
    }
    if (udm1_domain_inline_(&d, n)) {
        udm1_domain_values_(d.stream, d.key, d.index, d.dim, n, udm1_domain_words_(&d), 0, raw);
        return;
    }
    if (udm1_domain_pmj02_(&d, n)) {
        udm1_domain_pmj02_values_(&d, n, 0, raw);
        return;
    }
    if (udm1_domain_sobol_(&d, n)) {
        udm1_domain_sobol_values_(&d, n, 0, raw);
        return;
    }
    udm1_domain_library_(d, n, 0, raw);
}

UDM1_DRAW_ void udm1_domain_draw_f32(udm1_domain d, uint32_t n, float *out)
{
    if (d.key && udm1_domain_inline_(&d, n)) {
        udm1_domain_values_(d.stream, d.key, d.index, d.dim, n, udm1_domain_words_(&d), 1, out);
        return;
    }
    if (!d.key && d.stream && n - 1u < 4u) {
        udm1_stream_draw_f32(d.stream, d.index, d.dim, n, out);
        return;
    }
    if (udm1_domain_pmj02_(&d, n)) {
        udm1_domain_pmj02_values_(&d, n, 1, out);
        return;
    }
    if (udm1_domain_sobol_(&d, n)) {
        udm1_domain_sobol_values_(&d, n, 1, out);
        return;
    }
    udm1_domain_library_(d, n, 1, out);
}

UDM1_DRAW_ void udm1_domain_draw_f64(udm1_domain d, uint32_t n, double *out)
{
    if (d.key && udm1_domain_inline_(&d, n)) {
        udm1_domain_values_(d.stream, d.key, d.index, d.dim, n, udm1_domain_words_(&d), 2, out);
        return;
    }
    if (!d.key && d.stream && n - 1u < 4u) {
        udm1_stream_draw_f64(d.stream, d.index, d.dim, n, out);
        return;
    }
    if (udm1_domain_pmj02_(&d, n)) {
        udm1_domain_pmj02_values_(&d, n, 2, out);
        return;
    }
    if (udm1_domain_sobol_(&d, n)) {
        udm1_domain_sobol_values_(&d, n, 2, out);
        return;
    }
    udm1_domain_library_(d, n, 2, out);
}

#ifdef __cplusplus
}
#endif

#endif /* UDM1_DOMAIN_H */
