/* noise/lattice_impl.h - the lattice noises in one precision: the scalar reference that every vector
 * kernel of that precision equals bit for bit. Included once per precision by noise/lattice.c with
 *   REAL   float or double
 *   R(f)   the name of f in that precision (f##_f32 or f##_f64)
 *   RF(f)  the libm function f in that precision (floorf / floor, ...)
 *   ZERO_SIGN  nothing (double) or + 0.0f (float: the improved 3D gradient's zeros made +0)
 * Every value is computed with the same operations in the same order as udm1_noise_1d..3d always were:
 * the cell by an exact floor, the quintic (improved) or cubic (classic) fade, Perlin's gradients as
 * +-u +-v (a product by +-1 is exact), the nested lerps. The gradient is the derivative of that same
 * interpolation: the fades' derivatives times the differences of the corners' values, plus the
 * interpolated corners' gradient vectors; its value part is the value, bit for bit. */

/* Cell of x on one axis: the lattice indices of its two corners (wrapped by the period, then to
 * 0..255) and the offset t in [0, 1). Exact for every finite x: the floor and x - floor are exact, and
 * the index is taken from the floor exactly (fmod is exact; past 2^62 every value is a multiple of 256). */
static inline void R(cell)(REAL x, uint32_t period, int *i0, int *i1, REAL *t)
{
    REAL f = RF(floor)(x);
    *t = (x - f) + (REAL)0; /* exact; + 0 turns the -0 of x = -0 into +0, as Perlin's x - floor(x) */
    if (UDM1_UNLIKELY(period)) {
        double m = fmod((double)f, (double)period); /* exact (in double: a period need not be a float) */
        if (m < 0) m += period;
        uint32_t a = (uint32_t)m, b = a + 1 == period ? 0 : a + 1;
        *i0 = (int)(a & 255u);
        *i1 = (int)(b & 255u);
    } else {
        REAL m = RF(fabs)(f) < (REAL)0x1p62 ? f : RF(fmod)(f, (REAL)256);
        int a = (int)((int64_t)m & 255);
        *i0 = a;
        *i1 = (a + 1) & 255;
    }
}

static inline REAL R(fade5)(REAL t) { return t * t * t * (t * (t * 6 - 15) + 10); }
static inline REAL R(dfade5)(REAL t) { return 30 * t * t * (t * (t - 2) + 1); } /* 30 t^2 (t - 1)^2 */
static inline REAL R(fade3)(REAL t) { return t * t * (3 - 2 * t); }
static inline REAL R(dfade3)(REAL t) { return 6 * t * (1 - t); }
static inline REAL R(lerp)(REAL t, REAL a, REAL b) { return a + t * (b - a); }

/* A corner's gradient vector g (its dot product with the offset is the corner's value). Improved noise:
 * Perlin's +-u +-v, as the two coordinates it picks and their signs; classic: the table's vector. */
static inline REAL R(corner3)(const udm1_noise *n, int h, REAL x, REAL y, REAL z, REAL g[3])
{
    if (n->kind == UDM1_NOISE_IMPROVED) {
        const REAL c[3] = {x, y, z};
        const udm1_pick *k = &n->pick3[h];
        g[0] = g[1] = g[2] = 0;
        g[k->iu] = (REAL)k->su, g[k->iv] = (REAL)k->sv;
        /* (float: + 0 makes a zero +0, so that the vector kernels may take the dot product with the edge
         * vector instead: the same bits; double keeps Perlin's signed zeros) */
        return (REAL)k->su * c[k->iu] + (REAL)k->sv * c[k->iv] ZERO_SIGN;
    }
    g[0] = (REAL)n->g3[h][0], g[1] = (REAL)n->g3[h][1], g[2] = (REAL)n->g3[h][2];
    return g[0] * x + g[1] * y + g[2] * z;
}

static inline REAL R(corner2)(const udm1_noise *n, int h, REAL x, REAL y, REAL g[2])
{
    if (n->kind == UDM1_NOISE_IMPROVED) { /* noise1234: +-u +-2v, u = x (h & 7 < 4) or y */
        const REAL c[2] = {x, y};
        const udm1_pick *k = &n->pick2[h];
        g[0] = g[1] = 0;
        g[k->iu] = (REAL)k->su, g[k->iv] = (REAL)k->sv;
        return (REAL)k->su * c[k->iu] + (REAL)k->sv * c[k->iv];
    }
    g[0] = (REAL)n->g2[h][0], g[1] = (REAL)n->g2[h][1];
    return g[0] * x + g[1] * y;
}

/* noise1234's 4D gradient (Gustavson): the 32 vectors with three components +-1 and one 0, by h & 31:
 * u = x (h < 24) or y, v = y (h < 16) or z, w = z (h < 8) or t; +-u +-v +-w */
static inline REAL R(corner4)(int h, REAL x, REAL y, REAL z, REAL t, REAL g[4])
{
    h &= 31;
    const REAL c[4] = {x, y, z, t};
    int iu = h < 24 ? 0 : 1, iv = h < 16 ? 1 : 2, iw = h < 8 ? 2 : 3;
    REAL su = (h & 1) ? -1 : 1, sv = (h & 2) ? -1 : 1, sw = (h & 4) ? -1 : 1;
    g[0] = g[1] = g[2] = g[3] = 0;
    g[iu] = su, g[iv] = sv, g[iw] = sw;
    return su * c[iu] + sv * c[iv] + sw * c[iw];
}

/* 1D: noise1234's gradients +-(1..8) (improved) or the table's x (classic), scaled to about [-1, 1] */
static REAL R(noise1)(const udm1_noise *n, REAL x, REAL *grad)
{
    int X0, X1;
    R(cell)(x, n->period[0], &X0, &X1, &x);
    int classic = n->kind == UDM1_NOISE_CLASSIC;
    REAL u = classic ? R(fade3)(x) : R(fade5)(x);
    REAL scale = classic ? (REAL)1.0 : (REAL)0.188; /* noise1234's range scale */
    REAL ga = (REAL)n->g1[n->perm[X0]], gb = (REAL)n->g1[n->perm[X1]];
    REAL a = ga * x, b = gb * (x - 1);
    if (grad) {
        REAL du = classic ? R(dfade3)(x) : R(dfade5)(x);
        *grad = scale * (du * (b - a) + R(lerp)(u, ga, gb));
    }
    return scale * R(lerp)(u, a, b);
}

static REAL R(noise2)(const udm1_noise *n, REAL x, REAL y, REAL *grad)
{
    int X0, X1, Y0, Y1;
    R(cell)(x, n->period[0], &X0, &X1, &x);
    R(cell)(y, n->period[1], &Y0, &Y1, &y);
    int classic = n->kind == UDM1_NOISE_CLASSIC;
    REAL u = classic ? R(fade3)(x) : R(fade5)(x), v = classic ? R(fade3)(y) : R(fade5)(y);
    const uint8_t *p = n->perm;
    REAL scale = classic ? (REAL)1.0 : (REAL)0.507; /* noise1234's range scale */
    REAL g00[2], g10[2], g01[2], g11[2];
    REAL a = R(corner2)(n, p[p[X0] + Y0], x, y, g00), b = R(corner2)(n, p[p[X1] + Y0], x - 1, y, g10);
    REAL c = R(corner2)(n, p[p[X0] + Y1], x, y - 1, g01), d = R(corner2)(n, p[p[X1] + Y1], x - 1, y - 1, g11);
    if (grad) {
        REAL du = classic ? R(dfade3)(x) : R(dfade5)(x), dv = classic ? R(dfade3)(y) : R(dfade5)(y);
        for (int k = 0; k < 2; ++k)
            grad[k] = R(lerp)(v, R(lerp)(u, g00[k], g10[k]), R(lerp)(u, g01[k], g11[k]));
        grad[0] = scale * (du * R(lerp)(v, b - a, d - c) + grad[0]);
        grad[1] = scale * (dv * R(lerp)(u, c - a, d - b) + grad[1]);
    }
    return scale * R(lerp)(v, R(lerp)(u, a, b), R(lerp)(u, c, d));
}

static REAL R(noise3)(const udm1_noise *n, REAL x, REAL y, REAL z, REAL *grad)
{
    int X0, X1, Y0, Y1, Z0, Z1;
    R(cell)(x, n->period[0], &X0, &X1, &x);
    R(cell)(y, n->period[1], &Y0, &Y1, &y);
    R(cell)(z, n->period[2], &Z0, &Z1, &z);
    int classic = n->kind == UDM1_NOISE_CLASSIC;
    REAL u, v, w;
    if (classic) {
        u = R(fade3)(x), v = R(fade3)(y), w = R(fade3)(z);
    } else {
        u = R(fade5)(x), v = R(fade5)(y), w = R(fade5)(z);
    }
    const uint8_t *p = n->perm;
    int A = p[X0] + Y0, B = p[X1] + Y0, A1 = p[X0] + Y1, B1 = p[X1] + Y1;
    int AA = p[A] + Z0, AB = p[A1] + Z0, BA = p[B] + Z0, BB = p[B1] + Z0;
    int AA1 = p[A] + Z1, AB1 = p[A1] + Z1, BA1 = p[B] + Z1, BB1 = p[B1] + Z1;
    REAL G[8][3];
    REAL c000 = R(corner3)(n, p[AA], x, y, z, G[0]), c100 = R(corner3)(n, p[BA], x - 1, y, z, G[1]);
    REAL c010 = R(corner3)(n, p[AB], x, y - 1, z, G[2]), c110 = R(corner3)(n, p[BB], x - 1, y - 1, z, G[3]);
    REAL c001 = R(corner3)(n, p[AA1], x, y, z - 1, G[4]), c101 = R(corner3)(n, p[BA1], x - 1, y, z - 1, G[5]);
    REAL c011 = R(corner3)(n, p[AB1], x, y - 1, z - 1, G[6]);
    REAL c111 = R(corner3)(n, p[BB1], x - 1, y - 1, z - 1, G[7]);
    if (grad) {
        REAL du = classic ? R(dfade3)(x) : R(dfade5)(x), dv = classic ? R(dfade3)(y) : R(dfade5)(y);
        REAL dw = classic ? R(dfade3)(z) : R(dfade5)(z);
        for (int k = 0; k < 3; ++k)
            grad[k] = R(lerp)(w, R(lerp)(v, R(lerp)(u, G[0][k], G[1][k]), R(lerp)(u, G[2][k], G[3][k])),
                              R(lerp)(v, R(lerp)(u, G[4][k], G[5][k]), R(lerp)(u, G[6][k], G[7][k])));
        /* the corners' values as n = k0 + k1 u + k2 v + k3 w + k4 uv + k5 vw + k6 uw + k7 uvw, then each
         * partial derivative in u, v, w of that polynomial */
        REAL k1 = c100 - c000, k2 = c010 - c000, k3 = c001 - c000;
        REAL k4 = (c110 - c010) - k1, k5 = (c011 - c001) - k2, k6 = (c101 - c001) - k1;
        REAL k7 = ((c111 - c011) - (c101 - c001)) - k4;
        REAL k67 = k6 + k7 * v;
        grad[0] += du * ((k1 + k4 * v) + k67 * w);
        grad[1] += dv * ((k2 + k4 * u) + (k5 + k7 * u) * w);
        grad[2] += dw * ((k3 + k5 * v) + k67 * u);
    }
    return R(lerp)(w, R(lerp)(v, R(lerp)(u, c000, c100), R(lerp)(u, c010, c110)),
                   R(lerp)(v, R(lerp)(u, c001, c101), R(lerp)(u, c011, c111)));
}

/* 4D improved noise: the hash perm[perm[perm[perm[X] + Y] + Z] + W] of each of the 16 corners (the
 * permutation stored twice, as Perlin's), noise1234's gradients, the quintic fade; scaled by 0.87
 * (noise1234's) to about [-1, 1]. */
static REAL R(noise4)(const udm1_noise *n, REAL x, REAL y, REAL z, REAL t, REAL *grad)
{
    int X[2], Y[2], Z[2], W[2];
    R(cell)(x, n->period[0], &X[0], &X[1], &x);
    R(cell)(y, n->period[1], &Y[0], &Y[1], &y);
    R(cell)(z, n->period[2], &Z[0], &Z[1], &z);
    R(cell)(t, n->period_w, &W[0], &W[1], &t);
    REAL f[4] = {R(fade5)(x), R(fade5)(y), R(fade5)(z), R(fade5)(t)};
    const uint8_t *p = n->perm;
    REAL c[16], G[16][4];
    for (int k = 0; k < 16; ++k) { /* corner k: bit 0 x, bit 1 y, bit 2 z, bit 3 w */
        int a = k & 1, b = k >> 1 & 1, d = k >> 2 & 1, e = k >> 3 & 1;
        int h = p[p[p[p[X[a]] + Y[b]] + Z[d]] + W[e]];
        c[k] = R(corner4)(h, x - a, y - b, z - d, t - e, G[k]);
    }
    /* the nested lerps: x, then y, then z, then w */
    REAL l1[8], l2[4], l3[2];
    for (int k = 0; k < 8; ++k) l1[k] = R(lerp)(f[0], c[2 * k], c[2 * k + 1]);
    for (int k = 0; k < 4; ++k) l2[k] = R(lerp)(f[1], l1[2 * k], l1[2 * k + 1]);
    for (int k = 0; k < 2; ++k) l3[k] = R(lerp)(f[2], l2[2 * k], l2[2 * k + 1]);
    const REAL scale = (REAL)0.87;
    if (grad) {
        REAL s[4];
        for (int axis = 0; axis < 4; ++axis) {
            /* the interpolated gradient vectors, and the fade's derivative times the interpolated
             * differences along this axis (the other axes' fades weigh them) */
            REAL gv[16], dv[16];
            int m = 16;
            for (int k = 0; k < 16; ++k) gv[k] = G[k][axis];
            for (int k = 0; k < 16; ++k) dv[k] = c[k];
            for (int ax = 0; ax < 4; ++ax) {
                for (int k = 0; k < m / 2; ++k) {
                    gv[k] = R(lerp)(f[ax], gv[2 * k], gv[2 * k + 1]);
                    dv[k] = ax == axis ? dv[2 * k + 1] - dv[2 * k] : R(lerp)(f[ax], dv[2 * k], dv[2 * k + 1]);
                }
                m /= 2;
            }
            s[axis] = gv[0] + R(dfade5)(axis == 0 ? x : axis == 1 ? y : axis == 2 ? z : t) * dv[0];
        }
        for (int axis = 0; axis < 4; ++axis) grad[axis] = scale * s[axis];
    }
    return scale * R(lerp)(f[3], l3[0], l3[1]);
}
