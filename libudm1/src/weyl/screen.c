/* weyl/screen.c - the screen generators of progressive screen-space randomization (weyl/screen.h).
 *
 * For each dimension pair (2p, 2p + 1), alpha = (a, b) the top 64 bits of its generators, the search
 * scores SCREEN_CANDIDATES candidate matrices (G_2p, G_2p+1; H_2p, H_2p+1) and keeps the best (the first
 * on a tie). A candidate c = 1, 2, ... is point c of a four-dimensional Kronecker sequence in 0.64 fixed
 * point: 2^63 + c R_i (mod 2^64), R_i = 2^64 frac(g^-(i+1)), g the real root of x^5 = x + 1.
 * Score: over the modes h = (h1, h2), |h_i| <= SCREEN_H, one of each pair +-h, the energy
 *     E_n(h) = w(h) K_n(||h.alpha||),  w(h) = 2^40 / (r2 isqrt(r2)), r2 = 1 + |h|^2 (an integrand with
 *     edges: |f^(h)|^2 ~ |h|^-3),  K_n(x) = 2^40 / (2^20 + t^2), t = (804 n d) >> 30, d = 2^32 ||x||
 *     (K_n ~ 2^20 / (1 + (pi n x)^2), the Fejer kernel's envelope |D_n(x) / n|^2),
 * lands at the screen frequency nu(h) = (h.G, h.H) (mod 1, 32-bit signed parts) and counts there with the
 * window T(nu) = 1 - |nu|^2 / r^2 for |nu| < r = 1/4, else 0 (2^16 (r^2 - q) / r^2 on the 32-bit parts,
 * r^2 and q shifted right by 16 first): a margin over the 1/8 cycle per pixel measured, for integrands
 * that change from pixel to pixel. With L_n the sum and M_n the largest of (E_n(h) >> 16) T(nu(h)) and
 * T_n the sum of E_n(h), the score is the maximum over n in SCREEN_COUNTS of (L_n + 4 M_n) / T_n: the
 * energy at low frequency, and no single mode there that one integrand could make dominant. A last
 * dimension without a pair takes the search with b = 0 and h2 = 0.
 * Integer arithmetic throughout except the final ratios (one correctly rounded division each), so the
 * choice is the same on every machine and compiler. */
#include "weyl/screen.h"

#include <stdlib.h>

#define SCREEN_H 32
#define SCREEN_CANDIDATES 64
#define SCREEN_TOP_WEIGHT 4
#define SCREEN_NCOUNTS 16
static const uint32_t SCREEN_COUNTS[SCREEN_NCOUNTS] = {1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256};
static const uint64_t SCREEN_R[4] = {0xdb4f0b9175ae2165ull, 0xbbe0563303a4615full, 0xa0f2ec75a1fe1575ull,
                                     0x89e182857d9ed688ull};
#define SCREEN_MODES ((SCREEN_H + 1) * (2 * SCREEN_H + 1))

static uint64_t isqrt64(uint64_t v)
{
    uint64_t r = 0;
    while ((r + 1) * (r + 1) <= v) ++r;
    return r;
}

/* 2^32 ||x|| for x in 0.64 fixed point */
static uint64_t distance32(uint64_t x)
{
    return ((x >> 63) ? (0 - x) : x) >> 32;
}

typedef struct screen_modes {
    int32_t h1[SCREEN_MODES], h2[SCREEN_MODES];
    uint64_t e[SCREEN_MODES][SCREEN_NCOUNTS];
    uint64_t total[SCREEN_NCOUNTS];
    uint32_t count;
} screen_modes;

static void pair_generators(screen_modes *m, uint64_t a, uint64_t b, int single, uint64_t out[4])
{
    m->count = 0;
    for (uint32_t k = 0; k < SCREEN_NCOUNTS; ++k) m->total[k] = 0;
    for (int32_t h2 = 0; h2 <= (single ? 0 : SCREEN_H); ++h2)
        for (int32_t h1 = -SCREEN_H; h1 <= SCREEN_H; ++h1) {
            if (h2 == 0 && h1 <= 0) continue;
            uint32_t i = m->count++;
            m->h1[i] = h1, m->h2[i] = h2;
            uint64_t d = distance32((uint64_t)(int64_t)h1 * a + (uint64_t)h2 * b);
            uint64_t r2 = 1 + (uint64_t)(h1 * h1 + h2 * h2);
            uint64_t w = (1ull << 40) / (r2 * isqrt64(r2));
            for (uint32_t k = 0; k < SCREEN_NCOUNTS; ++k) {
                uint64_t t = (804ull * SCREEN_COUNTS[k] * d) >> 30;
                m->e[i][k] = (w * ((1ull << 40) / ((1ull << 20) + t * t))) >> 20;
                m->total[k] += m->e[i][k];
            }
        }
    const uint64_t r1 = ((1ull << 32) / 4) * ((1ull << 32) / 4);
    double best = 0.0;
    for (uint64_t c = 1; c <= SCREEN_CANDIDATES; ++c) {
        uint64_t g[4], low[SCREEN_NCOUNTS] = {0}, top[SCREEN_NCOUNTS] = {0};
        for (int i = 0; i < 4; ++i) g[i] = (1ull << 63) + c * SCREEN_R[i];
        for (uint32_t i = 0; i < m->count; ++i) {
            uint64_t u = (uint64_t)(int64_t)m->h1[i] * g[0] + (uint64_t)m->h2[i] * g[1];
            uint64_t v = (uint64_t)(int64_t)m->h1[i] * g[2] + (uint64_t)m->h2[i] * g[3];
            int64_t su = (int64_t)u >> 32, sv = (int64_t)v >> 32;
            uint64_t q = (uint64_t)(su * su) + (uint64_t)(sv * sv);
            if (q >= r1) continue;
            uint64_t t = ((r1 - q) >> 16) * 65536 / (r1 >> 16); /* the window, 16 bits */
            for (uint32_t k = 0; k < SCREEN_NCOUNTS; ++k) {
                uint64_t e = (m->e[i][k] >> 16) * t; /* E_n(h) T(nu), E's low 16 bits dropped */
                low[k] += e;
                if (e > top[k]) top[k] = e;
            }
        }
        double score = 0.0;
        for (uint32_t k = 0; k < SCREEN_NCOUNTS; ++k) {
            double s = (double)(low[k] + SCREEN_TOP_WEIGHT * top[k]) / (double)m->total[k];
            if (s > score) score = s;
        }
        if (c == 1 || score < best) {
            best = score;
            for (int i = 0; i < 4; ++i) out[i] = g[i];
        }
    }
}

udm1_status udm1_screen_generators(const char *fn, udm1_seq_t *seq)
{
    seq->screen_gen = malloc(sizeof(uint64_t) * 2 * (size_t)seq->dims);
    screen_modes *m = malloc(sizeof *m);
    if (!seq->screen_gen || !m) {
        free(m);
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory for the screen generators of %u dimensions", fn,
                         seq->dims);
    }
    for (uint32_t j = 0; j < seq->dims; j += 2) {
        int single = j + 1 == seq->dims;
        uint64_t g[4] = {0, 0, 0, 0};
        pair_generators(m, seq->gen[j].hi, single ? 0 : seq->gen[j + 1].hi, single, g);
        seq->screen_gen[2 * (size_t)j] = g[0];     /* G_j */
        seq->screen_gen[2 * (size_t)j + 1] = g[2]; /* H_j */
        if (!single) {
            seq->screen_gen[2 * (size_t)j + 2] = g[1];
            seq->screen_gen[2 * (size_t)j + 3] = g[3];
        }
    }
    free(m);
    return UDM1_OK;
}
