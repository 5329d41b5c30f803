/*
 * udm1/exact_sum.h - the exact sum of doubles, so that an estimate does not depend on how its values
 * were split, ordered or grouped.
 * Part of libudm1's public interface; udm1/udm1.h includes every part.
 */
#ifndef UDM1_EXACT_SUM_H
#define UDM1_EXACT_SUM_H

#include "udm1/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* (1.10) The words of an exact sum: a two's complement integer of UDM1_EXACT_SUM_WORDS 64-bit words,
 * least significant first, holding the sum times 2^1074 (every finite double is an integer multiple of
 * 2^-1074, the smallest subnormal). Its 2304 bits hold any sum of fewer than 2^64 finite doubles
 * exactly. Start from all zeros; two sums add as integers (with carries, modulo 2^2304). */
#define UDM1_EXACT_SUM_WORDS 36

/* Add n finite doubles x[0 .. n - 1] to the exact sum in words, exactly: no rounding, the same words for
 * any order of the values and any split of them over calls. Nothing is added if a value is not finite.
 * Errors: NULL_ARGUMENT (x with n > 0, or words), INVALID_ARGUMENT (a value is NaN or infinite: the
 * message names the first one's index). */
UDM1_API udm1_status udm1_exact_sum_add(const double *x, size_t n, uint64_t words[UDM1_EXACT_SUM_WORDS]);

#ifdef __cplusplus
}
#endif

#endif
