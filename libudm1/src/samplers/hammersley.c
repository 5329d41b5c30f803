/* hammersley.c - point sets with an n/K axis.
 *  hammersley: (n/K, phi_2(n), phi_3(n), phi_5(n), ...), exact.
 *  lp:         Larcher-Pillichshammer (n/K, LP(n)), LP(n) = the XOR of the
 *              columns 1 1..1 0..0 (k+1 leading ones) over the set bits k of n:
 *              an all-ones upper triangular generator matrix, a (0,m,2)-net for
 *              K = 2^m (Larcher and Pillichshammer 2001; as in pbrt-v2).
 *              Used in pairs: pair k >= 1 visits the points in its own order.
 * The n/K axis is floor(n 2^64 / K), exact; it is base-2 scrambled like the
 * other binary axes, so stratification survives for K = 2^m.
 */
#include "samplers/radical_inverse.h"
#include "samplers/samplers.h"
#include "seq/scramble.h"

#include <stdlib.h>

typedef struct hammersley { udm1_radix radix[1]; } hammersley; /* dims - 1 bases */

static uint64_t n_over_k(uint64_t n, uint64_t k) { return udm1_frac64(udm1_u128_make(0, n), udm1_u128_make(0, k)); }

static uint64_t hammersley_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    uint64_t r = udm1_word(seq, skey, dim);
    if (dim == 0) return udm1_randomize_base2(seq->mode, n_over_k(index, seq->point_count) + seq->offset[0], r);
    const hammersley *h = seq->data;
    return udm1_radical_inverse(index, &h->radix[dim - 1], seq->mode, r) + seq->offset[dim];
}

static void hammersley_fill(const udm1_seq_t *seq, uint64_t skey, uint64_t first, size_t count, uint32_t dim0,
                            uint32_t nd, uint64_t *raw)
{
    const hammersley *h = seq->data;
    for (uint32_t j = 0; j < nd; ++j) {
        uint32_t dim = dim0 + j;
        if (dim == 0) {
            for (size_t i = 0; i < count; ++i) raw[i * nd + j] = hammersley_value(seq, skey, first + i, 0);
            continue;
        }
        udm1_radical_fill(&h->radix[dim - 1], seq->mode, udm1_word(seq, skey, dim), first, count, seq->offset[dim],
                          raw + j, nd);
    }
}

static int hammersley_pin(const udm1_seq_t *seq, uint64_t skey, uint32_t dim, uint64_t *r, uint64_t *w0, uint64_t *w1)
{
    const hammersley *h = seq->data;
    if (seq->mode != UDM1_MODE_PERMUTE) return 0;
    *r = udm1_word(seq, skey, dim);
    *w0 = *w1 = 0;
    if (dim > 0) udm1_radical_pin(&h->radix[dim - 1], seq->mode, *r, w0, w1);
    return 1;
}

static uint64_t hammersley_pinned(const udm1_seq_t *seq, uint64_t index, uint32_t dim, uint64_t r, uint64_t w0,
                                  uint64_t w1)
{
    if (dim == 0) return udm1_randomize_base2(seq->mode, n_over_k(index, seq->point_count) + seq->offset[0], r);
    const hammersley *h = seq->data;
    return udm1_radical_pinned(index, &h->radix[dim - 1], seq->mode, r, w0, w1) + seq->offset[dim];
}

udm1_status udm1_init_hammersley(udm1_seq_t *seq)
{
    hammersley *h = (hammersley *)udm1_radix_table(seq->dims - 1);
    if (!h) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "udm1_seq_create: out of memory for %u primes", seq->dims);
    seq->data = h;
    return UDM1_OK;
}

/* the Larcher-Pillichshammer radical inverse of n as 0.64 */
static uint64_t lp64(uint64_t n)
{
    uint64_t v = 1ull << 63, x = 0;
    for (; n; n >>= 1, v |= v >> 1)
        if (n & 1) x ^= v;
    return x;
}

static uint64_t lp_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    uint32_t pair = dim / 2;
    uint64_t i = udm1_pair_index(seq, pair, index);
    uint64_t v = (dim & 1) ? lp64(i) : n_over_k(i, seq->point_count);
    return udm1_randomize_base2(seq->mode, v + seq->offset[dim], udm1_word(seq, skey, dim));
}

udm1_status udm1_init_lp(udm1_seq_t *seq)
{
    (void)seq; /* no tables: a value is computed from its index alone */
    return UDM1_OK;
}

const udm1_kind udm1_hammersley_kind = {.name = "hammersley", .value = hammersley_value, .fill = hammersley_fill,
                                        .pin = hammersley_pin, .pinned = hammersley_pinned};
const udm1_kind udm1_lp_kind = {.name = "lp", .value = lp_value};
