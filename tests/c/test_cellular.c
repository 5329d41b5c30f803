/* test_cellular.c - udm1_cellular_eval (double) and udm1_cellular_eval_f32 (float) under whichever kernel
 * udm1_isa() names (CTest runs this test under each UDM1_ISA level):
 *  - every output, metric, jitter, table, dimension and precision equals an independent brute-force
 *    transcription (all cells within 3 of the point, the documented arithmetic) bit for bit, near the
 *    origin and far from it (to 3e12, past 2^31), packed, one array per axis and strided, counts that leave tails;
 *  - Minkowski with exponent 2 and 1 equals Euclidean and Manhattan bit for bit; exponent 3 equals the
 *    transcription;
 *  - periodic textures repeat exactly, on every axis with a period;
 *  - F1 <= F2 <= F3; the distance to a feature point placed exactly is 0;
 *  - bad input: one message, the argument or point named.
 */
#include "check.h"

/* the transcription's fused multiply-add: the C library's, but on Windows, whose C library's (MinGW-w64's)
 * is not rounded once, the library's emulation (tests/c/test_fma.c checks it against the FMA instruction) */
#include "core/fma.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static udm1_noise *make(const char *table, uint32_t px, uint32_t py, uint32_t pz)
{
    udm1_noise_desc d;
    udm1_noise_desc_init(&d);
    d.table = table, d.seed = 7, d.period[0] = px, d.period[1] = py, d.period[2] = pz;
    udm1_noise *n = NULL;
    CHECK_STATUS(udm1_noise_create(&d, &n), UDM1_OK);
    return n;
}

static uint64_t rng = 5;
static double uniform(void)
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng >> 11) * 0x1p-53;
}

/* The documented definition, by brute force over the cells within 4 of the point's (enough: the 8 cells
 * around the point's nearest lattice corner hold points within 1.5 of it on every axis, so F3 <= 4.5 in
 * every metric, 3 sqrt(0.25 + ...) less in the others, while a cell 5 away is at least 4 away). */
typedef struct {
    uint8_t perm[256], off[768];
    uint32_t period[3];
} tables;

static long long mod(long long a, long long m) { return ((a % m) + m) % m; }

#define BRUTE(REAL, NAME, FLOOR, FMA, SQRT, POW, FABS)                                                              \
    static void NAME(const tables *T, int dims, const REAL *c, int metric, double jitter, double expo, REAL out[5])  \
    {                                                                                                               \
        REAL c1 = (REAL)jitter * (REAL)(1.0 / 256), c0 = (REAL)0.5 - (REAL)127.5 * c1, e = (REAL)expo;              \
        REAL t[3] = {0, 0, 0};                                                                                      \
        long long base[3] = {0, 0, 0};                                                                              \
        for (int a = 0; a < dims; ++a) {                                                                            \
            REAL f = FLOOR(c[a]);                                                                                   \
            t[a] = (c[a] - f) + (REAL)0;                                                                            \
            long long P = T->period[a] ? T->period[a] : 256;                                                        \
            base[a] = (long long)fmod((double)f, (double)P);                                                        \
        }                                                                                                           \
        REAL F[3] = {INFINITY, INFINITY, INFINITY};                                                                 \
        int nearest = 256;                                                                                          \
        int zr = dims == 3 ? 4 : 0;                                                                                 \
        for (int dz = -zr; dz <= zr; ++dz)                                                                          \
            for (int dy = -4; dy <= 4; ++dy)                                                                        \
                for (int dx = -4; dx <= 4; ++dx) {                                                                  \
                    int d[3] = {dx, dy, dz}, ix[3];                                                                 \
                    for (int a = 0; a < 3; ++a)                                                                     \
                        ix[a] = (int)(mod(base[a] + d[a], T->period[a] ? T->period[a] : 256) & 255);                \
                    int h = dims == 3 ? T->perm[(T->perm[(T->perm[ix[0]] + ix[1]) & 255] + ix[2]) & 255]            \
                                      : T->perm[(T->perm[ix[0]] + ix[1]) & 255];                                    \
                    REAL v[3] = {0, 0, 0}, D;                                                                       \
                    for (int a = 0; a < dims; ++a)                                                                  \
                        v[a] = FMA(c1, (REAL)T->off[3 * h + a], c0 - (t[a] - (REAL)d[a]));                          \
                    if (metric == 0) {                                                                              \
                        D = FMA(v[1], v[1], v[0] * v[0]);                                                           \
                        if (dims == 3) D = FMA(v[2], v[2], D);                                                      \
                    } else if (metric == 1) {                                                                       \
                        D = FABS(v[0]) + FABS(v[1]);                                                                \
                        if (dims == 3) D = D + FABS(v[2]);                                                          \
                    } else if (metric == 2) {                                                                       \
                        D = FABS(v[0]) > FABS(v[1]) ? FABS(v[0]) : FABS(v[1]);                                      \
                        if (dims == 3 && FABS(v[2]) > D) D = FABS(v[2]);                                            \
                    } else {                                                                                        \
                        D = POW(FABS(v[0]), e) + POW(FABS(v[1]), e);                                                \
                        if (dims == 3) D = D + POW(FABS(v[2]), e);                                                  \
                    }                                                                                               \
                    if (D < F[0] || (D == F[0] && h < nearest)) nearest = h;                                        \
                    if (D < F[2]) {                                                                                 \
                        int i = 2;                                                                                  \
                        while (i > 0 && D < F[i - 1]) F[i] = F[i - 1], --i;                                         \
                        F[i] = D;                                                                                   \
                    }                                                                                               \
                }                                                                                                   \
        REAL r[3];                                                                                                  \
        for (int k = 0; k < 3; ++k)                                                                                 \
            r[k] = metric == 0 ? SQRT(F[k]) : metric == 3 ? POW(F[k], (REAL)1 / e) : F[k];                          \
        out[0] = r[0], out[1] = r[1], out[2] = r[2], out[3] = r[1] - r[0];                                          \
        out[4] = (REAL)nearest / (REAL)255;                                                                         \
    }
BRUTE(double, brute_f64, floor, udm1_fma, sqrt, pow, fabs)
BRUTE(float, brute_f32, floorf, udm1_fmaf, sqrtf, powf, fabsf)

static tables tables_of(const udm1_noise *n, uint32_t px, uint32_t py, uint32_t pz)
{
    tables T;
    CHECK_STATUS(udm1_noise_tables(n, T.perm, NULL), UDM1_OK);
    CHECK_STATUS(udm1_cellular_offsets(n, T.off), UDM1_OK);
    T.period[0] = px, T.period[1] = py, T.period[2] = pz;
    return T;
}

#define N 203 /* leaves a tail after the 16-point groups */

static void against_brute_force(const char *table, uint32_t px, uint32_t py, uint32_t pz, double far)
{
    udm1_noise *n = make(table, px, py, pz);
    tables T = tables_of(n, px, py, pz);
    static double pts[N * 4], out[N];
    static float ptsf[N * 4], outf[N];
    for (int i = 0; i < N * 4; ++i) {
        pts[i] = (far ? far : 0) + (uniform() - 0.5) * 60.0;
        ptsf[i] = (float)pts[i];
    }
    static const double jitters[] = {1.0, 0.45, 0.0};
    static double ref[N][5];
    static float reff[N][5];
    for (uint32_t dims = 2; dims <= 3; ++dims)
        for (uint32_t metric = 0; metric <= 3; ++metric)
            for (int j = 0; j < 3; ++j) {
                if (!check_sampled()) continue; /* (UDM1_TEST_SAMPLE: a part of the matrix) */
                for (int i = 0; i < N; ++i) {
                    brute_f64(&T, (int)dims, pts + 4 * i, (int)metric, jitters[j], 3.0, ref[i]);
                    brute_f32(&T, (int)dims, ptsf + 4 * i, (int)metric, jitters[j], 3.0, reff[i]);
                }
                for (uint32_t output = 0; output <= 4; ++output) {
                    udm1_cellular_params p;
                    udm1_cellular_params_init(&p);
                    p.metric = metric, p.output = output, p.jitter = jitters[j], p.exponent = 3.0;
                    const double *axes[3] = {pts, pts + 1, pts + 2};
                    const float *axesf[3] = {ptsf, ptsf + 1, ptsf + 2};
                    CHECK_STATUS(udm1_cellular_eval(n, &p, dims, axes, 4, N, out), UDM1_OK);
                    CHECK_STATUS(udm1_cellular_eval_f32(n, &p, dims, axesf, 4, N, outf), UDM1_OK);
                    int bad = 0, badf = 0;
                    for (int i = 0; i < N; ++i) {
                        if (memcmp(&ref[i][output], &out[i], sizeof out[i]) != 0 && bad++ < 3)
                            fprintf(stderr, "%s dims %u metric %u jitter %g output %u point %d: %.17g, brute force %.17g\n",
                                    table ? table : "perlin", dims, metric, p.jitter, output, i, out[i], ref[i][output]);
                        if (memcmp(&reff[i][output], &outf[i], sizeof outf[i]) != 0 && badf++ < 3)
                            fprintf(stderr, "%s f32 dims %u metric %u jitter %g output %u point %d: %.9g, brute force %.9g\n",
                                    table ? table : "perlin", dims, metric, p.jitter, output, i, outf[i], reff[i][output]);
                    }
                    CHECK(bad == 0);
                    CHECK(badf == 0);
                }
            }
    udm1_noise_destroy(n);
}

/* The vector kernels load a column's cells (x, y fixed; z - 1, z, z + 1) from consecutive table entries: the
 * largest index they read is the column hash 255 at z's cell 0 (the cells 255, 0, 1 of z). Points in every
 * column whose hash is 255 (for each x one y: perm[perm[x] + y] = 255), at z cells 0, 255 and 1, in the
 * vector groups and the tail, against the brute force. */
static void column_wrap(const char *table)
{
    udm1_noise *n = make(table, 0, 0, 0);
    tables T = tables_of(n, 0, 0, 0);
    int inv255 = 0;
    for (int i = 0; i < 256; ++i)
        if (T.perm[i] == 255) inv255 = i;
    enum { M = 16 * 3 + 5 };
    static double pts[4 * M], out[M], ref[M][5];
    static float ptsf[4 * M], outf[M], reff[M][5];
    for (int i = 0; i < M; ++i) {
        int x = (17 * (i / 3)) & 255, y = (inv255 - T.perm[x]) & 255, z = (int[]){0, 255, 1}[i % 3];
        pts[4 * i] = x + 0.375 - (i & 1 ? 256.0 : 0.0), pts[4 * i + 1] = y + 0.625, pts[4 * i + 2] = z + 0.5;
        for (int a = 0; a < 3; ++a) ptsf[4 * i + a] = (float)pts[4 * i + a];
    }
    for (uint32_t output = UDM1_CELLULAR_F1; output <= UDM1_CELLULAR_F3; output += UDM1_CELLULAR_F3 - UDM1_CELLULAR_F1) {
        udm1_cellular_params p;
        udm1_cellular_params_init(&p);
        p.output = output, p.jitter = 1.0;
        const double *axes[3] = {pts, pts + 1, pts + 2};
        const float *axesf[3] = {ptsf, ptsf + 1, ptsf + 2};
        CHECK_STATUS(udm1_cellular_eval(n, &p, 3, axes, 4, M, out), UDM1_OK);
        CHECK_STATUS(udm1_cellular_eval_f32(n, &p, 3, axesf, 4, M, outf), UDM1_OK);
        for (int i = 0; i < M; ++i) {
            brute_f64(&T, 3, pts + 4 * i, (int)p.metric, p.jitter, p.exponent, ref[i]);
            brute_f32(&T, 3, ptsf + 4 * i, (int)p.metric, p.jitter, p.exponent, reff[i]);
            CHECKF(memcmp(&ref[i][output], &out[i], sizeof out[i]) == 0, "%s column wrap point %d: %.17g, brute force %.17g",
                   table ? table : "perlin", i, out[i], ref[i][output]);
            CHECKF(memcmp(&reff[i][output], &outf[i], sizeof outf[i]) == 0, "%s f32 column wrap point %d: %.9g, brute force %.9g",
                   table ? table : "perlin", i, outf[i], reff[i][output]);
        }
    }
    udm1_noise_destroy(n);
}

static void layouts_and_identities(void)
{
    udm1_noise *n = make("wr", 0, 0, 0);
    enum { M = 100 };
    static double xs[M], ys[M], zs[M], packed[3 * M], a[M], b[M], c[M];
    for (int i = 0; i < M; ++i) {
        xs[i] = packed[3 * i] = uniform() * 40 - 20;
        ys[i] = packed[3 * i + 1] = uniform() * 40 - 20;
        zs[i] = packed[3 * i + 2] = uniform() * 40 - 20;
    }
    const double *sep[3] = {xs, ys, zs}, *pk[3] = {packed, packed + 1, packed + 2};
    udm1_cellular_params p;
    udm1_cellular_params_init(&p);
    p.output = UDM1_CELLULAR_F2;
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, sep, 1, M, a), UDM1_OK);
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, pk, 3, M, b), UDM1_OK);
    CHECK(memcmp(a, b, sizeof a) == 0);
    for (int i = 0; i < M; ++i) /* one point at a time: the same as in bulk */
        CHECK_STATUS(udm1_cellular_eval(n, &p, 3, (const double *const[]){xs + i, ys + i, zs + i}, 1, 1, c + i), UDM1_OK);
    CHECK(memcmp(a, c, sizeof a) == 0);
    CHECK_STATUS(udm1_cellular_eval(n, NULL, 3, sep, 1, M, c), UDM1_OK); /* NULL params: the defaults (F1) */
    p.output = UDM1_CELLULAR_F1;
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, sep, 1, M, b), UDM1_OK);
    CHECK(memcmp(b, c, sizeof b) == 0);
    /* Minkowski 2 and 1 are Euclidean and Manhattan, bit for bit */
    for (uint32_t m = 0; m < 2; ++m) {
        p.metric = m;
        CHECK_STATUS(udm1_cellular_eval(n, &p, 3, sep, 1, M, a), UDM1_OK);
        p.metric = UDM1_CELLULAR_MINKOWSKI, p.exponent = m == 0 ? 2.0 : 1.0;
        CHECK_STATUS(udm1_cellular_eval(n, &p, 3, sep, 1, M, b), UDM1_OK);
        CHECK(memcmp(a, b, sizeof a) == 0);
    }
    /* F1 <= F2 <= F3, F2 - F1 their difference, CELL in [0, 1] */
    udm1_cellular_params_init(&p);
    double F[3][M], diff[M], cell[M];
    for (uint32_t o = 0; o < 3; ++o) {
        p.output = o;
        CHECK_STATUS(udm1_cellular_eval(n, &p, 3, sep, 1, M, F[o]), UDM1_OK);
    }
    p.output = UDM1_CELLULAR_F2_MINUS_F1;
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, sep, 1, M, diff), UDM1_OK);
    p.output = UDM1_CELLULAR_CELL;
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, sep, 1, M, cell), UDM1_OK);
    for (int i = 0; i < M; ++i) {
        CHECK(F[0][i] >= 0 && F[0][i] <= F[1][i] && F[1][i] <= F[2][i] && F[0][i] <= sqrt(3.0));
        CHECK(diff[i] == F[1][i] - F[0][i]);
        CHECK(cell[i] >= 0 && cell[i] <= 1 && cell[i] * 255 == floor(cell[i] * 255 + 0.5));
    }
    /* jitter 0: the feature points are the cells' centres; at a centre F1 is 0, at a corner sqrt(3)/2 */
    udm1_cellular_params_init(&p);
    p.jitter = 0;
    double centre = 0;
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, (const double *const[]){&(double){4.5}, &(double){-7.5}, &(double){1e6 + 0.5}}, 1, 1, &centre), UDM1_OK);
    CHECK(centre == 0.0);
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, (const double *const[]){&(double){4}, &(double){-7}, &(double){1e6}}, 1, 1, &centre), UDM1_OK);
    CHECK(centre == sqrt(0.75));
    udm1_noise_destroy(n);
}

static void periodic(void)
{
    const uint32_t P[3] = {5, 3, 300};
    udm1_noise *n = make("sobol-owen", P[0], P[1], P[2]);
    enum { M = 64 };
    static double pts[3 * M], moved[3 * M], a[M], b[M];
    static float ptsf[3 * M], movedf[3 * M], af[M], bf[M];
    for (int ax = 0; ax < 3; ++ax) {
        for (int i = 0; i < 3 * M; ++i) {
            pts[i] = floor(uniform() * 20480) / 1024 - 10; /* multiples of 2^-10: the moves are exact */
            moved[i] = pts[i] + (i % 3 == ax ? 7.0 * P[ax] : 0.0);
            ptsf[i] = (float)pts[i];
            movedf[i] = ptsf[i] + (i % 3 == ax ? 7.0f * (float)P[ax] : 0.0f);
        }
        const double *A[3] = {pts, pts + 1, pts + 2}, *B[3] = {moved, moved + 1, moved + 2};
        const float *Af[3] = {ptsf, ptsf + 1, ptsf + 2}, *Bf[3] = {movedf, movedf + 1, movedf + 2};
        udm1_cellular_params p;
        udm1_cellular_params_init(&p);
        p.output = UDM1_CELLULAR_F3;
        CHECK_STATUS(udm1_cellular_eval(n, &p, 3, A, 3, M, a), UDM1_OK);
        CHECK_STATUS(udm1_cellular_eval(n, &p, 3, B, 3, M, b), UDM1_OK);
        CHECKF(memcmp(a, b, sizeof a) == 0, "period on axis %d", ax);
        CHECK_STATUS(udm1_cellular_eval_f32(n, &p, 3, Af, 3, M, af), UDM1_OK);
        CHECK_STATUS(udm1_cellular_eval_f32(n, &p, 3, Bf, 3, M, bf), UDM1_OK);
        CHECKF(memcmp(af, bf, sizeof af) == 0, "float: period on axis %d", ax);
    }
    udm1_noise_destroy(n);
}

static void bad_input(void)
{
    udm1_noise *n = make(NULL, 0, 0, 0);
    double x[4] = {0.5, 1.5, NAN, 2.5}, out[4];
    const double *axes[3] = {x, x, x};
    udm1_cellular_params p;
    udm1_cellular_params_init(&p);
    CHECK_STATUS(udm1_cellular_eval(NULL, &p, 3, axes, 1, 4, out), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, NULL, 1, 4, out), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, axes, 1, 4, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, (const double *const[]){x, x, NULL}, 1, 4, out), UDM1_ERROR_NULL_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "axes[2]") != NULL);
    CHECK_STATUS(udm1_cellular_eval(n, &p, 1, axes, 1, 4, out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_cellular_eval(n, &p, 4, axes, 1, 4, out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, axes, 0, 4, out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, axes, 1, 4, out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "point 2") != NULL);
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, axes, 1, 2, out), UDM1_OK); /* the finite points before it */
    static const struct { const char *field; uint32_t metric, output, reserved; double jitter, exponent; } bad[] = {
        {"metric", 4, 0, 0, 1, 2},    {"output", 0, 5, 0, 1, 2},     {"reserved", 0, 0, 1, 1, 2},
        {"jitter", 0, 0, 0, 1.5, 2},  {"jitter", 0, 0, 0, -0.1, 2},  {"jitter", 0, 0, 0, NAN, 2},
        {"exponent", 3, 0, 0, 1, 0.5}, {"exponent", 3, 0, 0, 1, 65}, {"exponent", 3, 0, 0, 1, INFINITY},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; ++i) {
        udm1_cellular_params_init(&p);
        p.metric = bad[i].metric, p.output = bad[i].output, p.reserved = bad[i].reserved;
        p.jitter = bad[i].jitter, p.exponent = bad[i].exponent;
        CHECK_STATUS(udm1_cellular_eval(n, &p, 3, axes, 1, 2, out), UDM1_ERROR_INVALID_ARGUMENT);
        CHECKF(strstr(udm1_last_error(), bad[i].field) != NULL, "%s: %s", bad[i].field, udm1_last_error());
        float xf[2] = {0.5f, 1.5f}, of[2];
        CHECK_STATUS(udm1_cellular_eval_f32(n, &p, 2, (const float *const[]){xf, xf}, 1, 2, of), UDM1_ERROR_INVALID_ARGUMENT);
    }
    udm1_cellular_params_init(&p);
    p.struct_size = 8;
    CHECK_STATUS(udm1_cellular_eval(n, &p, 3, axes, 1, 2, out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "struct_size") != NULL);
    CHECK_STATUS(udm1_cellular_offsets(NULL, (uint8_t[768]){0}), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_cellular_offsets(n, NULL), UDM1_ERROR_NULL_ARGUMENT);
    udm1_noise_destroy(n);
}

int main(void)
{
    printf("udm1 %s, kernels: %s\n", udm1_version_string(), udm1_isa());
    against_brute_force(NULL, 0, 0, 0, 0);
    against_brute_force("drand48", 0, 0, 0, 0);
    against_brute_force("rd", 0, 0, 0, 0);
    against_brute_force("cmj", 0, 0, 0, 1e9);
    against_brute_force("rd", 0, 0, 0, 3e12); /* past 2^31: a double's index from its floor mod 256 */
    against_brute_force("golden", 5, 7, 300, 0);
    against_brute_force("sobol-owen", 2, 1, 3, 0);
    column_wrap(NULL);
    column_wrap("rd");
    layouts_and_identities();
    periodic();
    bad_input();
    CHECK_DONE();
}
