/* noise/cellular_impl.h - cellular noise in one precision: the scalar reference that the vector kernels
 * of that precision equal bit for bit. Included per precision (and per target) by noise/cellular.c and
 * noise/cellular_simd.c with
 *   REAL   float or double
 *   R(f)   the name of function f there (f##_f32, f##_f64, f##_f64_fma, ...)
 *   RT(f)  the name of type f in that precision (f##_f32 or f##_f64; with CELLULAR_REUSE_TYPES defined,
 *          the types are already defined)
 *   RF(f)  the libm function f in that precision (floorf / floor, ...)
 * and, in the copy compiled for processors with FMA, CELLULAR_FMA_INSTRUCTION (its fused multiply-adds the
 * C library's fma, one instruction there; elsewhere core/fma.h's, rounded once whatever the C library).
 * A candidate feature point's distance is measured in the metric's "power" form (Euclidean: the sum of
 * squares, fused: fma(v2, v2, fma(v1, v1, v0 v0)); Minkowski: the sum of |v|^e; Manhattan and Chebyshev:
 * the distance), compared there, and turned into a distance at the end (a square root, a root). A cell's candidate vector on axis a is
 * v = fma(c1, b, c0 - (t - d)): t the point's exact offset in its own cell, d the cell's integer offset from
 * it, b the feature point's 8-bit offset, c1 = jitter / 256 and c0 = 1/2 - 127.5 c1, so that the feature
 * point sits at 1/2 + jitter ((b + 1/2) / 256 - 1/2) in its cell. Since rounding is monotone, v lies
 * between its values for b = 0 and 255 as computed: the bounds the search prunes with. */

#include "core/fma.h"

#if defined(CELLULAR_FMA_INSTRUCTION)
#define CELLULAR_FMA RF(fma)
#else
#define CELLULAR_FMA RF(udm1_fma)
#endif

/* The point's cell on one axis: its offset t in [0, 1) (exact) and its index wrapped to 0..P-1, P the
 * period (0: 256); a neighbour d cells away then has index (index + d) mod P, & 255. */
static inline REAL R(cell_axis)(REAL x, uint32_t period, uint32_t *index)
{
    REAL f = RF(floor)(x);
    REAL t = (x - f) + (REAL)0;
    uint32_t P = period ? period : 256u;
    double fd = (double)f, m;
    if (fabs(fd) < 0x1p31) { /* exact: q P and fd - q P are integers below 2^32; q may be one off */
        m = fd - floor(fd / P) * P;
        if (m < 0) m += P;
        if (m >= P) m -= P;
    } else {
        m = fmod(fd, (double)P); /* exact */
        if (m < 0) m += P;
    }
    *index = (uint32_t)m;
    return t;
}

static inline uint32_t R(wrap)(uint32_t index, int d, uint32_t P)
{
    int64_t v = (int64_t)index + d;
    if (UDM1_UNLIKELY(v < 0 || v >= (int64_t)P)) { /* (a division only where the neighbour wraps) */
        v %= (int64_t)P;
        if (v < 0) v += P;
    }
    return (uint32_t)v & 255u;
}

/* |v| in the metric's power form, summed over the axes */
static inline REAL R(power_sum)(const REAL *v, uint32_t dims, uint32_t metric, REAL e)
{
    REAL s = 0;
    switch (metric) {
    case UDM1_CELLULAR_EUCLIDEAN: /* fused: one rounding per term */
        s = CELLULAR_FMA(v[1], v[1], v[0] * v[0]);
        if (dims == 3) s = CELLULAR_FMA(v[2], v[2], s);
        return s;
    case UDM1_CELLULAR_MANHATTAN:
        s = RF(fabs)(v[0]) + RF(fabs)(v[1]);
        if (dims == 3) s = s + RF(fabs)(v[2]);
        return s;
    case UDM1_CELLULAR_CHEBYSHEV:
        s = RF(fmax)(RF(fabs)(v[0]), RF(fabs)(v[1]));
        if (dims == 3) s = RF(fmax)(s, RF(fabs)(v[2]));
        return s;
    default:
        s = RF(pow)(RF(fabs)(v[0]), e) + RF(pow)(RF(fabs)(v[1]), e);
        if (dims == 3) s = s + RF(pow)(RF(fabs)(v[2]), e);
        return s;
    }
}

static inline REAL R(power_root)(REAL s, uint32_t metric, REAL e)
{
    switch (metric) {
    case UDM1_CELLULAR_EUCLIDEAN: return RF(sqrt)(s);
    case UDM1_CELLULAR_MINKOWSKI: return RF(pow)(s, (REAL)1 / e);
    default: return s;
    }
}

/* Whether a candidate with power-sum lower bound lb can still change the k nearest (F[k-1] the k-th):
 * with a margin of 2^-20 of F[k-1], so that rounding of either can never drop a nearer point. */
static inline int R(may_matter)(REAL lb, REAL worst) { return !(lb > worst + worst * (REAL)0x1p-20); }

#ifndef CELLULAR_REUSE_TYPES
/* The state of a search: the k smallest power sums so far, and the nearest point's entry */
typedef struct {
    REAL F[3];
    int nearest;    /* its entry */
    int offset[3];  /* its cell, from the point's */
} RT(nearest3);

#endif

/* Offer a candidate: the nearest is the smallest (D, h); F the k smallest D (as the vector kernels'
 * min/max network). */
static inline void R(offer)(RT(nearest3) *s, int k, REAL D, int h, const int d[3])
{
    /* without branches (a search's comparisons are unpredictable): selects and min/max */
    const int better = (D < s->F[0]) | ((D == s->F[0]) & (h < s->nearest));
    s->nearest = better ? h : s->nearest;
    s->offset[0] = better ? d[0] : s->offset[0];
    s->offset[1] = better ? d[1] : s->offset[1];
    s->offset[2] = better ? d[2] : s->offset[2];
    REAL t = D;
    for (int i = 0; i < k; ++i) {
        REAL lo = s->F[i] < t ? s->F[i] : t, hi = s->F[i] < t ? t : s->F[i];
        s->F[i] = lo;
        t = hi;
    }
}

#ifndef CELLULAR_REUSE_TYPES
typedef struct {
    uint32_t dims, metric, k, period[3];
    REAL e, c0, c1;
} RT(cellular_setup);

#endif

static inline void R(cellular_setup_init)(RT(cellular_setup) *u, const udm1_noise *n, uint32_t dims, uint32_t metric,
                                   uint32_t k, double jitter, double exponent)
{
    u->dims = dims, u->metric = metric, u->k = k;
    for (int a = 0; a < 3; ++a) u->period[a] = n->period[a];
    u->e = (REAL)exponent;
    u->c1 = (REAL)jitter * (REAL)(1.0 / 256); /* exact: a power of 2 */
    u->c0 = (REAL)0.5 - (REAL)127.5 * u->c1;
}

/* The gap on one axis between the point and the feature points of cells with K = c0 - (t - d) */
static inline REAL R(axis_gap)(const RT(cellular_setup) *u, REAL K)
{
    REAL top = CELLULAR_FMA(u->c1, (REAL)255, K);
    return K > 0 ? K : (top < 0 ? -top : 0);
}

/* The k (1..3) smallest power sums at point c (finite) into s. */
static void R(cellular_search)(const udm1_noise *n, const RT(cellular_setup) *u, const REAL *c, RT(nearest3) *out)
{
    RT(nearest3) local, *s = &local; /* in registers while it runs */
    const uint32_t dims = u->dims, k = u->k;
    REAL t[3] = {0, 0, 0};
    uint32_t idx[3] = {0, 0, 0}, P[3] = {256, 256, 256};
    for (uint32_t a = 0; a < dims; ++a) {
        t[a] = R(cell_axis)(c[a], u->period[a], &idx[a]);
        P[a] = u->period[a] ? u->period[a] : 256u;
    }
    s->F[0] = s->F[1] = s->F[2] = (REAL)INFINITY;
    s->nearest = 256;
    s->offset[0] = s->offset[1] = s->offset[2] = 0;
    /* the 3^dims cells around the point, all of them (pruning would cost more than it saves) */
    {
        int ix[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        REAL K[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        for (uint32_t a = 0; a < dims; ++a)
            for (int j = 0; j < 3; ++j) {
                ix[a][j] = (int)R(wrap)(idx[a], j - 1, P[a]);
                K[a][j] = u->c0 - (t[a] - (REAL)(j - 1));
            }
        const int zn = dims == 3 ? 3 : 1, cells = 9 * zn;
        int hs[27];
        REAL Ds[27];
        for (int jz = 0; jz < zn; ++jz) /* the hashes, then the distances, then the nearest: independent work first */
            for (int jy = 0; jy < 3; ++jy) {
                int hy = n->perm[ix[0][0]] + ix[1][jy], hy1 = n->perm[ix[0][1]] + ix[1][jy], hy2 = n->perm[ix[0][2]] + ix[1][jy];
                int *o = hs + 9 * jz + 3 * jy;
                o[0] = n->perm[hy], o[1] = n->perm[hy1], o[2] = n->perm[hy2];
                if (dims == 3) o[0] = n->perm[o[0] + ix[2][jz]], o[1] = n->perm[o[1] + ix[2][jz]], o[2] = n->perm[o[2] + ix[2][jz]];
            }
        for (int cc = 0; cc < cells; ++cc) {
            const int h = hs[cc], jx = cc % 3, jy = cc / 3 % 3, jz = cc / 9;
            REAL v[3] = {CELLULAR_FMA(u->c1, (REAL)n->feature[0][h], K[0][jx]),
                         CELLULAR_FMA(u->c1, (REAL)n->feature[1][h], K[1][jy]), 0};
            if (dims == 3) v[2] = CELLULAR_FMA(u->c1, (REAL)n->feature[2][h], K[2][jz]);
            Ds[cc] = R(power_sum)(v, dims, u->metric, u->e);
        }
        for (int cc = 0; cc < cells; ++cc) {
            const int d[3] = {cc % 3 - 1, cc / 3 % 3 - 1, dims == 3 ? cc / 9 - 1 : 0};
            R(offer)(s, (int)k, Ds[cc], hs[cc], d);
        }
    }
    for (int r = 1;; ++r) {
        /* the nearest possible point of the shell beyond r: one axis' gap to it */
        REAL gap = (REAL)INFINITY;
        for (uint32_t a = 0; a < dims; ++a) {
            REAL below = R(axis_gap)(u, u->c0 - (t[a] - (REAL)(r + 1))), above = R(axis_gap)(u, u->c0 - (t[a] + (REAL)(r + 1)));
            if (below < gap) gap = below;
            if (above < gap) gap = above;
        }
        REAL g[3] = {gap, 0, 0};
        if (!R(may_matter)(R(power_sum)(g, dims, u->metric, u->e), s->F[k - 1])) break;
        if (r > 64) break; /* unreachable: a shell's gap grows by 1 each time */
        const int q = r + 1, zr = dims == 3 ? q : 0; /* the shell of radius q, its cells pruned by their gaps */
        for (int dz = -zr; dz <= zr; ++dz)
            for (int dy = -q; dy <= q; ++dy)
                for (int dx = -q; dx <= q; ++dx) {
                    int m = abs(dx) > abs(dy) ? abs(dx) : abs(dy);
                    if (abs(dz) > m) m = abs(dz);
                    if (m != q) continue;
                    const int d[3] = {dx, dy, dz};
                    REAL K[3] = {0, 0, 0}, gg[3] = {0, 0, 0};
                    for (uint32_t a = 0; a < dims; ++a) {
                        K[a] = u->c0 - (t[a] - (REAL)d[a]);
                        gg[a] = R(axis_gap)(u, K[a]);
                    }
                    if (!R(may_matter)(R(power_sum)(gg, dims, u->metric, u->e), s->F[k - 1])) continue;
                    int h = dims == 3 ? n->perm[n->perm[n->perm[R(wrap)(idx[0], dx, P[0])] + R(wrap)(idx[1], dy, P[1])] +
                                                R(wrap)(idx[2], dz, P[2])]
                                      : n->perm[n->perm[R(wrap)(idx[0], dx, P[0])] + R(wrap)(idx[1], dy, P[1])];
                    REAL v[3] = {0, 0, 0};
                    for (uint32_t a = 0; a < dims; ++a) v[a] = CELLULAR_FMA(u->c1, (REAL)n->feature[a][h], K[a]);
                    R(offer)(s, (int)k, R(power_sum)(v, dims, u->metric, u->e), h, d);
                }
    }
    *out = local;
}

/* The output of a finished search */
static inline REAL R(cellular_output)(const RT(nearest3) *s, const RT(cellular_setup) *u, uint32_t output)
{
    switch (output) {
    case UDM1_CELLULAR_F1: return R(power_root)(s->F[0], u->metric, u->e);
    case UDM1_CELLULAR_F2: return R(power_root)(s->F[1], u->metric, u->e);
    case UDM1_CELLULAR_F3: return R(power_root)(s->F[2], u->metric, u->e);
    case UDM1_CELLULAR_F2_MINUS_F1:
        return R(power_root)(s->F[1], u->metric, u->e) - R(power_root)(s->F[0], u->metric, u->e);
    default: return (REAL)s->nearest / (REAL)255;
    }
}
#undef CELLULAR_FMA
