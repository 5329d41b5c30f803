/* test_domain_cache.c - the child domains a stream holds (udm1/stream.h, UDM1_STREAM_CHILDREN):
 *  - which streams hold them (the three inline kinds: Weyl, pmj02, Sobol; where they fit past `held`), and
 *    that each slot holds the key udm1_domain_child derives (its formula spelled out here) and the words
 *    mix64(key + K_j) of the child's dimensions 0..3, with the dimensions held left as they were;
 *  - a held child's draws equal, bit for bit, the same domain's drawn without the cache (the stream
 *    copied with the flag cleared: the draws hash per draw) and the library's udm1_domain_fill_raw, for
 *    n 1..4 and every output type, every block of the root's chain, keys held and not, the next() blocks
 *    of a held child (dimensions whose words are not held) and children of children;
 *  - a hint that does not fit its domain is not used: a domain moved to another stream (another stream id,
 *    another seed, another first dimension, another preset, a stream without a cache), a hint naming
 *    another slot or none: the draws equal the library's.
 * Built also with the scalar code and with AVX2, AVX-512 and GFNI targeted (c.domain_cache_inline_*).
 */
#include "check.h"

#include <udm1/udm1.h>

#include <stdio.h>
#include <string.h>

static uint64_t mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* udm1/domain.h's child key: mix64(K + dim + (key + 1) G), never 0 */
static uint64_t child_key(uint64_t parent_key, uint32_t parent_dim, uint64_t key)
{
    uint64_t k = mix64(parent_key + parent_dim + (key + 1) * 0x9E3779B97F4A7C15ull);
    return k ? k : 0x9E3779B97F4A7C15ull;
}

/* The domain's draws (inline, every output type, n 1..4) against the library's raw values: 0 where one
 * differs. A refused draw (the library's status) must be refused inline too (NaN). */
static int draws_agree(udm1_domain d, const char *what)
{
    int ok = 1;
    for (uint32_t n = 1; n <= 4; ++n) {
        uint64_t lib[4] = {0, 0, 0, 0}, raw[4] = {0, 0, 0, 0};
        float f[4] = {0, 0, 0, 0}, lf[4] = {0, 0, 0, 0};
        double g[4] = {0, 0, 0, 0};
        udm1_status s = udm1_domain_fill_raw(&d, n, lib);
        udm1_domain_draw_raw(d, n, raw);
        udm1_domain_draw_f32(d, n, f);
        udm1_domain_draw_f64(d, n, g);
        if (s != UDM1_OK) {
            for (uint32_t j = 0; j < n; ++j) ok &= raw[j] == 0 && f[j] != f[j] && g[j] != g[j];
            continue;
        }
        CHECK_STATUS(udm1_domain_fill_f32(&d, n, lf), UDM1_OK);
        for (uint32_t j = 0; j < n; ++j) ok &= raw[j] == lib[j] && memcmp(&f[j], &lf[j], sizeof f[j]) == 0 && g[j] == udm1_raw_to_f64(lib[j]);
    }
    CHECKF(ok, "%s: key %016llx dim %u index %llu hint %u", what, (unsigned long long)d.key, d.dim,
           (unsigned long long)d.index, d.reserved);
    return ok;
}

/* two domains' draws, bit for bit (the same derivation with and without the cache) */
static int same_draws(udm1_domain a, udm1_domain b)
{
    int ok = a.key == b.key && a.dim == b.dim && a.index == b.index;
    for (uint32_t n = 1; n <= 4; ++n) {
        uint64_t ra[4] = {0, 0, 0, 0}, rb[4] = {0, 0, 0, 0};
        float fa[4] = {0, 0, 0, 0}, fb[4] = {0, 0, 0, 0};
        double ga[4] = {0, 0, 0, 0}, gb[4] = {0, 0, 0, 0};
        udm1_domain_draw_raw(a, n, ra), udm1_domain_draw_raw(b, n, rb);
        udm1_domain_draw_f32(a, n, fa), udm1_domain_draw_f32(b, n, fb);
        udm1_domain_draw_f64(a, n, ga), udm1_domain_draw_f64(b, n, gb);
        ok &= memcmp(ra, rb, sizeof ra) == 0 && memcmp(fa, fb, sizeof fa) == 0 && memcmp(ga, gb, sizeof ga) == 0;
    }
    return ok;
}

static udm1_seq *make(const char *preset, uint32_t dims, uint64_t seed, uint32_t randomize)
{
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    udm1_preset_info info;
    if (udm1_preset_find(preset, &info) != UDM1_OK) return NULL;
    desc.preset = preset, desc.dimensions = info.max_dimensions < dims ? info.max_dimensions : dims, desc.seed = seed;
    desc.point_count = (info.flags & UDM1_PRESET_POINT_SET) ? 256 : 0;
    desc.randomize = randomize;
    if (randomize == UDM1_RANDOMIZE_SCREEN) desc.screen_spp = 16;
    udm1_seq *s = NULL;
    return udm1_seq_create_desc(&desc, &s) == UDM1_OK ? s : NULL;
}

static const char *const presets[] = {"wr", "rd", "pmj02", "sobol-owen", "sobol", "halton"};
static const uint32_t counts[] = {1, 3, 4, 5, 20, 26, 40, 42, 43, 51, 52, 64};
static const uint64_t indices[] = {0, 1, 2, 7, 100, 255, 65537, 0xFFFFFFFFull, 0x100000005ull};

/* what the stream holds, slot by slot */
static void test_slots(void)
{
    int held_seen = 0;
    for (size_t p = 0; p < sizeof presets / sizeof *presets; ++p)
        for (uint32_t r = UDM1_RANDOMIZE_NONE; r <= UDM1_RANDOMIZE_SCREEN; ++r) {
            udm1_seq *s = make(presets[p], 80, 7, r);
            if (!s) continue;
            for (size_t c = 0; c < sizeof counts / sizeof *counts; ++c)
                for (uint32_t first = 0; first <= 5; first += 5) {
                    udm1_stream st;
                    CHECK_STATUS(udm1_stream_init(&st, s, 3, first, counts[c]), UDM1_OK);
                    uint32_t kinds = (st.flags / UDM1_STREAM_CHILDREN) & 3u, blocks = (st.held + 3) / 4;
                    uint32_t room = (UDM1_STREAM_DIMS - st.held) / 4;
                    int inline_kind = (st.flags & (UDM1_STREAM_INLINE | UDM1_STREAM_PMJ02 | UDM1_STREAM_SOBOL)) != 0;
                    uint32_t want = !inline_kind || st.held == 0 ? 0 : 2 * room / blocks < 2 ? 2 * room / blocks : 2;
                    CHECKF(kinds == want, "%s randomize %u first %u count %u: %u keys per block, not %u", presets[p], r,
                           first, counts[c], kinds, want);
                    held_seen += kinds != 0;
                    for (uint32_t k = 0; k < kinds; ++k)
                        for (uint32_t b = 0; b < blocks; ++b) {
                            uint32_t slot = k * blocks + b;
                            uint64_t key = child_key(st.key, 4 * b, k);
                            const uint64_t *w = slot < room ? st.a_hi + 60 - 4 * slot : st.a_lo + 60 - 4 * (slot - room);
                            int ok = 63 - slot >= st.held && st.dim_key[63 - slot] == key &&
                                     (slot < room ? 60 - 4 * slot : 60 - 4 * (slot - room)) >= st.held;
                            for (uint32_t j = 0; j < 4; ++j) ok &= w[j] == mix64(key + st.dim_key[j]);
                            CHECKF(ok, "%s first %u count %u slot %u", presets[p], first, counts[c], slot);
                            udm1_domain d = udm1_domain_child(udm1_domain_next(udm1_domain_root(&st, 9), b), k);
                            CHECKF(d.key == key && d.reserved == slot + 1 && d.dim == 0 && udm1_domain_words_(&d) == w,
                                   "%s count %u: the child of key %u of block %u is not read from slot %u", presets[p],
                                   counts[c], k, b, slot);
                        }
                    /* the dimensions held are the stream's own: the same as a stream of as many dimensions holds */
                    for (uint32_t j = 0; j < st.held; ++j) {
                        udm1_stream ref;
                        CHECK_STATUS(udm1_stream_init(&ref, s, 3, first, st.held), UDM1_OK);
                        CHECKF(st.a_hi[j] == ref.a_hi[j] && st.a_lo[j] == ref.a_lo[j] && st.offset[j] == ref.offset[j] &&
                                   st.base[j] == ref.base[j] && st.dim_key[j] == ref.dim_key[j],
                               "%s count %u: dimension %u's words changed", presets[p], counts[c], j);
                    }
                }
            udm1_seq_destroy(s);
        }
    CHECK(held_seen > 0);
}

/* held children's draws: as without the cache, as the library */
static void test_draws(void)
{
    for (size_t p = 0; p < sizeof presets / sizeof *presets; ++p)
        for (uint32_t r = UDM1_RANDOMIZE_NONE; r <= UDM1_RANDOMIZE_SCREEN; ++r) {
            udm1_seq *s = make(presets[p], 80, 7, r);
            if (!s) continue;
            for (size_t c = 0; c < sizeof counts / sizeof *counts; c += 2) {
                udm1_stream st, plain;
                CHECK_STATUS(udm1_stream_init(&st, s, 5, c % 4 ? 5 : 0, counts[c]), UDM1_OK);
                plain = st;
                plain.flags &= ~(3u * UDM1_STREAM_CHILDREN);
                for (size_t i = 0; i < sizeof indices / sizeof *indices; ++i)
                    for (uint32_t b = 0; b <= 17; ++b)
                        for (uint64_t k = 0; k < 3; ++k) {
                            udm1_domain d = udm1_domain_child(udm1_domain_next(udm1_domain_root(&st, indices[i]), b), k);
                            udm1_domain e = udm1_domain_child(udm1_domain_next(udm1_domain_root(&plain, indices[i]), b), k);
                            CHECK(e.reserved == 0);
                            CHECKF(same_draws(d, e), "%s randomize %u count %u index %llu block %u key %llu", presets[p], r,
                                   counts[c], (unsigned long long)indices[i], b, (unsigned long long)k);
                            draws_agree(d, presets[p]);
                            draws_agree(udm1_domain_next(d, 1), presets[p]);           /* words not held */
                            draws_agree(udm1_domain_child(d, 0), presets[p]);          /* a child's child */
                            draws_agree(udm1_domain_split(udm1_domain_next(udm1_domain_root(&st, indices[i]), b), 0, 4, 3),
                                        presets[p]);
                        }
            }
            udm1_seq_destroy(s);
        }
}

/* hints that do not fit their domain */
static void test_stale_hints(void)
{
    udm1_seq *wr = make("wr", 64, 7, UDM1_RANDOMIZE_SHIFT), *wr2 = make("wr", 64, 8, UDM1_RANDOMIZE_SHIFT);
    udm1_seq *pmj = make("pmj02", 64, 7, UDM1_RANDOMIZE_PERMUTE), *sob = make("sobol-owen", 64, 7, UDM1_RANDOMIZE_OWEN);
    CHECK(wr && wr2 && pmj && sob);
    if (!wr || !wr2 || !pmj || !sob) return;
    udm1_stream a, others[7];
    CHECK_STATUS(udm1_stream_init(&a, wr, 1, 0, 20), UDM1_OK);
    CHECK_STATUS(udm1_stream_init(&others[0], wr, 2, 0, 20), UDM1_OK);  /* another stream id */
    CHECK_STATUS(udm1_stream_init(&others[1], wr2, 1, 0, 20), UDM1_OK); /* another seed */
    CHECK_STATUS(udm1_stream_init(&others[2], wr, 1, 5, 20), UDM1_OK);  /* another first dimension: the same keys */
    CHECK_STATUS(udm1_stream_init(&others[3], wr, 1, 0, 64), UDM1_OK);  /* no cache */
    CHECK_STATUS(udm1_stream_init(&others[4], pmj, 1, 0, 20), UDM1_OK); /* other kinds */
    CHECK_STATUS(udm1_stream_init(&others[5], sob, 1, 0, 20), UDM1_OK);
    CHECK_STATUS(udm1_stream_init(&others[6], wr, 1, 0, 8), UDM1_OK);   /* fewer blocks: other slots */
    CHECK((others[3].flags / UDM1_STREAM_CHILDREN) % 4 == 0);
    for (size_t i = 0; i < sizeof indices / sizeof *indices; ++i)
        for (uint32_t b = 0; b < 5; ++b) {
            udm1_domain d = udm1_domain_child(udm1_domain_next(udm1_domain_root(&a, indices[i]), b), 0);
            CHECK(d.reserved == b + 1);
            draws_agree(d, "held");
            for (int o = 0; o < 7; ++o) {
                udm1_domain moved = d;
                moved.stream = &others[o];
                draws_agree(moved, "moved to another stream");
            }
            for (uint32_t hint = 0; hint <= 8; ++hint) { /* every other slot, none, past the slots */
                udm1_domain named = d;
                named.reserved = hint == 8 ? 0xFFFFFFFFu : hint;
                CHECK(hint == b + 1 ? udm1_domain_words_(&named) != NULL : udm1_domain_words_(&named) == NULL);
                draws_agree(named, "another hint");
            }
            udm1_domain other_key = d;
            other_key.key ^= 1; /* the hint of a domain whose key is not the slot's */
            CHECK(udm1_domain_words_(&other_key) == NULL);
            draws_agree(other_key, "another key");
        }
    udm1_seq_destroy(wr), udm1_seq_destroy(wr2), udm1_seq_destroy(pmj), udm1_seq_destroy(sob);
}

int main(void)
{
    if (check_built_isa_missing()) return 77;
    test_slots();
    test_draws();
    test_stale_hints();
    CHECK_DONE();
}
