/* lattice_sequence.c - the embedded rank-1 lattice in base 2 ("lattice-seq"), an extensible lattice:
 *
 *   x_n = { phi_2(n) z + shift },   phi_2 the base-2 radical inverse,
 *
 * whose first 2^m points are, for every m, the rank-1 lattice { k z / 2^m } (k < 2^m) of generator
 * z mod 2^m: a rule doubles its points without dropping the ones it has, and the points of each power of
 * two are a lattice, whose Fourier structure udm1.integrate's lattice criterion reads. phi_2(n) in 0.64
 * fixed point is the bit reversal of n, so the raw value reverse64(n) z_j + o_j (mod 2^64) is exact for
 * every n < 2^64. z is the table of tools/lattice_search.py (component by component on the wrap-around
 * L2 discrepancy, the worst ratio to the best candidate over the sizes 2^6 .. 2^20; past 2^20 points the
 * sequence goes on, exact, as lattices of 2^21, 2^22, ... points not searched for). */
#include "core/bits.h"
#include "samplers/samplers.h"
#include "seq/scramble.h"

#include "samplers/lattice_sequence_table.h"

_Static_assert(sizeof(LATTICE_SEQ_Z) / sizeof(LATTICE_SEQ_Z[0]) == UDM1_LATTICE_SEQ_DIMS,
               "lattice_sequence_table.h has UDM1_LATTICE_SEQ_DIMS dimensions");

static uint64_t lattice_seq_raw(uint64_t index, uint32_t dim) { return udm1_reverse64(index) * LATTICE_SEQ_Z[dim]; }

static uint64_t lattice_seq_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    return udm1_randomize_base2(seq->mode, lattice_seq_raw(index, dim) + seq->offset[dim], udm1_word(seq, skey, dim));
}

/* rows [first, first + count) x dims [dim0, dim0 + nd): the words once, the bit reversal once and then
 * stepped: n -> n + 1 flips the trailing ones of n and the zero above them, so its reversal flips the top
 * t + 1 bits, t = the trailing ones of n. The random shift (the default) adds offset + word in one. */
static void lattice_seq_fill(const udm1_seq_t *seq, uint64_t skey, uint64_t first, size_t count, uint32_t dim0,
                             uint32_t nd, uint64_t *raw)
{
    uint64_t words[UDM1_LATTICE_SEQ_DIMS];
    const uint32_t *z = LATTICE_SEQ_Z + dim0;
    const uint64_t *offset = seq->offset + dim0;
    const int shift = seq->mode == UDM1_MODE_SHIFT;
    for (uint32_t j = 0; j < nd; ++j) {
        words[j] = udm1_word(seq, skey, dim0 + j);
        if (shift) words[j] += offset[j]; /* (phi z + o) + r = phi z + (o + r) mod 2^64 */
    }
    uint64_t phi = udm1_reverse64(first);
    for (size_t i = 0; i < count; ++i) {
        if (i) {
            uint64_t prev = first + i - 1; /* its trailing ones: below 64 (prev + 1 does not wrap: checked range) */
            phi ^= ~0ull << (63 - udm1_ctz64(~prev));
        }
        uint64_t *row = raw + i * nd;
        if (shift) {
            for (uint32_t j = 0; j < nd; ++j) row[j] = phi * z[j] + words[j];
        } else {
            for (uint32_t j = 0; j < nd; ++j) row[j] = udm1_randomize_base2(seq->mode, phi * z[j] + offset[j], words[j]);
        }
    }
}

udm1_status udm1_init_lattice_seq(udm1_seq_t *seq)
{
    (void)seq; /* no tables but the static generating vector */
    return UDM1_OK;
}

const udm1_kind udm1_lattice_seq_kind = {.name = "lattice-seq", .value = lattice_seq_value, .fill = lattice_seq_fill};
