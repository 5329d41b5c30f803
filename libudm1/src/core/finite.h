/* core/finite.h - the search for a NaN or infinite coordinate in a batch of points, made before the batch
 * writes its first output: a batch refused for one writes nothing. Vectorized (AVX-512 or AVX2 at
 * core/isa.h's level, portable code otherwise), it reads the coordinates once, a small part of the work
 * of the evaluation that follows. */
#ifndef UDM1_FINITE_H
#define UDM1_FINITE_H

#include "core/internal.h"

/* The first point i < count with a NaN or infinite coordinate axes[c][i * stride] (c < dims), and in *axis
 * the first such c (axis may be NULL); count if there is none. Axes in one array (axes[c] = axes[0] + c,
 * stride >= dims) and axes of stride 1 are read as contiguous runs, other layouts point by point. */
UDM1_HIDDEN size_t udm1_first_nonfinite_f64(uint32_t dims, const double *const *axes, size_t stride, size_t count,
                                            uint32_t *axis);
UDM1_HIDDEN size_t udm1_first_nonfinite_f32(uint32_t dims, const float *const *axes, size_t stride, size_t count,
                                            uint32_t *axis);

/* Whether p[0 .. len) holds a NaN or an infinity (a contiguous run, read as one). */
UDM1_HIDDEN int udm1_any_nonfinite_f64(const double *p, size_t len);
UDM1_HIDDEN int udm1_any_nonfinite_f32(const float *p, size_t len);

#endif /* UDM1_FINITE_H */
