/* presets.c - the presets by name: the paper's generator sets and the baselines, each with its init and
 * its sampler kind (see the table in udm1/seq.h). */
#include "samplers/samplers.h"
#include "weyl/weyl.h"

#include <stdlib.h>
#include <string.h>

/* 0.128 fractions of e and e^2, round to nearest; checked against mpmath in
 * tests/python/test_exact.py. */
static const uint64_t E_FRAC[2] = {0xB7E151628AED2A6Aull, 0xBF7158809CF4F3C7ull};
static const uint64_t E2_FRAC[2] = {0x63992E35376B730Cull, 0xE8EE881ADA2AEEA1ull};

enum spec_kind { SPEC_QUADRATIC, SPEC_E, SPEC_E2 };

/* (a + b sqrt(k)) / c, or e / e^2 */
typedef struct spec {
    int kind;
    int a;
    unsigned b, k, c;
} spec;

#define SQRT(k) {SPEC_QUADRATIC, 0, 1, k, 1}
#define PHI {SPEC_QUADRATIC, 1, 1, 5, 2}
#define HALF_1_SQRT3 {SPEC_QUADRATIC, 1, 1, 3, 2}
#define E_ {SPEC_E, 0, 0, 0, 0}
#define E2_ {SPEC_E2, 0, 0, 0, 0}

static const spec WR_AO[] = {SQRT(2), SQRT(13)};
static const spec WE[] = {E_, E2_};
static const spec WGR[] = {PHI, HALF_1_SQRT3};
/* Section 5.1 of the paper, in its order. */
static const spec WMMR[] = {SQRT(13),    SQRT(173),   SQRT(17),    SQRT(293),   SQRT(47),   SQRT(2213),
                            SQRT(67),    SQRT(4493),  SQRT(97),    SQRT(9413),  SQRT(167),  SQRT(27893),
                            SQRT(193),   SQRT(37253), SQRT(277),   SQRT(76733), SQRT(307),  SQRT(94253),
                            SQRT(317),   SQRT(100493), SQRT(487),  SQRT(237173)};
static const spec HWMMR[] = {PHI,        HALF_1_SQRT3, E_,          E2_,        SQRT(13),   SQRT(173),
                             SQRT(17),   SQRT(293),    SQRT(47),    SQRT(2213), SQRT(67),   SQRT(4493),
                             SQRT(97),   SQRT(9413),   SQRT(167),   SQRT(27893), SQRT(193), SQRT(37253),
                             SQRT(277),  SQRT(76733),  SQRT(307),   SQRT(94253)};
/* Beyond the paper: 64 square roots of primes chosen by udm1's greedy search so that the worst 2D
 * projection stays close to random-shifted quality at every N from 32 to 4096 (wrap-around L2
 * discrepancy, exact for Kronecker sets); made by
 * tools/alpha_search.py --dims 64 --max-prime 16384 --n-min 32 --n-max 4096. */
static const spec WOPT[] = {
    SQRT(6761), SQRT(1999), SQRT(9677), SQRT(10369), SQRT(12011), SQRT(647), SQRT(9319), SQRT(3467),
    SQRT(15299), SQRT(14197), SQRT(11393), SQRT(829), SQRT(10889), SQRT(12791), SQRT(8237), SQRT(4919),
    SQRT(877), SQRT(15061), SQRT(14929), SQRT(15731), SQRT(14563), SQRT(16007), SQRT(15149), SQRT(4297),
    SQRT(10949), SQRT(9883), SQRT(13597), SQRT(3371), SQRT(14827), SQRT(3613), SQRT(14923), SQRT(9839),
    SQRT(73), SQRT(7867), SQRT(8527), SQRT(4999), SQRT(7433), SQRT(769), SQRT(16249), SQRT(8753),
    SQRT(14369), SQRT(6607), SQRT(5749), SQRT(3797), SQRT(2749), SQRT(13397), SQRT(1693), SQRT(12301),
    SQRT(11833), SQRT(8087), SQRT(9431), SQRT(1993), SQRT(1973), SQRT(6581), SQRT(5801), SQRT(641),
    SQRT(3469), SQRT(2309), SQRT(9649), SQRT(12659), SQRT(15467), SQRT(1637), SQRT(6529), SQRT(10271)};
static const spec GOLDEN[] = {PHI};
static const spec EPISWR_WEYL[] = {SQRT(137)};

#define COUNT(a) ((uint32_t)(sizeof(a) / sizeof((a)[0])))

static void from_spec(const spec *s, udm1_generator *g);

static udm1_status weyl_alloc(udm1_seq_t *seq)
{
    seq->gen = malloc(sizeof(udm1_generator) * seq->dims);
    if (!seq->gen) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "udm1_seq_create: out of memory");
    return UDM1_OK;
}

static udm1_status from_list(udm1_seq_t *seq, const spec *list)
{
    udm1_status st = weyl_alloc(seq);
    for (uint32_t j = 0; st == UDM1_OK && j < seq->dims; ++j) from_spec(&list[j], &seq->gen[j]);
    return st;
}

static udm1_status init_wr(udm1_seq_t *seq)
{
    udm1_status st = weyl_alloc(seq);
    if (st != UDM1_OK) return st;
    uint64_t *primes = malloc(sizeof(uint64_t) * seq->dims);
    if (!primes || !udm1_first_primes(seq->dims, primes)) {
        free(primes);
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "udm1_seq_create: out of memory for %u primes", seq->dims);
    }
    for (uint32_t j = 0; j < seq->dims; ++j) udm1_gen_sqrt(primes[j], &seq->gen[j]);
    free(primes);
    return UDM1_OK;
}

static udm1_status init_wr_ao(udm1_seq_t *seq) { return from_list(seq, WR_AO); }
static udm1_status init_we(udm1_seq_t *seq) { return from_list(seq, WE); }
static udm1_status init_wgr(udm1_seq_t *seq) { return from_list(seq, WGR); }
static udm1_status init_wmmr(udm1_seq_t *seq) { return from_list(seq, WMMR); }
static udm1_status init_hwmmr(udm1_seq_t *seq) { return from_list(seq, HWMMR); }
static udm1_status init_golden(udm1_seq_t *seq) { return from_list(seq, GOLDEN); }
static udm1_status init_wopt(udm1_seq_t *seq) { return from_list(seq, WOPT); }

static udm1_status init_rd(udm1_seq_t *seq)
{
    udm1_status st = weyl_alloc(seq);
    if (st == UDM1_OK) udm1_gen_rd(seq->dims, seq->gen);
    return st;
}

static void epis_generator(uint64_t k, udm1_generator *g);

static udm1_status init_epis(udm1_seq_t *seq)
{
    udm1_status st = weyl_alloc(seq);
    if (st != UDM1_OK) return st;
    epis_generator(seq->point_count, &seq->gen[0]);
    if (seq->dims > 1) from_spec(&EPISWR_WEYL[0], &seq->gen[1]);
    return UDM1_OK;
}

#define POINT_SET UDM1_PRESET_POINT_SET
#define PAIRS UDM1_PRESET_PAIRS
static const udm1_preset PRESETS[] = {
    /* the paper's Weyl/Kronecker sets */
    {"wr", "WeylRichtmyer: square roots of the primes 2, 3, 5, 7, ... (paper 5.1)", UDM1_MAX_DIMENSIONS, 0,
     UDM1_MODE_SHIFT, init_wr, &udm1_weyl_kind},
    {"wr-ao", "WR for ambient occlusion: (sqrt2, sqrt13) (paper 4.2.1)", COUNT(WR_AO), 0, UDM1_MODE_SHIFT, init_wr_ao, &udm1_weyl_kind},
    {"we", "WeylExponential: (e, e^2) (paper 4.2.1)", COUNT(WE), 0, UDM1_MODE_SHIFT, init_we, &udm1_weyl_kind},
    {"wgr", "WeylGoldenRatio: ((1+sqrt5)/2, (1+sqrt3)/2) (paper 4.2.1)", COUNT(WGR), 0, UDM1_MODE_SHIFT, init_wgr, &udm1_weyl_kind},
    {"wmmr", "Weyl metallic means ratio: 22 square roots (paper 5.1)", COUNT(WMMR), 0, UDM1_MODE_SHIFT, init_wmmr, &udm1_weyl_kind},
    {"hwmmr", "Hybrid WMMR: golden ratios, e, e^2 and 18 square roots (paper 5.1)", COUNT(HWMMR), 0, UDM1_MODE_SHIFT,
     init_hwmmr, &udm1_weyl_kind},
    {"rd", "R_d: phi_d^-1 .. phi_d^-d, phi_d the root of x^(d+1) = x + 1 (Roberts 2018)", UDM1_MAX_DIMENSIONS, 0,
     UDM1_MODE_SHIFT, init_rd, &udm1_weyl_kind},
    {"golden", "Golden ratio Weyl sequence in 1D (= R_1)", 1, 0, UDM1_MODE_SHIFT, init_golden, &udm1_weyl_kind},
    {"epis", "EPIS point set {n/K + u} (paper 4.2.2)", 1, POINT_SET, UDM1_MODE_SHIFT, init_epis, &udm1_weyl_kind},
    {"episwr", "EPISWR point set: (EPIS, Weyl sqrt137) (paper 4.2.2)", 2, POINT_SET, UDM1_MODE_SHIFT, init_epis, &udm1_weyl_kind},
    /* the baselines */
    {"pcg32", "PCG32 (O'Neill 2014), seekable; 32 random bits per value", UDM1_MAX_DIMENSIONS, 0, UDM1_MODE_STREAMS,
     udm1_init_pcg32, &udm1_pcg32_kind},
    {"drand48", "drand48, bit-identical to the C library's; seekable", UDM1_MAX_DIMENSIONS, 0, UDM1_MODE_STREAMS,
     udm1_init_drand48, &udm1_drand48_kind},
    {"halton", "Halton: radical inverses in prime bases, random digit permutations", UDM1_MAX_DIMENSIONS, 0,
     UDM1_MODE_PERMUTE, udm1_init_halton, &udm1_halton_kind},
    {"halton-owen", "Halton, Owen-scrambled by hashing (base-b nested permutations)", UDM1_MAX_DIMENSIONS, 0,
     UDM1_MODE_OWEN, udm1_init_halton, &udm1_halton_kind},
    {"sobol", "Sobol, Joe-Kuo new-joe-kuo-6.21201, random digital shift", UDM1_SOBOL_MAX_DIMENSIONS, 0,
     UDM1_MODE_PERMUTE, udm1_init_sobol, &udm1_sobol_kind},
    {"sobol-owen", "Sobol, Owen-scrambled by hashing (Burley 2020)", UDM1_SOBOL_MAX_DIMENSIONS, 0, UDM1_MODE_OWEN,
     udm1_init_sobol, &udm1_sobol_kind},
    {"hammersley", "Hammersley point set (i/K, radical inverses 2, 3, 5, ...), random digital shift",
     UDM1_MAX_DIMENSIONS, POINT_SET, UDM1_MODE_PERMUTE, udm1_init_hammersley, &udm1_hammersley_kind},
    {"lp", "Larcher-Pillichshammer (i/K, LP(i)) point set, in pairs, random digital shift", UDM1_MAX_DIMENSIONS,
     POINT_SET | PAIRS, UDM1_MODE_PERMUTE, udm1_init_lp, &udm1_lp_kind},
    {"cmj", "Correlated multi-jittered (Kensler 2013), in pairs, a pattern per stream", UDM1_MAX_DIMENSIONS,
     POINT_SET | PAIRS, UDM1_MODE_STREAMS, udm1_init_cmj, &udm1_cmj_kind},
    {"grps", "Golden ratio point set (Schretter, Kobbelt, Dehaye 2012), in pairs", UDM1_MAX_DIMENSIONS,
     POINT_SET | PAIRS, UDM1_MODE_STREAMS, udm1_init_grps, &udm1_grps_kind},
    {"pmj02", "Progressive multi-jittered (0,2) (Christensen et al. 2018, Pharr 2019), in pairs", 64,
     POINT_SET | PAIRS, UDM1_MODE_PERMUTE, udm1_init_pmj02, &udm1_pmj02_kind},
    /* beyond the paper (appended: the indices of the presets above do not change) */
    {"wopt", "Weyl set from udm1's search: 64 square roots of primes, worst 2D projection kept near random-shift "
     "quality (tools/alpha_search.py)", COUNT(WOPT), 0, UDM1_MODE_SHIFT, init_wopt, &udm1_weyl_kind},
    {"lattice", "Rank-1 lattice {n z / K}, z by component-by-component search on the wrap-around L2 discrepancy",
     64, POINT_SET, UDM1_MODE_SHIFT, udm1_init_lattice, &udm1_weyl_kind},
    {"lattice-seq", "Embedded rank-1 lattice {phi_2(n) z}: a lattice at every power of two, z searched for 2^6 .. 2^20 "
     "(tools/lattice_search.py)", UDM1_LATTICE_SEQ_DIMS, 0, UDM1_MODE_SHIFT, udm1_init_lattice_seq,
     &udm1_lattice_seq_kind},
};

size_t udm1_preset_count(void) { return sizeof(PRESETS) / sizeof(PRESETS[0]); }

static void fill_info(const udm1_preset *p, udm1_preset_info *info)
{
    info->name = p->name;
    info->description = p->description;
    info->max_dimensions = p->max_dimensions;
    info->flags = p->flags;
}

udm1_status udm1_preset_get(size_t i, udm1_preset_info *info)
{
    if (!info) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_preset_get: info is NULL");
    if (i >= udm1_preset_count())
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "udm1_preset_get: index %zu is past the %zu presets", i,
                         udm1_preset_count());
    fill_info(&PRESETS[i], info);
    return UDM1_OK;
}

/* "NAME" or "NAME+tent" (the tent transform of preset NAME, see udm1/seq.h). */
int udm1_preset_is_tent(const char *name)
{
    size_t n = strlen(name);
    return n > 5 && strcmp(name + n - 5, "+tent") == 0;
}

const udm1_preset *udm1_preset_lookup(const char *name)
{
    size_t n = strlen(name) - (udm1_preset_is_tent(name) ? 5 : 0);
    for (size_t i = 0; i < udm1_preset_count(); ++i)
        if (strlen(PRESETS[i].name) == n && strncmp(PRESETS[i].name, name, n) == 0) return &PRESETS[i];
    return NULL;
}

udm1_status udm1_preset_find(const char *name, udm1_preset_info *info)
{
    if (!name || !info) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_preset_find: %s is NULL", name ? "info" : "name");
    const udm1_preset *p = udm1_preset_lookup(name);
    if (!p) return udm1_fail(UDM1_ERROR_UNKNOWN_PRESET, "udm1_preset_find: unknown preset '%.64s'", name);
    fill_info(p, info);
    return UDM1_OK;
}

static void from_spec(const spec *s, udm1_generator *g)
{
    switch (s->kind) {
    case SPEC_E:
    case SPEC_E2: {
        const uint64_t *f = s->kind == SPEC_E ? E_FRAC : E2_FRAC;
        g->hi = f[0];
        g->lo = f[1];
        g->nature = UDM1_NATURE_INDEPENDENT;
        g->radical = 0;
        break;
    }
    default:
        /* the table holds no perfect squares: tests/c/test_presets.c checks it */
        udm1_gen_quadratic(s->a, s->b, s->k, s->c, g);
        break;
    }
}

/* The EPIS axis n/K: A = ceil(2^128 / K), which makes the top 64 bits of n A
 * equal floor(n 2^64 / K) exactly for every n < K <= 2^32. */
static void epis_generator(uint64_t k, udm1_generator *g)
{
    g->nature = UDM1_NATURE_POINT_SET;
    g->radical = 0;
    if (k == 1) {
        g->hi = g->lo = 0;
        return;
    }
    /* floor((2^128 - 1) / K) + 1 */
    udm1_u128 q = udm1_u128_div(udm1_u128_make(UINT64_MAX, UINT64_MAX), udm1_u128_make(0, k));
    uint64_t qhi = udm1_u128_hi(q), qlo = udm1_u128_lo(q);
    qlo += 1;
    if (qlo == 0) ++qhi;
    g->hi = qhi;
    g->lo = qlo;
}
