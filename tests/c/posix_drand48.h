/* posix_drand48.h - the reference drand48 of the tests: the C library's srand48 and drand48 where the
 * platform has them (POSIX), and POSIX's definition of them elsewhere (Windows' C library has neither):
 * the 48-bit linear congruential generator X <- (0x5DEECE66D X + 11) mod 2^48, seeded with
 * X = (low 32 bits of the seed) 2^16 + 0x330E, each value X / 2^48 of the next X. Include it before any
 * other header (it defines _DEFAULT_SOURCE for the C library's declarations). */
#ifndef UDM1_TEST_POSIX_DRAND48_H
#define UDM1_TEST_POSIX_DRAND48_H

#if defined(_WIN32)
#include <stdint.h>

static uint64_t posix_drand48_state;

static void ref_srand48(long seed) { posix_drand48_state = ((uint64_t)(uint32_t)seed << 16) | 0x330Eu; }

static double ref_drand48(void)
{
    posix_drand48_state = (posix_drand48_state * 0x5DEECE66Dull + 0xBu) & ((1ull << 48) - 1);
    return (double)posix_drand48_state * 0x1p-48;
}
#else
#ifndef _DEFAULT_SOURCE
#define _DEFAULT_SOURCE /* srand48, drand48 */
#endif
#include <stdlib.h>

static void ref_srand48(long seed) { srand48(seed); }
static double ref_drand48(void) { return drand48(); }
#endif

#endif /* UDM1_TEST_POSIX_DRAND48_H */
