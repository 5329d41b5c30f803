/* test_properties.c - mathematical properties every udm1 sequence must have:
 *  - three-distance theorem: the first N points of {s + n alpha} cut the circle
 *    into gaps of at most three lengths, and the largest is the sum of the
 *    other two when there are three;
 *  - Weyl's criterion, quantitatively: |1/N sum_n e^{2 pi i h.x_n}| <=
 *    1 / (N |sin(pi {h.alpha})|), so exponential sums shrink like 1/N;
 *  - EPIS is exactly equidistant: sorted gaps all equal 1/K;
 *  - known constants: the first 64 bits of frac(sqrt(p)) for the first 8
 *    primes are the SHA-512 initial hash values (FIPS 180-4).
 */
#include "check.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* number of distinct gaps (exact, in 0.64 fixed point) of n circle points */
#define MAX_GAPS 8
#define PI 3.14159265358979323846

/* distinct gaps, up to MAX_GAPS (MAX_GAPS + 1 means more) */
static int distinct_gaps(uint64_t *v, size_t n, uint64_t gaps_out[MAX_GAPS])
{
    qsort(v, n, sizeof *v, cmp_u64);
    int count = 0;
    for (size_t i = 0; i < n; ++i) {
        uint64_t g = (i + 1 < n) ? v[i + 1] - v[i] : v[0] - v[n - 1]; /* wraps modulo 2^64 */
        int seen = 0;
        for (int k = 0; k < count; ++k)
            if (gaps_out[k] == g) seen = 1;
        if (!seen) {
            if (count == MAX_GAPS) return MAX_GAPS + 1;
            gaps_out[count++] = g;
        }
    }
    return count;
}

static void test_three_distance(void)
{
    static const struct { const char *name; uint32_t dims; } sets[] = {
        {"wr", 32}, {"wr-ao", 2}, {"we", 2}, {"wgr", 2}, {"wmmr", 22}, {"hwmmr", 22}, {"rd", 8}, {"golden", 1}};
    static const size_t sizes[] = {2, 3, 10, 100, 257, 1000, 4096};
    uint64_t *v = malloc(4096 * sizeof *v);
    for (size_t p = 0; p < sizeof sets / sizeof *sets; ++p) {
        udm1_seq *s = NULL;
        CHECK_STATUS(udm1_seq_create(sets[p].name, sets[p].dims, 0, 2024, &s), UDM1_OK);
        for (uint32_t j = 0; j < sets[p].dims; ++j)
            for (size_t si = 0; si < sizeof sizes / sizeof *sizes; ++si) {
                size_t n = sizes[si];
                /* exact integer gaps: a gap of the raw 0.64 values may differ by one unit
                 * from the real gap only through the truncation of each value, so compare
                 * the raw values of {n A} (offset removed) where gaps are exact sums of A */
                CHECK_STATUS(udm1_seq_fill_u64(s, 3, 1000000, n, j, 1, v, 1), UDM1_OK);
                uint64_t gaps[MAX_GAPS];
                int k = distinct_gaps(v, n, gaps);
                CHECKF(k <= MAX_GAPS, "%s dim %u N=%zu: more than %d gaps", sets[p].name, j, n, MAX_GAPS);
                if (k > MAX_GAPS) continue;
                /* truncation to 64 bits can split one real gap into g and g+1: merge those */
                int merged = k;
                for (int a = 0; a < k; ++a)
                    for (int b = a + 1; b < k; ++b)
                        if (gaps[a] + 1 == gaps[b] || gaps[b] + 1 == gaps[a]) --merged;
                CHECKF(merged <= 3, "%s dim %u N=%zu: %d distinct gaps", sets[p].name, j, n, merged);
            }
        udm1_seq_destroy(s);
    }
    free(v);
}

static double frac_dot(const udm1_seq *s, const int *h, const uint32_t *dims, int nd)
{
    /* {h . alpha} from the 0.128 fixed-point generators, in double */
    uint64_t acc = 0;
    for (int k = 0; k < nd; ++k) {
        uint64_t hi, lo;
        udm1_seq_alpha(s, dims[k], &hi, &lo);
        acc += (uint64_t)(int64_t)h[k] * hi;
    }
    return (double)acc * 0x1p-64;
}

static void test_weyl_sums(void)
{
    static const struct { const char *name; uint32_t dims; } sets[] = {
        {"wr", 6}, {"wr-ao", 2}, {"we", 2}, {"wgr", 2}, {"wmmr", 6}, {"hwmmr", 6}, {"rd", 3}, {"golden", 1}};
    static const int hs[][2] = {{1, 0}, {2, 0}, {3, 0}, {0, 1}, {1, 1}, {1, -1}, {2, -3}, {5, 7}};
    enum { NMAX = 100000 };
    double *x = malloc(sizeof(double) * NMAX * 2);
    for (size_t p = 0; p < sizeof sets / sizeof *sets; ++p) {
        udm1_seq *s = NULL;
        CHECK_STATUS(udm1_seq_create(sets[p].name, sets[p].dims, 0, 7, &s), UDM1_OK);
        for (uint32_t a = 0; a < sets[p].dims; ++a) {
            uint32_t b = sets[p].dims > 1 ? (a + 1) % sets[p].dims : a;
            uint32_t dims[2] = {a, b};
            int nd = sets[p].dims > 1 ? 2 : 1;
            CHECK_STATUS(udm1_seq_fill_f64(s, 0, 0, NMAX, a, 1, x, 2), UDM1_OK);
            CHECK_STATUS(udm1_seq_fill_f64(s, 0, 0, NMAX, b, 1, x + 1, 2), UDM1_OK);
            for (size_t hi = 0; hi < sizeof hs / sizeof *hs; ++hi) {
                if (nd == 1 && hs[hi][0] == 0) continue;
                int h[2] = {hs[hi][0], nd == 2 ? hs[hi][1] : 0};
                double t = frac_dot(s, h, dims, nd);
                double bound_num = 1.0 / fabs(sin(PI * t));
                double re = 0.0, im = 0.0, last = 0.0;
                size_t next = 10;
                for (size_t n = 0; n < NMAX; ++n) {
                    double ph = 2.0 * PI * (h[0] * x[2 * n] + h[1] * x[2 * n + 1]);
                    re += cos(ph);
                    im += sin(ph);
                    if (n + 1 == next) {
                        double avg = sqrt(re * re + im * im) / (double)(n + 1);
                        double bound = bound_num / (double)(n + 1) + 1e-9;
                        CHECKF(avg <= bound, "%s dims (%u,%u) h=(%d,%d) N=%zu: |S|/N %.3g > bound %.3g",
                               sets[p].name, a, b, h[0], h[1], n + 1, avg, bound);
                        last = avg;
                        next *= 10;
                    }
                }
                /* shrinks: at N = 10^5 the average is below 1e-5 times the bound's numerator */
                CHECK(last <= bound_num * 1e-5 + 1e-9);
            }
        }
        udm1_seq_destroy(s);
    }
    free(x);
}

static void test_epis_equidistant(void)
{
    static const uint64_t ks[] = {1, 2, 3, 7, 64, 1000, 65537};
    for (size_t i = 0; i < sizeof ks / sizeof *ks; ++i) {
        uint64_t k = ks[i];
        udm1_seq *s = NULL;
        CHECK_STATUS(udm1_seq_create("episwr", 2, k, 5, &s), UDM1_OK);
        uint64_t *v = malloc(k * sizeof *v);
        CHECK_STATUS(udm1_seq_fill_u64(s, 17, 0, k, 0, 1, v, 1), UDM1_OK);
        uint64_t off;
        udm1_seq_offset(s, 17, 0, &off);
        int bad = 0;
        for (uint64_t n = 0; n < k; ++n) {
            /* exactly floor(n 2^64 / K) + u */
            uint64_t expect;
#if defined(__SIZEOF_INT128__)
            __extension__ typedef unsigned __int128 u128;
            expect = (uint64_t)(((u128)n << 64) / k) + off;
#else
            expect = v[n];
#endif
            if (v[n] != expect) ++bad;
        }
        CHECKF(bad == 0, "K=%llu: %d values differ from floor(n 2^64/K) + u", (unsigned long long)k, bad);
        uint64_t gaps[MAX_GAPS];
        int g = k > 1 ? distinct_gaps(v, k, gaps) : 1;
        if (g > MAX_GAPS) g = MAX_GAPS; /* reported below as not equidistant */
        int merged = g;
        for (int a = 0; a < g; ++a)
            for (int b = a + 1; b < g; ++b)
                if (gaps[a] + 1 == gaps[b] || gaps[b] + 1 == gaps[a]) --merged;
        CHECKF(merged == 1, "K=%llu: gaps not all 1/K", (unsigned long long)k);
        free(v);
        udm1_seq_destroy(s);
    }
}

static void test_known_constants(void)
{
    static const uint64_t sha512_iv[8] = {0x6a09e667f3bcc908ull, 0xbb67ae8584caa73bull, 0x3c6ef372fe94f82bull,
                                          0xa54ff53a5f1d36f1ull, 0x510e527fade682d1ull, 0x9b05688c2b3e6c1full,
                                          0x1f83d9abfb41bd6bull, 0x5be0cd19137e2179ull};
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("wr", 8, 0, 0, &s), UDM1_OK);
    for (uint32_t j = 0; j < 8; ++j) {
        uint64_t hi, lo;
        udm1_seq_alpha(s, j, &hi, &lo);
        CHECKF(hi == sha512_iv[j], "sqrt(prime %u): %016llx", j, (unsigned long long)hi);
    }
    udm1_seq_destroy(s);
    /* wr-ao = (sqrt2, sqrt13); golden = wgr[0] = R_1; e = 2.B7E151628AED2A6A... */
    uint64_t hi, lo, hi2, lo2;
    CHECK_STATUS(udm1_seq_create("wr-ao", 2, 0, 0, &s), UDM1_OK);
    udm1_seq_alpha(s, 0, &hi, &lo);
    CHECK(hi == sha512_iv[0]);
    udm1_seq_destroy(s);
    CHECK_STATUS(udm1_seq_create("we", 2, 0, 0, &s), UDM1_OK);
    udm1_seq_alpha(s, 0, &hi, &lo);
    CHECK(hi == 0xB7E151628AED2A6Aull);
    udm1_seq_destroy(s);
    CHECK_STATUS(udm1_seq_create("golden", 1, 0, 0, &s), UDM1_OK);
    udm1_seq_alpha(s, 0, &hi, &lo);
    udm1_seq_destroy(s);
    CHECK_STATUS(udm1_seq_create("rd", 1, 0, 0, &s), UDM1_OK);
    udm1_seq_alpha(s, 0, &hi2, &lo2);
    udm1_seq_destroy(s);
    CHECK(hi == hi2 && lo == lo2);
    CHECK(hi == 0x9E3779B97F4A7C15ull); /* 2^64 / phi, the "golden gamma" of SplitMix64 */
}

int main(void)
{
    test_three_distance();
    test_weyl_sums();
    test_epis_equidistant();
    test_known_constants();
    CHECK_DONE();
}
