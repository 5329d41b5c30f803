/* test_fill.c - bulk fills equal per-sample calls bit for bit, for every
 * preset, output type, stride, dimension range, index range (including the
 * top of the 2^64 range) and split of a range; the cursor equals per-sample
 * calls; float and double outputs are never 1.0. Every preset, every
 * randomization, with the kernels of the instruction set in use (udm1_isa(); CTest runs this test
 * under each UDM1_ISA). */
#include "check.h"

#include <udm1/udm1.h>

#include <stdlib.h>
#include <string.h>

/* A sequence, or NULL when the preset lacks that randomization (screen: 16 samples per pixel) */
/* the tests' name for UDM1_RANDOMIZE_SCREEN with desc.screen_spp = 0 (progressive); SCREEN itself is
 * tested with screen_spp = 16 */
#define SCREEN_PROGRESSIVE (UDM1_RANDOMIZE_SCREEN + 1u)

static udm1_seq *try_make(const char *preset, uint32_t dims, uint64_t k, uint64_t seed, uint32_t randomize)
{
    udm1_seq_desc d;
    udm1_seq_desc_init(&d);
    d.preset = preset;
    d.dimensions = dims;
    d.point_count = k;
    d.seed = seed;
    d.randomize = randomize == SCREEN_PROGRESSIVE ? UDM1_RANDOMIZE_SCREEN : randomize;
    if (randomize == UDM1_RANDOMIZE_SCREEN) d.screen_spp = 16;
    udm1_seq *s = NULL;
    return udm1_seq_create_desc(&d, &s) == UDM1_OK ? s : NULL;
}

static udm1_seq *make(const char *preset, uint32_t dims, uint64_t k, uint64_t seed, uint32_t randomize)
{
    udm1_seq *s = try_make(preset, dims, k, seed, randomize);
    CHECKF(s != NULL, "%s: %s", preset, udm1_last_error());
    return s;
}

/* Preset `info` with up to 9 dimensions (64 points for a point set), seed 11 and `randomize` (screen:
 * 16 samples per pixel), or NULL if the preset lacks that randomization. */
static udm1_seq *variant(const udm1_preset_info *info, uint32_t randomize)
{
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    desc.preset = info->name, desc.dimensions = info->max_dimensions < 9 ? info->max_dimensions : 9;
    desc.point_count = (info->flags & UDM1_PRESET_POINT_SET) ? 64 : 0;
    desc.seed = 11, desc.randomize = randomize == SCREEN_PROGRESSIVE ? UDM1_RANDOMIZE_SCREEN : randomize;
    if (randomize == UDM1_RANDOMIZE_SCREEN) desc.screen_spp = 16;
    udm1_seq *s = NULL;
    return udm1_seq_create_desc(&desc, &s) == UDM1_OK ? s : NULL;
}

/* fill [first, first+count) x [d0, d0+nd) three ways and compare with samples */
static void compare_range(const udm1_seq *s, uint64_t stream, uint64_t first, size_t count, uint32_t d0, uint32_t nd,
                          size_t stride)
{
    size_t n = count * stride + 1;
    uint64_t *u = malloc(n * sizeof *u);
    double *f = malloc(n * sizeof *f);
    float *g = malloc(n * sizeof *g);
    if (!u || !f || !g) abort();
    for (size_t i = 0; i < n; ++i) {
        u[i] = 0xDEADBEEF;
        f[i] = -1.0;
        g[i] = -1.0f;
    }
    CHECK_STATUS(udm1_seq_fill_u64(s, stream, first, count, d0, nd, u, stride), UDM1_OK);
    CHECK_STATUS(udm1_seq_fill_f64(s, stream, first, count, d0, nd, f, stride), UDM1_OK);
    CHECK_STATUS(udm1_seq_fill_f32(s, stream, first, count, d0, nd, g, stride), UDM1_OK);
    int bad = 0;
    for (size_t i = 0; i < count && bad < 5; ++i) {
        for (uint32_t j = 0; j < stride; ++j) {
            size_t at = i * stride + j;
            if (j >= nd) { /* gaps of the stride untouched */
                if (u[at] != 0xDEADBEEF || f[at] != -1.0 || g[at] != -1.0f) ++bad;
                continue;
            }
            uint64_t eu = 0;
            udm1_seq_sample_u64(s, stream, first + i, d0 + j, &eu);
            /* the documented conversions of the raw value, and the per-sample calls on the first row */
            double ef = (double)(eu >> 11) * 0x1p-53;
            float eg = (float)(eu >> 40) * 0x1p-24f;
            if (i == 0) {
                double sf = -1;
                float sg = -1;
                udm1_seq_sample_f64(s, stream, first + i, d0 + j, &sf);
                udm1_seq_sample_f32(s, stream, first + i, d0 + j, &sg);
                if (sf != ef || sg != eg) ++bad;
            }
            if (u[at] != eu || memcmp(&f[at], &ef, sizeof ef) != 0 || memcmp(&g[at], &eg, sizeof eg) != 0) {
                fprintf(stderr, "  %s first=%llu count=%zu d0=%u nd=%u stride=%zu: i=%zu j=%u %016llx vs %016llx\n",
                        udm1_seq_name(s), (unsigned long long)first, count, d0, nd, stride, i, j,
                        (unsigned long long)u[at], (unsigned long long)eu);
                ++bad;
            }
            if (!(f[at] >= 0.0 && f[at] < 1.0 && g[at] >= 0.0f && g[at] < 1.0f)) ++bad;
        }
    }
    if (u[count * stride] != 0xDEADBEEF) ++bad; /* nothing written past the end */
    CHECKF(bad == 0, "%d mismatches", bad);
    free(u);
    free(f);
    free(g);
}

/* thorough: every first x count below; otherwise a few */
static void check_preset(const char *name, uint32_t D, uint64_t K, uint32_t randomize, int thorough)
{
    static const uint64_t firsts[] = {0, 999, 1ull << 63, 1, (1ull << 32) - 1, 1ull << 53};
    static const size_t counts[] = {0, 17, 1031, 1, 2, 7, 16, 255};
    size_t nf = thorough ? 6 : 3, nc = thorough ? 8 : 3;
    if (!check_sampled()) return; /* (UDM1_TEST_SAMPLE: a part of the matrix) */
    udm1_seq *s = try_make(name, D, K, 42, randomize);
    if (!s && randomize >= UDM1_RANDOMIZE_SCREEN) return; /* screen-space: the Weyl presets only */
    CHECKF(s != NULL, "%s randomize %u: %s", name, randomize, udm1_last_error());
    if (!s) return;
    for (size_t fi = 0; fi < nf; ++fi)
        for (size_t ci = 0; ci < nc; ++ci) {
            uint64_t first = firsts[fi];
            size_t count = counts[ci];
            if (K) { /* stay inside the point set */
                if (first >= K) first = first % K;
                if (count > K - first) count = (size_t)(K - first);
            }
            compare_range(s, 5, first, count, 0, D, D);                    /* contiguous */
            if (D > 1) compare_range(s, 5, first, count, 1, D - 1, D + 2); /* strided sub-range */
            compare_range(s, 6, first, count, D - 1, 1, 3);                /* one dimension, strided */
        }
    udm1_seq_destroy(s);
}

static void test_bulk_equals_samples(void)
{
    /* every preset, every randomization */
    for (size_t p = 0; p < udm1_preset_count(); ++p) {
        udm1_preset_info info;
        udm1_preset_get(p, &info);
        int point_set = (info.flags & UDM1_PRESET_POINT_SET) != 0;
        uint32_t dims[3] = {1, info.max_dimensions < 3 ? info.max_dimensions : 3,
                            info.max_dimensions < 23 ? info.max_dimensions : 23};
        for (int di = 0; di < 3; ++di)
            for (uint32_t r = UDM1_RANDOMIZE_NONE; r <= SCREEN_PROGRESSIVE; ++r)
                check_preset(info.name, dims[di], point_set ? 1000 : 0, r, r == UDM1_RANDOMIZE_DEFAULT && di == 1);
        if (point_set) check_preset(info.name, dims[1], 1, UDM1_RANDOMIZE_DEFAULT, 1);
    }
    /* many dimensions (the fill's chunking), Weyl and others */
    check_preset("wr", 600, 0, UDM1_RANDOMIZE_DEFAULT, 0);
    check_preset("sobol", 600, 0, UDM1_RANDOMIZE_OWEN, 0);
    check_preset("halton", 100, 0, UDM1_RANDOMIZE_NONE, 0);
    check_preset("pcg32", 2100, 0, UDM1_RANDOMIZE_DEFAULT, 0);
    /* the very top of the index range */
    udm1_seq *s = make("wr", 5, 0, 3, 1);
    compare_range(s, 0, UINT64_MAX - 100, 101, 0, 5, 5);
    compare_range(s, UINT64_MAX, UINT64_MAX, 1, 0, 5, 5);
    udm1_seq_destroy(s);
    s = make("sobol-owen", 5, 0, 3, 1);
    compare_range(s, 0, UINT64_MAX - 100, 101, 0, 5, 5);
    udm1_seq_destroy(s);
}

static void test_splits(void)
{
    udm1_seq *s = make("wr", 6, 0, 11, 1);
    enum { N = 3000, D = 6 };
    static float whole[N * D], parts[N * D];
    CHECK_STATUS(udm1_seq_fill_f32(s, 77, 1000, N, 0, D, whole, D), UDM1_OK);
    /* split at uneven points, and by dimension */
    size_t cuts[] = {0, 1, 17, 1024, 1025, 2999, N};
    for (size_t i = 0; i + 1 < sizeof cuts / sizeof *cuts; ++i)
        CHECK_STATUS(udm1_seq_fill_f32(s, 77, 1000 + cuts[i], cuts[i + 1] - cuts[i], 0, 4, parts + cuts[i] * D, D),
                     UDM1_OK);
    CHECK_STATUS(udm1_seq_fill_f32(s, 77, 1000, N, 4, 2, parts + 4, D), UDM1_OK);
    CHECK(memcmp(whole, parts, sizeof whole) == 0);
    /* streams differ, seeds differ, the unrandomized sequence ignores the stream */
    CHECK_STATUS(udm1_seq_fill_f32(s, 78, 1000, N, 0, D, parts, D), UDM1_OK);
    CHECK(memcmp(whole, parts, sizeof whole) != 0);
    udm1_seq_destroy(s);
    s = make("wr", 6, 0, 11, 0);
    CHECK_STATUS(udm1_seq_fill_f32(s, 1, 0, N, 0, D, whole, D), UDM1_OK);
    CHECK_STATUS(udm1_seq_fill_f32(s, 2, 0, N, 0, D, parts, D), UDM1_OK);
    CHECK(memcmp(whole, parts, sizeof whole) == 0);
    for (int j = 0; j < D; ++j) CHECK(whole[j] == 0.0f); /* point 0 of the unrandomized sequence is the origin */
    udm1_seq_destroy(s);
}

static void test_cursor(void)
{
    udm1_seq *s = make("wmmr", 22, 0, 5, 1);
    for (uint64_t idx = 0; idx < 50; ++idx) {
        udm1_cursor c;
        CHECK_STATUS(udm1_cursor_start(&c, s, 123, idx, 3), UDM1_OK);
        float v[2];
        udm1_cursor_2d(&c, v);
        float e0, e1;
        udm1_seq_sample_f32(s, 123, idx, 3, &e0);
        udm1_seq_sample_f32(s, 123, idx, 4, &e1);
        CHECK(v[0] == e0 && v[1] == e1);
        double x = udm1_cursor_1d_f64(&c), ex;
        udm1_seq_sample_f64(s, 123, idx, 5, &ex);
        CHECK(x == ex);
        CHECK(c.dimension == 6 && udm1_cursor_padded(&c) == 0);
        /* past the 22 dimensions: padded values, counted, in [0, 1), deterministic */
        c.dimension = 21;
        double p[2];
        udm1_cursor_2d_f64(&c, p);
        CHECK(udm1_cursor_padded(&c) == 1);
        CHECK(p[1] >= 0.0 && p[1] < 1.0);
        udm1_cursor again;
        udm1_cursor_start(&again, s, 123, idx, 22);
        CHECK(udm1_cursor_1d_f64(&again) == p[1]);
        udm1_cursor_start(&again, s, 123, idx + 1, 22); /* the next index differs */
        CHECK(udm1_cursor_1d_f64(&again) != p[1]);
    }
    udm1_seq_destroy(s);
}

/* udm1_cursor_fill equals successive 1D draws, for every preset and randomization, across
 * the sequence's last dimension into padding, in pieces of any length */
static void test_cursor_fill(void)
{
    for (size_t p = 0; p < udm1_preset_count(); ++p) {
        udm1_preset_info info;
        udm1_preset_get(p, &info);
        for (uint32_t r = UDM1_RANDOMIZE_NONE; r <= UDM1_RANDOMIZE_OWEN; ++r) {
            if (!check_sampled()) continue;
            udm1_seq *s = variant(&info, r);
            if (!s) continue; /* a randomization the preset lacks */
            for (uint64_t idx = 0; idx < 64; idx += 7) {
                udm1_cursor a, b, f;
                udm1_cursor_start(&a, s, 99, idx, 1);
                udm1_cursor_start(&b, s, 99, idx, 1);
                udm1_cursor_start(&f, s, 99, idx, 1);
                double one[50], many[50];
                float onef[50], manyf[50];
                for (int k = 0; k < 50; ++k) one[k] = udm1_cursor_1d_f64(&a), onef[k] = udm1_cursor_1d(&b);
                for (uint32_t at = 0, piece = 1; at < 50; at += piece, piece = piece * 2 + 1) {
                    uint32_t n = at + piece > 50 ? 50 - at : piece;
                    udm1_cursor c2 = f;
                    udm1_cursor_fill_f64(&f, n, many + at);
                    udm1_cursor_fill(&c2, n, manyf + at);
                    CHECK(c2.dimension == f.dimension && c2.padded == f.padded);
                }
                CHECKF(memcmp(one, many, sizeof one) == 0 && memcmp(onef, manyf, sizeof onef) == 0,
                       "%s randomize %u index %llu", info.name, r, (unsigned long long)idx);
                CHECK(f.dimension == a.dimension && udm1_cursor_padded(&f) == udm1_cursor_padded(&a));
            }
            udm1_seq_destroy(s);
        }
    }
}

static void test_padding_is_uniform(void)
{
    /* 1D set, draws 1..8 padded: mean 1/2, variance 1/12, no draw repeats */
    udm1_seq *s = make("golden", 1, 0, 99, 1);
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (uint64_t idx = 0; idx < 4096; ++idx) {
        udm1_cursor c;
        udm1_cursor_start(&c, s, idx * 31, idx, 1);
        for (int k = 0; k < 8; ++k) {
            double v = udm1_cursor_1d_f64(&c);
            sum += v;
            sum2 += v * v;
            ++n;
        }
        CHECK(udm1_cursor_padded(&c) == 8);
    }
    double mean = sum / n, var = sum2 / n - mean * mean;
    /* 5 sigma: sd of the mean is sqrt(1/12/n) = 0.0016 */
    CHECKF(mean > 0.5 - 0.008 && mean < 0.5 + 0.008, "mean %g", mean);
    CHECKF(var > 1.0 / 12 - 0.005 && var < 1.0 / 12 + 0.005, "variance %g", var);
    udm1_seq_destroy(s);
}

static void test_never_one(void)
{
    /* offset 2^64 - 1 and alpha tiny: raw values at the very top of [0, 1) */
    udm1_alpha a = {UDM1_ALPHA_FIXED, 0, 0, 0, 1, 0.0}; /* alpha = 2^-128 */
    uint64_t off = UINT64_MAX;
    udm1_seq_desc d;
    udm1_seq_desc_init(&d);
    d.dimensions = 1;
    d.alphas = &a;
    d.offsets = &off;
    d.randomize = UDM1_RANDOMIZE_NONE;
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_OK);
    float g[64];
    double f[64];
    uint64_t u = 0;
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 0, 64, 0, 1, g, 1), UDM1_OK);
    CHECK_STATUS(udm1_seq_fill_f64(s, 0, 0, 64, 0, 1, f, 1), UDM1_OK);
    CHECK_STATUS(udm1_seq_sample_u64(s, 0, 0, 0, &u), UDM1_OK);
    CHECK(u == UINT64_MAX);
    for (int i = 0; i < 64; ++i) {
        CHECK(g[i] < 1.0f && g[i] == 1.0f - 0x1p-24f);
        CHECK(f[i] < 1.0 && f[i] == 1.0 - 0x1p-53);
    }
    float one;
    CHECK_STATUS(udm1_seq_sample_f32(s, 0, 5, 0, &one), UDM1_OK);
    CHECK(one < 1.0f);
    udm1_cursor c;
    udm1_cursor_start(&c, s, 0, 3, 0);
    CHECK(udm1_cursor_1d(&c) < 1.0f);
    udm1_seq_destroy(s);

    /* a randomized sequence over many values: min >= 0, max < 1 */
    s = make("wr", 4, 0, 1, 1);
    static float big[1 << 20];
    float mx = 0.0f;
    for (uint64_t stream = 0; stream < 64; ++stream) {
        if (!check_sampled()) continue;
        CHECK_STATUS(udm1_seq_fill_f32(s, stream, stream << 40, (1 << 20) / 4, 0, 4, big, 4), UDM1_OK);
        for (size_t i = 0; i < (1 << 20); ++i) {
            if (big[i] > mx) mx = big[i];
            if (!(big[i] >= 0.0f && big[i] < 1.0f)) {
                CHECKF(0, "value %a out of [0,1)", (double)big[i]);
                break;
            }
        }
    }
    CHECK(mx < 1.0f && mx > 0.999f);
    udm1_seq_destroy(s);
}

/* udm1_seq_fill_points_f64 equals one cursor per point, bit for bit: every preset and randomization
 * (screen for the Weyl presets), dimension windows inside, across and past the set's own dimensions
 * (padding), runs of equal streams and changes of stream; and its errors. */
static void test_fill_points(void)
{
    enum { N = 23, ND = 13 };
    uint64_t streams[N], indices[N];
    for (int k = 0; k < N; ++k) {
        streams[k] = k < 9 ? 5 : k < 10 ? ((uint64_t)7 << 32 | 3) : k < 20 ? 0xFFFFFFFFFFFFull : 5; /* runs */
        indices[k] = (uint64_t)(k * 37) % 61;
    }
    for (size_t p = 0; p < udm1_preset_count(); ++p) {
        udm1_preset_info info;
        udm1_preset_get(p, &info);
        for (uint32_t r = UDM1_RANDOMIZE_NONE; r <= SCREEN_PROGRESSIVE; ++r) {
            if (!check_sampled()) continue;
            udm1_seq *s = variant(&info, r);
            if (!s) continue; /* a randomization the preset lacks */
            for (uint32_t first = 0; first < 12; first += 5) {
                double got[N * ND], want[N * ND];
                memset(got, 0xFF, sizeof got);
                CHECK_STATUS(udm1_seq_fill_points_f64(s, N, streams, indices, first, ND, got), UDM1_OK);
                for (int k = 0; k < N; ++k) {
                    udm1_cursor c;
                    udm1_cursor_start(&c, s, streams[k], indices[k], first);
                    for (int j = 0; j < ND; ++j) want[k * ND + j] = udm1_cursor_1d_f64(&c);
                }
                CHECKF(memcmp(got, want, sizeof got) == 0, "%s randomize %u first dimension %u", info.name, r, first);
            }
            if (info.flags & UDM1_PRESET_POINT_SET) {
                uint64_t bad[2] = {3, 64};
                double o[2];
                CHECK_STATUS(udm1_seq_fill_points_f64(s, 2, streams, bad, 0, 1, o), UDM1_ERROR_INDEX_RANGE);
                CHECK(strstr(udm1_last_error(), "indices[1] = 64") != NULL);
            }
            udm1_seq_destroy(s);
        }
    }
    /* the tent transform over a base-2 preset and over a Weyl sequence */
    const char *tents[] = {"sobol+tent", "wr+tent", "pmj02+tent"};
    for (int t = 0; t < 3; ++t) {
        udm1_seq *s = make(tents[t], 6, t == 2 ? 64 : 0, 3, UDM1_RANDOMIZE_DEFAULT);
        double got[N * 8], want[N * 8];
        CHECK_STATUS(udm1_seq_fill_points_f64(s, N, streams, indices, 1, 8, got), UDM1_OK);
        for (int k = 0; k < N; ++k) {
            udm1_cursor c;
            udm1_cursor_start(&c, s, streams[k], indices[k], 1);
            udm1_cursor_fill_f64(&c, 8, want + k * 8);
        }
        CHECKF(memcmp(got, want, sizeof got) == 0, "%s", tents[t]);
        udm1_seq_destroy(s);
    }
    udm1_seq *s = make("wr", 4, 0, 1, UDM1_RANDOMIZE_DEFAULT);
    double o[4];
    CHECK_STATUS(udm1_seq_fill_points_f64(NULL, 1, streams, indices, 0, 1, o), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_seq_fill_points_f64(s, 1, NULL, indices, 0, 1, o), UDM1_ERROR_NULL_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "streams") != NULL);
    CHECK_STATUS(udm1_seq_fill_points_f64(s, 1, streams, indices, 0, 1, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_seq_fill_points_f64(s, 0, NULL, NULL, 0, 1, NULL), UDM1_OK); /* nothing to do */
    udm1_seq_destroy(s);
}

int main(void)
{
    printf("kernels: %s\n", udm1_isa());
    test_bulk_equals_samples();
    test_splits();
    test_cursor();
    test_cursor_fill();
    test_padding_is_uniform();
    test_never_one();
    test_fill_points();
    CHECK_DONE();
}
