/* test_baselines.c - every baseline sampler has the property it must have:
 *  - drand48 bit-exact against the C library (POSIX's definition where it has none); PCG32 against the
 *    pcg32 demo;
 *  - elementary-interval stratification: Sobol (dims 0, 1), Hammersley and
 *    Larcher-Pillichshammer at K = 2^m, every 2^m prefix of PMJ02 (every pair),
 *    under no randomization, digital shifts and Owen scrambling;
 *  - Halton: the first b^k points of base b fill the b^k intervals once;
 *  - CMJ: one point per m x n stratum and per 1/K row (and column if K = m n);
 *  - golden ratio point sets: x is the sorted golden sequence (increasing),
 *    at most two points per 1/K stratum in x and in y;
 *  - every randomization gives uniform values (mean 1/2 over streams) and the
 *    documented limits give their errors.
 */
#include "posix_drand48.h"

#include "check.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

__extension__ typedef unsigned __int128 u128;

static udm1_seq *make(const char *preset, uint32_t dims, uint64_t k, uint64_t seed, uint32_t randomize)
{
    udm1_seq_desc d;
    udm1_seq_desc_init(&d);
    d.preset = preset;
    d.dimensions = dims;
    d.point_count = k;
    d.seed = seed;
    d.randomize = randomize;
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_OK);
    return s;
}

static void test_prngs(void)
{
    /* drand48: value (n, j) of D dims is call n*D + j after srand48(seed) */
    udm1_seq *s = make("drand48", 3, 0, 20261122, UDM1_RANDOMIZE_NONE);
    ref_srand48(20261122);
    double got[300];
    CHECK_STATUS(udm1_seq_fill_f64(s, 0, 0, 100, 0, 3, got, 3), UDM1_OK);
    int bad = 0;
    for (int i = 0; i < 300; ++i) bad += got[i] != ref_drand48();
    CHECKF(bad == 0, "%d drand48 values differ from the C library", bad);
    double far;
    ref_srand48(20261122);
    double ref = 0;
    for (int i = 0; i <= 3 * 1000 + 2; ++i) ref = ref_drand48();
    CHECK_STATUS(udm1_seq_sample_f64(s, 0, 1000, 2, &far), UDM1_OK); /* random access: a jump */
    CHECK(far == ref);
    udm1_seq_destroy(s);

    /* pcg32-demo: pcg32_srandom(42, 54) gives 0xa15c02b7 0x7b47f409 0xba1d3330 ... */
    static const uint32_t demo[6] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u, 0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
    s = make("pcg32", 1, 0, 42, UDM1_RANDOMIZE_NONE);
    uint64_t u[6];
    CHECK_STATUS(udm1_seq_fill_u64(s, 0, 0, 6, 0, 1, u, 1), UDM1_OK);
    for (int i = 0; i < 6; ++i) CHECKF((uint32_t)(u[i] >> 32) == demo[i], "pcg32 output %d: %08x", i, (unsigned)(u[i] >> 32));
    udm1_seq_destroy(s);
}

/* Is the point set (u64 pairs) stratified in every elementary interval of area 2^-m? */
static int is_net(const uint64_t *xy, size_t stride, uint32_t m)
{
    size_t n = (size_t)1 << m;
    unsigned char *seen = malloc(n);
    int ok = 1;
    for (uint32_t i = 0; i <= m && ok; ++i) {
        memset(seen, 0, n);
        for (size_t k = 0; k < n; ++k) {
            uint64_t x = i ? xy[k * stride] >> (64 - i) : 0;
            uint64_t y = (m - i) ? xy[k * stride + 1] >> (64 - (m - i)) : 0;
            size_t c = (size_t)(x << (m - i) | y);
            if (seen[c]++) {
                ok = 0;
                break;
            }
        }
    }
    free(seen);
    return ok;
}

static void test_nets(void)
{
    static const uint32_t modes[] = {UDM1_RANDOMIZE_NONE, UDM1_RANDOMIZE_PERMUTE, UDM1_RANDOMIZE_OWEN};
    enum { M = 12 };
    uint64_t *buf = malloc(sizeof(uint64_t) * ((size_t)1 << M) * 8);
    for (size_t mi = 0; mi < 3; ++mi) {
        /* Sobol: dims (0, 1) form a (0,2)-sequence: every aligned 2^m block is a net */
        udm1_seq *s = make("sobol", 4, 0, 5, modes[mi]);
        CHECK_STATUS(udm1_seq_fill_u64(s, 9, 0, (size_t)1 << M, 0, 2, buf, 2), UDM1_OK);
        for (uint32_t m = 0; m <= M; ++m) CHECKF(is_net(buf, 2, m), "sobol mode %u: prefix 2^%u", modes[mi], m);
        CHECKF(is_net(buf + 2 * 256, 2, 8), "sobol mode %u: block [256, 512)", modes[mi]);
        udm1_seq_destroy(s);
        s = make("sobol-owen", 2, 0, 5, modes[mi]);
        CHECK_STATUS(udm1_seq_fill_u64(s, 9, 0, (size_t)1 << M, 0, 2, buf, 2), UDM1_OK);
        CHECK(is_net(buf, 2, M));
        udm1_seq_destroy(s);
        /* Hammersley and LP with K = 2^m: (0,m,2)-nets, every pair of LP */
        for (uint32_t m = 1; m <= 10; m += 3) {
            size_t K = (size_t)1 << m;
            s = make("hammersley", 2, K, 5, modes[mi]);
            CHECK_STATUS(udm1_seq_fill_u64(s, 9, 0, K, 0, 2, buf, 2), UDM1_OK);
            CHECKF(is_net(buf, 2, m), "hammersley mode %u K=2^%u", modes[mi], m);
            udm1_seq_destroy(s);
            s = make("lp", 6, K, 5, modes[mi]);
            CHECK_STATUS(udm1_seq_fill_u64(s, 9, 0, K, 0, 6, buf, 6), UDM1_OK);
            for (int p = 0; p < 3; ++p) CHECKF(is_net(buf + 2 * p, 6, m), "lp mode %u K=2^%u pair %d", modes[mi], m, p);
            udm1_seq_destroy(s);
        }
        /* PMJ02: every prefix of 2^m points, every pair, K not a power of two */
        size_t K = 3000;
        s = make("pmj02", 5, K, 11, modes[mi]);
        CHECK_STATUS(udm1_seq_fill_u64(s, 9, 0, K, 0, 5, buf, 5), UDM1_OK);
        for (int p = 0; p < 2; ++p)
            for (uint32_t m = 0; ((size_t)1 << m) <= K; ++m)
                CHECKF(is_net(buf + 2 * p, 5, m), "pmj02 mode %u pair %d prefix 2^%u", modes[mi], p, m);
        /* the pairs are decorrelated: |corr(x of pair 0, x of pair 1)| small */
        double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
        for (size_t i = 0; i < K; ++i) {
            double a = (double)buf[5 * i] * 0x1p-64, b = (double)buf[5 * i + 2] * 0x1p-64;
            sx += a, sy += b, sxx += a * a, syy += b * b, sxy += a * b;
        }
        double corr = (sxy / K - sx / K * sy / K) / sqrt((sxx / K - sx * sx / K / K) * (syy / K - sy * sy / K / K));
        CHECKF(fabs(corr) < 0.1, "pmj02 pairs 0 and 1 correlate: %g", corr);
        udm1_seq_destroy(s);
    }
    /* negative control: random points are not a net */
    udm1_seq *r = make("pcg32", 2, 0, 5, UDM1_RANDOMIZE_DEFAULT);
    CHECK_STATUS(udm1_seq_fill_u64(r, 9, 0, 256, 0, 2, buf, 2), UDM1_OK);
    CHECK(!is_net(buf, 2, 8));
    udm1_seq_destroy(r);
    /* a larger PMJ02 table */
    udm1_seq *s = make("pmj02", 2, 1u << 16, 7, UDM1_RANDOMIZE_NONE);
    uint64_t *big = malloc(sizeof(uint64_t) * 2 * ((size_t)1 << 16));
    CHECK_STATUS(udm1_seq_fill_u64(s, 0, 0, (size_t)1 << 16, 0, 2, big, 2), UDM1_OK);
    for (uint32_t m = 0; m <= 16; ++m) CHECKF(is_net(big, 2, m), "pmj02 2^16: prefix 2^%u", m);
    /* every aligned block is a net too (what the shuffle of pairs k >= 1 relies on) */
    int blocks_bad = 0;
    for (uint32_t m = 1; m <= 12; ++m)
        for (size_t j = 0; j < ((size_t)1 << (16 - m)); ++j) blocks_bad += !is_net(big + 2 * (j << m), 2, m);
    CHECKF(blocks_bad == 0, "pmj02: %d aligned blocks are not nets", blocks_bad);
    free(big);
    udm1_seq_destroy(s);
    free(buf);
}

static void test_halton_strata(void)
{
    static const uint32_t modes[] = {UDM1_RANDOMIZE_NONE, UDM1_RANDOMIZE_PERMUTE, UDM1_RANDOMIZE_OWEN};
    static const uint32_t bases[] = {2, 3, 5, 7, 11, 13};
    for (size_t mi = 0; mi < 3; ++mi) {
        udm1_seq *s = make("halton", 6, 0, 3, modes[mi]);
        for (uint32_t j = 0; j < 6; ++j) {
            uint32_t b = bases[j];
            size_t n = (size_t)b * b * (b < 7 ? b : 1); /* b^3 or b^2 */
            uint64_t *x = malloc(sizeof(uint64_t) * n);
            unsigned char *seen = calloc(n, 1);
            CHECK_STATUS(udm1_seq_fill_u64(s, 4, 0, n, j, 1, x, 1), UDM1_OK);
            int bad = 0;
            for (size_t i = 0; i < n; ++i) {
                /* the raw value is floor(v 2^64): (raw + 1) n / 2^64 lands in v's interval even when
                 * v is exactly c / n, as the unscrambled values are */
                size_t c = (size_t)((((u128)x[i] + 1) * n) >> 64);
                if (c >= n || seen[c]++) ++bad;
            }
            CHECKF(bad == 0, "halton mode %u base %u: %d of %zu intervals hit twice", modes[mi], b, bad, n);
            free(x);
            free(seen);
        }
        udm1_seq_destroy(s);
    }
    /* exact values: phi_3(1) = 1/3, phi_3(5) = 7/9 (5 = 12 in base 3) */
    udm1_seq *s = make("halton", 2, 0, 0, UDM1_RANDOMIZE_NONE);
    uint64_t u;
    udm1_seq_sample_u64(s, 0, 1, 1, &u);
    CHECK(u == 0x5555555555555555ull);
    udm1_seq_sample_u64(s, 0, 5, 1, &u);
    CHECK(u == (uint64_t)((((u128)7) << 64) / 9));
    udm1_seq_sample_u64(s, 0, 6, 0, &u); /* 110 in base 2 -> 0.011 */
    CHECK(u == 0x6000000000000000ull);
    udm1_seq_destroy(s);
}

static void test_cmj_strata(void)
{
    static const uint32_t ks[] = {1, 2, 10, 16, 17, 64, 100, 1000, 1024};
    for (size_t ki = 0; ki < sizeof ks / sizeof *ks; ++ki) {
        uint32_t K = ks[ki], m = (uint32_t)sqrt((double)K), n;
        while ((m + 1) * (m + 1) <= K) ++m;
        n = (K + m - 1) / m;
        udm1_seq *s = make("cmj", 3, K, 17, UDM1_RANDOMIZE_DEFAULT);
        double *xy = malloc(sizeof(double) * 3 * K);
        CHECK_STATUS(udm1_seq_fill_f64(s, 21, 0, K, 0, 3, xy, 3), UDM1_OK);
        unsigned char *cells = calloc((size_t)m * n, 1), *rows = calloc(K, 1), *cols = calloc(K, 1);
        int bad = 0;
        for (uint32_t i = 0; i < K; ++i) {
            double x = xy[3 * i], y = xy[3 * i + 1];
            uint32_t cx = (uint32_t)(x * m), cy = (uint32_t)(y * n), ry = (uint32_t)(y * K), rx = (uint32_t)(x * K);
            if (cx >= m || cy >= n || cells[cy * m + cx]++) ++bad;
            if (ry >= K || rows[ry]++) ++bad;
            if (K == m * n && (rx >= K || cols[rx]++)) ++bad;
        }
        CHECKF(bad == 0, "cmj K=%u: %d strata hit twice", K, bad);
        free(cells);
        free(rows);
        free(cols);
        free(xy);
        udm1_seq_destroy(s);
    }
}

static void test_grps(void)
{
    static const uint32_t ks[] = {1, 2, 3, 13, 100, 144, 1000, 4181, 10000};
    for (size_t ki = 0; ki < sizeof ks / sizeof *ks; ++ki) {
        uint32_t K = ks[ki];
        for (uint64_t stream = 0; stream < 3; ++stream) {
            udm1_seq *s = make("grps", 2, K, stream + 1, UDM1_RANDOMIZE_DEFAULT);
            uint64_t *xy = malloc(sizeof(uint64_t) * 2 * K);
            CHECK_STATUS(udm1_seq_fill_u64(s, stream, 0, K, 0, 2, xy, 2), UDM1_OK);
            int bad = 0;
            unsigned char *sx = calloc(K, 1), *sy = calloc(K, 1);
            for (uint32_t i = 0; i < K; ++i) {
                if (i && xy[2 * i] <= xy[2 * (i - 1)]) ++bad; /* sorted */
                size_t cx = (size_t)(((u128)xy[2 * i] * K) >> 64);
                size_t cy = (size_t)(((u128)xy[2 * i + 1] * K) >> 64);
                if (++sx[cx] > 2 || ++sy[cy] > 2) ++bad;
            }
            CHECKF(bad == 0, "grps K=%u stream %llu: %d violations", K, (unsigned long long)stream, bad);
            free(sx);
            free(sy);
            free(xy);
            udm1_seq_destroy(s);
        }
    }
}

static void test_uniform_randomizations(void)
{
    /* for every preset and randomization, value (index 3, dim 1) over 4096 streams has mean 1/2 */
    static const uint32_t modes[] = {UDM1_RANDOMIZE_DEFAULT, UDM1_RANDOMIZE_SHIFT, UDM1_RANDOMIZE_PERMUTE,
                                     UDM1_RANDOMIZE_OWEN};
    for (size_t p = 0; p < udm1_preset_count(); ++p) {
        udm1_preset_info info;
        udm1_preset_get(p, &info);
        if (info.max_dimensions < 2) continue;
        for (size_t mi = 0; mi < 4; ++mi) {
            udm1_seq *s = make(info.name, 2, (info.flags & UDM1_PRESET_POINT_SET) ? 64 : 0, 99, modes[mi]);
            double sum = 0.0, sum2 = 0.0;
            enum { STREAMS = 4096 };
            for (uint64_t st = 0; st < STREAMS; ++st) {
                double v;
                udm1_seq_sample_f64(s, st, 3, 1, &v);
                sum += v;
                sum2 += v * v;
            }
            double mean = sum / STREAMS, var = sum2 / STREAMS - mean * mean;
            CHECKF(fabs(mean - 0.5) < 5.0 * sqrt(1.0 / 12.0 / STREAMS), "%s mode %u: mean %g", info.name, modes[mi], mean);
            CHECKF(fabs(var - 1.0 / 12.0) < 0.01, "%s mode %u: variance %g", info.name, modes[mi], var);
            udm1_seq_destroy(s);
        }
    }
}

static void test_dimensions_decorrelated(void)
{
    /* over 1024 points, no two of the first 8 dimensions correlate (|r| < 0.1) */
    enum { N = 1024, D = 8 };
    static double x[N * D];
    for (size_t p = 0; p < udm1_preset_count(); ++p) {
        udm1_preset_info info;
        udm1_preset_get(p, &info);
        uint32_t d = info.max_dimensions < D ? info.max_dimensions : D;
        if (d < 2) continue;
        udm1_seq *s = make(info.name, d, (info.flags & UDM1_PRESET_POINT_SET) ? N : 0, 3, UDM1_RANDOMIZE_DEFAULT);
        CHECK_STATUS(udm1_seq_fill_f64(s, 1, 0, N, 0, d, x, d), UDM1_OK);
        for (uint32_t a = 0; a < d; ++a)
            for (uint32_t b = a + 1; b < d; ++b) {
                double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
                for (int i = 0; i < N; ++i) {
                    double u = x[i * d + a], v = x[i * d + b];
                    sa += u, sb += v, saa += u * u, sbb += v * v, sab += u * v;
                }
                double cov = sab / N - sa / N * sb / N;
                double r = cov / sqrt((saa / N - sa * sa / N / N) * (sbb / N - sb * sb / N / N));
                CHECKF(fabs(r) < 0.1, "%s: dimensions %u and %u correlate, r = %.3f", info.name, a, b, r);
            }
        udm1_seq_destroy(s);
    }
}

static void test_limits(void)
{
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("sobol", UDM1_SOBOL_MAX_DIMENSIONS + 1, 0, 1, &s), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_create("sobol", UDM1_SOBOL_MAX_DIMENSIONS, 0, 1, &s), UDM1_OK);
    double v;
    CHECK_STATUS(udm1_seq_sample_f64(s, 0, UINT64_MAX, UDM1_SOBOL_MAX_DIMENSIONS - 1, &v), UDM1_OK);
    CHECK(v >= 0.0 && v < 1.0);
    udm1_seq_destroy(s);
    CHECK_STATUS(udm1_seq_create("pmj02", 2, (1u << 20) + 1, 1, &s), UDM1_ERROR_POINT_COUNT);
    CHECK_STATUS(udm1_seq_create("pmj02", 65, 16, 1, &s), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_create("pmj02", 64, 1u << 20, 1, &s), UDM1_ERROR_POINT_COUNT); /* K x pairs > 2^24 */
    CHECK_STATUS(udm1_seq_create("grps", 2, (1u << 26) + 1, 1, &s), UDM1_ERROR_POINT_COUNT);
    CHECK_STATUS(udm1_seq_create("cmj", 2, 0, 1, &s), UDM1_ERROR_POINT_COUNT);
    CHECK_STATUS(udm1_seq_create("halton", 2, 16, 1, &s), UDM1_ERROR_POINT_COUNT);
    /* point sets: index K is out of range; an odd D uses the first coordinate of the last pair */
    CHECK_STATUS(udm1_seq_create("cmj", 3, 16, 1, &s), UDM1_OK);
    CHECK_STATUS(udm1_seq_sample_f64(s, 0, 16, 0, &v), UDM1_ERROR_INDEX_RANGE);
    CHECK_STATUS(udm1_seq_sample_f64(s, 0, 15, 2, &v), UDM1_OK);
    uint64_t hi, lo;
    CHECK_STATUS(udm1_seq_alpha(s, 0, &hi, &lo), UDM1_ERROR_INVALID_ARGUMENT); /* not a Weyl sequence */
    udm1_alpha_report rep;
    CHECK_STATUS(udm1_seq_check(s, 16, &rep), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(udm1_seq_flags(s) == (UDM1_PRESET_POINT_SET | UDM1_PRESET_PAIRS));
    CHECK(udm1_seq_randomization(s) == UDM1_RANDOMIZE_DEFAULT);
    udm1_seq_destroy(s);
    CHECK_STATUS(udm1_seq_create("sobol-owen", 2, 0, 1, &s), UDM1_OK);
    CHECK(udm1_seq_randomization(s) == UDM1_RANDOMIZE_OWEN);
    udm1_seq_destroy(s);
}

int main(void)
{
    test_prngs();
    test_nets();
    test_halton_strata();
    test_cmj_strata();
    test_grps();
    test_uniform_randomizations();
    test_dimensions_decorrelated();
    test_limits();
    CHECK_DONE();
}
