/* test_golden.c - the library reproduces golden values computed by the
 * independent Python reference (tests/python/make_golden.py): raw values of
 * every preset at indices up to 2^64 - 1, per-stream shifts, and padded
 * cursor draws. They pin the sequence contract of udm1.h. */
#include "check.h"

#include <udm1/udm1.h>

#include <stdint.h>

#include "golden_values.h"

int main(void)
{
    enum { NCASES = sizeof GOLDEN_CASES / sizeof *GOLDEN_CASES };
    udm1_seq *seqs[NCASES];
    for (int c = 0; c < NCASES; ++c) {
        udm1_seq_desc d;
        udm1_seq_desc_init(&d);
        d.preset = GOLDEN_CASES[c].preset;
        d.dimensions = GOLDEN_CASES[c].dims;
        d.point_count = GOLDEN_CASES[c].k;
        d.seed = GOLDEN_CASES[c].seed;
        d.randomize = GOLDEN_CASES[c].randomize ? UDM1_RANDOMIZE_SHIFT : UDM1_RANDOMIZE_NONE;
        seqs[c] = NULL;
        CHECK_STATUS(udm1_seq_create_desc(&d, &seqs[c]), UDM1_OK);
    }
    int bad = 0;
    size_t nv = sizeof GOLDEN_VALUES / sizeof *GOLDEN_VALUES;
    for (size_t i = 0; i < nv; ++i) {
        const struct golden_value *g = &GOLDEN_VALUES[i];
        uint64_t u = 0, b = 0;
        udm1_seq_sample_u64(seqs[g->c], g->stream, g->index, g->dim, &u);
        udm1_seq_fill_u64(seqs[g->c], g->stream, g->index, 1, g->dim, 1, &b, 1);
        if (u != g->raw || b != g->raw) {
            if (bad++ < 10)
                fprintf(stderr, "golden %s stream %llx index %llx dim %u: %016llx, expected %016llx\n",
                        GOLDEN_CASES[g->c].preset, (unsigned long long)g->stream, (unsigned long long)g->index,
                        g->dim, (unsigned long long)u, (unsigned long long)g->raw);
        }
    }
    size_t np = sizeof GOLDEN_PADS / sizeof *GOLDEN_PADS;
    for (size_t i = 0; i < np; ++i) {
        const struct golden_value *g = &GOLDEN_PADS[i];
        udm1_cursor cur;
        CHECK_STATUS(udm1_cursor_start(&cur, seqs[g->c], g->stream, g->index, g->dim), UDM1_OK);
        double v = udm1_cursor_1d_f64(&cur);
        if (v != (double)(g->raw >> 11) * 0x1p-53 && bad++ < 10)
            fprintf(stderr, "golden pad %s dim %u: %a\n", GOLDEN_CASES[g->c].preset, g->dim, v);
    }
    CHECKF(bad == 0, "%d of %zu golden values differ", bad, nv + np);
    CHECK(nv > 1000 && np > 100);
    for (int c = 0; c < NCASES; ++c) udm1_seq_destroy(seqs[c]);
    CHECK_DONE();
}
