/* noise.c - lattice gradient noise (Perlin 1985 and 2002) whose tables come
 * from Perlin's reference permutation, from drand48 (the paper's baseline) or
 * from any udm1 sequence; see udm1.h for the definitions. */
#include "core/hash.h"
#include "noise/noise_tables.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* Ken Perlin's permutation, from his reference Improved Noise (2002): needed to
 * reproduce his reference values. */
static const uint8_t PERLIN[256] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103, 30,  69,  142,
    8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,  197, 62,  94,  252, 219, 203,
    117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174, 20,  125, 136, 171, 168, 68,  175, 74,  165,
    71,  134, 139, 48,  27,  166, 77,  146, 158, 231, 83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,
    55,  46,  245, 40,  244, 102, 143, 54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,
    18,  169, 200, 196, 135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250,
    124, 123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,  182, 189,
    28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,
    129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,
    242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,
    181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114,
    67,  29,  24,  72,  243, 141, 128, 195, 78,  66,  215, 61,  156, 180};

/* Perlin's 16 gradient directions of Improved Noise, by hash & 15 */
static const double EDGES[16][3] = {{1, 1, 0},  {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1},  {-1, 0, 1},
                                    {1, 0, -1}, {-1, 0, -1}, {0, 1, 1}, {0, -1, 1},  {0, 1, -1}, {0, -1, -1},
                                    {1, 1, 0},  {0, -1, 1}, {-1, 1, 0}, {0, -1, -1}};

void udm1_noise_desc_init(udm1_noise_desc *desc)
{
    if (!desc) return;
    memset(desc, 0, sizeof *desc);
    desc->struct_size = (uint32_t)sizeof *desc;
    desc->kind = UDM1_NOISE_IMPROVED;
}

static void sphere(double u, double v, double out[3])
{
    double z = 1.0 - 2.0 * u, r = sqrt(fmax(0.0, 1.0 - z * z)), phi = 2.0 * PI * v;
    out[0] = r * cos(phi);
    out[1] = r * sin(phi);
    out[2] = z;
}

/* Holian et al.'s shuffled nested Weyl transform of value k: {G {(k+1) x} + 1/2} */
static double snws(uint64_t raw, uint64_t k)
{
    uint64_t nested = (k + 1u) * raw;
    uint64_t u = nested * UDM1_GOLDEN_GAMMA + (1ull << 63);
    return (double)(u >> 11) * 0x1p-53;
}

static udm1_status tables_from_sequence(udm1_noise *n, const char *preset, uint64_t seed)
{
    udm1_preset_info info;
    udm1_status st = udm1_preset_find(preset, &info);
    if (st != UDM1_OK) return udm1_fail(UDM1_ERROR_UNKNOWN_PRESET, "udm1_noise_create: unknown table '%.64s'", preset);
    uint32_t dims = info.max_dimensions < 3 ? info.max_dimensions : 3;
    int point_set = (info.flags & UDM1_PRESET_POINT_SET) != 0;
    uint64_t count = point_set ? 256 : 768;
    udm1_seq *seq = NULL;
    st = udm1_seq_create(preset, dims, point_set ? 256 : 0, seed, &seq);
    if (st != UDM1_OK) return st;
    uint64_t raw[768 * 3];
    st = udm1_seq_fill_u64(seq, 0, 0, (size_t)count, 0, dims, raw, dims);
    udm1_seq_destroy(seq);
    if (st != UDM1_OK) return st;
    /* permutation: Fisher-Yates driven by the whitened dimension 0 */
    uint8_t p[256];
    for (int i = 0; i < 256; ++i) p[i] = (uint8_t)i;
    for (int i = 255; i >= 1; --i) {
        uint64_t k = (uint64_t)(255 - i);
        int j = (int)(snws(raw[k * dims], k) * (i + 1));
        uint8_t t = p[i];
        p[i] = p[j];
        p[j] = t;
    }
    memcpy(n->perm, p, 256);
    /* gradients: dimensions (1, 2) where there are 3, else the whitened dimension 0 further on */
    for (uint64_t k = 0; k < 256; ++k) {
        double u, v;
        if (dims >= 3) {
            u = (double)(raw[k * dims + 1] >> 11) * 0x1p-53;
            v = (double)(raw[k * dims + 2] >> 11) * 0x1p-53;
        } else if (!point_set) {
            u = snws(raw[(256 + 2 * k) * dims], 256 + 2 * k);
            v = snws(raw[(257 + 2 * k) * dims], 257 + 2 * k);
        } else { /* a point set of fewer than 3 dimensions: its own dimension 0 and 1 whitened */
            u = snws(raw[k * dims], k + 256);
            v = snws(raw[k * dims + (dims - 1)], k + 512);
        }
        sphere(u, v, n->grad[k]);
    }
    /* feature points: the sequence's points (dimensions 0, 1, 2), or its values whitened */
    for (uint64_t k = 0; k < 256; ++k)
        for (uint32_t c = 0; c < 3; ++c)
            n->feature[c][k] = dims >= 3 ? (uint8_t)(raw[k * dims + c] >> 56)
                                         : (uint8_t)(snws(raw[k * dims + c % dims], k + 256 * (c + 3)) * 256.0);
    return UDM1_OK;
}

/* The draws of srand48(seed) and drand48(), from the library's own drand48 preset (bit-identical to the C
 * library's, which not every platform has): its one-dimensional sequence without randomization. */
#define DRAND48_DRAWS (2 * 256 + 256 + 3 * 256)

static udm1_status tables_from_drand48(udm1_noise *n, uint64_t seed)
{
    udm1_seq_desc d;
    udm1_seq_desc_init(&d);
    d.preset = "drand48", d.dimensions = 1, d.seed = seed & 0xFFFFFFFFu, d.randomize = UDM1_RANDOMIZE_NONE;
    udm1_seq *seq = NULL;
    double r[DRAND48_DRAWS];
    udm1_status st = udm1_seq_create_desc(&d, &seq);
    if (st != UDM1_OK) return st;
    st = udm1_seq_fill_f64(seq, 0, 0, DRAND48_DRAWS, 0, 1, r, 1);
    udm1_seq_destroy(seq);
    if (st != UDM1_OK) return st;
    const double *next = r;
    for (int k = 0; k < 256; ++k, next += 2) sphere(next[0], next[1], n->grad[k]);
    for (int i = 0; i < 256; ++i) n->perm[i] = (uint8_t)i;
    for (int i = 0; i < 256; ++i) { /* the paper's (scratchapixel's) swap shuffle */
        int j = (int)(*next++ * 256.0);
        uint8_t t = n->perm[i];
        n->perm[i] = n->perm[j];
        n->perm[j] = t;
    }
    for (int k = 0; k < 256; ++k) /* feature point offsets: the next draws */
        for (int c = 0; c < 3; ++c) n->feature[c][k] = (uint8_t)(*next++ * 256.0);
    return UDM1_OK;
}

/* Perlin's gradient of Improved Noise is +-u +-v: u is x (h < 8) or y; v is y (h < 4), x (h = 12,
 * 14) or z; the signs from bits 0 and 1. As a table: the coordinates picked and their signs (a
 * product by +-1 is exact), so the value equals his branches bit for bit, and so does the vector
 * kernel that blends the same coordinates. */
static udm1_pick perlin_pick(int h)
{
    h &= 15;
    udm1_pick k;
    k.iu = h < 8 ? 0 : 1;
    k.iv = h < 4 ? 1 : (h == 12 || h == 14 ? 0 : 2);
    k.su = (h & 1) ? -1.0 : 1.0;
    k.sv = (h & 2) ? -1.0 : 1.0;
    return k;
}

/* Size of the first (1.2) layout of udm1_noise_desc, a constant: later layouts only append. */
#define NOISE_DESC_V1_SIZE (offsetof(udm1_noise_desc, reserved) + sizeof(uint32_t))

udm1_status udm1_noise_create(const udm1_noise_desc *caller_desc, udm1_noise **out)
{
    static const char fn[] = "udm1_noise_create";
    if (out) *out = NULL;
    if (!caller_desc || !out)
        return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, caller_desc ? "out" : "desc");
    udm1_noise_desc copy; /* only the caller's struct_size bytes are read */
    udm1_status read =
        udm1_read_struct(fn, "desc", "udm1_noise_desc_init", caller_desc, NOISE_DESC_V1_SIZE, &copy, sizeof copy);
    if (read != UDM1_OK) return read;
    const udm1_noise_desc *desc = &copy;
    if (desc->kind > UDM1_NOISE_CLASSIC || desc->reserved)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: desc.kind %u is not a udm1_noise_kind", fn, desc->kind);
    for (int a = 0; a < 3; ++a)
        if (desc->period[a] > (1u << 30))
            return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: desc.period[%d] = %u is above 2^30", fn, a,
                             desc->period[a]);
    if (desc->period_w > (1u << 30) || desc->reserved_w)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: desc.period_w = %u is above 2^30 (or reserved_w is not 0)", fn,
                         desc->period_w);
    udm1_noise *n = calloc(1, sizeof *n);
    if (!n) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory", fn);
    n->kind = desc->kind;
    memcpy(n->period, desc->period, sizeof n->period);
    n->period_w = desc->period_w;
    udm1_status st = UDM1_OK;
    if (!desc->table || strcmp(desc->table, "perlin") == 0) {
        memcpy(n->perm, PERLIN, 256);
        for (int k = 0; k < 256; ++k) {
            double len = sqrt(EDGES[k & 15][0] * EDGES[k & 15][0] + EDGES[k & 15][1] * EDGES[k & 15][1] +
                              EDGES[k & 15][2] * EDGES[k & 15][2]);
            for (int c = 0; c < 3; ++c) n->grad[k][c] = EDGES[k & 15][c] / len;
            for (int c = 0; c < 3; ++c) /* feature point offsets: a hash of (entry, axis) */
                n->feature[c][k] = (uint8_t)(udm1_mix64(UDM1_SEED_SALT + 3u * (uint64_t)k + (uint64_t)c) >> 56);
        }
    } else if (strcmp(desc->table, "drand48") == 0) {
        st = tables_from_drand48(n, desc->seed);
    } else {
        st = tables_from_sequence(n, desc->table, desc->seed);
    }
    if (st != UDM1_OK) {
        free(n);
        return st;
    }
    memcpy(n->perm + 256, n->perm, 256);
    const uint8_t *p = n->perm;
    for (int i = 0; i < 512; ++i) n->pair[i] = p[i] | (i < 511 ? p[i + 1] << 8 : 0);
    for (int i = 0; i < 514; ++i) {
        uint8_t h = p[i & 255];
        n->cell4[i] = (uint32_t)h | (uint32_t)n->feature[0][h] << 8 | (uint32_t)n->feature[1][h] << 16 |
                      (uint32_t)n->feature[2][h] << 24;
    }
    for (int i = 0; i < 512; ++i) n->triple[i] = p[i & 255] | p[(i + 1) & 255] << 8 | p[(i + 2) & 255] << 16;
    for (int x = 0; x < 256; ++x) {
        const uint8_t *a = p + p[x], *b = p + p[(x + 1) & 255]; /* the columns of x and x + 1 */
        for (int y = 0; y < 256; ++y) {
            int y1 = (y + 1) & 255;
            n->hash4[x * 256 + y] = (uint32_t)a[y] | (uint32_t)a[y1] << 8 | (uint32_t)b[y] << 16 | (uint32_t)b[y1] << 24;
        }
    }
    for (int h = 0; h < 256; ++h) {
        n->pick3[h] = perlin_pick(h);
        int h7 = h & 7;
        udm1_pick k2 = {h7 < 4 ? 0 : 1, h7 < 4 ? 1 : 0, (h7 & 1) ? -1.0 : 1.0, (h7 & 2) ? -2.0 : 2.0};
        n->pick2[h] = k2;
    }
    /* the gradients the evaluation reads, by corner hash: Perlin's edges for the improved
     * noise (a dot product with +-1/0 components equals his branches exactly), the
     * table for the classic noise; 2D and 1D: noise1234's sets */
    for (int h = 0; h < 256; ++h) {
        for (int c = 0; c < 3; ++c) n->g3[h][c] = n->kind == UDM1_NOISE_IMPROVED ? EDGES[h & 15][c] : n->grad[h][c];
        int h7 = h & 7;
        double u = (h7 & 1) ? -1.0 : 1.0, v = (h7 & 2) ? -2.0 : 2.0; /* +-u +-2v, u = x (h7 < 4) or y */
        n->g2[h][0] = n->kind == UDM1_NOISE_IMPROVED ? (h7 < 4 ? u : v) : n->grad[h][0];
        n->g2[h][1] = n->kind == UDM1_NOISE_IMPROVED ? (h7 < 4 ? v : u) : n->grad[h][1];
        double g = 1.0 + (h & 7);
        n->g1[h] = n->kind == UDM1_NOISE_IMPROVED ? ((h & 8) ? -g : g) : n->grad[h][0];
    }
    /* the wave sources of the ripples and waves patterns: normalized DNoise((i, 0, 0)) */
    for (int i = 0; i < UDM1_NOISE_WAVES; ++i) {
        double *s = n->wave_source[i];
        s[0] = udm1_noise_3d(n, (double)i, 0.0, 0.0);
        s[1] = udm1_noise_3d(n, i + 31.416, -47.853, 12.793);
        s[2] = udm1_noise_3d(n, i - 101.234, 67.125, -23.478);
        double len = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        if (len > 0)
            for (int c = 0; c < 3; ++c) s[c] /= len;
    }
    *out = n;
    return UDM1_OK;
}

void udm1_noise_destroy(udm1_noise *noise) { free(noise); }

udm1_status udm1_noise_tables(const udm1_noise *noise, uint8_t *perm, double *gradients)
{
    if (!noise) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_noise_tables: noise is NULL");
    if (perm) memcpy(perm, noise->perm, 256);
    if (gradients) memcpy(gradients, noise->grad, sizeof noise->grad);
    return UDM1_OK;
}

udm1_status udm1_noise_points(const udm1_noise *n, uint32_t dims, const double *xyz, size_t count, size_t stride,
                              double *out)
{
    static const char fn[] = "udm1_noise_points";
    if (!n || !xyz || !out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: a pointer argument is NULL", fn);
    if (dims < 1 || dims > 3) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: dims %u is not 1, 2 or 3", fn, dims);
    if (stride < dims) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: stride %zu < dims %u", fn, stride, dims);
    const double *axes[3] = {xyz, xyz + 1, xyz + 2};
    return udm1_noise_batch_f64(fn, n, dims, axes, stride, count, out, NULL);
}
