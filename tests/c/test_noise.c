/* test_noise.c - the noise and its patterns:
 *  - Perlin's reference values, including two derived by hand in the comments;
 *  - range, mean and variance; determinism; tileability with any period;
 *  - continuity of the derivative across lattice planes;
 *  - far coordinates (past 2^31, 1e12, 1e300): finite, correct, no overflow;
 *  - tables from sequences have the spectrum of random permutations; drand48's are the C library's;
 *  - patterns in [0, 1], POV-Ray's closed forms, colour maps, bad inputs.
 */
#include "posix_drand48.h"

#include "check.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static udm1_noise *make(const char *table, uint64_t seed, uint32_t kind, uint32_t px, uint32_t py, uint32_t pz)
{
    udm1_noise_desc d;
    udm1_noise_desc_init(&d);
    d.table = table;
    d.seed = seed;
    d.kind = kind;
    d.period[0] = px;
    d.period[1] = py;
    d.period[2] = pz;
    udm1_noise *n = NULL;
    CHECK_STATUS(udm1_noise_create(&d, &n), UDM1_OK);
    return n;
}

static uint64_t rng = 7;
static double uniform(void)
{
    uint64_t z = (rng += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1p-53;
}

static void test_reference(void)
{
    udm1_noise *n = make(NULL, 0, UDM1_NOISE_IMPROVED, 0, 0, 0);
    /* Perlin's published value (ImprovedNoise.java) */
    CHECK(udm1_noise_3d(n, 3.14, 42, 7) == 0.13691995878400012);
    /* (0.5, 0.5, 0.5): cell (0,0,0), fade(1/2) = 1/2, so the mean of the 8 corners' grad . offset.
     * Corner hashes (h & 15): 000 -> 4, 100 -> 6, 010 -> 12, 110 -> 0, 001 -> 7, 101 -> 4, 011 -> 14,
     * 111 -> 3, giving +1, -1, 0, -1, 0, -1, -1, +1 with offsets (+-1/2, +-1/2, +-1/2): sum -2, mean -1/4. */
    CHECK(udm1_noise_3d(n, 0.5, 0.5, 0.5) == -0.25);
    /* (-4.2, 10, 6): checked against an independent transcription of Perlin's code
     * (tests/python/test_noise.py); not the 0.188416 some notes give */
    CHECK(fabs(udm1_noise_3d(n, -4.2, 10, 6) - 0.14208) < 1e-12);
    /* the lattice points are zeros */
    CHECK(udm1_noise_3d(n, 3, -7, 11) == 0.0 && udm1_noise_2d(n, 5, 9) == 0.0 && udm1_noise_1d(n, -2) == 0.0);
    uint8_t perm[256];
    int seen[256] = {0};
    CHECK_STATUS(udm1_noise_tables(n, perm, NULL), UDM1_OK);
    CHECK(perm[0] == 151 && perm[255] == 180);
    for (int i = 0; i < 256; ++i) seen[perm[i]]++;
    for (int i = 0; i < 256; ++i) CHECK(seen[i] == 1);
    udm1_noise_destroy(n);
}

/* An independent transcription of Perlin's ImprovedNoise.java (and, with table gradients and the
 * cubic fade, of the classic noise), on the tables udm1_noise_tables hands out. */
static double transcribed_noise3(const uint8_t perm[256], double grad[256][3], int classic, double x, double y,
                                 double z)
{
    int p[512];
    for (int i = 0; i < 512; ++i) p[i] = perm[i & 255];
    double fx = floor(x), fy = floor(y), fz = floor(z);
    int X = (int)((long long)fx & 255), Y = (int)((long long)fy & 255), Z = (int)((long long)fz & 255);
    x -= fx, y -= fy, z -= fz;
    double t[3] = {x, y, z}, f[3];
    for (int k = 0; k < 3; ++k)
        f[k] = classic ? t[k] * t[k] * (3 - 2 * t[k]) : t[k] * t[k] * t[k] * (t[k] * (t[k] * 6 - 15) + 10);
    int A = p[X] + Y, AA = p[A] + Z, AB = p[A + 1] + Z, B = p[X + 1] + Y, BA = p[B] + Z, BB = p[B + 1] + Z;
#define G(h, a, b, c)                                                                                                 \
    (classic ? grad[h][0] * (a) + grad[h][1] * (b) + grad[h][2] * (c)                                                \
             : ((((h) & 15) < 8 ? (a) : (b)) * (((h) & 1) ? -1.0 : 1.0) +                                           \
                (((h) & 15) < 4 ? (b) : (((h) & 15) == 12 || ((h) & 15) == 14) ? (a) : (c)) * (((h) & 2) ? -1.0 : 1.0)))
#define L(t, a, b) ((a) + (t) * ((b) - (a)))
    double r = L(f[2], L(f[1], L(f[0], G(p[AA], x, y, z), G(p[BA], x - 1, y, z)),
                         L(f[0], G(p[AB], x, y - 1, z), G(p[BB], x - 1, y - 1, z))),
                 L(f[1], L(f[0], G(p[AA + 1], x, y, z - 1), G(p[BA + 1], x - 1, y, z - 1)),
                         L(f[0], G(p[AB + 1], x, y - 1, z - 1), G(p[BB + 1], x - 1, y - 1, z - 1))));
#undef G
#undef L
    return r;
}

/* The same for 2D: Gustavson's noise1234 (+-u +-2v, u = x for h & 7 < 4, else y; scaled by 0.507),
 * or table gradients and the cubic fade for the classic noise. */
static double transcribed_noise2(const uint8_t perm[256], double grad[256][3], int classic, double x, double y)
{
    int p[512];
    for (int i = 0; i < 512; ++i) p[i] = perm[i & 255];
    double fx = floor(x), fy = floor(y);
    int X = (int)((long long)fx & 255), Y = (int)((long long)fy & 255);
    x -= fx, y -= fy;
    double fu = classic ? x * x * (3 - 2 * x) : x * x * x * (x * (x * 6 - 15) + 10);
    double fv = classic ? y * y * (3 - 2 * y) : y * y * y * (y * (y * 6 - 15) + 10);
#define G(h, a, b)                                                                                                    \
    (classic ? grad[h][0] * (a) + grad[h][1] * (b)                                                                   \
             : ((((h) & 7) < 4 ? (a) : (b)) * (((h) & 1) ? -1.0 : 1.0) +                                            \
                (((h) & 7) < 4 ? (b) : (a)) * (((h) & 2) ? -2.0 : 2.0)))
#define L(t, a, b) ((a) + (t) * ((b) - (a)))
    double r = L(fv, L(fu, G(p[p[X] + Y], x, y), G(p[p[X + 1] + Y], x - 1, y)),
                 L(fu, G(p[p[X] + Y + 1], x, y - 1), G(p[p[X + 1] + Y + 1], x - 1, y - 1)));
#undef G
#undef L
    return (classic ? 1.0 : 0.507) * r;
}

static void test_equals_transcription(void)
{
    /* udm1_noise_3d and _2d equal the transcriptions bit for bit (signed zeros included): Perlin's,
     * a sequence's and drand48's tables, improved and classic, near and far (1e12) */
    static const char *tables[] = {NULL, "wr", "drand48"};
    static double grad[256][3];
    for (int t = 0; t < 3; ++t)
        for (uint32_t kind = 0; kind <= 1; ++kind) {
            udm1_noise *n = make(tables[t], 5, kind, 0, 0, 0);
            uint8_t perm[256];
            CHECK_STATUS(udm1_noise_tables(n, perm, &grad[0][0]), UDM1_OK);
            int bad = 0;
            for (int i = 0; i < 20000; ++i) {
                double s = i % 10 == 0 ? 1e12 : 600.0;
                double x = (uniform() - 0.5) * s, y = (uniform() - 0.5) * s, z = (uniform() - 0.5) * s;
                if (i % 7 == 3) x = -0.0;
                if (i % 11 == 4) y = -0.0, z = i % 2 ? 255.0 : -0.0;
                double a = udm1_noise_3d(n, x, y, z), b = transcribed_noise3(perm, grad, kind == UDM1_NOISE_CLASSIC, x, y, z);
                bad += memcmp(&a, &b, sizeof a) != 0;
                a = udm1_noise_2d(n, x, y), b = transcribed_noise2(perm, grad, kind == UDM1_NOISE_CLASSIC, x, y);
                bad += memcmp(&a, &b, sizeof a) != 0;
            }
            CHECKF(bad == 0, "table %d kind %u: %d of 2 x 20000 values (3D, 2D) differ from the transcription", t, kind,
                   bad);
            udm1_noise_destroy(n);
        }
}

static void moments(udm1_noise *n, int dims, double *mean, double *var, double *maxabs)
{
    enum { N = 200000 };
    double s = 0, s2 = 0, m = 0;
    for (int i = 0; i < N; ++i) {
        double x = uniform() * 512 - 256, y = uniform() * 512 - 256, z = uniform() * 512 - 256;
        double v = dims == 3 ? udm1_noise_3d(n, x, y, z) : dims == 2 ? udm1_noise_2d(n, x, y) : udm1_noise_1d(n, x);
        s += v;
        s2 += v * v;
        if (fabs(v) > m) m = fabs(v);
    }
    *mean = s / N;
    *var = s2 / N - *mean * *mean;
    *maxabs = m;
}

static void test_range_and_moments(void)
{
    static const char *tables[] = {NULL, "drand48", "wr", "wmmr", "rd", "sobol-owen"};
    for (size_t t = 0; t < sizeof tables / sizeof *tables; ++t)
        for (uint32_t kind = 0; kind <= 1; ++kind)
            for (int dims = 1; dims <= 3; ++dims) {
                udm1_noise *n = make(tables[t], 3, kind, 0, 0, 0);
                double mean, var, m;
                moments(n, dims, &mean, &var, &m);
                const char *name = tables[t] ? tables[t] : "perlin";
                /* centred, a real variance, bounded (Perlin's noise is not bounded by 1: ~1.04) */
                CHECKF(fabs(mean) < 0.02, "%s kind %u %dD: mean %g", name, kind, dims, mean);
                CHECKF(var > 0.01 && var < 0.25, "%s kind %u %dD: variance %g", name, kind, dims, var);
                CHECKF(m < 1.2 && m > 0.25, "%s kind %u %dD: max |n| %g", name, kind, dims, m);
                udm1_noise_destroy(n);
            }
}

static void test_determinism_and_seeds(void)
{
    udm1_noise *a = make("wr", 11, 1, 0, 0, 0), *b = make("wr", 11, 1, 0, 0, 0), *c = make("wr", 12, 1, 0, 0, 0);
    uint8_t pa[256], pb[256], pc[256];
    double ga[768], gb[768];
    udm1_noise_tables(a, pa, ga);
    udm1_noise_tables(b, pb, gb);
    udm1_noise_tables(c, pc, NULL);
    CHECK(memcmp(pa, pb, 256) == 0 && memcmp(ga, gb, sizeof ga) == 0);
    CHECK(memcmp(pa, pc, 256) != 0);
    for (int k = 0; k < 256; ++k) /* unit gradients */
        CHECK(fabs(ga[3 * k] * ga[3 * k] + ga[3 * k + 1] * ga[3 * k + 1] + ga[3 * k + 2] * ga[3 * k + 2] - 1) < 1e-12);
    CHECK(udm1_noise_3d(a, 1.3, 2.7, -0.4) == udm1_noise_3d(b, 1.3, 2.7, -0.4));
    udm1_noise_destroy(a);
    udm1_noise_destroy(b);
    udm1_noise_destroy(c);
}

/* The "drand48" table is the paper's construction from the C library's srand48(seed) and drand48() (the
 * library draws them from its own drand48): 256 gradients from two draws each, then the swap shuffle. */
static void test_drand48_table(void)
{
    static const uint64_t seeds[] = {0, 11, 20261122, 0xFFFFFFFFu, 0x1234567800000005ull /* (low 32 bits: 5) */};
    for (size_t s = 0; s < sizeof seeds / sizeof *seeds; ++s) {
        udm1_noise *n = make("drand48", seeds[s], 0, 0, 0, 0);
        uint8_t perm[256], want_perm[256];
        double grad[768], want_grad[768];
        CHECK_STATUS(udm1_noise_tables(n, perm, grad), UDM1_OK);
        ref_srand48((long)(seeds[s] & 0xFFFFFFFFu));
        for (int k = 0; k < 256; ++k) {
            double u = ref_drand48(), v = ref_drand48();
            double z = 1.0 - 2.0 * u, r = sqrt(fmax(0.0, 1.0 - z * z)), phi = 2.0 * PI * v;
            want_grad[3 * k] = r * cos(phi), want_grad[3 * k + 1] = r * sin(phi), want_grad[3 * k + 2] = z;
        }
        for (int i = 0; i < 256; ++i) want_perm[i] = (uint8_t)i;
        for (int i = 0; i < 256; ++i) {
            int j = (int)(ref_drand48() * 256.0);
            uint8_t t = want_perm[i];
            want_perm[i] = want_perm[j], want_perm[j] = t;
        }
        CHECKF(memcmp(perm, want_perm, sizeof perm) == 0, "seed %llu: the permutation differs from srand48's",
               (unsigned long long)seeds[s]);
        CHECKF(memcmp(grad, want_grad, sizeof grad) == 0, "seed %llu: the gradients differ from srand48's",
               (unsigned long long)seeds[s]);
        udm1_noise_destroy(n);
    }
}

static void test_tileable(void)
{
    static const uint32_t periods[] = {1, 2, 3, 7, 64, 256, 300, 1000};
    for (size_t k = 0; k < sizeof periods / sizeof *periods; ++k) {
        uint32_t P = periods[k];
        for (uint32_t kind = 0; kind <= 1; ++kind) {
            udm1_noise *n = make("hwmmr", 5, kind, P, P + 1, 3);
            double worst = 0;
            for (int i = 0; i < 2000; ++i) {
                double x = uniform() * P, y = uniform() * (P + 1), z = uniform() * 3;
                double v = udm1_noise_3d(n, x, y, z);
                worst = fmax(worst, fabs(v - udm1_noise_3d(n, x + P, y, z)));
                worst = fmax(worst, fabs(v - udm1_noise_3d(n, x - 3.0 * P, y + (P + 1), z - 3)));
                worst = fmax(worst, fabs(udm1_noise_2d(n, x, y) - udm1_noise_2d(n, x + P, y - (P + 1))));
                worst = fmax(worst, fabs(udm1_noise_1d(n, x) - udm1_noise_1d(n, x + 2.0 * P)));
            }
            /* opposite edges of a texture over [0, P): x = 0 and x = P */
            for (int i = 0; i < 100; ++i) {
                double y = uniform() * (P + 1);
                worst = fmax(worst, fabs(udm1_noise_3d(n, 0.0, y, 0.5) - udm1_noise_3d(n, (double)P, y, 0.5)));
            }
            CHECKF(worst <= 1e-12, "period %u kind %u: edges differ by %g", P, kind, worst);
            udm1_noise_destroy(n);
        }
    }
    /* without a period the lattice repeats every 256 */
    udm1_noise *n = make(NULL, 0, 0, 0, 0, 0);
    CHECK(udm1_noise_3d(n, 0.25, 1.5, 2.75) == udm1_noise_3d(n, 0.25 + 256 * 1024, 1.5, 2.75));
    udm1_noise_destroy(n);
}

static void test_derivative_continuity(void)
{
    /* one-sided derivatives just left and right of lattice planes agree (C1; the quintic fade is C2) */
    for (uint32_t kind = 0; kind <= 1; ++kind) {
        udm1_noise *n = make("wr", 2, kind, 0, 0, 0);
        double worst = 0, scale = 0;
        for (int i = 0; i < 500; ++i) {
            double k = floor(uniform() * 100) - 50, y = uniform() * 9, z = uniform() * 9, h = 1e-6;
            double left = (udm1_noise_3d(n, k, y, z) - udm1_noise_3d(n, k - h, y, z)) / h;
            double right = (udm1_noise_3d(n, k + h, y, z) - udm1_noise_3d(n, k, y, z)) / h;
            worst = fmax(worst, fabs(left - right));
            scale = fmax(scale, fabs(left));
        }
        CHECKF(worst < 1e-4 && scale > 0.1, "kind %u: derivative jumps by %g (derivatives up to %g)", kind, worst, scale);
        udm1_noise_destroy(n);
    }
}

static void test_far_coordinates(void)
{
    udm1_noise *n = make("wr", 1, 0, 0, 0, 0);
    static const double far[] = {2147483648.0 + 0.37, -2147483649.0 - 0.61, 4294967296.5, 1e12 + 0.3, -1e12 - 0.7,
                                 9.2e18 + 2048, -9.3e18, 1e300, -1e300, 0x1p52 + 0.5, 0x1p62, -0x1p63};
    for (size_t i = 0; i < sizeof far / sizeof *far; ++i) {
        double v = udm1_noise_3d(n, far[i], far[i] * 0.5, 3.3);
        CHECKF(isfinite(v) && fabs(v) < 1.2, "noise(%g, ...) = %g", far[i], v);
        CHECK(isfinite(udm1_noise_2d(n, far[i], 1.7)) && isfinite(udm1_noise_1d(n, far[i])));
    }
    /* the largest doubles together: each finite, their sum not (a fuzzing finding: that sum gave NaN) */
    CHECK(isfinite(udm1_noise_3d(n, -1.7e308, 2.5, -1.6e308)) && isfinite(udm1_noise_2d(n, 1.7e308, 1.7e308)));
    /* exact shifts by multiples of 256 do not change the value, however far */
    CHECK(udm1_noise_3d(n, 0.25, 0.5, 0.75) == udm1_noise_3d(n, 0.25 + 0x1p40, 0.5 - 0x1p45, 0.75 + 256.0 * 1e9));
    /* at 1e8 and 1e12 the noise still varies from point to point (float libraries give ~47 values) */
    int distinct = 0;
    double prev = NAN;
    for (int i = 0; i < 1000; ++i) {
        double v = udm1_noise_3d(n, 1e12 + i * 0.01, 2.5, 0.5);
        distinct += v != prev;
        prev = v;
    }
    CHECKF(distinct > 990, "only %d distinct values at 1e12", distinct);
    /* non-finite input: NaN, not a crash */
    CHECK(isnan(udm1_noise_3d(n, NAN, 0, 0)) && isnan(udm1_noise_2d(n, INFINITY, 0)) && isnan(udm1_noise_1d(n, -INFINITY)));
    udm1_noise_destroy(n);
}

/* largest |DFT|^2 over mean |DFT|^2 of a permutation seen as a signal (k = 1..128) */
static double spike(const uint8_t *p)
{
    double mean = 127.5, best = 0, sum = 0;
    for (int k = 1; k <= 128; ++k) {
        double re = 0, im = 0;
        for (int i = 0; i < 256; ++i) {
            re += (p[i] - mean) * cos(2 * PI * k * i / 256.0);
            im -= (p[i] - mean) * sin(2 * PI * k * i / 256.0);
        }
        double e = re * re + im * im;
        sum += e;
        if (e > best) best = e;
    }
    return best / (sum / 128);
}

static void test_table_spectrum(void)
{
    /* the reference: 200 Fisher-Yates permutations from a PRNG */
    double random_max = 0;
    for (int t = 0; t < 200; ++t) {
        uint8_t p[256];
        for (int i = 0; i < 256; ++i) p[i] = (uint8_t)i;
        for (int i = 255; i >= 1; --i) {
            int j = (int)(uniform() * (i + 1));
            uint8_t s = p[i];
            p[i] = p[j];
            p[j] = s;
        }
        random_max = fmax(random_max, spike(p));
    }
    /* ranking {n sqrt2} (the naive construction) is far outside: the three-distance lattice */
    uint8_t ranked[256];
    {
        double key[256];
        int idx[256];
        for (int i = 0; i < 256; ++i) key[i] = fmod(i * 1.4142135623730951, 1.0), idx[i] = i;
        for (int i = 1; i < 256; ++i) /* insertion sort by key */
            for (int j = i; j > 0 && key[idx[j - 1]] > key[idx[j]]; --j) {
                int s = idx[j];
                idx[j] = idx[j - 1];
                idx[j - 1] = s;
            }
        for (int i = 0; i < 256; ++i) ranked[i] = (uint8_t)idx[i];
    }
    CHECKF(spike(ranked) > 2 * random_max, "ranking: spike %g vs random max %g", spike(ranked), random_max);
    /* udm1's tables, from every sequence preset, several seeds: inside the random range */
    for (size_t p = 0; p < udm1_preset_count(); ++p) {
        udm1_preset_info info;
        udm1_preset_get(p, &info);
        for (uint64_t seed = 0; seed < 8; ++seed) {
            udm1_noise *n = make(info.name, seed, 0, 0, 0, 0);
            uint8_t perm[256];
            udm1_noise_tables(n, perm, NULL);
            double s = spike(perm);
            CHECKF(s <= random_max, "table from %s seed %llu: spike %g above random max %g", info.name,
                   (unsigned long long)seed, s, random_max);
            udm1_noise_destroy(n);
        }
    }
}

static void test_patterns(void)
{
    udm1_noise *n = make("wr", 4, 0, 0, 0, 0);
    for (uint32_t pat = UDM1_PATTERN_BOZO; pat <= UDM1_PATTERN_WAVES; ++pat) {
        udm1_pattern_params p;
        udm1_pattern_params_init(&p, pat);
        if (pat != UDM1_PATTERN_LEOPARD && pat != UDM1_PATTERN_ONION) p.turbulence[0] = p.turbulence[1] = 0.5;
        static float img[64 * 64];
        double o[3] = {-3, -2, 0.7}, sx[3] = {0.1, 0, 0}, sy[3] = {0, 0.1, 0.01};
        CHECK_STATUS(udm1_pattern_grid(n, &p, 64, 64, 0, 64, o, sx, sy, img), UDM1_OK);
        float lo = 1, hi = 0;
        for (int i = 0; i < 64 * 64; ++i) lo = fminf(lo, img[i]), hi = fmaxf(hi, img[i]);
        CHECKF(lo >= 0.0f && hi <= 1.0f && hi > lo, "%s: values in [%g, %g]", udm1_pattern_name(pat), lo, hi);
        CHECK(udm1_pattern_from_name(udm1_pattern_name(pat)) == pat);
    }
    udm1_pattern_params p;
    /* closed forms: marble without turbulence is a triangle wave of x; leopard; onion */
    udm1_pattern_params_init(&p, UDM1_PATTERN_MARBLE);
    CHECK(fabs(udm1_pattern_eval(n, &p, 0.25, 3, 4) - 0.5) < 1e-12);
    CHECK(fabs(udm1_pattern_eval(n, &p, 2.75, 3, 4) - 0.5) < 1e-4); /* fmod by 1.00001 */
    udm1_pattern_params_init(&p, UDM1_PATTERN_LEOPARD);
    double l = (sin(0.3) + sin(0.6) + sin(0.9)) / 3;
    CHECK(fabs(udm1_pattern_eval(n, &p, 0.3, 0.6, 0.9) - l * l) < 1e-12);
    udm1_pattern_params_init(&p, UDM1_PATTERN_ONION);
    CHECK(fabs(udm1_pattern_eval(n, &p, 3, 4, 0) - 0.0) < 1e-4 && fabs(udm1_pattern_eval(n, &p, 0.3, 0.4, 0) - 0.5) < 1e-4);
    /* bozo is N(P) = (1 + noise) / 2 */
    udm1_pattern_params_init(&p, UDM1_PATTERN_BOZO);
    CHECK(fabs(udm1_pattern_eval(n, &p, 1.3, 2.1, 0.4) - (0.5 + 0.5 * udm1_noise_3d(n, 1.3, 2.1, 0.4))) < 1e-4);
    /* fbm with one octave is the noise; turbulence >= its first octave */
    udm1_pattern_params_init(&p, UDM1_PATTERN_FBM);
    p.octaves = 1;
    CHECK(udm1_pattern_eval(n, &p, 1.3, 2.1, 0.4) == udm1_noise_3d(n, 1.3, 2.1, 0.4));
    /* bad parameters */
    float img[4];
    double o[3] = {0, 0, 0}, s[3] = {1, 0, 0};
    p.octaves = 11;
    CHECK_STATUS(udm1_pattern_grid(n, &p, 2, 2, 0, 2, o, s, s, img), UDM1_ERROR_INVALID_ARGUMENT);
    p.octaves = 3;
    p.omega = NAN;
    CHECK_STATUS(udm1_pattern_grid(n, &p, 2, 2, 0, 2, o, s, s, img), UDM1_ERROR_INVALID_ARGUMENT);
    p.omega = 0.5;
    p.pattern = 99;
    CHECK_STATUS(udm1_pattern_grid(n, &p, 2, 2, 0, 2, o, s, s, img), UDM1_ERROR_INVALID_ARGUMENT);
    p.pattern = UDM1_PATTERN_BOZO;
    CHECK_STATUS(udm1_pattern_grid(n, &p, 2, 2, 1, 2, o, s, s, img), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_pattern_grid(n, &p, 0, 2, 0, 2, o, s, s, img), UDM1_ERROR_INVALID_ARGUMENT);
    double bad[3] = {0, INFINITY, 0}, out[1];
    CHECK_STATUS(udm1_pattern_grid(n, &p, 2, 2, 0, 2, bad, s, s, img), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_pattern_points(n, &p, bad, 1, 3, out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_pattern_points(NULL, &p, o, 1, 3, out), UDM1_ERROR_NULL_ARGUMENT);
    udm1_noise_destroy(n);
}

static void test_color_maps(void)
{
    const udm1_color_entry *e;
    size_t count;
    float rgb[3];
    CHECK_STATUS(udm1_pattern_default_colors(UDM1_PATTERN_BOZO, &e, &count), UDM1_OK);
    CHECK(count == 6);
    CHECK_STATUS(udm1_color_map_eval(e, count, 0.1, rgb), UDM1_OK); /* below the first: white */
    CHECK(rgb[0] == 1 && rgb[1] == 1 && rgb[2] == 1);
    CHECK_STATUS(udm1_color_map_eval(e, count, 0.4, rgb), UDM1_OK); /* exactly at a hard edge: the first colour */
    CHECK(rgb[0] == 1 && rgb[1] == 1);
    CHECK_STATUS(udm1_color_map_eval(e, count, 0.4000001, rgb), UDM1_OK); /* just above: green */
    CHECK(rgb[0] == 0 && rgb[1] == 1 && rgb[2] == 0);
    CHECK_STATUS(udm1_color_map_eval(e, count, 0.95, rgb), UDM1_OK); /* above the last: red */
    CHECK(rgb[0] == 1 && rgb[1] == 0);
    CHECK_STATUS(udm1_pattern_default_colors(UDM1_PATTERN_GRANITE, &e, &count), UDM1_OK);
    CHECK_STATUS(udm1_color_map_eval(e, count, 0.25, rgb), UDM1_OK); /* grey ramp: interpolation */
    CHECK(fabs(rgb[0] - 0.25f) < 1e-6f);
    udm1_color_entry unsorted[2] = {{0.5, {0, 0, 0}}, {0.2, {1, 1, 1}}};
    CHECK_STATUS(udm1_color_map_eval(unsorted, 2, 0.3, rgb), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_color_map_eval(unsorted, 0, 0.3, rgb), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_pattern_default_colors(0, &e, &count), UDM1_ERROR_INVALID_ARGUMENT);
}

static void test_batch_equals_per_call(void)
{
    /* the batch call (vectorized where the processor allows) equals the scalar one bit for bit, with
     * the kernel in use (udm1_isa(); CTest runs this test under each UDM1_ISA): also around groups with
     * far coordinates that go to the scalar code, at -0.0 (a zero's sign), for counts that leave a block
     * part full or a tail, packed (stride = dims) and strided */
    enum { N = 4099 };
    static double xyz[3 * N], a[N], b[N];
    for (int i = 0; i < 3 * N; ++i) {
        double r = uniform();
        xyz[i] = i % 97 == 5 ? (r - 0.5) * 1e12 : i % 89 == 3 ? 2147483647.5 : i % 83 == 1 ? -0.0 : (r - 0.5) * 2000.0;
    }
    for (int i = 0; i < 12; ++i) xyz[3 * (N - 13 + i) + i % 3] = i < 6 ? -0.0 : 0.0; /* in the last block */
    static const char *tables[] = {NULL, "wr", "drand48"};
    static const size_t counts[] = {N, 70, 37, 5};           /* 64 full blocks and a tail; part-full blocks */
    for (int c = 0; c < 3 * 2; ++c) {                        /* table, kind */
        int t = c / 2;
        uint32_t kind = (uint32_t)(c % 2);
        udm1_noise *n = make(tables[t], 9, kind, 0, 0, 0);
        for (uint32_t dims = 1; dims <= 3; ++dims)
            for (size_t stride = dims; stride <= 3; stride += 3 - dims > 0 ? 3 - dims : 1)
                for (size_t k = 0; k < sizeof counts / sizeof counts[0]; ++k) {
                    size_t m = counts[k];
                    const double *from = xyz + (N - m) * 3; /* the last m points of the strided array */
                    CHECK_STATUS(udm1_noise_points(n, dims, from, m, stride, a), UDM1_OK);
                    for (size_t i = 0; i < m; ++i) {
                        const double *q = from + stride * i;
                        b[i] = dims == 3   ? udm1_noise_3d(n, q[0], q[1], q[2])
                               : dims == 2 ? udm1_noise_2d(n, q[0], q[1])
                                           : udm1_noise_1d(n, q[0]);
                    }
                    CHECKF(memcmp(a, b, m * sizeof a[0]) == 0,
                           "%s: table %d kind %u dims %u stride %zu count %zu: batch differs from per call", udm1_isa(),
                           t, kind, dims, stride, m);
                }
        udm1_noise_destroy(n);
    }
}

static void test_batch_refuses_non_finite(void)
{
    /* a NaN or infinity anywhere is refused and the first one named, with the kernel in use, packed
     * (stride = dims) and strided, in every coordinate: in the first group, across a block's edge,
     * in the tail (N is not a multiple of 4), after a far coordinate in the same block (a group the
     * scalar code takes) and before a second bad point */
    enum { N = 5003 };
    static double xyz[4 * N], out[N];
    for (int i = 0; i < 4 * N; ++i) xyz[i] = (uniform() - 0.5) * 200.0;
    udm1_noise *n = make("wr", 1, 0, 0, 0, 0);
    static const size_t at[] = {0, 63, 64, 1023, 1024, 3001, N - 2};
    static const double bad[] = {NAN, INFINITY, -INFINITY};
    {
        for (uint32_t dims = 1; dims <= 3; ++dims)
            for (size_t stride = dims; stride <= 4; stride += 4 - dims > 0 ? 4 - dims : 1)
                for (size_t k = 0; k < sizeof at / sizeof at[0]; ++k)
                    for (uint32_t c = 0; c < dims; ++c) {
                        double *v = &xyz[at[k] * stride + c], keep = *v;
                        double *far = at[k] >= 3 ? &xyz[(at[k] - 3) * stride] : NULL, keep_far = far ? *far : 0;
                        double *second = at[k] + 1 < N ? &xyz[(at[k] + 1) * stride] : NULL,
                               keep_second = second ? *second : 0;
                        *v = bad[(k + c) % 3];
                        if (far) *far = 3e9;
                        if (second) *second = NAN;
                        CHECK_STATUS(udm1_noise_points(n, dims, xyz, N, stride, out), UDM1_ERROR_INVALID_ARGUMENT);
                        char want[64];
                        snprintf(want, sizeof want, "point %zu coordinate %u is not finite", at[k], c);
                        CHECKF(strstr(udm1_last_error(), want) != NULL, "%s dims %u stride %zu: '%s' lacks '%s'", udm1_isa(),
                               dims, stride, udm1_last_error(), want);
                        *v = keep;
                        if (far) *far = keep_far;
                        if (second) *second = keep_second;
                    }
        CHECK_STATUS(udm1_noise_points(n, 3, xyz, N, 3, out), UDM1_OK);
    }
    udm1_noise_destroy(n);
}

static void test_grid_equals_eval(void)
{
    /* image rows (batched for noise and fBm) equal the per-point evaluation bit for bit */
    udm1_noise *n = make("rd", 3, 0, 0, 0, 0);
    enum { W = 37, H = 5 };
    static float img[W * H];
    double o[3] = {-13.7, 4.1, 0.3}, sx[3] = {0.173, 0.01, 0}, sy[3] = {0, 0.19, 0.07};
    for (uint32_t pat = UDM1_PATTERN_NOISE; pat <= UDM1_PATTERN_WAVES; ++pat) {
        udm1_pattern_params p;
        udm1_pattern_params_init(&p, pat);
        CHECK_STATUS(udm1_pattern_grid(n, &p, W, H, 0, H, o, sx, sy, img), UDM1_OK);
        int bad = 0;
        for (int j = 0; j < H; ++j)
            for (int i = 0; i < W; ++i) {
                double a = i + 0.5, b = j + 0.5, q[3];
                for (int c = 0; c < 3; ++c) q[c] = o[c] + a * sx[c] + b * sy[c];
                float e = (float)udm1_pattern_eval(n, &p, q[0], q[1], q[2]);
                bad += memcmp(&e, &img[j * W + i], sizeof e) != 0;
            }
        CHECKF(bad == 0, "%s: %d grid pixels differ from the per-point evaluation", udm1_pattern_name(pat), bad);
    }
    udm1_noise_destroy(n);
}

static void test_bad_input(void)
{
    udm1_noise_desc d;
    udm1_noise *n = (udm1_noise *)&d;
    CHECK_STATUS(udm1_noise_create(NULL, &n), UDM1_ERROR_NULL_ARGUMENT);
    CHECK(n == NULL);
    udm1_noise_desc_init(&d);
    CHECK_STATUS(udm1_noise_create(&d, NULL), UDM1_ERROR_NULL_ARGUMENT);
    d.kind = 7;
    CHECK_STATUS(udm1_noise_create(&d, &n), UDM1_ERROR_INVALID_ARGUMENT);
    d.kind = 0;
    d.period[1] = (1u << 30) + 1;
    CHECK_STATUS(udm1_noise_create(&d, &n), UDM1_ERROR_INVALID_ARGUMENT);
    d.period[1] = 0;
    d.table = "nope";
    CHECK_STATUS(udm1_noise_create(&d, &n), UDM1_ERROR_UNKNOWN_PRESET);
    CHECK(strstr(udm1_last_error(), "'nope'") != NULL);
    d.table = NULL;
    d.struct_size = 4;
    CHECK_STATUS(udm1_noise_create(&d, &n), UDM1_ERROR_INVALID_ARGUMENT);
    udm1_noise_destroy(NULL);
    CHECK_STATUS(udm1_noise_tables(NULL, NULL, NULL), UDM1_ERROR_NULL_ARGUMENT);
}

int main(void)
{
    test_reference();
    test_equals_transcription();
    test_range_and_moments();
    test_determinism_and_seeds();
    test_drand48_table();
    test_tileable();
    test_derivative_continuity();
    test_far_coordinates();
    test_table_spectrum();
    test_patterns();
    test_color_maps();
    test_batch_equals_per_call();
    test_batch_refuses_non_finite();
    test_grid_equals_eval();
    test_bad_input();
    CHECK_DONE();
}
