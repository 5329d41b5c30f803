/* batch.c - the lattice noise batches (udm1_noise_eval, udm1_noise_eval_f32, udm1_noise_points), all or
 * nothing: a batch writes its outputs only once every coordinate is known to be finite, and costs about
 * what it did when it refused a point as it came to it.
 *
 * A check of the whole input before the evaluation is a second pass over memory: for a batch whose
 * coordinates do not stay in the cache (a million points) it measured a quarter to a half of the
 * evaluation's time. So a large batch that a vector kernel takes goes in two parts: the kernel evaluates
 * the first quarter of the points into memory of its own while it checks the other three quarters beside
 * them (noise/side_check.h: loads that the processor overlaps with the evaluation), then the first part is
 * copied and the rest evaluated in place. A small batch (its coordinates stay in the cache), a layout the
 * side check does not read (strided axes of separate arrays) and the scalar kinds are checked first. A
 * refused batch's first non-finite point is then found by the plain search, for the message. */
#include "core/finite.h"
#include "noise/noise_tables.h"

#include <stdlib.h>
#include <string.h>

#define FUSED_MIN_POINTS 4096 /* below: checked first */
#define FUSED_AHEAD 3         /* points checked beside the kernel per point it evaluates into scratch */

#define REAL double
#define R(fn) fn##_f64
#include "noise/batch_impl.h"
#undef REAL
#undef R

#define REAL float
#define R(fn) fn##_f32
#include "noise/batch_impl.h"
#undef REAL
#undef R
