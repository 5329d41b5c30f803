/* halton.c - the Halton sequence: dimension j is the radical inverse of the
 * index in the j-th prime base (2, 3, 5, ...), exact (radical_inverse.c). */
#include "samplers/radical_inverse.h"
#include "samplers/samplers.h"
#include "seq/scramble.h"
#include "weyl/generators.h"

#include <stdlib.h>

typedef struct halton { udm1_radix radix[1]; } halton; /* dims entries */

udm1_radix *udm1_radix_table(uint32_t count)
{
    size_t n = count ? count : 1;
    udm1_radix *rx = malloc(sizeof(udm1_radix) * n);
    uint64_t *primes = malloc(sizeof(uint64_t) * n);
    if (rx && primes && udm1_first_primes(count, primes)) {
        for (uint32_t j = 0; j < count; ++j) udm1_radix_init(&rx[j], (uint32_t)primes[j]);
        free(primes);
        return rx;
    }
    free(rx);
    free(primes);
    return NULL;
}

static uint64_t halton_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    const halton *h = seq->data;
    uint64_t r = udm1_word(seq, skey, dim);
    return udm1_radical_inverse(index, &h->radix[dim], seq->mode, r) + seq->offset[dim];
}

static void halton_fill(const udm1_seq_t *seq, uint64_t skey, uint64_t first, size_t count, uint32_t dim0, uint32_t nd,
                        uint64_t *raw)
{
    const halton *h = seq->data;
    for (uint32_t j = 0; j < nd; ++j) {
        uint32_t dim = dim0 + j;
        udm1_radical_fill(&h->radix[dim], seq->mode, udm1_word(seq, skey, dim), first, count, seq->offset[dim],
                          raw + j, nd);
    }
}

static int halton_pin(const udm1_seq_t *seq, uint64_t skey, uint32_t dim, uint64_t *r, uint64_t *w0, uint64_t *w1)
{
    const halton *h = seq->data;
    if (seq->mode != UDM1_MODE_PERMUTE) return 0;
    *r = udm1_word(seq, skey, dim);
    udm1_radical_pin(&h->radix[dim], seq->mode, *r, w0, w1);
    return 1;
}

static uint64_t halton_pinned(const udm1_seq_t *seq, uint64_t index, uint32_t dim, uint64_t r, uint64_t w0, uint64_t w1)
{
    const halton *h = seq->data;
    return udm1_radical_pinned(index, &h->radix[dim], seq->mode, r, w0, w1) + seq->offset[dim];
}

udm1_status udm1_init_halton(udm1_seq_t *seq)
{
    halton *h = (halton *)udm1_radix_table(seq->dims);
    if (!h) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "udm1_seq_create: out of memory for %u primes", seq->dims);
    seq->data = h;
    return UDM1_OK;
}

const udm1_kind udm1_halton_kind = {
    .name = "halton", .value = halton_value, .fill = halton_fill, .pin = halton_pin, .pinned = halton_pinned};
