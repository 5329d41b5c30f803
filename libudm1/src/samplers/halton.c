/* halton.c - the Halton sequence: dimension j is the radical inverse of the
 * index in the j-th prime base (2, 3, 5, ...), exact (radical_inverse.c). */
#include "samplers/samplers.h"
#include "seq/scramble.h"

#include <stdlib.h>

typedef struct halton { uint64_t primes[1]; } halton; /* dims entries */

static uint64_t halton_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    const halton *h = seq->data;
    uint64_t r = udm1_word(seq, skey, dim);
    return udm1_radical_inverse(index, (uint32_t)h->primes[dim], seq->mode, r) + seq->offset[dim];
}

udm1_status udm1_init_halton(udm1_seq_t *seq)
{
    halton *h = malloc(sizeof(uint64_t) * seq->dims);
    if (!h || !udm1_first_primes(seq->dims, h->primes)) {
        free(h);
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "udm1_seq_create: out of memory for %u primes", seq->dims);
    }
    seq->data = h;
    return UDM1_OK;
}

const udm1_kind udm1_halton_kind = {.name = "halton", .value = halton_value};
