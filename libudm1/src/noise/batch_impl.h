/* noise/batch_impl.h - a lattice noise batch in one precision, all or nothing (noise/batch.c). Included
 * once per precision by noise/batch.c with
 *   REAL   float or double
 *   R(f)   the name of f in that precision (f##_f32 or f##_f64) */

/* Points [from, from + count) of the batch into value[0 .. count) and gradient[0 .. dims count) (either
 * may be NULL): the vector kernel, checking side beside them, then the scalar code for the points it left
 * (its groups end there, or it stopped before a group with a non-finite coordinate: the caller must have
 * checked those). How many the kernel computed. */
static size_t R(evaluate)(const udm1_noise *n, uint32_t dims, const REAL *const *axes, size_t stride, size_t from,
                          size_t count, REAL *value, REAL *gradient, udm1_side_check *side, int tail)
{
    const REAL *at[4] = {NULL, NULL, NULL, NULL};
    for (uint32_t c = 0; c < dims; ++c) at[c] = axes[c] + from * stride;
    size_t done = R(udm1_noise_eval_fast)(n, dims, at, stride, count, value, gradient, side);
    for (size_t i = done; tail && i < count; ++i) {
        REAL c[4];
        for (uint32_t k = 0; k < dims; ++k) c[k] = at[k][i * stride];
        REAL v = R(udm1_lattice)(n, dims, c, gradient ? gradient + i * dims : NULL);
        if (value) value[i] = v;
    }
    return done;
}

/* The check of points [from, count) beside a kernel that runs `iterations` iterations: the runs that hold
 * their coordinates (one per axis of stride 1, or one for axes in one array whose stride is at most 4 per
 * coordinate), read evenly over the iterations; in ends, each run's end. 0 for another layout. */
static int R(side_runs)(uint32_t dims, const REAL *const *axes, size_t stride, size_t from, size_t count,
                        size_t iterations, udm1_side_check *side, const REAL **ends)
{
    int packed = stride >= dims && stride <= 4 * (size_t)dims;
    for (uint32_t c = 1; packed && c < dims; ++c) packed = axes[c] == axes[0] + c;
    size_t len; /* elements per run */
    if (packed) {
        side->runs = 1;
        side->at[0] = (const char *)(axes[0] + from * stride);
        len = (count - 1 - from) * stride + dims;
    } else if (stride == 1) {
        side->runs = dims;
        for (uint32_t c = 0; c < dims; ++c) side->at[c] = (const char *)(axes[c] + from);
        len = count - from;
    } else {
        return 0;
    }
    for (unsigned r = 0; r < side->runs; ++r) ends[r] = (const REAL *)(const void *)side->at[r] + len;
    size_t bytes = len * sizeof(REAL), vectors = (bytes / 64 + iterations - 1) / iterations;
    side->vectors = (unsigned)(vectors ? vectors : 1);
    side->steps = bytes / (64 * (size_t)side->vectors); /* whole steps; the rest is read after the kernel */
    if (side->steps > iterations) side->steps = iterations;
    side->bad = 0;
    return 1;
}

udm1_status R(udm1_noise_batch)(const char *fn, const udm1_noise *n, uint32_t dims, const REAL *const *axes,
                                size_t stride, size_t count, REAL *value, REAL *gradient)
{
    size_t group = dims >= 2 ? R(udm1_noise_eval_group)(n, dims, axes, stride, value, gradient) : 0;
    size_t per_point = (value ? 1 : 0) + (gradient ? dims : 0); /* outputs per point */
    udm1_side_check side = {{NULL, NULL, NULL, NULL}, 0, 0, 0, 0};
    const REAL *ends[4];
    size_t first = 0; /* the points evaluated into scratch memory first */
    if (group && count >= FUSED_MIN_POINTS) { /* a first part, the others checked beside it */
        first = count / (FUSED_AHEAD + 1) / group * group;
        if (!R(side_runs)(dims, axes, stride, first, count, first / group, &side, ends)) first = 0;
    } else if (group && per_point < dims) { /* all of a small batch's groups: copying costs less than a check */
        first = count / group * group;
    }
    REAL local[SCRATCH_BYTES / sizeof(REAL)], *scratch = NULL; /* (a small batch's scratch: on the stack) */
    if (first)
        scratch = per_point * first <= sizeof local / sizeof(REAL) ? local : malloc(sizeof(REAL) * per_point * first);
    if (scratch) {
        /* the kernel checks the points it evaluates as it goes (it stops before a group that is not
         * finite), and the others beside them, or after it where they are few */
        REAL *v = value ? scratch : NULL, *g = gradient ? scratch + (value ? first : 0) : NULL;
        int bad = R(evaluate)(n, dims, axes, stride, 0, first, v, g, &side, 0) < first || side.bad;
        for (unsigned r = 0; !bad && r < side.runs; ++r) /* what the kernel's steps did not reach */
            bad = R(udm1_any_nonfinite)((const REAL *)(const void *)side.at[r],
                                        (size_t)(ends[r] - (const REAL *)(const void *)side.at[r]));
        if (!bad && !side.runs) {
            const REAL *rest[4] = {NULL, NULL, NULL, NULL};
            for (uint32_t c = 0; c < dims; ++c) rest[c] = axes[c] + first * stride;
            bad = R(udm1_first_nonfinite)(dims, rest, stride, count - first, NULL) < count - first;
        }
        if (!bad) { /* every coordinate finite: the first part copied, the rest evaluated in place */
            if (value) memcpy(value, v, sizeof(REAL) * first);
            if (gradient) memcpy(gradient, g, sizeof(REAL) * dims * first);
            R(evaluate)(n, dims, axes, stride, first, count - first, value ? value + first : NULL,
                        gradient ? gradient + dims * first : NULL, NULL, 1);
            if (scratch != local) free(scratch);
            return UDM1_OK;
        }
        if (scratch != local) free(scratch); /* below: the point named */
    }
    /* the whole input checked first, then evaluated in place: layouts and kinds the kernels do not take,
     * small batches with more outputs than coordinates (a check costs less than a copy), and a batch
     * refused (its first point not finite named) */
    uint32_t axis = 0;
    size_t bad = R(udm1_first_nonfinite)(dims, axes, stride, count, &axis);
    if (bad < count) return udm1_not_finite(fn, bad, axis);
    R(evaluate)(n, dims, axes, stride, 0, count, value, gradient, NULL, 1);
    return UDM1_OK;
}
