/* samplers/radical_inverse.h - exact base-b radical inverses with digit scrambling (radical_inverse.c),
 * for Halton and Hammersley: a base's constants, the value of one index, and the ways a fill or a
 * stream computes many values of one (base, randomization word) faster, to the same bits. */
#ifndef UDM1_RADICAL_INVERSE_H
#define UDM1_RADICAL_INVERSE_H

#include "core/divisor.h"
#include "seq/seq.h"

/* The stream splits (udm1_radical_pin): the fewest digits s with b^s >= 2^10, and with b^s >= 2^20. */
#define UDM1_RADIX_SPLITS 2

/* A base's constants (udm1_radix_init). */
typedef struct udm1_radix {
    uint32_t base;        /* b >= 2 */
    uint32_t digits;      /* K: b^K >= 2^64 > b^(K-1) (base 2: 64) */
    uint32_t mask;        /* udm1_permute_mask(b) */
    uint32_t split[UDM1_RADIX_SPLITS];
    uint64_t magic;       /* udm1_mod32_magic(b) */
    udm1_divisor divisor; /* b */
    uint64_t limit[UDM1_RADIX_SPLITS];       /* b^split[i] */
    udm1_divisor power[UDM1_RADIX_SPLITS];   /* b^split[i] */
} udm1_radix;

UDM1_HIDDEN void udm1_radix_init(udm1_radix *rx, uint32_t base);

/* The constants of the first count primes' bases (2, 3, 5, ...), allocated (free()); NULL when out of memory
 * (halton.c). */
UDM1_HIDDEN udm1_radix *udm1_radix_table(uint32_t count);

/* The radical inverse of n as 0.64 (floor), exact; its digits permuted per mode, r the dimension's random
 * word. */
UDM1_HIDDEN uint64_t udm1_radical_inverse(uint64_t n, const udm1_radix *rx, uint32_t mode, uint64_t r);

/* The same values, plus add, of indices [first, first + count) into out[0], out[stride], ... (count > 0,
 * first + count - 1 <= 2^64 - 1). */
UDM1_HIDDEN void udm1_radical_fill(const udm1_radix *rx, uint32_t mode, uint64_t r, uint64_t first, size_t count,
                                   uint64_t add, uint64_t *out, size_t stride);

/* A stream's two words for (rx, mode, r), and the value of n from them: udm1_radical_inverse's bits. */
UDM1_HIDDEN void udm1_radical_pin(const udm1_radix *rx, uint32_t mode, uint64_t r, uint64_t *w0, uint64_t *w1);
UDM1_HIDDEN uint64_t udm1_radical_pinned(uint64_t n, const udm1_radix *rx, uint32_t mode, uint64_t r, uint64_t w0,
                                         uint64_t w1);

#endif /* UDM1_RADICAL_INVERSE_H */
