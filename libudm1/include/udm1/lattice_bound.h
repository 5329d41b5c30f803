/*
 * udm1/lattice_bound.h - the error bound of an embedded rank-1 lattice rule read from its Fourier
 * coefficients, kept as the lattice doubles: the stopping rule of integration to a tolerance.
 * Part of libudm1's public interface; udm1/udm1.h includes every part.
 *
 * The sequence "lattice-seq" holds, at every power of two n = 2^m, a shifted rank-1 lattice: its point
 * i (i < n) is lattice point k = bitrev_m(i) of {k z / n + shift} (bitrev_m reverses the low m bits).
 * The discrete Fourier transform of f's values over k, divided by n, is Y[l] = the sum of f's Fourier
 * coefficients over the wavenumbers h with h.z = l (mod n), each times a phase of the shift; Y[0] is
 * the rule's mean. A udm1_lattice_bound keeps S = n Y (l = 0 .. n/2: the values are real, so
 * Y[n - l] is the conjugate of Y[l]) across doublings, and an order of the wavenumber classes in which
 * each class of n splits into l and l + n of 2n with the larger coefficient first (the kappa map of
 * Hickernell and Jimenez Rugama's CubLattice_g, as QMCPy's CubQMCLatticeG keeps it: a doubling
 * reorders the top `lag` levels only).
 *
 * The bound is fudge 2^-m times the sum of |Y| over the positions [n / 2^(lag + 1), n / 2^lag) of the
 * order. It holds the error of the rule's mean when f's Fourier coefficients decay steadily: the
 * cone assumption of CubLattice_g (fudge 5, lag 4 there), true of smooth integrands periodized (Baker's
 * transform), not of every f.
 *
 * The library computes no transform: the caller passes, for each n new values, their discrete Fourier
 * transform T[l] = sum_k v_k e^(-2 pi i k l / n), l = 0 .. n/2, with the new values in lattice order:
 * value j of the n (sequence index first + j) at k = bitrev_m(j). Any real-input FFT gives it (FFTW's
 * r2c, pocketfft, numpy.fft.rfft).
 */
#ifndef UDM1_LATTICE_BOUND_H
#define UDM1_LATTICE_BOUND_H

#include "udm1/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* (1.11) An embedded lattice rule's spectrum and bound. Not thread-safe while it is changed (add,
 * reset); a const handle may be read from many threads. */
typedef struct udm1_lattice_bound udm1_lattice_bound;

/* Create one that reads the bound at `lag` (1 .. 30) with the constant `fudge` (finite, > 0), with
 * room for `capacity` points (0 or more: the buffers grow as points are added; room given up front is
 * never copied). Errors: NULL_ARGUMENT (out), INVALID_ARGUMENT (lag, fudge, capacity above 2^32),
 * OUT_OF_MEMORY; on failure *out is set to NULL. */
UDM1_API udm1_status udm1_lattice_bound_create(uint32_t lag, double fudge, uint64_t capacity,
                                               udm1_lattice_bound **out);
UDM1_API void udm1_lattice_bound_destroy(udm1_lattice_bound *bound);

/* Forget the points, keep the memory (to start a new rule without touching fresh pages). */
UDM1_API void udm1_lattice_bound_reset(udm1_lattice_bound *bound);

/* Add n values through their transform (n/2 + 1 complex numbers as (re, im) pairs, see above): the
 * first n = 2^m points (m > lag) when there are none, and then the next n = as many as there are
 * (sequence indices n .. 2n - 1: the odd points of the doubled lattice). Errors: NULL_ARGUMENT,
 * INVALID_ARGUMENT (n not a power of two above 2^lag at the start, n not the points held later, past
 * 2^32 points, a coefficient not finite: the message names the first; nothing is changed),
 * OUT_OF_MEMORY (nothing is changed). */
UDM1_API udm1_status udm1_lattice_bound_add(udm1_lattice_bound *bound, const double *transform, uint64_t n);

/* The points added so far: 0, or n = 2^m. 0 and udm1_last_error() set for a NULL handle. */
UDM1_API uint64_t udm1_lattice_bound_points(const udm1_lattice_bound *bound);

/* The error bound fudge 2^-m sum |Y[order[p]]|, p in [n / 2^(lag + 1), n / 2^lag): +infinity when the
 * sum overflows. Errors: NULL_ARGUMENT, INVALID_ARGUMENT (no points yet). */
UDM1_API udm1_status udm1_lattice_bound_error(const udm1_lattice_bound *bound, double *error);

/* Y[l] for l in [first, first + count) (< n), as (re, im) pairs into out. Errors: NULL_ARGUMENT,
 * INDEX_RANGE. */
UDM1_API udm1_status udm1_lattice_bound_coefficients(const udm1_lattice_bound *bound, uint64_t first,
                                                     uint64_t count, double *out);

/* The wavenumber classes at positions [first, first + count) (< n) of the order (position 0 holds
 * class 0). Errors: NULL_ARGUMENT, INDEX_RANGE. */
UDM1_API udm1_status udm1_lattice_bound_order(const udm1_lattice_bound *bound, uint64_t first, uint64_t count,
                                              uint64_t *out);

#ifdef __cplusplus
}
#endif

#endif
