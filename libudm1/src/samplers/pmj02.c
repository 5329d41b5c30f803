/* pmj02.c - progressive multi-jittered (0,2) sequences (Christensen, Kensler,
 * Kilpatrick, "Progressive Multi-Jittered Sample Sequences", EGSR 2018), with
 * the stratum search of Pharr ("Efficient Generation of Points that Satisfy
 * Two-Dimensional Elementary Intervals", JCGT 2019).
 *
 * Tables of K points (32-bit coordinates) are built at creation, one per pair
 * of dimensions, from a PCG32 stream keyed by (seed, pair). With n = 4^k
 * points placed, each alone in its cell of the 2^k x 2^k grid:
 *  (a) for each old point, a new one in the diagonally opposite subcell of its
 *      cell (2n points);
 *  (b) for each old point, a new one in the horizontally adjacent subcell;
 *  (c) for each point of (b), a new one in its diagonally opposite subcell.
 * Inside the chosen subcell, x and y are drawn uniformly among the strata that
 * keep every elementary interval of the new power of two empty: the finer
 * x-strata only meet grids with few y-bits, whose rows the subcell fixes, and
 * the other way round, so x and y are chosen independently by walking down
 * the occupied-cell bitsets (Pharr). Every prefix of 2^m points is then a
 * (0,m,2)-net in base 2, and so is every aligned block of 2^m points;
 * tests/c/test_baselines.c checks both.
 */
#include "samplers/samplers.h"
#include "seq/scramble.h"

#include <stdlib.h>
#include <string.h>

typedef struct rng { uint64_t state, inc; } rng;

static uint32_t rng_next(rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ull + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18) ^ old) >> 27), rot = (uint32_t)(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

static uint32_t rng_below(rng *r, uint32_t n) /* uniform in [0, n), n >= 1 */
{
    uint32_t threshold = (0u - n) % n, x;
    do x = rng_next(r);
    while (x < threshold);
    return x % n;
}

typedef struct builder {
    uint32_t m;        /* the target: 2^m points */
    uint64_t *grids;   /* m + 1 bitsets of 2^m cells: grid i has 2^i columns, 2^(m-i) rows */
    size_t words;      /* 64-bit words per grid */
    uint32_t *leaves;  /* scratch for valid strata */
    uint32_t nleaves;
    rng r;
} builder;

static size_t cell(uint32_t m, uint32_t i, uint32_t x, uint32_t y) { return ((size_t)x << (m - i)) | y; }

static int occupied(const builder *b, uint32_t i, uint32_t x, uint32_t y)
{
    size_t c = cell(b->m, i, x, y);
    return (int)((b->grids[(size_t)i * b->words + c / 64] >> (c % 64)) & 1u);
}

static void mark(builder *b, uint32_t X, uint32_t Y)
{
    for (uint32_t i = 0; i <= b->m; ++i) {
        uint32_t x = i ? X >> (32 - i) : 0, y = (b->m - i) ? Y >> (32 - (b->m - i)) : 0;
        size_t c = cell(b->m, i, x, y);
        b->grids[(size_t)i * b->words + c / 64] |= 1ull << (c % 64);
    }
}

static int set_target(builder *b, uint32_t m, const uint32_t *xs, const uint32_t *ys, uint32_t count)
{
    b->m = m;
    b->words = ((size_t)1 << m) / 64 + 1;
    free(b->grids);
    b->grids = calloc((size_t)(m + 1) * b->words, sizeof(uint64_t));
    if (!b->grids) return 0;
    for (uint32_t k = 0; k < count; ++k) mark(b, xs[k], ys[k]);
    return 1;
}

/* x strata: extend the prefix one bit per grid, from grid h to grid m, keeping
 * the cells whose row (the top m-i bits of y, fixed by the subcell) is free */
static void walk_x(builder *b, uint32_t i, uint32_t prefix, uint32_t hy, uint32_t h)
{
    if (occupied(b, i, prefix, hy >> (h - (b->m - i)))) return;
    if (i == b->m) {
        b->leaves[b->nleaves++] = prefix;
        return;
    }
    walk_x(b, i + 1, prefix << 1, hy, h);
    walk_x(b, i + 1, (prefix << 1) | 1u, hy, h);
}

/* y strata: the same with the axes swapped (grid i has m-i y-bits) */
static void walk_y(builder *b, uint32_t i, uint32_t prefix, uint32_t hx, uint32_t h)
{
    if (occupied(b, i, hx >> (h - i), prefix)) return;
    if (i == 0) {
        b->leaves[b->nleaves++] = prefix;
        return;
    }
    walk_y(b, i - 1, prefix << 1, hx, h);
    walk_y(b, i - 1, (prefix << 1) | 1u, hx, h);
}

/* Place a point in subcell (hx, hy) at h = ceil(m/2) bits per axis. */
static int place(builder *b, uint32_t hx, uint32_t hy, uint32_t *X, uint32_t *Y)
{
    uint32_t m = b->m, h = (m + 1) / 2;
    b->nleaves = 0;
    walk_x(b, h, hx, hy, h);
    if (b->nleaves == 0) return 0;
    uint32_t xs = b->leaves[rng_below(&b->r, b->nleaves)];
    b->nleaves = 0;
    walk_y(b, m - h, hy, hx, h);
    if (b->nleaves == 0) return 0;
    uint32_t ys = b->leaves[rng_below(&b->r, b->nleaves)];
    *X = m ? (xs << (32 - m)) | (rng_next(&b->r) >> m) : rng_next(&b->r);
    *Y = m ? (ys << (32 - m)) | (rng_next(&b->r) >> m) : rng_next(&b->r);
    mark(b, *X, *Y);
    return 1;
}

static uint32_t top(uint32_t v, uint32_t bits) { return bits ? v >> (32 - bits) : 0; }

/* Fill xs, ys with K points of a pmj02 sequence. Returns 0 on failure. */
static int build(uint32_t *xs, uint32_t *ys, uint32_t K, uint64_t key)
{
    builder b;
    memset(&b, 0, sizeof b);
    b.r.inc = (udm1_mix64(key) << 1) | 1u;
    b.r.state = udm1_mix64(key ^ 0x504D4A3032ull) + b.r.inc;
    b.leaves = malloc(sizeof(uint32_t) * (K + 2));
    int ok = b.leaves != NULL;
    xs[0] = rng_next(&b.r);
    ys[0] = rng_next(&b.r);
    uint32_t count = 1;
    for (uint32_t k = 0; ok && count < K; ++k) {
        uint32_t n = 1u << (2 * k), h = k + 1;
        /* (a) diagonally opposite subcells: 2n points, m = 2k + 1 */
        ok = set_target(&b, 2 * k + 1, xs, ys, count);
        for (uint32_t j = 0; ok && j < n && count < K; ++j, ++count)
            ok = place(&b, top(xs[j], h) ^ 1u, top(ys[j], h) ^ 1u, &xs[count], &ys[count]);
        if (!ok || count >= K) break;
        /* (b) horizontally adjacent subcells, then (c) their diagonal opposites: m = 2k + 2 */
        ok = set_target(&b, 2 * k + 2, xs, ys, count);
        uint32_t first_b = count;
        for (uint32_t j = 0; ok && j < n && count < K; ++j, ++count)
            ok = place(&b, top(xs[j], h) ^ 1u, top(ys[j], h), &xs[count], &ys[count]);
        for (uint32_t j = 0; ok && j < n && count < K; ++j, ++count)
            ok = place(&b, top(xs[first_b + j], h) ^ 1u, top(ys[first_b + j], h) ^ 1u, &xs[count], &ys[count]);
    }
    free(b.grids);
    free(b.leaves);
    return ok;
}

typedef struct pmj02 {
    uint32_t pairs;
    uint32_t bits;  /* m with 2^m >= K */
    uint32_t xy[1]; /* blocks of 4 dimensions x K x 4: dimension d of point i is xy[d / 4][i][d % 4] (pairs
                     * after the first stored shuffled; an odd last pair's block padded with zeros) */
} pmj02;

/* Pairs k >= 1 read their points in a shuffled order: the index, as an m-bit
 * fraction, Owen-scrambled (Burley's shuffle), walking again while past K.
 * Owen scrambling maps aligned blocks of 2^a indices onto aligned blocks, and
 * every aligned block of a PMJ02 table is itself a (0,a,2)-net, so every
 * power-of-two prefix of every pair stays stratified, while the pairs are
 * decorrelated (the same index no longer means the same stratum pattern).
 * The table stores each pair in its shuffled order (made once, at creation),
 * so a value is one load. */
static uint64_t shuffled(uint32_t bits, uint64_t K, uint32_t key, uint64_t index)
{
    if (bits == 0) return index;
    uint32_t sh = 32 - bits, j = (uint32_t)index;
    do j = udm1_owen32(j << sh, key) >> sh;
    while (j >= K);
    return j;
}

static uint64_t pmj02_base2(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    (void)skey;
    const pmj02 *t = seq->data;
    uint64_t v = (uint64_t)t->xy[((dim / 4) * seq->point_count + index) * 4 + dim % 4] << 32;
    return v + seq->offset[dim];
}

/* pmj02_base2 of dimensions dim0 .. dim0 + m - 1 */
static void pmj02_base2_point(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim0, uint32_t m,
                              uint64_t *raw)
{
    (void)skey;
    const pmj02 *t = seq->data;
    for (uint32_t j = 0; j < m; ++j) {
        uint32_t dim = dim0 + j;
        raw[j] = ((uint64_t)t->xy[((dim / 4) * seq->point_count + index) * 4 + dim % 4] << 32) + seq->offset[dim];
    }
}

static uint64_t pmj02_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    return udm1_randomize_base2(seq->mode, pmj02_base2(seq, skey, index, dim), udm1_word(seq, skey, dim));
}

udm1_status udm1_init_pmj02(udm1_seq_t *seq)
{
    uint64_t K = seq->point_count;
    uint32_t pairs = (seq->dims + 1) / 2;
    if (K > (1u << 20) || K * pairs > (1u << 24))
        return udm1_fail(UDM1_ERROR_POINT_COUNT,
                         "udm1_seq_create: pmj02 takes K <= 2^20 and K x pairs <= 2^24, got K = %llu with %u pairs",
                         (unsigned long long)K, pairs);
    pmj02 *t = calloc(1, sizeof(pmj02) + sizeof(uint32_t) * 4 * K * ((pairs + 1) / 2));
    uint32_t *xs = malloc(sizeof(uint32_t) * K), *ys = malloc(sizeof(uint32_t) * K);
    int ok = t && xs && ys;
    uint32_t bits = 0;
    while (((uint64_t)1 << bits) < K) ++bits;
    for (uint32_t p = 0; ok && p < pairs; ++p) {
        ok = build(xs, ys, (uint32_t)K, seq->seed_key ^ udm1_mix64(0x504D4A3032ull + p));
        uint32_t key = udm1_key32(seq->seed_key, 0x504D4A53u, p);
        for (uint64_t i = 0; ok && i < K; ++i) {
            uint64_t at = p ? shuffled(bits, K, key, i) : i;
            t->xy[((p / 2) * K + i) * 4 + (p % 2) * 2] = xs[at];
            t->xy[((p / 2) * K + i) * 4 + (p % 2) * 2 + 1] = ys[at];
        }
    }
    free(xs);
    free(ys);
    if (!ok) {
        free(t);
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "udm1_seq_create: out of memory for pmj02 tables");
    }
    t->pairs = pairs;
    t->bits = bits;
    seq->data = t;
    return UDM1_OK;
}

const udm1_kind udm1_pmj02_kind = {.name = "pmj02", .value = pmj02_value, .base2 = pmj02_base2,
                                   .base2_point = pmj02_base2_point};

const uint32_t *udm1_pmj02_stream_table(const udm1_seq_t *seq, uint32_t *bits)
{
    if (seq->kind != &udm1_pmj02_kind) return NULL;
    const pmj02 *t = seq->data;
    *bits = t->bits;
    return t->xy;
}
