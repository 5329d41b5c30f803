/* batch.c - the lattice noise batches (udm1_noise_eval, udm1_noise_eval_f32, udm1_noise_points), all or
 * nothing: a batch writes its outputs only once every coordinate is known to be finite.
 *
 * The vector kernels check the coordinates of the points they evaluate as they go, at no cost, but they
 * write as they go too; a check of the whole input before them is a second pass over memory. Measured
 * against the kernels alone (one thread, CPU time, alternating calls): 5-8% for 2048 points, 7-13% for
 * 32768, 20-45% for a million, whose coordinates do not stay in the cache. So where a kernel applies:
 *  - a large batch (FUSED_MIN_POINTS or more) goes in two parts: the kernel evaluates a first part into
 *    memory of its own while it checks the coordinates of the others beside them (noise/side_check.h:
 *    loads the processor overlaps with the evaluation), then the first part is copied and the rest
 *    evaluated in place (a million points: 5-20% more than the kernels alone);
 *  - a small batch with fewer outputs than coordinates per point goes to scratch whole (a copy of its
 *    outputs reads less than a check of its coordinates), its few last points checked after;
 *  - the others (more outputs than coordinates, strided axes of separate arrays, the scalar kinds), and a
 *    batch refused (its first non-finite point named), are checked first. */
#include "core/finite.h"
#include "noise/noise_tables.h"

#include <stdlib.h>
#include <string.h>

#define FUSED_MIN_POINTS 4096 /* below: the kernel evaluates all its groups into scratch, then the copy */
#define SCRATCH_BYTES 16384    /* scratch on the stack up to this, else allocated */

/* FUSED_AHEAD: the points checked beside the kernel per point it evaluates into scratch. The fewer, the
 * more is copied; the more, the more the check reads while the first part runs. Measured at a million
 * points: doubles (24 bytes of coordinates per point against 8 of value) best at 1, floats at 3. */
#define REAL double
#define R(fn) fn##_f64
#define FUSED_AHEAD 1
#include "noise/batch_impl.h"
#undef FUSED_AHEAD
#undef REAL
#undef R

#define REAL float
#define R(fn) fn##_f32
#define FUSED_AHEAD 3
#include "noise/batch_impl.h"
#undef FUSED_AHEAD
#undef REAL
#undef R
