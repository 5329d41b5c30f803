/* test_stream.c - udm1/stream.h and udm1/domain.h:
 *  - a stream's draws (inline where they apply, through the library elsewhere) equal the cursor, for
 *    every preset and randomization, every output type, indices below and above 2^32 and at the top of
 *    the range, dimensions held, not held (past the stream's count too) and padded; a point set's index
 *    past K is NaN and an error;
 *  - a root domain is its stream's dimensions 0..3; a child's inline draws equal udm1_domain_fill_raw
 *    (the library's own computation) bit for bit, and every kind's draws are its raw values converted;
 *  - a child's index permutation of a point set is a permutation of its K points;
 *  - statistics: a child domain's 2D projection has the discrepancy of the sequence's own points, and
 *    sibling domains are decorrelated within each pixel (thresholds justified where they are tested).
 * Built also with -mavx2 and with AVX-512 flags (c.stream_inline_*): the header's vector paths, which the
 * caller's compiler flags choose, give the same values.
 */
#include "check.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the tests' name for UDM1_RANDOMIZE_SCREEN with desc.screen_spp = 0 (progressive); SCREEN itself is
 * tested with screen_spp = 16 */
#define SCREEN_PROGRESSIVE (UDM1_RANDOMIZE_SCREEN + 1u)

static udm1_seq *variant(const udm1_preset_info *info, uint32_t dims, uint32_t randomize)
{
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    desc.preset = info->name, desc.dimensions = info->max_dimensions < dims ? info->max_dimensions : dims;
    desc.point_count = (info->flags & UDM1_PRESET_POINT_SET) ? 64 : 0;
    desc.seed = 11, desc.randomize = randomize == SCREEN_PROGRESSIVE ? UDM1_RANDOMIZE_SCREEN : randomize;
    if (randomize == UDM1_RANDOMIZE_SCREEN) desc.screen_spp = 16;
    udm1_seq *s = NULL;
    return udm1_seq_create_desc(&desc, &s) == UDM1_OK ? s : NULL;
}

/* the cursor's n raw values from (stream, index, dim) */
static void cursor_raw(const udm1_seq *s, uint64_t stream, uint64_t index, uint32_t dim, uint32_t n, double *f64,
                       float *f32)
{
    udm1_cursor c;
    CHECK_STATUS(udm1_cursor_start(&c, s, stream, index, dim), UDM1_OK);
    for (uint32_t j = 0; j < n; ++j) f64[j] = udm1_cursor_1d_f64(&c);
    CHECK_STATUS(udm1_cursor_start(&c, s, stream, index, dim), UDM1_OK);
    for (uint32_t j = 0; j < n; ++j) f32[j] = udm1_cursor_1d(&c);
}

static void test_stream_equals_cursor(void)
{
    static const uint64_t streams[] = {5, ((uint64_t)7 << 32) | 3};
    /* (2186, 2187 and 100000: about and past a radical inverse's first split in base 3, radical_inverse.h) */
    static const uint64_t seqs[] = {0, 1, 999, 2186, 2187, 100000, 0xFFFFFFFFull, 0x100000000ull, (1ull << 40) + 3, UINT64_MAX};
    static const uint32_t firsts[] = {0, 3}, counts[] = {1, 9, 20};
    int inline_seen = 0, library_seen = 0;
    for (size_t p = 0; p < udm1_preset_count(); ++p) {
        udm1_preset_info info;
        udm1_preset_get(p, &info);
        for (uint32_t r = UDM1_RANDOMIZE_NONE; r <= SCREEN_PROGRESSIVE; ++r) {
            udm1_seq *s = variant(&info, 9, r);
            if (!s) continue;
            uint64_t K = udm1_seq_point_count(s);
            for (size_t a = 0; a < 2; ++a)
                for (size_t f = 0; f < 2; ++f)
                    for (size_t c = 0; c < 3; ++c) {
                        udm1_stream st;
                        CHECK_STATUS(udm1_stream_init(&st, s, streams[a], firsts[f], counts[c]), UDM1_OK);
                        (st.flags & UDM1_STREAM_INLINE) ? ++inline_seen : ++library_seen;
                        for (size_t i = 0; i < sizeof seqs / sizeof seqs[0]; ++i) {
                            uint64_t index = K ? seqs[i] % K : seqs[i];
                            /* (past the stream's count too: dimensions of the sequence it does not hold) */
                            for (uint32_t dim = 0, end = counts[c] + 8; dim < end; dim += 2) {
                                uint32_t n = end - dim < 4 ? end - dim : 4;
                                double want64[4], got64[4];
                                float want32[4], got32[4];
                                uint64_t raw[4];
                                cursor_raw(s, streams[a], index, firsts[f] + dim, n, want64, want32);
                                udm1_stream_draw_f64(&st, index, dim, n, got64);
                                udm1_stream_draw_f32(&st, index, dim, n, got32);
                                udm1_stream_draw_raw(&st, index, dim, n, raw);
                                int same = memcmp(want64, got64, n * sizeof(double)) == 0 &&
                                           memcmp(want32, got32, n * sizeof(float)) == 0;
                                for (uint32_t j = 0; j < n; ++j)
                                    same = same && udm1_raw_to_f64(raw[j]) == want64[j];
                                CHECKF(same, "%s randomize %u stream %llu first %u count %u index %llu dim %u", info.name,
                                       r, (unsigned long long)streams[a], firsts[f], counts[c],
                                       (unsigned long long)index, dim);
                            }
                        }
                        if (K) { /* an index past a point set: NaN and a message, nothing else */
                            float v[2] = {0, 0};
                            udm1_stream_draw_f32(&st, K, 0, 1, v);
                            CHECK(isnan(v[0]) && v[1] == 0);
                            CHECK(strstr(udm1_last_error(), ": index") != NULL);
                        }
                    }
            udm1_seq_destroy(s);
        }
    }
    CHECK(inline_seen > 0 && library_seen > 0);
    /* errors */
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("wr", 4, 0, 1, &s), UDM1_OK);
    udm1_stream st;
    memset(&st, 0x5A, sizeof st);
    CHECK_STATUS(udm1_stream_init(&st, s, 0, 0, 0), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_stream_init(&st, s, 0, 0, UDM1_STREAM_DIMS + 1), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_stream_init(&st, s, 0, UDM1_DIMENSION_INDEX_LIMIT - 1, 2), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_stream_init(NULL, s, 0, 0, 2), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_stream_init(&st, NULL, 0, 0, 2), UDM1_ERROR_NULL_ARGUMENT);
    CHECK(st.struct_size == 0x5A5A5A5Au); /* left unchanged */
    float v = 0;
    udm1_stream_draw_f32(NULL, 0, 0, 1, &v);
    CHECK(isnan(v));
    udm1_seq_destroy(s);
}

static void test_domains_agree(void)
{
    int inline_seen = 0;
    for (size_t p = 0; p < udm1_preset_count(); ++p) {
        udm1_preset_info info;
        udm1_preset_get(p, &info);
        for (uint32_t r = UDM1_RANDOMIZE_NONE; r <= SCREEN_PROGRESSIVE; ++r) {
            udm1_seq *s = variant(&info, 6, r);
            if (!s) continue;
            uint64_t K = udm1_seq_point_count(s);
            for (uint32_t first = 0; first < 5; first += 4) {
                udm1_stream st;
                CHECK_STATUS(udm1_stream_init(&st, s, 77, first, 8), UDM1_OK);
                for (uint64_t i = 0; i < 40; ++i) {
                    uint64_t index = K ? i % K : (i < 20 ? i : i * 0x9E3779B97F4A7C15ull);
                    udm1_domain root = udm1_domain_root(&st, index);
                    /* the root is the stream's dimensions 0..3 */
                    double a[4], b[4];
                    udm1_domain_draw_f64(root, 4, a);
                    udm1_stream_draw_f64(&st, index, 0, 4, b);
                    CHECKF(memcmp(a, b, sizeof a) == 0, "%s root", info.name);
                    /* the root's chain of next() is the stream's dimensions */
                    udm1_domain_draw_f64(udm1_domain_next(root, 1), 4, a);
                    udm1_stream_draw_f64(&st, index, 4, 4, b);
                    CHECKF(memcmp(a, b, sizeof a) == 0, "%s root next", info.name);
                    udm1_domain ds[5] = {udm1_domain_child(root, i % 3), udm1_domain_split(root, 5, 4, (uint32_t)i % 4),
                                         udm1_domain_chain(root, 2, i), udm1_domain_next(udm1_domain_child(root, 1), 1),
                                         udm1_domain_child(udm1_domain_next(root, 1), 1)};
                    if (K && ds[1].index >= K) { /* a split past a point set's K points: refused */
                        uint64_t lib[4];
                        CHECK_STATUS(udm1_domain_fill_raw(&ds[1], 4, lib), UDM1_ERROR_INDEX_RANGE);
                        ds[1] = ds[0];
                    }
                    for (int k = 0; k < 5; ++k) {
                        uint64_t lib[4], raw[4];
                        float f[4];
                        double g[4];
                        CHECK_STATUS(udm1_domain_fill_raw(&ds[k], 4, lib), UDM1_OK);
                        inline_seen += udm1_domain_inline_(&ds[k], 4);
                        udm1_domain_draw_raw(ds[k], 4, raw);
                        udm1_domain_draw_f32(ds[k], 4, f);
                        udm1_domain_draw_f64(ds[k], 3, g);
                        int same = memcmp(lib, raw, sizeof lib) == 0;
                        for (int j = 0; j < 4; ++j) same = same && f[j] == udm1_raw_to_f32(lib[j]) && f[j] < 1.0f;
                        for (int j = 0; j < 3; ++j) same = same && g[j] == udm1_raw_to_f64(lib[j]);
                        CHECKF(same, "%s randomize %u first %u index %llu domain %d", info.name, r, first,
                               (unsigned long long)index, k);
                        /* fewer dimensions: a prefix of the same values */
                        uint64_t two[2];
                        udm1_domain_draw_raw(ds[k], 2, two);
                        CHECK(two[0] == lib[0] && two[1] == lib[1]);
                    }
                    /* a child of the next block is another domain than the child of the first */
                    CHECK(udm1_domain_child(udm1_domain_next(root, 1), 1).key != udm1_domain_child(root, 1).key);
                    /* a child's values differ from its parent's and its sibling's */
                    uint64_t c0[4], c1[4];
                    udm1_domain_draw_raw(udm1_domain_child(root, 0), 4, c0);
                    udm1_domain_draw_raw(udm1_domain_child(root, 1), 4, c1);
                    CHECK(memcmp(c0, c1, sizeof c0) != 0);
                }
            }
            udm1_seq_destroy(s);
        }
    }
    CHECK(inline_seen > 0);
    /* errors */
    udm1_domain none = {NULL, 1, 0, 0, 0};
    uint64_t raw[4];
    CHECK_STATUS(udm1_domain_fill_raw(&none, 2, raw), UDM1_ERROR_NULL_ARGUMENT);
    float f = 0;
    udm1_domain_draw_f32(none, 1, &f);
    CHECK(isnan(f));
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("sobol-owen", 4, 0, 1, &s), UDM1_OK);
    udm1_stream st;
    CHECK_STATUS(udm1_stream_init(&st, s, 0, 0, 4), UDM1_OK);
    udm1_domain d = udm1_domain_child(udm1_domain_root(&st, 0), 1);
    CHECK_STATUS(udm1_domain_fill_raw(&d, 5, raw), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_domain_fill_raw(&d, 0, raw), UDM1_ERROR_DIMENSION);
    udm1_seq_destroy(s);
}

/* The derivations as udm1/domain.h documents them (tests/python/test_domains.py pins the values of the
 * domains they reach against the independent reference) */
static void test_derivations(void)
{
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("wr", 4, 0, 9, &s), UDM1_OK);
    udm1_stream st;
    CHECK_STATUS(udm1_stream_init(&st, s, 42, 0, 8), UDM1_OK);
    const uint64_t G = UDM1_GOLDEN_GAMMA;
    udm1_domain root = udm1_domain_root(&st, 7);
    CHECK(root.key == 0 && root.index == 7 && root.dim == 0);
    udm1_domain c = udm1_domain_child(root, 5);
    CHECK(c.key == udm1_mix64(st.key + 6 * G) && c.index == 7 && c.dim == 0);
    udm1_domain n = udm1_domain_next(c, 2);
    CHECK(n.key == c.key && n.dim == 8 && n.index == 7);
    CHECK(udm1_domain_child(n, 1).key == udm1_mix64(c.key + 8 + 2 * G) && udm1_domain_child(n, 1).dim == 0);
    CHECK(udm1_domain_child(udm1_domain_next(root, 1), 0).key == udm1_mix64(st.key + 4 + G));
    udm1_domain sp = udm1_domain_split(n, 3, 4, 2);
    CHECK(sp.key == udm1_mix64(c.key + 8 + 4 * G) && sp.index == 7 * 4 + 2);
    CHECK(udm1_domain_chain(root, 2, 9).key == udm1_mix64(udm1_mix64(st.key + 3 * G) + 10 * G));
    CHECK(udm1_domain_next(root, 0x40000000u).dim == 0xFFFFFFFFu); /* kept at the limit, not wrapped */
    float v[2];
    udm1_domain_draw_f32(udm1_domain_next(root, 0x40000000u), 2, v);
    CHECK(isnan(v[0]) && isnan(v[1]));
    udm1_seq_destroy(s);
}

static void test_point_set_permutation(void)
{
    /* hammersley's dimension 0 unrandomized is i/K: a child's values over its K samples are each i/K once */
    static const uint64_t Ks[] = {1, 2, 3, 64, 100, 1000};
    for (size_t t = 0; t < sizeof Ks / sizeof Ks[0]; ++t) {
        uint64_t K = Ks[t];
        udm1_seq_desc desc;
        udm1_seq_desc_init(&desc);
        desc.preset = "hammersley", desc.dimensions = 2, desc.point_count = K, desc.randomize = UDM1_RANDOMIZE_NONE;
        udm1_seq *s = NULL;
        CHECK_STATUS(udm1_seq_create_desc(&desc, &s), UDM1_OK);
        udm1_stream st;
        CHECK_STATUS(udm1_stream_init(&st, s, 9, 0, 2), UDM1_OK);
        char *seen = calloc(K, 1);
        int moved = 0;
        for (uint64_t i = 0; i < K; ++i) {
            uint64_t raw[1];
            udm1_domain d = udm1_domain_child(udm1_domain_root(&st, i), 4);
            CHECK_STATUS(udm1_domain_fill_raw(&d, 1, raw), UDM1_OK);
            uint64_t k = (uint64_t)floor(udm1_raw_to_f64(raw[0]) * (double)K + 0.5); /* i/K back to i */
            CHECKF(k < K && !seen[k], "K = %llu: sample %llu gives point %llu twice or outside", (unsigned long long)K,
                   (unsigned long long)i, (unsigned long long)k);
            if (k < K) seen[k] = 1;
            moved += k != i;
        }
        CHECK(K < 8 || moved > 0);
        free(seen);
        udm1_seq_destroy(s);
    }
}

/* N points of dimensions (0, 1) of a domain over samples 0..N-1 */
static void domain_points(const udm1_stream *st, uint64_t key, int child, uint32_t N, double *xy)
{
    for (uint32_t i = 0; i < N; ++i) {
        udm1_domain d = udm1_domain_root(st, i);
        if (child) d = udm1_domain_child(d, key);
        udm1_domain_draw_f64(d, 2, xy + 2 * i);
    }
}

static void test_domain_discrepancy(void)
{
    /* A child's first 2^k samples are 2^k consecutive points of the sequence, shifted: the wrap-around
     * discrepancy (shift-invariant) equals that of the sequence's own first 2^k points up to the
     * rounding of the doubles. Between powers of two the set is the previous power's run plus a nested
     * random subset of the next run: its discrepancy lies between the sequence's own and that of random
     * points (1-10x the sequence's own here); asserted below the expectation for random points. */
    static const char *names[] = {"wr", "rd", "wopt"};
    static const uint32_t Ns[] = {64, 256, 100, 300};
    for (int t = 0; t < 3; ++t) {
        udm1_seq_desc desc;
        udm1_seq_desc_init(&desc);
        desc.preset = names[t], desc.dimensions = 4, desc.randomize = UDM1_RANDOMIZE_NONE;
        udm1_seq *plain = NULL, *s = NULL;
        CHECK_STATUS(udm1_seq_create_desc(&desc, &plain), UDM1_OK);
        CHECK_STATUS(udm1_seq_create(names[t], 4, 0, 3, &s), UDM1_OK);
        udm1_stream st;
        CHECK_STATUS(udm1_stream_init(&st, s, 12, 0, 4), UDM1_OK);
        for (int k = 0; k < 4; ++k) {
            uint32_t N = Ns[k];
            double *own = malloc(sizeof(double) * 2 * N), *dom = malloc(sizeof(double) * 2 * N), w0, w1, wr;
            CHECK_STATUS(udm1_seq_fill_f64(plain, 0, 0, N, 0, 2, own, 2), UDM1_OK);
            CHECK_STATUS(udm1_discrepancy(own, N, 2, 2, UDM1_DISCREPANCY_WRAP_AROUND, &w0), UDM1_OK);
            CHECK_STATUS(udm1_discrepancy_random(N, 2, UDM1_DISCREPANCY_WRAP_AROUND, &wr), UDM1_OK);
            for (uint64_t key = 0; key < 8; ++key) {
                domain_points(&st, key, 1, N, dom);
                CHECK_STATUS(udm1_discrepancy(dom, N, 2, 2, UDM1_DISCREPANCY_WRAP_AROUND, &w1), UDM1_OK);
                int pow2 = (N & (N - 1)) == 0;
                CHECKF(pow2 ? fabs(w1 - w0) <= 1e-9 * w0 : w1 < wr, "%s N %u key %llu: WD %.6g, the sequence's %.6g",
                       names[t], N, (unsigned long long)key, w1, w0);
            }
            free(own), free(dom);
        }
        udm1_seq_destroy(plain), udm1_seq_destroy(s);
    }
    /* sobol-owen: a child's first 2^m samples are a (0, m)-net in dimensions (0, 1): each of the 2^m
     * elementary boxes of every shape 2^a x 2^(m-a) holds exactly one point */
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("sobol-owen", 4, 0, 5, &s), UDM1_OK);
    udm1_stream st;
    CHECK_STATUS(udm1_stream_init(&st, s, 3, 0, 4), UDM1_OK);
    enum { M = 8, N = 1 << M };
    double xy[2 * N];
    for (uint64_t key = 0; key < 4; ++key) {
        domain_points(&st, key, 1, N, xy);
        for (int a = 0; a <= M; ++a) {
            int count[N] = {0}, ok = 1;
            for (int i = 0; i < N; ++i) {
                int bx = (int)(xy[2 * i] * (1 << a)), by = (int)(xy[2 * i + 1] * (1 << (M - a)));
                if (++count[bx * (1 << (M - a)) + by] > 1) ok = 0;
            }
            CHECKF(ok, "sobol-owen domain %llu: boxes 2^%d x 2^%d hold more than one point", (unsigned long long)key, a,
                   M - a);
        }
    }
    udm1_seq_destroy(s);
}

/* Pearson correlation of n pairs */
static double correlation(const double *x, const double *y, int n)
{
    double mx = 0, my = 0, sxy = 0, sxx = 0, syy = 0;
    for (int i = 0; i < n; ++i) mx += x[i], my += y[i];
    mx /= n, my /= n;
    for (int i = 0; i < n; ++i) {
        sxy += (x[i] - mx) * (y[i] - my);
        sxx += (x[i] - mx) * (x[i] - mx);
        syy += (y[i] - my) * (y[i] - my);
    }
    return sxy / sqrt(sxx * syy);
}

static void test_domain_decorrelation(void)
{
    /* Two siblings of one sample, over P pixels of N samples each: the within-pixel correlation r of a
     * dimension of one with a dimension of the other. For independent uniform pairs r has mean 0 and
     * variance 1/(N - 1); over P = 4096 pixels the mean of r then has standard deviation
     * sqrt(1 / (15 * 4096)) = 0.004, so |mean r| < 0.02 is a 5-sigma bound on a linear dependence. The
     * mean of r^2 (the variance of r; relative standard deviation about sqrt(2 / P) = 2 %) shows any
     * dependence: 1.0-1.2x the independent value for the Weyl sequences and the PRNG, up to 1.55x for the
     * base-2 constructions (Sobol, Halton, PMJ02: their values and the index permutation share the dyadic
     * digit tree), so 2 / (N - 1) is the bound. The negative control - the same generator with
     * independent shifts but no index permutation, a Kronecker sequence's failure mode - exceeds it. Point
     * sets have K = N, their intended use. */    enum { P = 4096, N = 16 };
    static const char *names[] = {"wr", "rd", "wopt", "sobol-owen", "pmj02", "halton-owen", "pcg32", "cmj", "lattice"};
    static double x[N], y[N];
    for (int t = 0; t < 9; ++t) {
        udm1_preset_info info;
        CHECK_STATUS(udm1_preset_find(names[t], &info), UDM1_OK);
        udm1_seq *s = NULL;
        CHECK_STATUS(udm1_seq_create(names[t], 4, (info.flags & UDM1_PRESET_POINT_SET) ? N : 0, 21, &s), UDM1_OK);
        for (int dx = 0; dx < 2; ++dx) {
            double sum = 0, sum2 = 0;
            for (uint64_t p = 0; p < P; ++p) {
                udm1_stream st;
                CHECK_STATUS(udm1_stream_init(&st, s, p, 0, 4), UDM1_OK);
                for (int i = 0; i < N; ++i) {
                    udm1_domain root = udm1_domain_root(&st, (uint64_t)i);
                    double a[2], b[2];
                    udm1_domain_draw_f64(udm1_domain_child(root, 10), 2, a);
                    udm1_domain_draw_f64(udm1_domain_child(root, 11), 2, b);
                    x[i] = a[dx], y[i] = b[0];
                }
                double r = correlation(x, y, N);
                sum += r, sum2 += r * r;
            }
            double mean = sum / P, var = sum2 / P;
            CHECKF(fabs(mean) < 0.02 && var < 2.0 / (N - 1), "%s: sibling dims (%d, 0): mean r %.4f, mean r^2 %.4f",
                   names[t], dx, mean, var);
        }
        udm1_seq_destroy(s);
    }
    /* the negative control: wr dimension 0 with two independent shifts and no index permutation */
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("wr", 1, 0, 21, &s), UDM1_OK);
    double sum2 = 0;
    for (uint64_t p = 0; p < P; ++p) {
        for (int i = 0; i < N; ++i) {
            CHECK_STATUS(udm1_seq_sample_f64(s, 2 * p, (uint64_t)i, 0, &x[i]), UDM1_OK);
            CHECK_STATUS(udm1_seq_sample_f64(s, 2 * p + 1, (uint64_t)i, 0, &y[i]), UDM1_OK);
        }
        double r = correlation(x, y, N);
        sum2 += r * r;
    }
    CHECKF(sum2 / P > 2.0 / (N - 1), "the negative control passes: mean r^2 %.4f", sum2 / P);
    udm1_seq_destroy(s);
}

/* Streams that start deep in a long sequence (the inline Sobol and pmj02 draws read tables by dimension: their
 * far dimensions too, and a stream past them through the library), every randomization, against the cursor. */
static void test_far_streams(void)
{
    static const char *const presets[] = {"sobol", "sobol-owen", "pmj02", "wr"};
    static const uint32_t firsts[] = {60, 190, 250, 300};
    for (size_t p = 0; p < sizeof presets / sizeof presets[0]; ++p) {
        udm1_preset_info info;
        CHECK_STATUS(udm1_preset_find(presets[p], &info), UDM1_OK);
        for (uint32_t r = UDM1_RANDOMIZE_NONE; r <= UDM1_RANDOMIZE_OWEN; ++r) {
            udm1_seq *s = variant(&info, 320, r);
            if (!s) continue;
            uint64_t K = udm1_seq_point_count(s);
            for (size_t f = 0; f < sizeof firsts / sizeof firsts[0]; ++f) {
                udm1_stream st;
                CHECK_STATUS(udm1_stream_init(&st, s, 9, firsts[f], 16), UDM1_OK);
                for (uint64_t index = 0; index < 300; index += 7)
                    for (uint32_t dim = 0; dim < 16; dim += 4) {
                        uint64_t i = K ? index % K : index * 997;
                        double want64[4], got64[4];
                        float want32[4], got32[4];
                        cursor_raw(s, 9, i, firsts[f] + dim, 4, want64, want32);
                        udm1_stream_draw_f64(&st, i, dim, 4, got64);
                        udm1_stream_draw_f32(&st, i, dim, 4, got32);
                        CHECKF(memcmp(want64, got64, sizeof got64) == 0 && memcmp(want32, got32, sizeof got32) == 0,
                               "%s randomize %u first %u index %llu dim %u", presets[p], r, firsts[f],
                               (unsigned long long)i, dim);
                    }
            }
            udm1_seq_destroy(s);
        }
    }
}

int main(void)
{
    if (check_built_isa_missing()) return 77;
    test_stream_equals_cursor();
    test_far_streams();
    test_domains_agree();
    test_derivations();
    test_point_set_permutation();
    test_domain_discrepancy();
    test_domain_decorrelation();
    CHECK_DONE();
}
