/* test_descriptor_layouts.c - callers built against other releases' headers: a udm1_seq_desc, a
 * udm1_noise_desc and a udm1_pattern_params laid out as in 1.5 (the layouts are written out here, not
 * taken from the header) are
 * accepted with the values a current caller gets; a newer caller's longer layout is accepted when its
 * unknown fields are zero and refused, naming struct_size, when one is set; a shorter one than 1.0's
 * is refused. */
#include "check.h"

#include <udm1/udm1.h>

#include <string.h>

/* udm1_seq_desc as udm1 1.5 declared it (1.0's layout; screen_spp was `reserved` before 1.4) */
typedef struct seq_desc_1_5 {
    uint32_t struct_size;
    uint32_t dimensions;
    const char *preset;
    const udm1_alpha *alphas;
    const uint64_t *offsets;
    uint64_t point_count;
    uint64_t seed;
    uint32_t randomize;
    uint32_t screen_spp;
} seq_desc_1_5;

/* a caller of a future 1.x that appended two fields */
typedef struct seq_desc_next {
    seq_desc_1_5 known;
    uint64_t appended_a;
    uint32_t appended_b;
} seq_desc_next;

/* udm1_noise_desc as 1.5 declared it */
typedef struct noise_desc_1_5 {
    uint32_t struct_size;
    uint32_t kind;
    const char *table;
    uint64_t seed;
    uint32_t period[3];
    uint32_t reserved;
} noise_desc_1_5;

/* udm1_pattern_params as 1.5 declared it (1.2's layout) */
typedef struct pattern_params_1_5 {
    uint32_t struct_size, pattern, octaves, wave;
    double omega, lambda, turbulence[3], frequency, phase, exponent, agate_turb;
} pattern_params_1_5;

static void fill_1_5(seq_desc_1_5 *d, uint32_t size)
{
    memset(d, 0, sizeof *d);
    d->struct_size = size;
    d->dimensions = 3;
    d->preset = "wr";
    d->seed = 77;
    d->randomize = UDM1_RANDOMIZE_SCREEN;
    d->screen_spp = 16;
}

/* the sequence's values at a few (stream, index, dim), to compare two handles */
static int same_values(const udm1_seq *a, const udm1_seq *b)
{
    for (uint64_t s = 0; s < 4; ++s)
        for (uint64_t i = 0; i < 50; i += 7)
            for (uint32_t j = 0; j < 3; ++j) {
                uint64_t va = 1, vb = 2;
                if (udm1_seq_sample_u64(a, s * 0x100000001ull, i, j, &va) != UDM1_OK) return 0;
                if (udm1_seq_sample_u64(b, s * 0x100000001ull, i, j, &vb) != UDM1_OK) return 0;
                if (va != vb) return 0;
            }
    return 1;
}

int main(void)
{
    udm1_seq_desc now;
    udm1_seq_desc_init(&now);
    now.dimensions = 3;
    now.preset = "wr";
    now.seed = 77;
    now.randomize = UDM1_RANDOMIZE_SCREEN;
    now.screen_spp = 16;
    udm1_seq *ref = NULL;
    CHECK_STATUS(udm1_seq_create_desc(&now, &ref), UDM1_OK);

    /* the 1.5 layout, its own size */
    seq_desc_1_5 old;
    fill_1_5(&old, (uint32_t)sizeof old);
    CHECKF(sizeof old == 56 || sizeof(void *) != 8, "the 1.5 layout is 56 bytes on LP64, not %zu", sizeof old);
    udm1_seq *from_old = NULL;
    CHECK_STATUS(udm1_seq_create_desc((const udm1_seq_desc *)(const void *)&old, &from_old), UDM1_OK);
    CHECK(from_old && ref && same_values(ref, from_old));
    udm1_seq_destroy(from_old);

    /* a newer caller: unknown fields zero -> accepted, the same sequence */
    seq_desc_next next;
    memset(&next, 0, sizeof next);
    fill_1_5(&next.known, (uint32_t)sizeof next);
    udm1_seq *from_next = NULL;
    CHECK_STATUS(udm1_seq_create_desc((const udm1_seq_desc *)(const void *)&next, &from_next), UDM1_OK);
    CHECK(from_next && ref && same_values(ref, from_next));
    udm1_seq_destroy(from_next);
    /* ... an unknown field set -> refused, naming struct_size; *out NULL */
    next.appended_b = 5;
    from_next = (udm1_seq *)&next;
    CHECK_STATUS(udm1_seq_create_desc((const udm1_seq_desc *)(const void *)&next, &from_next),
                 UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(from_next == NULL);
    CHECKF(strstr(udm1_last_error(), "struct_size") && strstr(udm1_last_error(), "newer"), "message: %s",
           udm1_last_error());
    next.appended_b = 0;
    next.appended_a = 1;
    CHECK_STATUS(udm1_seq_create_desc((const udm1_seq_desc *)(const void *)&next, &from_next),
                 UDM1_ERROR_INVALID_ARGUMENT);

    /* shorter than the first layout */
    fill_1_5(&old, 52);
    CHECK_STATUS(udm1_seq_create_desc((const udm1_seq_desc *)(const void *)&old, &from_old),
                 UDM1_ERROR_INVALID_ARGUMENT);
    CHECKF(strstr(udm1_last_error(), "struct_size 52"), "message: %s", udm1_last_error());

    /* the noise descriptor of 1.5 (read as if period_w were 0), today's, and a longer one */
    noise_desc_1_5 nd_old;
    memset(&nd_old, 0, sizeof nd_old);
    nd_old.struct_size = (uint32_t)sizeof nd_old;
    nd_old.seed = 3;
    struct { udm1_noise_desc known; uint64_t appended; } nd;
    memset(&nd, 0, sizeof nd);
    udm1_noise_desc_init(&nd.known);
    nd.known.seed = 3;
    udm1_noise *n_old = NULL, *n_new = NULL, *n_next = NULL;
    CHECK_STATUS(udm1_noise_create((const udm1_noise_desc *)(const void *)&nd_old, &n_old), UDM1_OK);
    udm1_noise_desc cur;
    udm1_noise_desc_init(&cur);
    cur.seed = 3;
    CHECK_STATUS(udm1_noise_create(&cur, &n_new), UDM1_OK);
    nd.known.struct_size = (uint32_t)sizeof nd;
    CHECK_STATUS(udm1_noise_create((const udm1_noise_desc *)(const void *)&nd, &n_next), UDM1_OK);
    if (n_old && n_new && n_next)
        CHECK(udm1_noise_3d(n_old, 0.3, 1.7, 2.2) == udm1_noise_3d(n_new, 0.3, 1.7, 2.2) &&
              udm1_noise_3d(n_next, 0.3, 1.7, 2.2) == udm1_noise_3d(n_new, 0.3, 1.7, 2.2) &&
              udm1_noise_4d(n_old, 0.3, 1.7, 2.2, 9.1) == udm1_noise_4d(n_new, 0.3, 1.7, 2.2, 9.1));
    nd.appended = 9;
    udm1_noise *n_bad = (udm1_noise *)&nd;
    CHECK_STATUS(udm1_noise_create((const udm1_noise_desc *)(const void *)&nd, &n_bad), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(n_bad == NULL);
    /* pattern params of 1.5: the fields it knew, the others their defaults (crackle's too) */
    for (uint32_t pattern = UDM1_PATTERN_MARBLE; pattern <= UDM1_PATTERN_CRACKLE; pattern += UDM1_PATTERN_CRACKLE - UDM1_PATTERN_MARBLE) {
        udm1_pattern_params cur_p;
        udm1_pattern_params_init(&cur_p, pattern);
        pattern_params_1_5 old_p;
        memcpy(&old_p, &cur_p, sizeof old_p);
        old_p.struct_size = (uint32_t)sizeof old_p;
        double a = udm1_pattern_eval(n_new, (const udm1_pattern_params *)(const void *)&old_p, 0.3, 1.7, 2.2);
        double b = udm1_pattern_eval(n_new, &cur_p, 0.3, 1.7, 2.2);
        CHECKF(a == b && a == a, "pattern %u: %g from the 1.5 layout, %g from today's", pattern, a, b);
        old_p.struct_size = 40; /* shorter than 1.2's */
        a = udm1_pattern_eval(n_new, (const udm1_pattern_params *)(const void *)&old_p, 0.3, 1.7, 2.2);
        CHECK(a != a && strstr(udm1_last_error(), "struct_size 40"));
    }
    udm1_noise_destroy(n_old);
    udm1_noise_destroy(n_new);
    udm1_noise_destroy(n_next);
    udm1_seq_destroy(ref);
    CHECK_DONE();
}
