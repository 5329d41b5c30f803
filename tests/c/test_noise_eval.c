/* test_noise_eval.c - udm1_noise_eval (double) and udm1_noise_eval_f32 (float), values and analytic
 * gradients in 1 to 4 dimensions, under whichever kernel udm1_isa() names (CTest runs this test under
 * each UDM1_ISA level):
 *  - float values equal an independent float transcription of Perlin's improved noise (3D) and of
 *    noise1234 (2D) bit for bit, signed zeros included: every table, near and far (to 1e12), packed,
 *    one array per axis and strided, counts that leave tails;
 *  - double values equal udm1_noise_1d..4d bit for bit; 4D equals an independent transcription;
 *  - float values and gradients of a batch equal those of each point alone (the scalar code) bit for bit,
 *    zeros' signs included (lattice points, -0 and halves);
 *  - with a gradient asked for, the values are the value-only call's bit for bit;
 *  - gradients against central differences of the noise (double), and float's against double's;
 *  - float far from the origin: as accurate as the double code at the same (float) coordinates;
 *  - 4D periodic in w (a looping texture) and in x, exactly; classic noise has no 4D;
 *  - points in rows of 1 to 6 numbers (the kernels' strided loads and gathers), noise and cellular noise
 *    in float and double: the values of one array per axis bit for bit, the rows at the very end of
 *    their allocation (nothing past the last point is read: AddressSanitizer's build);
 *  - large batches (the kernels check the coordinates of the later points while they evaluate the first
 *    ones into memory of their own: noise/batch.c) equal the same batch in pieces of 1000 bit for bit, in
 *    every layout, also with NaN in the unused columns of rows (read by that check, then found harmless);
 *  - bad input: one message, the point named.
 */
#include "check.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static udm1_noise *make(const char *table, uint32_t kind, uint32_t px, uint32_t pw)
{
    udm1_noise_desc d;
    udm1_noise_desc_init(&d);
    d.table = table, d.seed = 11, d.kind = kind, d.period[0] = px, d.period_w = pw;
    udm1_noise *n = NULL;
    CHECK_STATUS(udm1_noise_create(&d, &n), UDM1_OK);
    return n;
}

static uint64_t rng = 3;
static double uniform(void)
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng >> 11) * 0x1p-53;
}

/* Perlin's ImprovedNoise (3D) and noise1234 (2D) transcribed in float on the table's permutation */
static float transcribed3f(const uint8_t perm[256], float x, float y, float z)
{
    int p[512];
    for (int i = 0; i < 512; ++i) p[i] = perm[i & 255];
    float fx = floorf(x), fy = floorf(y), fz = floorf(z);
    int X = (int)((long long)fx & 255), Y = (int)((long long)fy & 255), Z = (int)((long long)fz & 255);
    x = (x - fx) + 0.0f, y = (y - fy) + 0.0f, z = (z - fz) + 0.0f;
    float u = x * x * x * (x * (x * 6 - 15) + 10), v = y * y * y * (y * (y * 6 - 15) + 10);
    float w = z * z * z * (z * (z * 6 - 15) + 10);
    int A = p[X] + Y, AA = p[A] + Z, AB = p[A + 1] + Z, B = p[X + 1] + Y, BA = p[B] + Z, BB = p[B + 1] + Z;
#define G(h, a, b, c)                                                                                                 \
    ((((((h) & 15) < 8 ? (a) : (b)) * (((h) & 1) ? -1.0f : 1.0f)) +                                                 \
      ((((h) & 15) < 4 ? (b) : (((h) & 15) == 12 || ((h) & 15) == 14) ? (a) : (c)) * (((h) & 2) ? -1.0f : 1.0f))) + \
     0.0f) /* (udm1's float noise turns a corner's zero to +0) */
#define L(t, a, b) ((a) + (t) * ((b) - (a)))
    float r = L(w, L(v, L(u, G(p[AA], x, y, z), G(p[BA], x - 1, y, z)), L(u, G(p[AB], x, y - 1, z), G(p[BB], x - 1, y - 1, z))),
                L(v, L(u, G(p[AA + 1], x, y, z - 1), G(p[BA + 1], x - 1, y, z - 1)),
                  L(u, G(p[AB + 1], x, y - 1, z - 1), G(p[BB + 1], x - 1, y - 1, z - 1))));
#undef G
    return r;
}

static float transcribed2f(const uint8_t perm[256], float x, float y)
{
    int p[512];
    for (int i = 0; i < 512; ++i) p[i] = perm[i & 255];
    float fx = floorf(x), fy = floorf(y);
    int X = (int)((long long)fx & 255), Y = (int)((long long)fy & 255);
    x = (x - fx) + 0.0f, y = (y - fy) + 0.0f;
    float u = x * x * x * (x * (x * 6 - 15) + 10), v = y * y * y * (y * (y * 6 - 15) + 10);
#define G(h, a, b) (((((h) & 7) < 4 ? (a) : (b)) * (((h) & 1) ? -1.0f : 1.0f)) + ((((h) & 7) < 4 ? (b) : (a)) * (((h) & 2) ? -2.0f : 2.0f)))
    float r = L(v, L(u, G(p[p[X] + Y], x, y), G(p[p[X + 1] + Y], x - 1, y)),
                L(u, G(p[p[X] + Y + 1], x, y - 1), G(p[p[X + 1] + Y + 1], x - 1, y - 1)));
#undef G
    return 0.507f * r;
}

/* 4D improved noise transcribed in double: Perlin's hashing, noise1234's grad4, scaled by 0.87 */
static double transcribed4(const uint8_t perm[256], const double c[4])
{
    int p[512], X[4];
    for (int i = 0; i < 512; ++i) p[i] = perm[i & 255];
    double t[4], f[4];
    for (int k = 0; k < 4; ++k) {
        double fl = floor(c[k]);
        X[k] = (int)((long long)fl & 255), t[k] = (c[k] - fl) + 0.0;
        f[k] = t[k] * t[k] * t[k] * (t[k] * (t[k] * 6 - 15) + 10);
    }
    double v[16];
    for (int k = 0; k < 16; ++k) {
        int a = k & 1, b = k >> 1 & 1, d = k >> 2 & 1, e = k >> 3 & 1;
        int h = p[p[p[p[X[0] + a] + X[1] + b] + X[2] + d] + X[3] + e] & 31;
        double x = t[0] - a, y = t[1] - b, z = t[2] - d, w = t[3] - e;
        double uu = h < 24 ? x : y, vv = h < 16 ? y : z, ww = h < 8 ? z : w;
        v[k] = ((h & 1) ? -uu : uu) + ((h & 2) ? -vv : vv) + ((h & 4) ? -ww : ww);
    }
    for (int m = 16, ax = 0; m > 1; m /= 2, ++ax)
        for (int k = 0; k < m / 2; ++k) v[k] = L(f[ax], v[2 * k], v[2 * k + 1]);
    return 0.87 * v[0];
}
#undef L

enum { N = 4099 };

static void test_float_equals_transcription(void)
{
    static float soa[3][N], packed[3 * N], strided[5 * N], out[N], out2[N], grad[3 * N];
    for (int i = 0; i < N; ++i)
        for (int c = 0; c < 3; ++c) {
            double r = uniform();
            float v = i % 97 == 5 ? (float)((r - 0.5) * 1e12) : i % 89 == 3 ? 2147483647.0f : i % 83 == 1 ? -0.0f
                                                                                               : (float)((r - 0.5) * 600);
            if (i % 79 == 7) v = (float)((r - 0.5) * 4e7); /* where a float's offset has few bits */
            soa[c][i] = packed[3 * i + c] = strided[5 * i + c] = v;
        }
    static const char *tables[] = {NULL, "wr", "drand48"};
    static const size_t counts[] = {N, 37, 5};
    for (int t = 0; t < 3; ++t) {
        udm1_noise *n = make(tables[t], UDM1_NOISE_IMPROVED, 0, 0);
        uint8_t perm[256];
        CHECK_STATUS(udm1_noise_tables(n, perm, NULL), UDM1_OK);
        for (uint32_t dims = 2; dims <= 3; ++dims)
            for (int layout = 0; layout < 3; ++layout)
                for (size_t k = 0; k < 3; ++k) {
                    size_t m = counts[k], off = N - m;
                    const float *axes[3];
                    size_t stride = layout == 0 ? 1 : layout == 1 ? 3 : 5;
                    for (int c = 0; c < 3; ++c)
                        axes[c] = layout == 0 ? soa[c] + off : layout == 1 ? packed + 3 * off + c : strided + 5 * off + c;
                    CHECK_STATUS(udm1_noise_eval_f32(n, dims, axes, stride, m, out, NULL), UDM1_OK);
                    CHECK_STATUS(udm1_noise_eval_f32(n, dims, axes, stride, m, out2, grad), UDM1_OK);
                    int bad = 0, bad_with_grad = 0;
                    for (size_t i = 0; i < m; ++i) {
                        float x = soa[0][off + i], y = soa[1][off + i], z = soa[2][off + i];
                        float want = dims == 3 ? transcribed3f(perm, x, y, z) : transcribed2f(perm, x, y);
                        bad += memcmp(&want, &out[i], sizeof want) != 0;
                        bad_with_grad += memcmp(&out2[i], &out[i], sizeof want) != 0;
                    }
                    CHECKF(bad == 0 && bad_with_grad == 0,
                           "%s: table %d dims %u layout %d count %zu: %d values differ from the transcription, %d with "
                           "the gradient from without",
                           udm1_isa(), t, dims, layout, m, bad, bad_with_grad);
                }
        udm1_noise_destroy(n);
    }
}

/* The float batch (the vector kernels in groups of 8 or 16) against the scalar float code for the point
 * alone (a call of one point), values and gradients bit for bit, zeros' signs included: lattice points,
 * -0 and halves on some axes, where corners' values and the gradient's terms are zeros of either sign. */
static void test_float_equals_per_call(void)
{
    static float xs[3][N], v[N], g[3 * N];
    for (int i = 0; i < N; ++i)
        for (int c = 0; c < 3; ++c) {
            double r = (uniform() - 0.5) * 500;
            xs[c][i] = (float)r;
            if (i % 3 != 1) continue;
            double u = uniform();
            xs[c][i] = u < 0.4 ? (float)floor(r) : u < 0.55 ? -0.0f : u < 0.7 ? 0.0f : u < 0.85 ? (float)floor(r) + 0.5f : xs[c][i];
        }
    static const char *tables[] = {NULL, "wr", "drand48"};
    for (int t = 0; t < 3; ++t) {
        udm1_noise *n = make(tables[t], UDM1_NOISE_IMPROVED, 0, 0);
        for (uint32_t dims = 2; dims <= 3; ++dims) {
            const float *axes[3] = {xs[0], xs[1], xs[2]};
            CHECK_STATUS(udm1_noise_eval_f32(n, dims, axes, 1, N, v, g), UDM1_OK);
            int bad = 0;
            for (int i = 0; i < N; ++i) {
                const float *one[3] = {xs[0] + i, xs[1] + i, xs[2] + i};
                float v1, g1[3];
                CHECK_STATUS(udm1_noise_eval_f32(n, dims, one, 1, 1, &v1, g1), UDM1_OK);
                bad += memcmp(&v1, &v[i], sizeof v1) != 0 || memcmp(g1, g + (size_t)i * dims, sizeof(float) * dims) != 0;
            }
            CHECKF(bad == 0, "%s: table %d dims %u: %d float values or gradients differ from the per-point call", udm1_isa(), t,
                   dims, bad);
        }
        udm1_noise_destroy(n);
    }
}

static void test_double_equals_per_call(void)
{
    static double xs[4][N], v[N], v2[N], g[4 * N];
    for (int i = 0; i < N; ++i)
        for (int c = 0; c < 4; ++c) {
            xs[c][i] = i % 53 == 2 ? (uniform() - 0.5) * 1e12 : (uniform() - 0.5) * 500;
            if (i % 7 == 3) /* lattice points, -0 and halves: values and gradients of zero, with their signs */
                xs[c][i] = uniform() < 0.5 ? floor(xs[c][i]) : uniform() < 0.3 ? -0.0 : floor(xs[c][i]) + 0.5;
        }
    for (uint32_t kind = 0; kind <= 1; ++kind) {
        udm1_noise *n = make("wr", kind, 0, 0), *p = make(NULL, kind, 6, 0);
        for (int q = 0; q < 2; ++q) {
            udm1_noise *m = q ? p : n;
            for (uint32_t dims = 1; dims <= (kind == UDM1_NOISE_IMPROVED ? 4u : 3u); ++dims) {
                const double *axes[4] = {xs[0], xs[1], xs[2], xs[3]};
                CHECK_STATUS(udm1_noise_eval(m, dims, axes, 1, N, v, NULL), UDM1_OK);
                CHECK_STATUS(udm1_noise_eval(m, dims, axes, 1, N, v2, g), UDM1_OK);
                int bad = 0;
                for (int i = 0; i < N; ++i) {
                    double want = dims == 1   ? udm1_noise_1d(m, xs[0][i])
                                  : dims == 2 ? udm1_noise_2d(m, xs[0][i], xs[1][i])
                                  : dims == 3 ? udm1_noise_3d(m, xs[0][i], xs[1][i], xs[2][i])
                                              : udm1_noise_4d(m, xs[0][i], xs[1][i], xs[2][i], xs[3][i]);
                    bad += memcmp(&want, &v[i], sizeof want) != 0 || memcmp(&want, &v2[i], sizeof want) != 0;
                    /* the gradient as the scalar code gives it for the point alone, zeros' signs included */
                    const double *one[4] = {xs[0] + i, xs[1] + i, xs[2] + i, xs[3] + i};
                    double g1[4], v1;
                    CHECK_STATUS(udm1_noise_eval(m, dims, one, 1, 1, &v1, g1), UDM1_OK);
                    bad += memcmp(g1, g + (size_t)i * dims, sizeof(double) * dims) != 0;
                }
                CHECKF(bad == 0, "%s: kind %u periodic %d dims %u: %d values or gradients differ from the per-point call", udm1_isa(),
                       kind, q, dims, bad);
            }
        }
        udm1_noise_destroy(n), udm1_noise_destroy(p);
    }
}

static void test_4d(void)
{
    udm1_noise *n = make("wr", UDM1_NOISE_IMPROVED, 0, 0);
    uint8_t perm[256];
    CHECK_STATUS(udm1_noise_tables(n, perm, NULL), UDM1_OK);
    int bad = 0;
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        double c[4];
        for (int k = 0; k < 4; ++k) c[k] = (uniform() - 0.5) * (i % 10 == 0 ? 1e9 : 300);
        double a = udm1_noise_4d(n, c[0], c[1], c[2], c[3]), b = transcribed4(perm, c);
        bad += memcmp(&a, &b, sizeof a) != 0;
        worst = fmax(worst, fabs(a));
    }
    CHECKF(bad == 0, "4D: %d of 20000 values differ from the transcription", bad);
    CHECKF(worst > 0.5 && worst < 1.2, "4D: largest |noise| %.4f, not about 1", worst);
    CHECK(udm1_noise_4d(n, 3, -7, 12, 100) == 0); /* a lattice point */
    udm1_noise_destroy(n);
    /* periodic in w (period 7: a texture that loops over 7 units of time) and in x (period 5), exactly */
    udm1_noise *p = make(NULL, UDM1_NOISE_IMPROVED, 5, 7);
    int wrong = 0;
    for (int i = 0; i < 5000; ++i) {
        /* multiples of 2^-20, so that adding the periods is exact */
        double x = ldexp(floor(ldexp((uniform() - 0.5) * 40, 20)), -20), y = uniform() * 9, z = uniform() * 9;
        double w = ldexp(floor(ldexp((uniform() - 0.5) * 40, 20)), -20);
        double a = udm1_noise_4d(p, x, y, z, w);
        wrong += a != udm1_noise_4d(p, x + 5, y, z, w) || a != udm1_noise_4d(p, x, y, z, w + 7) ||
                 a != udm1_noise_4d(p, x - 10, y, z, w - 21);
    }
    CHECKF(wrong == 0, "4D periodic: %d of 5000 points differ from their periodic images", wrong);
    udm1_noise_destroy(p);
    udm1_noise *c = make(NULL, UDM1_NOISE_CLASSIC, 0, 0);
    CHECK(isnan(udm1_noise_4d(c, 0.5, 0.5, 0.5, 0.5)) && strstr(udm1_last_error(), "improved") != NULL);
    const double x = 0.5, *ax[4] = {&x, &x, &x, &x};
    double v;
    CHECK_STATUS(udm1_noise_eval(c, 4, ax, 1, 1, &v, NULL), UDM1_ERROR_INVALID_ARGUMENT);
    udm1_noise_destroy(c);
}

/* the gradient against central differences of the noise, in double; float's against double's */
static void test_gradients(void)
{
    for (uint32_t kind = 0; kind <= 1; ++kind) {
        udm1_noise *n = make(kind ? "drand48" : NULL, kind, 0, 0), *p = make("wr", kind, 9, 0);
        for (int q = 0; q < 2; ++q) {
            udm1_noise *m = q ? p : n;
            for (uint32_t dims = 1; dims <= (kind == UDM1_NOISE_IMPROVED ? 4u : 3u); ++dims) {
                double worst = 0, worst_f = 0;
                for (int i = 0; i < 3000; ++i) {
                    double c[4], g[4], v;
                    for (int k = 0; k < 4; ++k) c[k] = (float)((uniform() - 0.5) * 60); /* floats, for the float path */
                    const double *ax[4] = {&c[0], &c[1], &c[2], &c[3]};
                    CHECK_STATUS(udm1_noise_eval(m, dims, ax, 1, 1, &v, g), UDM1_OK);
                    for (uint32_t k = 0; k < dims; ++k) {
                        /* h = 1e-5: the truncation error (h^2 times the third derivative, under 1e3 here) and
                         * the rounding (1e-16 / h) both below 1e-7; a wrong term is of the order of 1 */
                        double lo[4], hi[4], vl, vh, h = 1e-5;
                        memcpy(lo, c, sizeof c), memcpy(hi, c, sizeof c);
                        lo[k] -= h, hi[k] += h;
                        const double *al[4] = {&lo[0], &lo[1], &lo[2], &lo[3]}, *ah[4] = {&hi[0], &hi[1], &hi[2], &hi[3]};
                        CHECK_STATUS(udm1_noise_eval(m, dims, al, 1, 1, &vl, NULL), UDM1_OK);
                        CHECK_STATUS(udm1_noise_eval(m, dims, ah, 1, 1, &vh, NULL), UDM1_OK);
                        worst = fmax(worst, fabs(g[k] - (vh - vl) / (2 * h)));
                    }
                    float cf[4] = {(float)c[0], (float)c[1], (float)c[2], (float)c[3]}, gf[4], vf;
                    const float *af[4] = {&cf[0], &cf[1], &cf[2], &cf[3]};
                    CHECK_STATUS(udm1_noise_eval_f32(m, dims, af, 1, 1, &vf, gf), UDM1_OK);
                    worst_f = fmax(worst_f, fabs(vf - v));
                    for (uint32_t k = 0; k < dims; ++k) worst_f = fmax(worst_f, fabs(gf[k] - g[k]) / 30);
                }
                CHECKF(worst < 1e-6, "kind %u periodic %d dims %u: gradient against central differences: %.3g", kind,
                       q, dims, worst);
                /* float against double at the same coordinates: a few float roundings of values about 1 */
                CHECKF(worst_f < 2e-5, "kind %u periodic %d dims %u: float against double: %.3g", kind, q, dims, worst_f);
            }
        }
        udm1_noise_destroy(n), udm1_noise_destroy(p);
    }
}

/* far from the origin a float's offset in its cell keeps the float's precision: the float noise equals
 * the double noise at the same coordinates within float rounding, up to where floats are integers */
static void test_float_far(void)
{
    udm1_noise *n = make("wr", UDM1_NOISE_IMPROVED, 0, 0);
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        double s = ldexp(1.0, 4 + i % 28); /* 16 .. 2^31 */
        float c[3] = {(float)((uniform() - 0.5) * s), (float)((uniform() - 0.5) * s), (float)((uniform() - 0.5) * s)}, v;
        const float *af[3] = {&c[0], &c[1], &c[2]};
        CHECK_STATUS(udm1_noise_eval_f32(n, 3, af, 1, 1, &v, NULL), UDM1_OK);
        worst = fmax(worst, fabs(v - udm1_noise_3d(n, c[0], c[1], c[2])));
    }
    CHECKF(worst < 1e-5, "float against double far from the origin: %.3g", worst);
    /* past 2^24 every float is an integer: the noise of integer coordinates, 0 */
    float big[3] = {3e9f, -5e10f, 7e20f}, v = 1;
    const float *ab[3] = {&big[0], &big[1], &big[2]};
    CHECK_STATUS(udm1_noise_eval_f32(n, 3, ab, 1, 1, &v, NULL), UDM1_OK);
    CHECK(v == 0);
    udm1_noise_destroy(n);
}

/* One evaluation of every batch function on points in rows of `stride` numbers (the last row ends the
 * allocation) against the same points in one array per axis. */
static void test_rows(void)
{
    enum { M = 1000 };
    static double soa64[3][M], out64[2][M], grad64[2][3 * M];
    static float soa32[3][M], out32[2][M], grad32[2][3 * M];
    for (int i = 0; i < M; ++i)
        for (int c = 0; c < 3; ++c) soa64[c][i] = soa32[c][i] = (float)((uniform() - 0.5) * (i % 31 == 4 ? 1e7 : 300));
    udm1_noise *n = make("wr", UDM1_NOISE_IMPROVED, 0, 0);
    udm1_cellular_params cp;
    udm1_cellular_params_init(&cp);
    for (uint32_t dims = 2; dims <= 3; ++dims)
        for (size_t stride = dims; stride <= 6; ++stride)
            for (size_t m = M; m >= 3; m = m / 3 - 1) { /* tails of every length class */
                size_t len = (m - 1) * stride + dims; /* the last row ends at the last coordinate */
                double *r64 = malloc(len * sizeof *r64);
                float *r32 = malloc(len * sizeof *r32);
                CHECK(r64 && r32);
                for (size_t i = 0; i < m; ++i)
                    for (uint32_t c = 0; c < dims; ++c)
                        r64[i * stride + c] = soa64[c][M - m + i], r32[i * stride + c] = soa32[c][M - m + i];
                const double *a64[3] = {soa64[0] + M - m, soa64[1] + M - m, soa64[2] + M - m}, *q64[3] = {r64, r64 + 1, r64 + 2};
                const float *a32[3] = {soa32[0] + M - m, soa32[1] + M - m, soa32[2] + M - m}, *q32[3] = {r32, r32 + 1, r32 + 2};
                int bad = 0;
                for (int which = 0; which < 4; ++which) {
                    for (int layout = 0; layout < 2; ++layout) {
                        const double *const *x64 = layout ? q64 : a64;
                        const float *const *x32 = layout ? q32 : a32;
                        size_t st = layout ? stride : 1;
                        if (which == 0) CHECK_STATUS(udm1_noise_eval(n, dims, x64, st, m, out64[layout], grad64[layout]), UDM1_OK);
                        if (which == 1) CHECK_STATUS(udm1_noise_eval_f32(n, dims, x32, st, m, out32[layout], grad32[layout]), UDM1_OK);
                        if (which == 2) CHECK_STATUS(udm1_cellular_eval(n, &cp, dims, x64, st, m, out64[layout]), UDM1_OK);
                        if (which == 3) CHECK_STATUS(udm1_cellular_eval_f32(n, &cp, dims, x32, st, m, out32[layout]), UDM1_OK);
                    }
                    if (which % 2 == 0)
                        bad += memcmp(out64[0], out64[1], m * sizeof(double)) != 0 ||
                               (which == 0 && memcmp(grad64[0], grad64[1], m * dims * sizeof(double)) != 0);
                    else
                        bad += memcmp(out32[0], out32[1], m * sizeof(float)) != 0 ||
                               (which == 1 && memcmp(grad32[0], grad32[1], m * dims * sizeof(float)) != 0);
                }
                CHECKF(bad == 0, "%s: dims %u, rows of %zu, %zu points: %d of 4 batch functions differ from one array per axis",
                       udm1_isa(), dims, stride, m, bad);
                free(r64), free(r32);
            }
    udm1_noise_destroy(n);
}

/* A batch of m points against the same batch in pieces of 1000 (each checked before it is evaluated). */
static int batch_equals_pieces(const udm1_noise *n, uint32_t dims, const void *const *axes, size_t stride, size_t m,
                               int f32, int points, int gradient)
{
    size_t size = f32 ? sizeof(float) : sizeof(double);
    char *v1 = malloc(m * size), *v2 = malloc(m * size), *g1 = malloc(m * dims * size), *g2 = malloc(m * dims * size);
    CHECK(v1 && v2 && g1 && g2);
    int same = 1;
    for (int whole = 1; whole >= 0; --whole) {
        char *v = whole ? v1 : v2, *g = whole ? g1 : g2;
        for (size_t at = 0, k = whole ? m : 1000; at < m; at += k) {
            size_t c = m - at < k ? m - at : k;
            const void *sub[4];
            for (uint32_t a = 0; a < dims; ++a) sub[a] = (const char *)axes[a] + at * stride * size;
            udm1_status st;
            if (points)
                st = udm1_noise_points(n, dims, sub[0], c, stride, (double *)(void *)(v + at * size));
            else if (f32)
                st = udm1_noise_eval_f32(n, dims, (const float *const *)sub, stride, c, (float *)(void *)(v + at * size),
                                         gradient ? (float *)(void *)(g + at * dims * size) : NULL);
            else
                st = udm1_noise_eval(n, dims, (const double *const *)sub, stride, c, (double *)(void *)(v + at * size),
                                     gradient ? (double *)(void *)(g + at * dims * size) : NULL);
            same &= st == UDM1_OK;
        }
    }
    same &= memcmp(v1, v2, m * size) == 0 && (!gradient || memcmp(g1, g2, m * dims * size) == 0);
    free(v1), free(v2), free(g1), free(g2);
    return same;
}

static void test_large_batches(void)
{
    enum { M = 9001 };
    static double soa64[3][M], rows64[4 * M];
    static float soa32[3][M], rows32[4 * M];
    udm1_noise *n = make("wr", UDM1_NOISE_IMPROVED, 0, 0);
    const size_t counts[] = {4096, 4097, 5003, M};
    for (size_t t = 0; t < sizeof counts / sizeof counts[0]; ++t) {
        size_t m = counts[t];
        for (size_t i = 0; i < m; ++i)
            for (int c = 0; c < 3; ++c) {
                double v = (uniform() - 0.5) * (i % 97 == 5 ? 1e10 : 200); /* some past 2^31: the scalar groups */
                soa64[c][i] = soa32[c][i] = (float)v;
            }
        for (uint32_t dims = 2; dims <= 3; ++dims)
            for (size_t stride = 1; stride <= 4; ++stride) {
                if (stride > 1 && stride < dims) continue;
                const void *a64[3], *a32[3];
                if (stride == 1) {
                    for (uint32_t c = 0; c < 3; ++c) a64[c] = soa64[c], a32[c] = soa32[c];
                } else {
                    for (size_t i = 0; i < m; ++i)
                        for (size_t c = 0; c < stride; ++c) { /* unused columns: NaN */
                            rows64[i * stride + c] = c < dims ? soa64[c][i] : NAN;
                            rows32[i * stride + c] = c < dims ? soa32[c][i] : NAN;
                        }
                    for (uint32_t c = 0; c < 3; ++c) a64[c] = rows64 + c, a32[c] = rows32 + c;
                }
                for (int gradient = 0; gradient <= 1; ++gradient) {
                    CHECKF(batch_equals_pieces(n, dims, a32, stride, m, 1, 0, gradient),
                           "%s: float, dims %u, stride %zu, %zu points, gradient %d", udm1_isa(), dims, stride, m, gradient);
                    CHECKF(batch_equals_pieces(n, dims, a64, stride, m, 0, 0, gradient),
                           "%s: double, dims %u, stride %zu, %zu points, gradient %d", udm1_isa(), dims, stride, m, gradient);
                }
                if (stride >= dims)
                    CHECKF(batch_equals_pieces(n, dims, a64, stride, m, 0, 1, 0), "%s: points, dims %u, stride %zu, %zu points",
                           udm1_isa(), dims, stride, m);
            }
    }
    udm1_noise_destroy(n);
}

static void test_bad_input(void)
{
    udm1_noise *n = make(NULL, UDM1_NOISE_IMPROVED, 0, 0);
    float x[40], v[40], g[120];
    for (int i = 0; i < 40; ++i) x[i] = (float)i * 0.37f;
    const float *ax[3] = {x, x, x};
    x[33] = NAN;
    CHECK_STATUS(udm1_noise_eval_f32(n, 3, ax, 1, 40, v, g), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "point 33") != NULL);
    x[33] = 1;
    CHECK_STATUS(udm1_noise_eval_f32(n, 5, ax, 1, 40, v, NULL), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_noise_eval_f32(n, 0, ax, 1, 40, v, NULL), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_noise_eval_f32(n, 3, ax, 0, 40, v, NULL), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_noise_eval_f32(n, 3, ax, 1, 40, NULL, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_noise_eval_f32(NULL, 3, ax, 1, 40, v, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_noise_eval_f32(n, 3, NULL, 1, 40, v, NULL), UDM1_ERROR_NULL_ARGUMENT);
    const float *missing[3] = {x, NULL, x};
    CHECK_STATUS(udm1_noise_eval_f32(n, 3, missing, 1, 40, v, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "axes[1]") != NULL);
    CHECK_STATUS(udm1_noise_eval_f32(n, 3, ax, 1, 0, v, NULL), UDM1_OK); /* nothing to do */
    udm1_noise_desc d;
    udm1_noise_desc_init(&d);
    d.period_w = (1u << 30) + 1;
    udm1_noise *bad = NULL;
    CHECK_STATUS(udm1_noise_create(&d, &bad), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(bad == NULL && strstr(udm1_last_error(), "period_w") != NULL);
    udm1_noise_destroy(n);
}

int main(void)
{
    test_float_equals_transcription();
    test_float_equals_per_call();
    test_double_equals_per_call();
    test_4d();
    test_gradients();
    test_float_far();
    test_rows();
    test_large_batches();
    test_bad_input();
    CHECK_DONE();
}
