/* test_draw_digest.c - a digest of the library's values at random (preset, stream, index, dimension)
 * draws, so that two builds - the unsigned __int128 one and the portable 128-bit one (UDM1_PORTABLE_INT128,
 * what MSVC builds), or the x86-64 build and an arm64 or Windows one - can be compared bit for bit.
 *
 *   test_draw_digest [--draws N] [--seed S] [--small-sets 1] [--out FILE] [--expect FILE]
 *
 * Every preset, also with "+tent", in every randomization it takes (screen-space both fixed and
 * progressive), sequences of 24 dimensions and point sets of 12 (K from 64 to 65537, or to 1000 with
 * --small-sets 1: the emulators' quick run, whose time goes to the lattices' construction); N draws
 * (default 10^7) in groups of 16 that
 * share a sequence, a stream id and a first dimension. Each draw takes a random index (a third of them
 * below 2^16, a third below 2^32, a third anywhere in 2^64 - or below K for a point set) and a random
 * dimension, and folds into the digest: the per-sample value (udm1_seq_sample_u64), the inline draw of
 * udm1/stream.h (compiled into this program: its own 128-bit code) of 1 to 4 dimensions, and a child
 * domain's draw of udm1/domain.h; each group also a small bulk fill (udm1_seq_fill_u64) and every status.
 * Every 16th group also folds noise at 21 random points (near the origin or up to 1e9 away; 2D or 3D):
 * improved noise of four tables and Perlin's classic noise, in double (per call and batch, with gradients)
 * and float (batch: the vector kernels), and cellular noise in the Euclidean, Manhattan and Chebyshev
 * metrics, every output, double and float. (Not the classic kind of a table from a sequence or drand48,
 * whose gradients come from the C library's cos and sin, nor the Minkowski metric, its pow: C libraries
 * round those differently - README.md, "Platforms".)
 * The digest h <- (h xor v) * P (P odd) changes with any one value, so equal digests mean equal values but
 * for chance (2^-64 a pair). It prints one line per sixteenth of the draws and a total: a difference names
 * the sixteenth where it is. --out writes those lines to FILE; --expect compares them with FILE's and fails
 * on any difference (what CTest runs against the reference build's program, tests/CMakeLists.txt). */
#include "check.h"

#include <udm1/udm1.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NOISE_EVERY 16u /* groups per noise group */
#define NOISE_POINTS 21u
#define NOISES 5

#define SCREEN_PROGRESSIVE (UDM1_RANDOMIZE_SCREEN + 1u)
#define GROUP 16u
#define MAX_SEQS 1024

static uint64_t rng_state;
static uint64_t next64(void) /* splitmix64 */
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static uint64_t digest = 0xCBF29CE484222325ull;
static void fold(uint64_t v) { digest = (digest ^ v) * 0x100000001B3ull; }

typedef struct {
    udm1_seq *seq;
    uint32_t dims;
    uint64_t k; /* point count, 0 for a sequence */
} config;

static config seqs[MAX_SEQS];
static size_t nseqs;

static void add(const char *name, uint32_t dims, uint64_t k, uint32_t randomize)
{
    udm1_seq_desc d;
    udm1_seq_desc_init(&d);
    d.preset = name, d.dimensions = dims, d.point_count = k, d.seed = next64();
    d.randomize = randomize == SCREEN_PROGRESSIVE ? UDM1_RANDOMIZE_SCREEN : randomize;
    if (randomize == UDM1_RANDOMIZE_SCREEN) d.screen_spp = 16;
    udm1_seq *s = NULL;
    if (nseqs < MAX_SEQS && udm1_seq_create_desc(&d, &s) == UDM1_OK) seqs[nseqs].seq = s, seqs[nseqs].dims = dims, seqs[nseqs++].k = k;
}

static void make_sequences(int small_sets)
{
    static const uint64_t all_counts[] = {64, 1000, 4099, 65537}, small_counts[] = {64, 100, 257, 1000};
    const uint64_t *point_counts = small_sets ? small_counts : all_counts;
    for (size_t p = 0; p < udm1_preset_count(); ++p) {
        udm1_preset_info info;
        udm1_preset_get(p, &info);
        uint32_t most = info.flags & UDM1_PRESET_POINT_SET ? 12 : 24; /* (a lattice's construction grows with D K) */
        uint32_t dims = info.max_dimensions < most ? info.max_dimensions : most;
        for (int tent = 0; tent < 2; ++tent) {
            char name[64];
            snprintf(name, sizeof name, "%s%s", info.name, tent ? "+tent" : "");
            for (uint32_t r = UDM1_RANDOMIZE_NONE; r <= SCREEN_PROGRESSIVE; ++r) {
                if (info.flags & UDM1_PRESET_POINT_SET)
                    add(name, dims, point_counts[(p + r + (uint32_t)tent) % 4], r);
                else
                    add(name, dims, 0, r);
            }
        }
    }
}

static udm1_noise *noises[NOISES];

static void make_noises(void)
{
    static const char *tables[NOISES] = {NULL, "drand48", "wr", "sobol-owen", NULL};
    for (int k = 0; k < NOISES; ++k) {
        udm1_noise_desc d;
        udm1_noise_desc_init(&d);
        d.table = tables[k], d.seed = next64() & 0xFFFF, d.kind = k == NOISES - 1 ? UDM1_NOISE_CLASSIC : UDM1_NOISE_IMPROVED;
        CHECK_STATUS(udm1_noise_create(&d, &noises[k]), UDM1_OK);
    }
}

static void fold_doubles(const double *v, size_t n)
{
    for (size_t i = 0; i < n; ++i) {
        uint64_t b;
        memcpy(&b, &v[i], sizeof b);
        fold(b);
    }
}

static void fold_floats(const float *v, size_t n)
{
    for (size_t i = 0; i < n; ++i) {
        uint32_t b;
        memcpy(&b, &v[i], sizeof b);
        fold(b);
    }
}

static void noise_group(void)
{
    const udm1_noise *n = noises[next64() % NOISES];
    uint32_t dims = 2 + (uint32_t)(next64() % 2);
    double scale = next64() % 4 ? 64.0 : 2e9, p[3 * NOISE_POINTS], v[NOISE_POINTS], g[3 * NOISE_POINTS];
    float pf[3 * NOISE_POINTS], vf[NOISE_POINTS], gf[3 * NOISE_POINTS];
    for (size_t i = 0; i < 3 * NOISE_POINTS; ++i) {
        p[i] = ((double)(next64() >> 11) * 0x1p-53 - 0.5) * scale;
        pf[i] = (float)p[i];
    }
    const double *axes[3] = {p, p + 1, p + 2};
    const float *axesf[3] = {pf, pf + 1, pf + 2};
    fold((uint64_t)udm1_noise_eval(n, dims, axes, 3, NOISE_POINTS, v, g));
    fold_doubles(v, NOISE_POINTS), fold_doubles(g, dims * NOISE_POINTS);
    fold((uint64_t)udm1_noise_eval_f32(n, dims, axesf, 3, NOISE_POINTS, vf, gf));
    fold_floats(vf, NOISE_POINTS), fold_floats(gf, dims * NOISE_POINTS);
    double one = udm1_noise_3d(n, p[0], p[1], p[2]);
    fold_doubles(&one, 1);
    udm1_cellular_params c;
    udm1_cellular_params_init(&c);
    c.metric = (uint32_t)(next64() % 3), c.output = (uint32_t)(next64() % 5);
    c.jitter = next64() % 2 ? 1.0 : (double)(next64() % 256) / 256.0;
    fold((uint64_t)udm1_cellular_eval(n, &c, dims, axes, 3, NOISE_POINTS, v));
    fold_doubles(v, NOISE_POINTS);
    fold((uint64_t)udm1_cellular_eval_f32(n, &c, dims, axesf, 3, NOISE_POINTS, vf));
    fold_floats(vf, NOISE_POINTS);
}

static uint64_t random_index(const config *c)
{
    uint64_t r = next64();
    if (c->k) return r % c->k;
    switch (r % 3) {
    case 0: return next64() & 0xFFFFu;
    case 1: return next64() & 0xFFFFFFFFu;
    default: return next64();
    }
}

static void group(void)
{
    const config *c = &seqs[next64() % nseqs];
    uint64_t stream = next64() % 4 ? next64() : ((next64() & 0xFFFF) << 32 | (next64() & 0xFFFF)); /* (pixels) */
    uint32_t first = (uint32_t)(next64() % c->dims);
    udm1_stream st;
    fold((uint64_t)udm1_stream_init(&st, c->seq, stream, first, GROUP));
    for (uint32_t i = 0; i < GROUP; ++i) {
        uint64_t index = random_index(c), raw[4] = {0, 0, 0, 0}, v = 0;
        uint32_t dim = (uint32_t)(next64() % GROUP), n = 1 + (uint32_t)(next64() % 4);
        if (dim + n > GROUP) dim = GROUP - n;
        fold((uint64_t)udm1_seq_sample_u64(c->seq, stream, index, (first + dim) % c->dims, &v));
        fold(v);
        udm1_stream_draw_raw(&st, index, dim, n, raw);
        for (uint32_t j = 0; j < n; ++j) fold(raw[j]);
        udm1_domain d = udm1_domain_next(udm1_domain_child(udm1_domain_root(&st, index), next64()), dim / 4);
        udm1_domain_draw_raw(d, n, raw);
        for (uint32_t j = 0; j < n; ++j) fold(raw[j]);
    }
    uint64_t block[4 * 8];
    uint32_t nd = 1 + (uint32_t)(next64() % 4), d0 = (uint32_t)(next64() % c->dims);
    if (d0 + nd > c->dims) nd = c->dims - d0;
    uint64_t start = random_index(c);
    size_t rows = c->k && c->k - start < 8 ? (size_t)(c->k - start) : 8;
    fold((uint64_t)udm1_seq_fill_u64(c->seq, stream, start, rows, d0, nd, block, nd));
    for (size_t j = 0; j < rows * nd; ++j) fold(block[j]);
}

int main(int argc, char **argv)
{
    uint64_t draws = 10000000, seed = 1, small_sets = 0;
    const char *out = NULL, *expect = NULL;
    for (int a = 1; a < argc; a += 2) {
        if (a + 1 == argc) {
            fprintf(stderr, "test_draw_digest: option '%s' has no value\n", argv[a]);
            return 2;
        }
        if (strcmp(argv[a], "--draws") == 0) draws = strtoull(argv[a + 1], NULL, 10);
        else if (strcmp(argv[a], "--seed") == 0) seed = strtoull(argv[a + 1], NULL, 10);
        else if (strcmp(argv[a], "--small-sets") == 0) small_sets = strtoull(argv[a + 1], NULL, 10);
        else if (strcmp(argv[a], "--out") == 0) out = argv[a + 1];
        else if (strcmp(argv[a], "--expect") == 0) expect = argv[a + 1];
        else {
            fprintf(stderr, "test_draw_digest: unknown option '%s'\n", argv[a]);
            return 2;
        }
    }
    rng_state = seed * 0xD1B54A32D192ED03ull;
    make_sequences(small_sets != 0);
    make_noises();
    CHECKF(nseqs > 100 && nseqs < MAX_SEQS, "%llu sequences made", (unsigned long long)nseqs);

    char lines[17][160];
    uint64_t groups = (draws + GROUP - 1) / GROUP, done = 0;
    for (int part = 0; part < 16; ++part) {
        uint64_t until = groups * (uint64_t)(part + 1) / 16;
        for (; done < until; ++done) {
            group();
            if (done % NOISE_EVERY == 0) noise_group();
        }
        snprintf(lines[part], sizeof lines[part], "draws below %llu: %016llx\n",
                 (unsigned long long)(done * GROUP), (unsigned long long)digest);
    }
    snprintf(lines[16], sizeof lines[16], "total: %llu draws of %llu sequences, seed %llu: %016llx\n",
             (unsigned long long)(done * GROUP), (unsigned long long)nseqs, (unsigned long long)seed, (unsigned long long)digest);
    for (int l = 0; l < 17; ++l) fputs(lines[l], stdout);
    for (size_t i = 0; i < nseqs; ++i) udm1_seq_destroy(seqs[i].seq);
    for (int k = 0; k < NOISES; ++k) udm1_noise_destroy(noises[k]);

    if (out) {
        FILE *f = fopen(out, "w");
        CHECKF(f != NULL, "cannot write %s", out);
        for (int l = 0; f && l < 17; ++l) fputs(lines[l], f);
        if (f) fclose(f);
    }
    if (expect) {
        FILE *f = fopen(expect, "r");
        CHECKF(f != NULL, "cannot read %s", expect);
        char want[160];
        for (int l = 0; f && l < 17; ++l) {
            if (!fgets(want, sizeof want, f)) want[0] = 0;
            CHECKF(strcmp(want, lines[l]) == 0, "differs from %s: this build's\n  %s the reference's\n  %s", expect,
                   lines[l], want);
        }
        if (f) fclose(f);
    }
    CHECK_DONE();
}
