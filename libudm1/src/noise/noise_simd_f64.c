/* noise_simd_f64.c - the double noise of udm1_noise_eval and udm1_noise_points on 16 points at a time with
 * AVX-512 and VBMI: the hashes of 16 points in one register (the permutation held in four registers,
 * looked up 64 bytes at a time, a point's four hashes of a step in the bytes of its lane, as the float
 * kernel), the arithmetic in two registers of 8 doubles. Its operations are the scalar double code's in
 * the same order (noise/lattice_impl.h): the exact floor and offset, the quintic fade, the nested lerps,
 * and for the gradient the same derivative; a 3D corner's +-u +-v is the dot product with Perlin's edge
 * vector, fma(gx, x, fma(gy, y, gz z)) with the edges looked up in registers: with one component 0 and
 * two +-1 that is the one rounding of +-u +-v, the same value unless it is zero, when its sign may
 * differ. A zero's sign changes no non-zero result of sums, differences and products, so only a value or
 * gradient component that is itself zero may differ: those points are recomputed by the scalar code.
 * So every value equals udm1_noise_1d..3d bit for bit, signed zeros included (tests/c/test_noise.c,
 * test_noise_eval.c). Improved noise in 2D and 3D, not periodic, any layout of the coordinates.
 * Without AVX-512 VBMI, an AVX2 + FMA kernel on 8 points at a time (below: gathers from the combined
 * tables, Perlin's 3D +-u +-v as a dot product whose zero components are zeros of the sign that keeps
 * the scalar code's signed zeros, noise1234's 2D as blends and sign flips). The rest (1D,
 * 4D, classic, periodic) goes to the scalar code. */
#include "core/isa.h"
#include "noise/noise_tables.h"

#include <math.h>

#if defined(UDM1_HAVE_ISA_KERNELS)
#include <immintrin.h>

#include "noise/byte_table.h"
#include "noise/side_check.h"
#include "noise/strided_loads.h"

#define AVX512 __attribute__((target("avx512f,avx512vl,avx512dq,avx512bw,avx512vbmi")))



AVX512 static inline __mmask8 not_finite8(__m512d x) { return _mm512_fpclass_pd_mask(x, 0x01 | 0x08 | 0x10 | 0x80); }

/* floor and the offset in the cell (exact), and the lower corner's index, of which the hashes read the
 * low byte (the index mod 256): the conversion is exact below 2^63 and gives 0x8000000000000000 above
 * (a multiple of 256 there, as every double past 2^60) */
AVX512 static inline __m512d axis8(__m512d x, __m256i *i0)
{
    __m512d f = _mm512_roundscale_pd(x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    *i0 = _mm512_cvtepi64_epi32(_mm512_cvttpd_epi64(f));
    return _mm512_add_pd(_mm512_sub_pd(x, f), _mm512_setzero_pd());
}

AVX512 static inline __m512i join16(__m256i lo, __m256i hi)
{
    return _mm512_inserti64x4(_mm512_castsi256_si512(lo), hi, 1);
}

AVX512 static inline __m512d fade8(__m512d t)
{
    __m512d a = _mm512_mul_pd(_mm512_mul_pd(t, t), t);
    __m512d b = _mm512_sub_pd(_mm512_mul_pd(t, _mm512_set1_pd(6.0)), _mm512_set1_pd(15.0));
    b = _mm512_add_pd(_mm512_mul_pd(t, b), _mm512_set1_pd(10.0));
    return _mm512_mul_pd(a, b);
}

AVX512 static inline __m512d dfade8(__m512d t) /* 30 t t (t (t - 2) + 1) */
{
    __m512d a = _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(30.0), t), t);
    __m512d b = _mm512_add_pd(_mm512_mul_pd(t, _mm512_sub_pd(t, _mm512_set1_pd(2.0))), _mm512_set1_pd(1.0));
    return _mm512_mul_pd(a, b);
}

AVX512 static inline __m512d lerp8(__m512d t, __m512d a, __m512d b)
{
    return _mm512_add_pd(a, _mm512_mul_pd(t, _mm512_sub_pd(b, a)));
}

/* Perlin's 16 edge directions by hash & 15, each component's 16 values in two registers */
typedef struct {
    __m512d lo[3], hi[3];
} edges16;

/* A corner's gradient g (its hash in byte k of each 64-bit lane of W) and its value g . (x, y, z) =
 * fma(gx, x, fma(gy, y, gz z)): with one component 0 and two +-1, one rounding of +-u +-v, so Perlin's
 * value whenever it is not zero (a zero's sign may differ: the caller redoes such points) */
AVX512 static inline __m512d dot8(const edges16 *E, __m512i W, const int k, __m512d x, __m512d y, __m512d z,
                                  __m512d g[3])
{
    __m512i idx = k ? _mm512_srli_epi64(W, 8 * k) : W; /* (permutex2var reads the low 4 bits) */
    for (int c = 0; c < 3; ++c) g[c] = _mm512_permutex2var_pd(E->lo[c], idx, E->hi[c]);
    return _mm512_fmadd_pd(g[0], x, _mm512_fmadd_pd(g[1], y, _mm512_mul_pd(g[2], z)));
}

/* noise1234's 2D: u = x (h & 7 < 4) or y, v the other; +-u +-2v */
AVX512 static inline __m512d corner2_8(__m512i H, const int k, const int h, __m512d x, __m512d y)
{
    const int s = 8 * k;
    __mmask8 below4 = (__mmask8)(_mm512_testn_epi32_mask(H, _mm512_set1_epi32(4 << s)) >> (8 * h));
    __m512d sign = _mm512_set1_pd(-0.0);
    __m512d u = _mm512_mask_blend_pd(below4, y, x);
    __m512d v = _mm512_mul_pd(_mm512_set1_pd(2.0), _mm512_mask_blend_pd(below4, x, y));
    u = _mm512_mask_xor_pd(u, (__mmask8)(_mm512_test_epi32_mask(H, _mm512_set1_epi32(1 << s)) >> (8 * h)), u, sign);
    v = _mm512_mask_xor_pd(v, (__mmask8)(_mm512_test_epi32_mask(H, _mm512_set1_epi32(2 << s)) >> (8 * h)), v, sign);
    return _mm512_add_pd(u, v);
}

AVX512 static inline void gvec2_8(__m512i H, const int k, const int h, __m512d g[2])
{
    const int s = 8 * k;
    __mmask8 below4 = (__mmask8)(_mm512_testn_epi32_mask(H, _mm512_set1_epi32(4 << s)) >> (8 * h));
    __m512d one = _mm512_set1_pd(1.0), two = _mm512_set1_pd(2.0), sign = _mm512_set1_pd(-0.0);
    __m512d su = _mm512_mask_xor_pd(one, (__mmask8)(_mm512_test_epi32_mask(H, _mm512_set1_epi32(1 << s)) >> (8 * h)), one, sign);
    __m512d sv = _mm512_mask_xor_pd(two, (__mmask8)(_mm512_test_epi32_mask(H, _mm512_set1_epi32(2 << s)) >> (8 * h)), two, sign);
    g[0] = _mm512_mask_blend_pd(below4, sv, su);
    g[1] = _mm512_mask_blend_pd(below4, su, sv);
}

/* g[0..k-1] (8 lanes each) into out[k j + c] */
AVX512 static inline void store_interleaved8(double *out, const __m512d *g, int k)
{
    double tmp[3][8];
    for (int c = 0; c < k; ++c) _mm512_storeu_pd(tmp[c], g[c]);
    for (int j = 0; j < 8; ++j)
        for (int c = 0; c < k; ++c) out[k * j + c] = tmp[c][j];
}

/* The hashes of 16 points: [h000, h010, h100, h110] and [h001, h011, h101, h111] (3D), or [h00, h01, h10,
 * h11] (2D, H1 not made), from the lower corners' indices */
AVX512 static inline void hashes(const byte_table *T, __m512i X0, __m512i Y0, __m512i Z0, int dims, __m512i *H0,
                                 __m512i *H1)
{
    /* in bytes (mod 256, as the doubled table): [p[X0], p[X0], p[X1], p[X1]] with X1 = X0 + 1, then
     * [A, A1, B, B1] = [p[X0] + Y0, p[X0] + Y1, p[X1] + Y0, p[X1] + Y1] looked up, then plus Z0, Z0 + 1 */
    __m512i px = byte_table_lookup(T, _mm512_add_epi8(byte_table_spread4(X0), _mm512_set1_epi32(0x01010000)));
    __m512i ab = byte_table_lookup(T, _mm512_add_epi8(px, _mm512_add_epi8(byte_table_spread4(Y0), _mm512_set1_epi32(0x01000100))));
    if (dims == 2) {
        *H0 = ab;
        return;
    }
    __m512i z0 = _mm512_add_epi8(ab, byte_table_spread4(Z0));
    *H0 = byte_table_lookup(T, z0);
    *H1 = byte_table_lookup(T, _mm512_add_epi8(z0, _mm512_set1_epi8(1)));
}

/* One half (8 points) of a 3D group, the hashes W0 = [h000, h010, h100, h110], W1 = [h001, h011, h101,
 * h111] in the bytes of 64-bit lanes: values into value[0..7] and gradients into gradient[0..23]; the
 * mask of the lanes whose value or a gradient component is zero (their sign is the scalar code's job) */
AVX512 static inline __attribute__((always_inline)) __mmask8 half3(const edges16 *E, __m512i W0, __m512i W1,
                                                                    __m512d x, __m512d y, __m512d z, double *value,
                                                                    double *gradient, const int with_gradient)
{
    const __m512d one = _mm512_set1_pd(1.0), zero = _mm512_setzero_pd();
    __m512d x1 = _mm512_sub_pd(x, one), y1 = _mm512_sub_pd(y, one), z1 = _mm512_sub_pd(z, one);
    __m512d u = fade8(x), v = fade8(y), w = fade8(z);
    __m512d G[8][3];
    __m512d c000 = dot8(E, W0, 0, x, y, z, G[0]), c100 = dot8(E, W0, 2, x1, y, z, G[1]);
    __m512d c010 = dot8(E, W0, 1, x, y1, z, G[2]), c110 = dot8(E, W0, 3, x1, y1, z, G[3]);
    __m512d c001 = dot8(E, W1, 0, x, y, z1, G[4]), c101 = dot8(E, W1, 2, x1, y, z1, G[5]);
    __m512d c011 = dot8(E, W1, 1, x, y1, z1, G[6]), c111 = dot8(E, W1, 3, x1, y1, z1, G[7]);
    __m512d val = lerp8(w, lerp8(v, lerp8(u, c000, c100), lerp8(u, c010, c110)),
                        lerp8(v, lerp8(u, c001, c101), lerp8(u, c011, c111)));
    __mmask8 zeros = _mm512_cmp_pd_mask(val, zero, _CMP_EQ_OQ);
    if (value) _mm512_storeu_pd(value, val);
    if (with_gradient) {
        __m512d g[3];
        for (int k = 0; k < 3; ++k)
            g[k] = lerp8(w, lerp8(v, lerp8(u, G[0][k], G[1][k]), lerp8(u, G[2][k], G[3][k])),
                         lerp8(v, lerp8(u, G[4][k], G[5][k]), lerp8(u, G[6][k], G[7][k])));
        __m512d du = dfade8(x), dv = dfade8(y), dw = dfade8(z);
        __m512d k1 = _mm512_sub_pd(c100, c000), k2 = _mm512_sub_pd(c010, c000), k3 = _mm512_sub_pd(c001, c000);
        __m512d k4 = _mm512_sub_pd(_mm512_sub_pd(c110, c010), k1), k5 = _mm512_sub_pd(_mm512_sub_pd(c011, c001), k2);
        __m512d k6 = _mm512_sub_pd(_mm512_sub_pd(c101, c001), k1);
        __m512d k7 = _mm512_sub_pd(_mm512_sub_pd(_mm512_sub_pd(c111, c011), _mm512_sub_pd(c101, c001)), k4);
        __m512d k67 = _mm512_add_pd(k6, _mm512_mul_pd(k7, v));
        __m512d pu = _mm512_add_pd(_mm512_add_pd(k1, _mm512_mul_pd(k4, v)), _mm512_mul_pd(k67, w));
        __m512d pv = _mm512_add_pd(_mm512_add_pd(k2, _mm512_mul_pd(k4, u)), _mm512_mul_pd(_mm512_add_pd(k5, _mm512_mul_pd(k7, u)), w));
        __m512d pw = _mm512_add_pd(_mm512_add_pd(k3, _mm512_mul_pd(k5, v)), _mm512_mul_pd(k67, u));
        g[0] = _mm512_add_pd(g[0], _mm512_mul_pd(du, pu));
        g[1] = _mm512_add_pd(g[1], _mm512_mul_pd(dv, pv));
        g[2] = _mm512_add_pd(g[2], _mm512_mul_pd(dw, pw));
        for (int k = 0; k < 3; ++k) zeros |= _mm512_cmp_pd_mask(g[k], zero, _CMP_EQ_OQ);
        store_interleaved8(gradient, g, 3);
    }
    return zeros;
}

AVX512 static inline __attribute__((always_inline)) void half2(__m512i H, const int h, __m512d x, __m512d y,
                                                                double *value, double *gradient, const int with_gradient)
{
    const __m512d one = _mm512_set1_pd(1.0), scale = _mm512_set1_pd(0.507);
    __m512d x1 = _mm512_sub_pd(x, one), y1 = _mm512_sub_pd(y, one);
    __m512d u = fade8(x), v = fade8(y);
    __m512d a = corner2_8(H, 0, h, x, y), b = corner2_8(H, 2, h, x1, y), c = corner2_8(H, 1, h, x, y1);
    __m512d d = corner2_8(H, 3, h, x1, y1);
    if (value) _mm512_storeu_pd(value, _mm512_mul_pd(scale, lerp8(v, lerp8(u, a, b), lerp8(u, c, d))));
    if (with_gradient) {
        __m512d G[4][2], g[2];
        gvec2_8(H, 0, h, G[0]), gvec2_8(H, 2, h, G[1]), gvec2_8(H, 1, h, G[2]), gvec2_8(H, 3, h, G[3]);
        for (int k = 0; k < 2; ++k) g[k] = lerp8(v, lerp8(u, G[0][k], G[1][k]), lerp8(u, G[2][k], G[3][k]));
        __m512d du = dfade8(x), dv = dfade8(y);
        g[0] = _mm512_mul_pd(scale, _mm512_add_pd(_mm512_mul_pd(du, lerp8(v, _mm512_sub_pd(b, a), _mm512_sub_pd(d, c))), g[0]));
        g[1] = _mm512_mul_pd(scale, _mm512_add_pd(_mm512_mul_pd(dv, lerp8(u, _mm512_sub_pd(c, a), _mm512_sub_pd(d, b))), g[1]));
        store_interleaved8(gradient, g, 2);
    }
}

AVX512 static inline __attribute__((always_inline)) size_t kernel_f64(const udm1_noise *n, const uint32_t dims,
                                                                     const double *const *axes, size_t stride,
                                                                     size_t count, double *value, double *gradient,
                                                                     const int with_gradient, udm1_side_check *side)
{
    const byte_table T = byte_table_load(n->perm);
    edges16 E;
    for (int c = 0; c < 3; ++c) {
        double t[16];
        for (int h = 0; h < 16; ++h) t[h] = n->g3[h][c]; /* improved noise: EDGES[h & 15] */
        E.lo[c] = _mm512_loadu_pd(t), E.hi[c] = _mm512_loadu_pd(t + 8);
    }
    const strided_loads L = strided_loads_init(stride, 8);
    __m512d checked = _mm512_setzero_pd();
    size_t i = 0;
    for (; i + 16 <= count; i += 16) {
        checked = udm1_side_step512_pd(side, checked);
        __m512d c[3][2];
        __mmask8 bad = 0;
        for (uint32_t a = 0; a < dims; ++a)
            for (int h = 0; h < 2; ++h) {
                c[a][h] = strided_load8(&L, axes[a] + (i + 8 * h) * stride);
                bad |= not_finite8(c[a][h]);
            }
        if (bad) break; /* the caller reports it */
        __m256i idx[3][2] = {{_mm256_setzero_si256(), _mm256_setzero_si256()},
                             {_mm256_setzero_si256(), _mm256_setzero_si256()},
                             {_mm256_setzero_si256(), _mm256_setzero_si256()}};
        for (uint32_t a = 0; a < dims; ++a)
            for (int h = 0; h < 2; ++h) c[a][h] = axis8(c[a][h], &idx[a][h]);
        __m512i X0 = join16(idx[0][0], idx[0][1]), Y0 = join16(idx[1][0], idx[1][1]), H0, H1;
        __m512i Z0 = dims == 3 ? join16(idx[2][0], idx[2][1]) : X0;
        hashes(&T, X0, Y0, Z0, (int)dims, &H0, &H1);
        if (dims == 3) {
            for (int h = 0; h < 2; ++h) {
                __m512i W0 = _mm512_cvtepu32_epi64(h ? _mm512_extracti64x4_epi64(H0, 1) : _mm512_castsi512_si256(H0));
                __m512i W1 = _mm512_cvtepu32_epi64(h ? _mm512_extracti64x4_epi64(H1, 1) : _mm512_castsi512_si256(H1));
                __mmask8 redo = half3(&E, W0, W1, c[0][h], c[1][h], c[2][h], value ? value + i + 8 * h : NULL,
                                      with_gradient ? gradient + 3 * (i + 8 * h) : NULL, with_gradient);
                while (redo) { /* a zero: its sign as the scalar code gives it */
                    int l = __builtin_ctz(redo);
                    redo &= (__mmask8)(redo - 1);
                    size_t at = i + 8 * (size_t)h + (size_t)l;
                    double q[3] = {axes[0][at * stride], axes[1][at * stride], axes[2][at * stride]}, g[3];
                    double r = udm1_lattice_f64(n, 3, q, with_gradient ? g : NULL);
                    if (value) value[at] = r;
                    if (with_gradient)
                        for (int k = 0; k < 3; ++k) gradient[3 * at + k] = g[k];
                }
            }
        } else {
            for (int h = 0; h < 2; ++h)
                half2(H0, h, c[0][h], c[1][h], value ? value + i + 8 * h : NULL,
                      with_gradient ? gradient + 2 * (i + 8 * h) : NULL, with_gradient);
        }
    }
    udm1_side_end512_pd(side, checked);
    return i;
}

AVX512 static size_t noise_f64_avx512(const udm1_noise *n, uint32_t dims, const double *const *axes, size_t stride,
                                      size_t count, double *value, double *gradient, udm1_side_check *side)
{
    if (dims == 3)
        return gradient ? kernel_f64(n, 3, axes, stride, count, value, gradient, 1, side)
                        : kernel_f64(n, 3, axes, stride, count, value, NULL, 0, side);
    return gradient ? kernel_f64(n, 2, axes, stride, count, value, gradient, 1, side)
                    : kernel_f64(n, 2, axes, stride, count, value, NULL, 0, side);
}

/* ---- AVX2 + FMA: 8 points, the arithmetic in two halves of 4 doubles ----
 * The hashes of 8 points by gathers from the combined tables (noise_tables.h: hash4, a cell's four column
 * hashes in one word; pair, a column's hashes at z and z + 1), Perlin's 3D gradients by byte shuffles of
 * the hash and noise1234's 2D ones as blends and sign flips (the scalar double code's +-u +-v, signed
 * zeros included), the rest the scalar code's operations. */
#define AVX2 __attribute__((target("avx2,fma")))

AVX2 static inline __m256d load4d(const double *p, size_t stride, __m128i vindex)
{
    return stride == 1 ? _mm256_loadu_pd(p) : _mm256_i32gather_pd(p, vindex, 8);
}

AVX2 static inline int finite4d(__m256d x)
{
    __m256d ax = _mm256_andnot_pd(_mm256_set1_pd(-0.0), x);
    return _mm256_movemask_pd(_mm256_cmp_pd(ax, _mm256_set1_pd(INFINITY), _CMP_LT_OQ)) == 0xF;
}

/* the exact offset in the cell, and the lower corner's index mod 256 (f - 256 floor(f / 256): exact for
 * every finite floor f, as the scalar code's (int64_t)f & 255) */
AVX2 static inline __m256d axis4d(__m256d x, __m128i *i0)
{
    __m256d f = _mm256_floor_pd(x);
    __m256d m = _mm256_sub_pd(f, _mm256_mul_pd(_mm256_floor_pd(_mm256_mul_pd(f, _mm256_set1_pd(1.0 / 256))),
                                               _mm256_set1_pd(256.0)));
    *i0 = _mm256_cvttpd_epi32(m);
    return _mm256_add_pd(_mm256_sub_pd(x, f), _mm256_setzero_pd());
}

AVX2 static inline __m256d fade4d(__m256d t)
{
    __m256d a = _mm256_mul_pd(_mm256_mul_pd(t, t), t);
    __m256d b = _mm256_sub_pd(_mm256_mul_pd(t, _mm256_set1_pd(6.0)), _mm256_set1_pd(15.0));
    b = _mm256_add_pd(_mm256_mul_pd(t, b), _mm256_set1_pd(10.0));
    return _mm256_mul_pd(a, b);
}

AVX2 static inline __m256d dfade4d(__m256d t)
{
    __m256d a = _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(30.0), t), t);
    __m256d b = _mm256_add_pd(_mm256_mul_pd(t, _mm256_sub_pd(t, _mm256_set1_pd(2.0))), _mm256_set1_pd(1.0));
    return _mm256_mul_pd(a, b);
}

AVX2 static inline __m256d lerp4d(__m256d t, __m256d a, __m256d b)
{
    return _mm256_add_pd(a, _mm256_mul_pd(t, _mm256_sub_pd(b, a)));
}

AVX2 static inline __m256d mask4d(__m128i h, int bits, int equal) /* (h & bits) == equal, as a lane mask */
{
    __m128i m = _mm_cmpeq_epi32(_mm_and_si128(h, _mm_set1_epi32(bits)), _mm_set1_epi32(equal));
    return _mm256_castsi256_pd(_mm256_cvtepi32_epi64(m));
}

AVX2 static inline __m256d flip4d(__m256d v, __m128i h, int bit) /* negate the lanes where h & bit */
{
    return _mm256_xor_pd(v, _mm256_and_pd(mask4d(h, bit, bit), _mm256_set1_pd(-0.0)));
}

/* its vector: +-1 on the axes of u and v, +0 on the third */
AVX2 static inline void gvec3_4d(__m128i h, __m256d g[3])
{
    __m256d below8 = mask4d(h, 8, 0), below4 = mask4d(h, 12, 0), is12or14 = mask4d(h, 13, 12);
    __m256d one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd();
    __m256d su = flip4d(one, h, 1), sv = flip4d(one, h, 2);
    __m256d v_on_x = _mm256_andnot_pd(below4, is12or14);
    __m256d v_on_z = _mm256_andnot_pd(_mm256_or_pd(below4, is12or14), _mm256_castsi256_pd(_mm256_set1_epi64x(-1)));
    g[0] = _mm256_blendv_pd(_mm256_blendv_pd(zero, sv, v_on_x), su, below8);
    g[1] = _mm256_blendv_pd(su, _mm256_blendv_pd(zero, sv, below4), below8);
    g[2] = _mm256_blendv_pd(zero, sv, v_on_z);
}

/* noise1234's 2D: u = x (h & 7 < 4) or y, v the other; +-u +-2v */
AVX2 static inline __m256d grad2_4d(__m128i h, __m256d x, __m256d y)
{
    __m256d below4 = mask4d(h, 4, 0);
    __m256d u = _mm256_blendv_pd(y, x, below4);
    __m256d v = _mm256_mul_pd(_mm256_set1_pd(2.0), _mm256_blendv_pd(x, y, below4));
    return _mm256_add_pd(flip4d(u, h, 1), flip4d(v, h, 2));
}

AVX2 static inline void gvec2_4d(__m128i h, __m256d g[2])
{
    __m256d below4 = mask4d(h, 4, 0);
    __m256d su = flip4d(_mm256_set1_pd(1.0), h, 1), sv = flip4d(_mm256_set1_pd(2.0), h, 2);
    g[0] = _mm256_blendv_pd(sv, su, below4);
    g[1] = _mm256_blendv_pd(su, sv, below4);
}

AVX2 static inline void store_interleaved4d(double *out, const __m256d *g, int k)
{
    double tmp[3][4];
    for (int c = 0; c < k; ++c) _mm256_storeu_pd(tmp[c], g[c]);
    for (int j = 0; j < 4; ++j)
        for (int c = 0; c < k; ++c) out[k * j + c] = tmp[c][j];
}

/* Perlin's 3D gradient by the hash's low four bits without blends: each component doubled (+-2, or a zero)
 * is a double whose low seven bytes are 0, so its top byte comes from a 16-entry byte table (vpshufb). A
 * zero component is -0 on an offset in [0, 1) (never -0 itself) and +0 on an offset - 1 (negative), so
 * its product with the offset is always -0, which adds nothing to a sum, signed zeros included: the dot
 * product by fused multiply-adds is the one rounding of the scalar code's +-u +-v, doubled (exact), its
 * zero's sign as the scalar code's; halving is exact. */
static const signed char EDGE3[3][16] = {{1, -1, 1, -1, 1, -1, 1, -1, 0, 0, 0, 0, 1, 0, -1, 0},
                                         {1, 1, -1, -1, 0, 0, 0, 0, 1, -1, 1, -1, 1, -1, 1, -1},
                                         {0, 0, 0, 0, 1, 1, -1, -1, 1, 1, -1, -1, 0, 1, 0, -1}};

typedef struct {
    __m256i t[3][2]; /* by axis, then the offset (0: in [0, 1), a zero -0; 1: minus 1, a zero +0) */
} edges2_4d;

AVX2 static inline edges2_4d edges2_4d_load(void)
{
    edges2_4d e;
    for (int a = 0; a < 3; ++a)
        for (int up = 0; up < 2; ++up) {
            uint8_t b[16];
            for (int h = 0; h < 16; ++h) b[h] = EDGE3[a][h] > 0 ? 0x40 : EDGE3[a][h] < 0 ? 0xC0 : up ? 0x00 : 0x80;
            e.t[a][up] = _mm256_broadcastsi128_si256(_mm_loadu_si128((const __m128i *)b));
        }
    return e;
}

/* a pair's two hashes (bytes 0 and 1 of each lane of q) as the low four bits of bytes 0 and 7 of 64-bit lanes */
AVX2 static inline __m256i pair_index4d(__m128i q)
{
    const __m256i to07 = _mm256_set_epi64x(0x0980808080808008ll, 0x0180808080808000ll, 0x0980808080808008ll,
                                           0x0180808080808000ll);
    return _mm256_and_si256(_mm256_shuffle_epi8(_mm256_cvtepu32_epi64(q), to07), _mm256_set1_epi8(15));
}

/* byte k (0 or 7) of each 64-bit lane of t as the top byte of a double, the rest 0 */
AVX2 static inline __m256d top_byte4d(__m256i t, const int k)
{
    return _mm256_castsi256_pd(k ? _mm256_and_si256(t, _mm256_set1_epi64x((long long)0xFF00000000000000ull)) : _mm256_slli_epi64(t, 56));
}

/* the corner of the hash in byte k (0: z, 7: z + 1) of the index i, on the x offset up_x (0: x, 1: x - 1)
 * and y offset up_y */
AVX2 static inline __m256d corner3_4d(const edges2_4d *e, __m256i i, const int k, const int up_x, const int up_y,
                                      __m256d x, __m256d y, __m256d z)
{
    __m256d acc = _mm256_mul_pd(top_byte4d(_mm256_shuffle_epi8(e->t[2][k ? 1 : 0], i), k), z);
    acc = _mm256_fmadd_pd(top_byte4d(_mm256_shuffle_epi8(e->t[1][up_y], i), k), y, acc);
    acc = _mm256_fmadd_pd(top_byte4d(_mm256_shuffle_epi8(e->t[0][up_x], i), k), x, acc);
    return _mm256_mul_pd(acc, _mm256_set1_pd(0.5));
}

/* One half (4 points) of a 3D group: the corner hashes qA, qB, qA1, qB1 (at z in the low byte, at z + 1 in
 * the next) */
AVX2 static inline __attribute__((always_inline)) void half3_avx2(__m128i qA, __m128i qB, __m128i qA1, __m128i qB1,
                                                                   __m256d x, __m256d y, __m256d z, double *value,
                                                                   double *gradient, const int with_gradient)
{
    const __m256d one = _mm256_set1_pd(1.0);
    __m256d x1 = _mm256_sub_pd(x, one), y1 = _mm256_sub_pd(y, one), z1 = _mm256_sub_pd(z, one);
    __m256d u = fade4d(x), v = fade4d(y), w = fade4d(z);
    __m128i hA1 = _mm_srli_epi32(qA, 8), hB1 = _mm_srli_epi32(qB, 8), hA11 = _mm_srli_epi32(qA1, 8),
            hB11 = _mm_srli_epi32(qB1, 8);
    const edges2_4d E = edges2_4d_load();
    __m256i iA = pair_index4d(qA), iB = pair_index4d(qB), iA1 = pair_index4d(qA1), iB1 = pair_index4d(qB1);
    __m256d c000 = corner3_4d(&E, iA, 0, 0, 0, x, y, z), c100 = corner3_4d(&E, iB, 0, 1, 0, x1, y, z);
    __m256d c010 = corner3_4d(&E, iA1, 0, 0, 1, x, y1, z), c110 = corner3_4d(&E, iB1, 0, 1, 1, x1, y1, z);
    __m256d c001 = corner3_4d(&E, iA, 7, 0, 0, x, y, z1), c101 = corner3_4d(&E, iB, 7, 1, 0, x1, y, z1);
    __m256d c011 = corner3_4d(&E, iA1, 7, 0, 1, x, y1, z1), c111 = corner3_4d(&E, iB1, 7, 1, 1, x1, y1, z1);
    if (value)
        _mm256_storeu_pd(value, lerp4d(w, lerp4d(v, lerp4d(u, c000, c100), lerp4d(u, c010, c110)),
                                       lerp4d(v, lerp4d(u, c001, c101), lerp4d(u, c011, c111))));
    if (with_gradient) {
        __m256d G[8][3], g[3];
        gvec3_4d(qA, G[0]), gvec3_4d(qB, G[1]), gvec3_4d(qA1, G[2]), gvec3_4d(qB1, G[3]);
        gvec3_4d(hA1, G[4]), gvec3_4d(hB1, G[5]), gvec3_4d(hA11, G[6]), gvec3_4d(hB11, G[7]);
        for (int k = 0; k < 3; ++k)
            g[k] = lerp4d(w, lerp4d(v, lerp4d(u, G[0][k], G[1][k]), lerp4d(u, G[2][k], G[3][k])),
                          lerp4d(v, lerp4d(u, G[4][k], G[5][k]), lerp4d(u, G[6][k], G[7][k])));
        __m256d du = dfade4d(x), dv = dfade4d(y), dw = dfade4d(z);
        __m256d k1 = _mm256_sub_pd(c100, c000), k2 = _mm256_sub_pd(c010, c000), k3 = _mm256_sub_pd(c001, c000);
        __m256d k4 = _mm256_sub_pd(_mm256_sub_pd(c110, c010), k1), k5 = _mm256_sub_pd(_mm256_sub_pd(c011, c001), k2);
        __m256d k6 = _mm256_sub_pd(_mm256_sub_pd(c101, c001), k1);
        __m256d k7 = _mm256_sub_pd(_mm256_sub_pd(_mm256_sub_pd(c111, c011), _mm256_sub_pd(c101, c001)), k4);
        __m256d k67 = _mm256_add_pd(k6, _mm256_mul_pd(k7, v));
        __m256d pu = _mm256_add_pd(_mm256_add_pd(k1, _mm256_mul_pd(k4, v)), _mm256_mul_pd(k67, w));
        __m256d pv = _mm256_add_pd(_mm256_add_pd(k2, _mm256_mul_pd(k4, u)), _mm256_mul_pd(_mm256_add_pd(k5, _mm256_mul_pd(k7, u)), w));
        __m256d pw = _mm256_add_pd(_mm256_add_pd(k3, _mm256_mul_pd(k5, v)), _mm256_mul_pd(k67, u));
        g[0] = _mm256_add_pd(g[0], _mm256_mul_pd(du, pu));
        g[1] = _mm256_add_pd(g[1], _mm256_mul_pd(dv, pv));
        g[2] = _mm256_add_pd(g[2], _mm256_mul_pd(dw, pw));
        store_interleaved4d(gradient, g, 3);
    }
}

/* One half of a 2D group: the corner hashes [h00, h01, h10, h11] in the bytes of c */
AVX2 static inline __attribute__((always_inline)) void half2_avx2(__m128i c, __m256d x, __m256d y, double *value,
                                                                   double *gradient, const int with_gradient)
{
    const __m256d one = _mm256_set1_pd(1.0), scale = _mm256_set1_pd(0.507);
    __m256d x1 = _mm256_sub_pd(x, one), y1 = _mm256_sub_pd(y, one);
    __m256d u = fade4d(x), v = fade4d(y);
    __m128i h01 = _mm_srli_epi32(c, 8), h10 = _mm_srli_epi32(c, 16), h11 = _mm_srli_epi32(c, 24);
    __m256d a = grad2_4d(c, x, y), b = grad2_4d(h10, x1, y), cc = grad2_4d(h01, x, y1), d = grad2_4d(h11, x1, y1);
    if (value) _mm256_storeu_pd(value, _mm256_mul_pd(scale, lerp4d(v, lerp4d(u, a, b), lerp4d(u, cc, d))));
    if (with_gradient) {
        __m256d G[4][2], g[2];
        gvec2_4d(c, G[0]), gvec2_4d(h10, G[1]), gvec2_4d(h01, G[2]), gvec2_4d(h11, G[3]);
        for (int k = 0; k < 2; ++k) g[k] = lerp4d(v, lerp4d(u, G[0][k], G[1][k]), lerp4d(u, G[2][k], G[3][k]));
        __m256d du = dfade4d(x), dv = dfade4d(y);
        g[0] = _mm256_mul_pd(scale, _mm256_add_pd(_mm256_mul_pd(du, lerp4d(v, _mm256_sub_pd(b, a), _mm256_sub_pd(d, cc))), g[0]));
        g[1] = _mm256_mul_pd(scale, _mm256_add_pd(_mm256_mul_pd(dv, lerp4d(u, _mm256_sub_pd(cc, a), _mm256_sub_pd(d, b))), g[1]));
        store_interleaved4d(gradient, g, 2);
    }
}

/* The first stage of 8 points: their offsets in the cell (c, two halves of 4 per axis) and their hashes, the
 * loads and gathers, which the kernel issues a step ahead of the arithmetic that reads them, so that their
 * latency overlaps the previous points' arithmetic (as the float kernel); ok 0 where a coordinate is not
 * finite */
typedef struct {
    __m256d c[3][2];
    __m256i q, qA, qA1, qB, qB1;
    int ok;
} f64_stage;

AVX2 static inline __attribute__((always_inline)) void f64_stage_load(const udm1_noise *n, const uint32_t dims,
                                                                      const double *const *axes, size_t stride,
                                                                      __m128i vindex, size_t i, f64_stage *s)
{
    const __m256i m255 = _mm256_set1_epi32(255);
    const int *hash4 = (const int *)n->hash4, *pair = n->pair;
    int ok = 1;
    for (uint32_t a = 0; a < dims; ++a)
        for (int h = 0; h < 2; ++h) {
            s->c[a][h] = load4d(axes[a] + (i + 4 * (size_t)h) * stride, stride, vindex);
            ok &= finite4d(s->c[a][h]);
        }
    s->ok = ok;
    __m128i idx[3][2];
    for (uint32_t a = 0; a < dims; ++a)
        for (int h = 0; h < 2; ++h) s->c[a][h] = axis4d(s->c[a][h], &idx[a][h]);
    /* (the indices are 0..255 where the coordinates are finite; masked, so that a NaN's or an infinity's,
     * whose lanes the kernel never uses, stay in the tables too) */
    __m256i X0 = _mm256_and_si256(_mm256_set_m128i(idx[0][1], idx[0][0]), m255);
    __m256i Y0 = _mm256_and_si256(_mm256_set_m128i(idx[1][1], idx[1][0]), m255);
    /* the four column hashes [p[A], p[A1], p[B], p[B1]] (2D: the corner hashes [h00, h01, h10, h11]) */
    __m256i q = _mm256_i32gather_epi32(hash4, _mm256_or_si256(_mm256_slli_epi32(X0, 8), Y0), 4);
    s->q = q;
    if (dims == 3) { /* each column's hashes at z and z + 1 in one load (the doubled permutation's pairs) */
        __m256i Z0 = _mm256_and_si256(_mm256_set_m128i(idx[2][1], idx[2][0]), m255);
        s->qA = _mm256_i32gather_epi32(pair, _mm256_add_epi32(_mm256_and_si256(q, m255), Z0), 4);
        s->qA1 = _mm256_i32gather_epi32(pair, _mm256_add_epi32(_mm256_and_si256(_mm256_srli_epi32(q, 8), m255), Z0), 4);
        s->qB = _mm256_i32gather_epi32(pair, _mm256_add_epi32(_mm256_and_si256(_mm256_srli_epi32(q, 16), m255), Z0), 4);
        s->qB1 = _mm256_i32gather_epi32(pair, _mm256_add_epi32(_mm256_srli_epi32(q, 24), Z0), 4);
    }
}

AVX2 static inline __attribute__((always_inline)) size_t kernel_f64_avx2(const udm1_noise *n, const uint32_t dims,
                                                                         const double *const *axes, size_t stride,
                                                                         size_t count, double *value, double *gradient,
                                                                         const int with_gradient, udm1_side_check *side)
{
    const __m128i vindex = _mm_mullo_epi32(_mm_setr_epi32(0, 1, 2, 3), _mm_set1_epi32((int)stride));
    __m256d checked = _mm256_setzero_pd();
    size_t i = 0;
    f64_stage st[2];
    if (count >= 8) f64_stage_load(n, dims, axes, stride, vindex, 0, &st[0]);
    for (int cur = 0; i + 8 <= count; i += 8, cur ^= 1) {
        checked = udm1_side_step256_pd(side, checked);
        const f64_stage *s = &st[cur];
        if (!s->ok) break; /* the caller reports it */
        if (i + 16 <= count) f64_stage_load(n, dims, axes, stride, vindex, i + 8, &st[cur ^ 1]);
#define HALF(v) (h ? _mm256_extracti128_si256(v, 1) : _mm256_castsi256_si128(v))
        if (dims == 3) {
            for (int h = 0; h < 2; ++h)
                half3_avx2(HALF(s->qA), HALF(s->qB), HALF(s->qA1), HALF(s->qB1), s->c[0][h], s->c[1][h], s->c[2][h],
                           value ? value + i + 4 * (size_t)h : NULL, with_gradient ? gradient + 3 * (i + 4 * (size_t)h) : NULL,
                           with_gradient);
        } else {
            for (int h = 0; h < 2; ++h)
                half2_avx2(HALF(s->q), s->c[0][h], s->c[1][h], value ? value + i + 4 * (size_t)h : NULL,
                           with_gradient ? gradient + 2 * (i + 4 * (size_t)h) : NULL, with_gradient);
        }
#undef HALF
    }
    udm1_side_end256_pd(side, checked);
    return i;
}

AVX2 static size_t noise_f64_avx2(const udm1_noise *n, uint32_t dims, const double *const *axes, size_t stride,
                                  size_t count, double *value, double *gradient, udm1_side_check *side)
{
    if (dims == 3)
        return gradient ? kernel_f64_avx2(n, 3, axes, stride, count, value, gradient, 1, side)
                        : kernel_f64_avx2(n, 3, axes, stride, count, value, NULL, 0, side);
    return gradient ? kernel_f64_avx2(n, 2, axes, stride, count, value, gradient, 1, side)
                    : kernel_f64_avx2(n, 2, axes, stride, count, value, NULL, 0, side);
}

size_t udm1_noise_eval_group_f64(const udm1_noise *n, uint32_t dims, const double *const *axes, size_t stride,
                                 const double *value, const double *gradient)
{
    if (n->kind != UDM1_NOISE_IMPROVED || n->period[0] || n->period[1] || n->period[2]) return 0;
    if (dims < 2 || dims > 3) return 0;
    if (stride > (1u << 26)) return 0; /* (a gather's offsets must fit an int) */
    (void)axes, (void)value, (void)gradient;
    return udm1_isa_vbmi() ? 16 : udm1_isa_level() >= UDM1_ISA_AVX2 ? 8 : 0;
}

size_t udm1_noise_eval_fast_f64(const udm1_noise *n, uint32_t dims, const double *const *axes, size_t stride,
                                size_t count, double *value, double *gradient, udm1_side_check *side)
{
    udm1_side_check none = {{NULL}, 0, 0, 0, 0};
    if (!side) side = &none;
    size_t group = udm1_noise_eval_group_f64(n, dims, axes, stride, value, gradient);
    if (group == 16) return noise_f64_avx512(n, dims, axes, stride, count, value, gradient, side);
    if (group == 8) /* (AVX-512 without VBMI takes the AVX2 kernel) */
        return noise_f64_avx2(n, dims, axes, stride, count, value, gradient, side);
    return 0;
}

#else
size_t udm1_noise_eval_group_f64(const udm1_noise *n, uint32_t dims, const double *const *axes, size_t stride,
                                 const double *value, const double *gradient)
{
    (void)n, (void)dims, (void)axes, (void)stride, (void)value, (void)gradient;
    return 0;
}

size_t udm1_noise_eval_fast_f64(const udm1_noise *n, uint32_t dims, const double *const *axes, size_t stride,
                                size_t count, double *value, double *gradient, udm1_side_check *side)
{
    (void)n, (void)dims, (void)axes, (void)stride, (void)count, (void)value, (void)gradient, (void)side;
    return 0;
}
#endif
