/* noise_simd_f32.c - the float noise of udm1_noise_eval_f32 on 16 points at a time (AVX-512 with VBMI:
 * the permutation held in four registers and looked up 64 bytes at a time, a point's four hashes of a
 * step in the bytes of its lane) or 8 (AVX2: the combined tables hash4 and pair of noise_tables.h read by
 * gathers), with the scalar float code's operations in the same order (noise/lattice_impl.h), so the same
 * bits: the exact floor and offset, the quintic fade, Perlin's 3D gradients as the dot product with the
 * edge vector (its components by a permutation of registers, or in AVX2 by byte shuffles of the hash),
 * noise1234's 2D ones as blends and sign flips in AVX2, the nested lerps, and for the gradient the same
 * derivative. Improved noise in 2D and 3D, not periodic;
 * everything else (1D, 4D, classic, periodic, a stride too large for a gather) is left to the scalar
 * code. Chosen at run time by core/isa.h: the AVX-512 kernel where the processor has AVX-512 VBMI too
 * (UDM1_ISA=avx2 or baseline caps the choice), else the AVX2 one. */
#include "core/isa.h"
#include "noise/noise_tables.h"

#include <math.h>

#if defined(UDM1_HAVE_ISA_KERNELS)
#include <immintrin.h>

#include "noise/byte_table.h"
#include "noise/side_check.h"
#include "noise/strided_loads.h"

/* ---- AVX-512 (F, VL, DQ, BW, VBMI): 16 points ---- */
#define AVX512 __attribute__((target("avx512f,avx512vl,avx512dq,avx512bw,avx512vbmi")))



AVX512 static inline __mmask16 not_finite16(__m512 x) /* NaN or infinite */
{
    return _mm512_fpclass_ps_mask(x, 0x01 | 0x08 | 0x10 | 0x80);
}

/* floor, the offset in the cell (exact) and the lower corner's index, of which only the low byte (the
 * index mod 256) is read (a coordinate past 2^31 is a multiple of 256: its conversion's 0x80000000 has
 * the low byte 0, as the scalar code's index) */
AVX512 static inline __m512 axis16(__m512 x, __m512i *i0)
{
    __m512 f = _mm512_roundscale_ps(x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    *i0 = _mm512_cvttps_epi32(f);
    return _mm512_add_ps(_mm512_sub_ps(x, f), _mm512_setzero_ps());
}

AVX512 static inline __m512 fade16(__m512 t)
{
    __m512 a = _mm512_mul_ps(_mm512_mul_ps(t, t), t);
    __m512 b = _mm512_sub_ps(_mm512_mul_ps(t, _mm512_set1_ps(6.0f)), _mm512_set1_ps(15.0f));
    b = _mm512_add_ps(_mm512_mul_ps(t, b), _mm512_set1_ps(10.0f));
    return _mm512_mul_ps(a, b);
}

AVX512 static inline __m512 dfade16(__m512 t) /* 30 t t (t (t - 2) + 1) */
{
    __m512 a = _mm512_mul_ps(_mm512_mul_ps(_mm512_set1_ps(30.0f), t), t);
    __m512 b = _mm512_add_ps(_mm512_mul_ps(t, _mm512_sub_ps(t, _mm512_set1_ps(2.0f))), _mm512_set1_ps(1.0f));
    return _mm512_mul_ps(a, b);
}

AVX512 static inline __m512 lerp16(__m512 t, __m512 a, __m512 b)
{
    return _mm512_add_ps(a, _mm512_mul_ps(t, _mm512_sub_ps(b, a)));
}

/* lerp16 where b - a is a small integer (0, +-1, +-2): t (b - a) is exact, so the fused form rounds alike */
AVX512 static inline __m512 lerp16x(__m512 t, __m512 a, __m512 b)
{
    return _mm512_fmadd_ps(t, _mm512_sub_ps(b, a), a);
}

/* The gradient vectors by hash & 15 as tables of their components: Perlin's 16 edges (3D), noise1234's
 * +-u +-2v (2D; its 8 repeated). A corner's value is the dot product with its vector: the products are
 * exact (components +-1, +-2 or 0), so the sum rounds as the scalar code's +-u +-v does; in 3D the scalar
 * float code adds 0 to turn a zero's sign to +0, as here (lattice_impl.h). */
static const float EDGES[3][16] = {{1, -1, 1, -1, 1, -1, 1, -1, 0, 0, 0, 0, 1, 0, -1, 0},
                                   {1, 1, -1, -1, 0, 0, 0, 0, 1, -1, 1, -1, 1, -1, 1, -1},
                                   {0, 0, 0, 0, 1, 1, -1, -1, 1, 1, -1, -1, 0, 1, 0, -1}};
static const float G2[3][16] = {{1, -1, 1, -1, 2, 2, -2, -2, 1, -1, 1, -1, 2, 2, -2, -2},
                                {2, 2, -2, -2, 1, -1, 1, -1, 2, 2, -2, -2, 1, -1, 1, -1},
                                {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}};

typedef struct {
    __m512 x, y, z;
} tables512;

/* the components of the vector of the hash in byte k of H */
AVX512 static inline void gvec16(const tables512 *t, __m512i H, const int k, __m512 g[3])
{
    __m512i h = k ? _mm512_srli_epi32(H, 8 * k) : H; /* (the permutation reads bits 0..3) */
    g[0] = _mm512_permutexvar_ps(h, t->x), g[1] = _mm512_permutexvar_ps(h, t->y), g[2] = _mm512_permutexvar_ps(h, t->z);
}

/* The dot products by fused multiply-adds: each product is exact, so each step rounds as an addition
 * does. From an accumulator of +0, 3D's zeros come out +0 and its two non-zero terms are rounded once,
 * as the scalar float code's (+-u +-v) + 0; 2D's two terms are the scalar code's. */
AVX512 static inline __m512 dot3_16(const __m512 g[3], __m512 x, __m512 y, __m512 z)
{
    return _mm512_fmadd_ps(g[0], x, _mm512_fmadd_ps(g[1], y, _mm512_fmadd_ps(g[2], z, _mm512_setzero_ps())));
}

AVX512 static inline __m512 corner16(const tables512 *t, __m512i H, const int k, __m512 x, __m512 y, __m512 z)
{
    __m512 g[3];
    gvec16(t, H, k, g);
    return dot3_16(g, x, y, z);
}

AVX512 static inline __m512 dot2_16(const __m512 g[3], __m512 x, __m512 y)
{
    return _mm512_fmadd_ps(g[1], y, _mm512_mul_ps(g[0], x));
}

/* g[0..k-1] (16 lanes each, k = 2 or 3) into out[k j + c], by permutations across the registers */
static const int INTERLEAVE2[2][16] = {{0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23},
                                       {8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31}};
/* per third of the output: from g[0] and g[1] (the lanes of g[2] left 0), then g[2]'s lanes (mask) */
static const int INTERLEAVE3[3][2][16] = {
    {{0, 16, 0, 1, 17, 0, 2, 18, 0, 3, 19, 0, 4, 20, 0, 5}, {0, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0}},
    {{21, 0, 6, 22, 0, 7, 23, 0, 8, 24, 0, 9, 25, 0, 10, 26}, {0, 5, 0, 0, 6, 0, 0, 7, 0, 0, 8, 0, 0, 9, 0, 0}},
    {{0, 11, 27, 0, 12, 28, 0, 13, 29, 0, 14, 30, 0, 15, 31, 0}, {10, 0, 0, 11, 0, 0, 12, 0, 0, 13, 0, 0, 14, 0, 0, 15}}};
static const __mmask16 INTERLEAVE3_MASK[3] = {0x4924, 0x2492, 0x9249};

AVX512 static inline void store_interleaved16(float *out, const __m512 *g, int k)
{
    if (k == 2) {
        for (int o = 0; o < 2; ++o)
            _mm512_storeu_ps(out + 16 * o, _mm512_permutex2var_ps(g[0], _mm512_loadu_si512(INTERLEAVE2[o]), g[1]));
        return;
    }
    for (int o = 0; o < 3; ++o) {
        __m512 t = _mm512_permutex2var_ps(g[0], _mm512_loadu_si512(INTERLEAVE3[o][0]), g[1]);
        t = _mm512_mask_permutexvar_ps(t, INTERLEAVE3_MASK[o], _mm512_loadu_si512(INTERLEAVE3[o][1]), g[2]);
        _mm512_storeu_ps(out + 16 * o, t);
    }
}

/* a's low byte plus the bytes of `plus` (each 0 or 1) in the bytes of its lane, mod 256: the indices
 * [i, i, i + 1, i + 1] or [i, i + 1, i, i + 1] of a cell's corners in one shuffle and one add */
AVX512 static inline __m512i spread4_plus(__m512i a, int plus)
{
    return _mm512_add_epi8(byte_table_spread4(a), _mm512_set1_epi32(plus));
}

/* The 3D kernel, specialized by the compiler for the values alone (with_gradient 0: nothing else live
 * across the corners, no spills) and for values and gradients. */
AVX512 static inline __attribute__((always_inline)) size_t noise3_avx512_k(const udm1_noise *n,
                                                                          const float *const *axes, size_t stride,
                                                                          size_t count, float *value, float *gradient,
                                                                          const int with_gradient,
                                                                          udm1_side_check *side)
{
    const byte_table T = byte_table_load(n->perm);
    const strided_loads L = strided_loads_init(stride, 16);
    const __m512 onef = _mm512_set1_ps(1.0f);
    const tables512 E = {_mm512_loadu_ps(EDGES[0]), _mm512_loadu_ps(EDGES[1]), _mm512_loadu_ps(EDGES[2])};
    __m512 checked = _mm512_setzero_ps();
    size_t i = 0;
    for (; i + 16 <= count; i += 16) {
        checked = udm1_side_step512_ps(side, checked);
        __m512 x = strided_load16(&L, axes[0] + i * stride), y = strided_load16(&L, axes[1] + i * stride);
        __m512 z = strided_load16(&L, axes[2] + i * stride);
        if (not_finite16(x) | not_finite16(y) | not_finite16(z)) break; /* the caller reports it */
        __m512i X0, Y0, Z0;
        x = axis16(x, &X0), y = axis16(y, &Y0), z = axis16(z, &Z0);
        /* the hashes, four to a lane, in bytes (mod 256, as the doubled table): [p[X0], p[X0], p[X1],
         * p[X1]], then [A, A1, B, B1] = [p[X0] + Y0, p[X0] + Y1, p[X1] + Y0, p[X1] + Y1] looked up, then
         * plus Z0 and Z1 = Z0 + 1 */
        __m512i px = byte_table_lookup(&T, spread4_plus(X0, 0x01010000));
        __m512i ab = byte_table_lookup(&T, _mm512_add_epi8(px, spread4_plus(Y0, 0x01000100)));
        __m512i z0 = _mm512_add_epi8(ab, byte_table_spread4(Z0));
        __m512i H0 = byte_table_lookup(&T, z0);                                              /* [h000, h010, h100, h110] */
        __m512i H1 = byte_table_lookup(&T, _mm512_add_epi8(z0, _mm512_set1_epi8(1))); /* [h001, h011, h101, h111] */
        __m512 x1 = _mm512_sub_ps(x, onef), y1 = _mm512_sub_ps(y, onef), z1 = _mm512_sub_ps(z, onef);
        __m512 u = fade16(x), v = fade16(y), w = fade16(z);
        /* corners 000, 100, 010, 110, 001, 101, 011, 111: each vector made where it is used (all of them
         * at once would not fit the 32 registers) */
        __m512 c000 = corner16(&E, H0, 0, x, y, z), c100 = corner16(&E, H0, 2, x1, y, z);
        __m512 c010 = corner16(&E, H0, 1, x, y1, z), c110 = corner16(&E, H0, 3, x1, y1, z);
        __m512 c001 = corner16(&E, H1, 0, x, y, z1), c101 = corner16(&E, H1, 2, x1, y, z1);
        __m512 c011 = corner16(&E, H1, 1, x, y1, z1), c111 = corner16(&E, H1, 3, x1, y1, z1);
        if (value)
            _mm512_storeu_ps(value + i, lerp16(w, lerp16(v, lerp16(u, c000, c100), lerp16(u, c010, c110)),
                                               lerp16(v, lerp16(u, c001, c101), lerp16(u, c011, c111))));
        if (with_gradient) {
            __m512 G[8][3], g[3];
            gvec16(&E, H0, 0, G[0]), gvec16(&E, H0, 2, G[1]), gvec16(&E, H0, 1, G[2]), gvec16(&E, H0, 3, G[3]);
            gvec16(&E, H1, 0, G[4]), gvec16(&E, H1, 2, G[5]), gvec16(&E, H1, 1, G[6]), gvec16(&E, H1, 3, G[7]);
            for (int k = 0; k < 3; ++k)  /* (first level: u times a difference of small integers, exact: fused) */
                g[k] = lerp16(w, lerp16(v, lerp16x(u, G[0][k], G[1][k]), lerp16x(u, G[2][k], G[3][k])),
                              lerp16(v, lerp16x(u, G[4][k], G[5][k]), lerp16x(u, G[6][k], G[7][k])));
            __m512 du = dfade16(x), dv = dfade16(y), dw = dfade16(z);
            __m512 k1 = _mm512_sub_ps(c100, c000), k2 = _mm512_sub_ps(c010, c000), k3 = _mm512_sub_ps(c001, c000);
            __m512 k4 = _mm512_sub_ps(_mm512_sub_ps(c110, c010), k1), k5 = _mm512_sub_ps(_mm512_sub_ps(c011, c001), k2);
            __m512 k6 = _mm512_sub_ps(_mm512_sub_ps(c101, c001), k1);
            __m512 k7 = _mm512_sub_ps(_mm512_sub_ps(_mm512_sub_ps(c111, c011), _mm512_sub_ps(c101, c001)), k4);
            __m512 k67 = _mm512_add_ps(k6, _mm512_mul_ps(k7, v));
            __m512 pu = _mm512_add_ps(_mm512_add_ps(k1, _mm512_mul_ps(k4, v)), _mm512_mul_ps(k67, w));
            __m512 pv = _mm512_add_ps(_mm512_add_ps(k2, _mm512_mul_ps(k4, u)), _mm512_mul_ps(_mm512_add_ps(k5, _mm512_mul_ps(k7, u)), w));
            __m512 pw = _mm512_add_ps(_mm512_add_ps(k3, _mm512_mul_ps(k5, v)), _mm512_mul_ps(k67, u));
            g[0] = _mm512_add_ps(g[0], _mm512_mul_ps(du, pu));
            g[1] = _mm512_add_ps(g[1], _mm512_mul_ps(dv, pv));
            g[2] = _mm512_add_ps(g[2], _mm512_mul_ps(dw, pw));
            store_interleaved16(gradient + 3 * i, g, 3);
        }
    }
    udm1_side_end512_ps(side, checked);
    return i;
}

AVX512 static size_t noise3_avx512(const udm1_noise *n, const float *const *axes, size_t stride, size_t count,
                                   float *value, float *gradient, udm1_side_check *side)
{
    return gradient ? noise3_avx512_k(n, axes, stride, count, value, gradient, 1, side)
                    : noise3_avx512_k(n, axes, stride, count, value, NULL, 0, side);
}

AVX512 static size_t noise2_avx512(const udm1_noise *n, const float *const *axes, size_t stride, size_t count,
                                   float *value, float *gradient, udm1_side_check *side)
{
    const byte_table T = byte_table_load(n->perm);
    const strided_loads L = strided_loads_init(stride, 16);
    const __m512 onef = _mm512_set1_ps(1.0f), scale = _mm512_set1_ps(0.507f);
    const tables512 E = {_mm512_loadu_ps(G2[0]), _mm512_loadu_ps(G2[1]), _mm512_loadu_ps(G2[2])};
    __m512 checked = _mm512_setzero_ps();
    size_t i = 0;
    for (; i + 16 <= count; i += 16) {
        checked = udm1_side_step512_ps(side, checked);
        __m512 x = strided_load16(&L, axes[0] + i * stride), y = strided_load16(&L, axes[1] + i * stride);
        if (not_finite16(x) | not_finite16(y)) break;
        __m512i X0, Y0;
        x = axis16(x, &X0), y = axis16(y, &Y0);
        __m512i px = byte_table_lookup(&T, spread4_plus(X0, 0x01010000));
        __m512i H = byte_table_lookup(&T, _mm512_add_epi8(px, spread4_plus(Y0, 0x01000100))); /* [h00, h01, h10, h11] */
        __m512 x1 = _mm512_sub_ps(x, onef), y1 = _mm512_sub_ps(y, onef);
        __m512 u = fade16(x), v = fade16(y);
        __m512 G[4][3]; /* corners 00, 10, 01, 11 */
        gvec16(&E, H, 0, G[0]), gvec16(&E, H, 2, G[1]), gvec16(&E, H, 1, G[2]), gvec16(&E, H, 3, G[3]);
        __m512 a = dot2_16(G[0], x, y), b = dot2_16(G[1], x1, y), c = dot2_16(G[2], x, y1), d = dot2_16(G[3], x1, y1);
        if (value) _mm512_storeu_ps(value + i, _mm512_mul_ps(scale, lerp16(v, lerp16(u, a, b), lerp16(u, c, d))));
        if (gradient) {
            __m512 g[2];
            for (int k = 0; k < 2; ++k) g[k] = lerp16(v, lerp16(u, G[0][k], G[1][k]), lerp16(u, G[2][k], G[3][k]));
            __m512 du = dfade16(x), dv = dfade16(y);
            g[0] = _mm512_mul_ps(scale, _mm512_add_ps(_mm512_mul_ps(du, lerp16(v, _mm512_sub_ps(b, a), _mm512_sub_ps(d, c))), g[0]));
            g[1] = _mm512_mul_ps(scale, _mm512_add_ps(_mm512_mul_ps(dv, lerp16(u, _mm512_sub_ps(c, a), _mm512_sub_ps(d, b))), g[1]));
            store_interleaved16(gradient + 2 * i, g, 2);
        }
    }
    udm1_side_end512_ps(side, checked);
    return i;
}

/* ---- AVX2: 8 points ---- */
#define AVX2 __attribute__((target("avx2,fma")))

AVX2 static inline __m256 load8(const float *p, size_t stride, __m256i vindex)
{
    return stride == 1 ? _mm256_loadu_ps(p) : _mm256_i32gather_ps(p, vindex, 4);
}

AVX2 static inline __m256 finite8_mask(__m256 x) /* |x| < inf (not NaN), as a lane mask */
{
    return _mm256_cmp_ps(_mm256_andnot_ps(_mm256_set1_ps(-0.0f), x), _mm256_set1_ps(INFINITY), _CMP_LT_OQ);
}

AVX2 static inline int finite8(__m256 x)
{
    __m256 ax = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), x);
    return _mm256_movemask_ps(_mm256_cmp_ps(ax, _mm256_set1_ps(INFINITY), _CMP_LT_OQ)) == 0xFF;
}

AVX2 static inline __m256 axis8(__m256 x, __m256i *i0)
{
    __m256 f = _mm256_floor_ps(x);
    *i0 = _mm256_and_si256(_mm256_cvttps_epi32(f), _mm256_set1_epi32(255));
    return _mm256_add_ps(_mm256_sub_ps(x, f), _mm256_setzero_ps());
}

AVX2 static inline __m256 fade8(__m256 t)
{
    __m256 a = _mm256_mul_ps(_mm256_mul_ps(t, t), t);
    __m256 b = _mm256_sub_ps(_mm256_mul_ps(t, _mm256_set1_ps(6.0f)), _mm256_set1_ps(15.0f));
    b = _mm256_add_ps(_mm256_mul_ps(t, b), _mm256_set1_ps(10.0f));
    return _mm256_mul_ps(a, b);
}

AVX2 static inline __m256 dfade8(__m256 t)
{
    __m256 a = _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(30.0f), t), t);
    __m256 b = _mm256_add_ps(_mm256_mul_ps(t, _mm256_sub_ps(t, _mm256_set1_ps(2.0f))), _mm256_set1_ps(1.0f));
    return _mm256_mul_ps(a, b);
}

AVX2 static inline __m256 lerp8(__m256 t, __m256 a, __m256 b)
{
    return _mm256_add_ps(a, _mm256_mul_ps(t, _mm256_sub_ps(b, a)));
}

/* lerp8 where b - a is a small integer (0, +-1, +-2): t (b - a) is exact, so the fused form rounds alike */
AVX2 static inline __m256 lerp8x(__m256 t, __m256 a, __m256 b)
{
    return _mm256_fmadd_ps(t, _mm256_sub_ps(b, a), a);
}

AVX2 static inline __m256 mask8(__m256i h, int bits, int equal) /* (h & bits) == equal, as a lane mask */
{
    return _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(h, _mm256_set1_epi32(bits)), _mm256_set1_epi32(equal)));
}

AVX2 static inline __m256 flip8(__m256 v, __m256i h, int bit) /* negate the lanes where h & bit */
{
    __m256 m = _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(h, _mm256_set1_epi32(bit)), _mm256_set1_epi32(bit)));
    return _mm256_xor_ps(v, _mm256_and_ps(m, _mm256_set1_ps(-0.0f)));
}

AVX2 static inline __m256 grad2_8(__m256i h, __m256 x, __m256 y)
{
    __m256 below4 = mask8(h, 4, 0);
    __m256 u = _mm256_blendv_ps(y, x, below4);
    __m256 v = _mm256_mul_ps(_mm256_set1_ps(2.0f), _mm256_blendv_ps(x, y, below4));
    return _mm256_add_ps(flip8(u, h, 1), flip8(v, h, 2));
}

AVX2 static inline void gvec2_8(__m256i h, __m256 g[2])
{
    __m256 below4 = mask8(h, 4, 0);
    __m256 su = flip8(_mm256_set1_ps(1.0f), h, 1), sv = flip8(_mm256_set1_ps(2.0f), h, 2);
    g[0] = _mm256_blendv_ps(sv, su, below4);
    g[1] = _mm256_blendv_ps(su, sv, below4);
}

/* 8 points' gradients g[0..k-1] (k 2 or 3) stored interleaved, out[k j + c] = g[c][j], in k vector stores: each
 * store's lane l holds point (8 o + l) / k of component (8 o + l) % k, the sources permuted alike and blended */
AVX2 static inline void store_interleaved8(float *out, const __m256 *g, int k)
{
    if (k == 2) {
        __m256 lo = _mm256_unpacklo_ps(g[0], g[1]), hi = _mm256_unpackhi_ps(g[0], g[1]); /* points 0 1 | 4 5, 2 3 | 6 7 */
        _mm256_storeu_ps(out, _mm256_permute2f128_ps(lo, hi, 0x20));
        _mm256_storeu_ps(out + 8, _mm256_permute2f128_ps(lo, hi, 0x31));
        return;
    }
#define UDM1_STORE3_(o, i0, i1, i2, i3, i4, i5, i6, i7, m1, m2)                                                      \
    do {                                                                                                             \
        const __m256i ix = _mm256_setr_epi32(i0, i1, i2, i3, i4, i5, i6, i7);                                      \
        __m256 r = _mm256_blend_ps(_mm256_permutevar8x32_ps(g[0], ix), _mm256_permutevar8x32_ps(g[1], ix), m1);    \
        _mm256_storeu_ps(out + 8 * (o), _mm256_blend_ps(r, _mm256_permutevar8x32_ps(g[2], ix), m2));               \
    } while (0)
    UDM1_STORE3_(0, 0, 0, 0, 1, 1, 1, 2, 2, 0x92, 0x24);
    UDM1_STORE3_(1, 2, 3, 3, 3, 4, 4, 4, 5, 0x24, 0x49);
    UDM1_STORE3_(2, 5, 5, 6, 6, 6, 7, 7, 7, 0x49, 0x92);
#undef UDM1_STORE3_
}

/* Perlin's 3D gradient by the hash's low four bits without blends: each component doubled (+-2 or 0) is
 * a float whose low three bytes are 0, so its top byte comes from a 16-entry byte table (vpshufb), for
 * the hashes of every byte of a lane at once. */
typedef struct {
    __m256i x, y, z; /* the top bytes of 2 g by hash & 15 */
} edges2_8;

AVX2 static inline edges2_8 edges2_load(void)
{
    /* gx = 1, -1, 1, -1, 1, -1, 1, -1, 0, 0, 0, 0, 1, 0, -1, 0; gy = 1, 1, -1, -1, 0, 0, 0, 0, 1, -1, 1, -1,
     * 1, -1, 1, -1; gz = 0, 0, 0, 0, 1, 1, -1, -1, 1, 1, -1, -1, 0, 1, 0, -1 (EDGES) */
    uint8_t b[3][16];
    for (int k = 0; k < 3; ++k)
        for (int h = 0; h < 16; ++h) b[k][h] = EDGES[k][h] > 0 ? 0x40 : EDGES[k][h] < 0 ? 0xC0 : 0x00;
    edges2_8 e;
    e.x = _mm256_broadcastsi128_si256(_mm_loadu_si128((const __m128i *)b[0]));
    e.y = _mm256_broadcastsi128_si256(_mm_loadu_si128((const __m128i *)b[1]));
    e.z = _mm256_broadcastsi128_si256(_mm_loadu_si128((const __m128i *)b[2]));
    return e;
}

/* 2 g for a pair's two hashes (bytes 0 and 1 of each lane of q, the bits above the low four of each
 * ignored), as bytes 0 and 3 of each lane (the others not used) */
typedef struct {
    __m256i x, y, z;
} edge_bytes8;

AVX2 static inline edge_bytes8 edge_bytes(const edges2_8 *e, __m256i q)
{
    const __m256i to03 = _mm256_setr_epi32(0x01808000, 0x05808004, 0x09808008, 0x0D80800C, 0x01808000, 0x05808004, 0x09808008, 0x0D80800C);
    __m256i i = _mm256_and_si256(_mm256_shuffle_epi8(q, to03), _mm256_set1_epi8(15));
    edge_bytes8 r = {_mm256_shuffle_epi8(e->x, i), _mm256_shuffle_epi8(e->y, i), _mm256_shuffle_epi8(e->z, i)};
    return r;
}

/* byte k (0 or 3) of each lane of t as the top byte of a float, the rest 0 */
AVX2 static inline __m256 top_byte8(__m256i t, const int k)
{
    return _mm256_castsi256_ps(k ? _mm256_and_si256(t, _mm256_set1_epi32((int)0xFF000000u)) : _mm256_slli_epi32(t, 24));
}

/* The corner's value of the hash in byte k (0 or 3): the dot product with 2 g by fused multiply-adds from +0,
 * halved. Each product is exact; the two non-zero terms are rounded once, as the scalar code's
 * (+-u +-v) + 0, doubled (exact: a sum of two floats doubled rounds as the doubled sum), and a zero comes
 * out +0 (the accumulator is never -0); halving is exact. */
AVX2 static inline __m256 corner3_8(const edge_bytes8 *g, const int k, __m256 x, __m256 y, __m256 z)
{
    __m256 acc = _mm256_fmadd_ps(top_byte8(g->z, k), z, _mm256_setzero_ps());
    acc = _mm256_fmadd_ps(top_byte8(g->y, k), y, acc);
    acc = _mm256_fmadd_ps(top_byte8(g->x, k), x, acc);
    return _mm256_mul_ps(acc, _mm256_set1_ps(0.5f));
}

/* the corner's gradient vector (+-1 or 0 each) */
AVX2 static inline void gvec3_bytes8(const edge_bytes8 *g, const int k, __m256 v[3])
{
    const __m256 half = _mm256_set1_ps(0.5f);
    v[0] = _mm256_mul_ps(top_byte8(g->x, k), half), v[1] = _mm256_mul_ps(top_byte8(g->y, k), half);
    v[2] = _mm256_mul_ps(top_byte8(g->z, k), half);
}

/* The first stage of 8 points of the 3D kernel: their offsets in the cell and the four columns' hashes at z
 * and z + 1 (the loads and gathers, which the kernel issues a step ahead of the arithmetic that reads them, so
 * that their latency overlaps the previous points' arithmetic); ok 0 where a coordinate is not finite (the
 * gathers' indices stay in the tables: a NaN's or infinity's index is 0) */
typedef struct {
    __m256 x, y, z;
    __m256i qA, qA1, qB, qB1;
    int ok;
} noise3_stage8;

AVX2 static inline noise3_stage8 noise3_stage(const int *hash4, const int *pair, const float *const *axes, size_t i,
                                              size_t stride, __m256i vindex)
{
    const __m256i m255 = _mm256_set1_epi32(255);
    noise3_stage8 r;
    __m256 x = load8(axes[0] + i * stride, stride, vindex), y = load8(axes[1] + i * stride, stride, vindex);
    __m256 z = load8(axes[2] + i * stride, stride, vindex);
    r.ok = _mm256_movemask_ps(_mm256_and_ps(_mm256_and_ps(finite8_mask(x), finite8_mask(y)), finite8_mask(z))) == 0xFF;
    __m256i X0, Y0, Z0;
    r.x = axis8(x, &X0), r.y = axis8(y, &Y0), r.z = axis8(z, &Z0);
    /* the four column hashes [p[A], p[A1], p[B], p[B1]] in one load, then each column's hashes at z and z + 1
     * in one load (the doubled permutation's pairs) */
    __m256i c = _mm256_i32gather_epi32(hash4, _mm256_or_si256(_mm256_slli_epi32(X0, 8), Y0), 4);
    r.qA = _mm256_i32gather_epi32(pair, _mm256_add_epi32(_mm256_and_si256(c, m255), Z0), 4);
    r.qA1 = _mm256_i32gather_epi32(pair, _mm256_add_epi32(_mm256_and_si256(_mm256_srli_epi32(c, 8), m255), Z0), 4);
    r.qB = _mm256_i32gather_epi32(pair, _mm256_add_epi32(_mm256_and_si256(_mm256_srli_epi32(c, 16), m255), Z0), 4);
    r.qB1 = _mm256_i32gather_epi32(pair, _mm256_add_epi32(_mm256_srli_epi32(c, 24), Z0), 4);
    return r;
}

/* specialized by the compiler for the values alone (with_gradient 0) and for values and gradients, as the
 * AVX-512 kernel */
AVX2 static inline __attribute__((always_inline)) size_t noise3_avx2_k(const udm1_noise *n, const float *const *axes,
                                                                      size_t stride, size_t count, float *value,
                                                                      float *gradient, const int with_gradient,
                                                                      udm1_side_check *side)
{
    const __m256i vindex = _mm256_mullo_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), _mm256_set1_epi32((int)stride));
    const __m256 onef = _mm256_set1_ps(1.0f);
    const int *hash4 = (const int *)n->hash4, *pair = n->pair;
    const edges2_8 E = edges2_load();
    __m256 checked = _mm256_setzero_ps();
    size_t i = 0;
    noise3_stage8 st[2];
    if (count >= 8) st[0] = noise3_stage(hash4, pair, axes, 0, stride, vindex);
    for (int cur = 0; i + 8 <= count; i += 8, cur ^= 1) {
        checked = udm1_side_step256_ps(side, checked);
        if (!st[cur].ok) break; /* the caller reports it */
        if (i + 16 <= count) st[cur ^ 1] = noise3_stage(hash4, pair, axes, i + 8, stride, vindex);
        const __m256 x = st[cur].x, y = st[cur].y, z = st[cur].z;
        const __m256i qA = st[cur].qA, qA1 = st[cur].qA1, qB = st[cur].qB, qB1 = st[cur].qB1;
        __m256 x1 = _mm256_sub_ps(x, onef), y1 = _mm256_sub_ps(y, onef), z1 = _mm256_sub_ps(z, onef);
        __m256 u = fade8(x), v = fade8(y), w = fade8(z);
        /* each column's hashes at z and z + 1 (bytes 0 and 3 of its edge bytes) */
        edge_bytes8 gA = edge_bytes(&E, qA), gB = edge_bytes(&E, qB), gA1 = edge_bytes(&E, qA1), gB1 = edge_bytes(&E, qB1);
        __m256 c000 = corner3_8(&gA, 0, x, y, z), c100 = corner3_8(&gB, 0, x1, y, z);
        __m256 c010 = corner3_8(&gA1, 0, x, y1, z), c110 = corner3_8(&gB1, 0, x1, y1, z);
        __m256 c001 = corner3_8(&gA, 3, x, y, z1), c101 = corner3_8(&gB, 3, x1, y, z1);
        __m256 c011 = corner3_8(&gA1, 3, x, y1, z1), c111 = corner3_8(&gB1, 3, x1, y1, z1);
        if (value)
            _mm256_storeu_ps(value + i, lerp8(w, lerp8(v, lerp8(u, c000, c100), lerp8(u, c010, c110)),
                                              lerp8(v, lerp8(u, c001, c101), lerp8(u, c011, c111))));
        if (with_gradient) {
            __m256 G[8][3];
            gvec3_bytes8(&gA, 0, G[0]), gvec3_bytes8(&gB, 0, G[1]), gvec3_bytes8(&gA1, 0, G[2]), gvec3_bytes8(&gB1, 0, G[3]);
            gvec3_bytes8(&gA, 3, G[4]), gvec3_bytes8(&gB, 3, G[5]), gvec3_bytes8(&gA1, 3, G[6]), gvec3_bytes8(&gB1, 3, G[7]);
            __m256 g[3];
            for (int k = 0; k < 3; ++k) /* (first level: u times a difference of small integers, exact: fused) */
                g[k] = lerp8(w, lerp8(v, lerp8x(u, G[0][k], G[1][k]), lerp8x(u, G[2][k], G[3][k])),
                             lerp8(v, lerp8x(u, G[4][k], G[5][k]), lerp8x(u, G[6][k], G[7][k])));
            __m256 du = dfade8(x), dv = dfade8(y), dw = dfade8(z);
            __m256 k1 = _mm256_sub_ps(c100, c000), k2 = _mm256_sub_ps(c010, c000), k3 = _mm256_sub_ps(c001, c000);
            __m256 k4 = _mm256_sub_ps(_mm256_sub_ps(c110, c010), k1), k5 = _mm256_sub_ps(_mm256_sub_ps(c011, c001), k2);
            __m256 k6 = _mm256_sub_ps(_mm256_sub_ps(c101, c001), k1);
            __m256 k7 = _mm256_sub_ps(_mm256_sub_ps(_mm256_sub_ps(c111, c011), _mm256_sub_ps(c101, c001)), k4);
            __m256 k67 = _mm256_add_ps(k6, _mm256_mul_ps(k7, v));
            __m256 pu = _mm256_add_ps(_mm256_add_ps(k1, _mm256_mul_ps(k4, v)), _mm256_mul_ps(k67, w));
            __m256 pv = _mm256_add_ps(_mm256_add_ps(k2, _mm256_mul_ps(k4, u)), _mm256_mul_ps(_mm256_add_ps(k5, _mm256_mul_ps(k7, u)), w));
            __m256 pw = _mm256_add_ps(_mm256_add_ps(k3, _mm256_mul_ps(k5, v)), _mm256_mul_ps(k67, u));
            g[0] = _mm256_add_ps(g[0], _mm256_mul_ps(du, pu));
            g[1] = _mm256_add_ps(g[1], _mm256_mul_ps(dv, pv));
            g[2] = _mm256_add_ps(g[2], _mm256_mul_ps(dw, pw));
            store_interleaved8(gradient + 3 * i, g, 3);
        }
    }
    udm1_side_end256_ps(side, checked);
    return i;
}

AVX2 static size_t noise3_avx2(const udm1_noise *n, const float *const *axes, size_t stride, size_t count,
                               float *value, float *gradient, udm1_side_check *side)
{
    return gradient ? noise3_avx2_k(n, axes, stride, count, value, gradient, 1, side)
                    : noise3_avx2_k(n, axes, stride, count, value, NULL, 0, side);
}

AVX2 static size_t noise2_avx2(const udm1_noise *n, const float *const *axes, size_t stride, size_t count,
                               float *value, float *gradient, udm1_side_check *side)
{
    const __m256i vindex = _mm256_mullo_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), _mm256_set1_epi32((int)stride));
    const __m256 onef = _mm256_set1_ps(1.0f), scale = _mm256_set1_ps(0.507f);
    const int *hash4 = (const int *)n->hash4;
    __m256 checked = _mm256_setzero_ps();
    size_t i = 0;
    for (; i + 8 <= count; i += 8) {
        checked = udm1_side_step256_ps(side, checked);
        __m256 x = load8(axes[0] + i * stride, stride, vindex), y = load8(axes[1] + i * stride, stride, vindex);
        if (!(finite8(x) && finite8(y))) break;
        __m256i X0, Y0;
        x = axis8(x, &X0), y = axis8(y, &Y0);
        __m256i c = _mm256_i32gather_epi32(hash4, _mm256_or_si256(_mm256_slli_epi32(X0, 8), Y0), 4); /* [h00, h01, h10, h11] */
        __m256 x1 = _mm256_sub_ps(x, onef), y1 = _mm256_sub_ps(y, onef);
        __m256 u = fade8(x), v = fade8(y);
        __m256i h01 = _mm256_srli_epi32(c, 8), h10 = _mm256_srli_epi32(c, 16), h11 = _mm256_srli_epi32(c, 24);
        __m256 a = grad2_8(c, x, y), b = grad2_8(h10, x1, y), cc = grad2_8(h01, x, y1), d = grad2_8(h11, x1, y1);
        if (value) _mm256_storeu_ps(value + i, _mm256_mul_ps(scale, lerp8(v, lerp8(u, a, b), lerp8(u, cc, d))));
        if (gradient) {
            __m256 G[4][2];
            gvec2_8(c, G[0]), gvec2_8(h10, G[1]), gvec2_8(h01, G[2]), gvec2_8(h11, G[3]);
            __m256 g[2];
            for (int k = 0; k < 2; ++k) g[k] = lerp8(v, lerp8(u, G[0][k], G[1][k]), lerp8(u, G[2][k], G[3][k]));
            __m256 du = dfade8(x), dv = dfade8(y);
            g[0] = _mm256_mul_ps(scale, _mm256_add_ps(_mm256_mul_ps(du, lerp8(v, _mm256_sub_ps(b, a), _mm256_sub_ps(d, cc))), g[0]));
            g[1] = _mm256_mul_ps(scale, _mm256_add_ps(_mm256_mul_ps(dv, lerp8(u, _mm256_sub_ps(cc, a), _mm256_sub_ps(d, b))), g[1]));
            store_interleaved8(gradient + 2 * i, g, 2);
        }
    }
    udm1_side_end256_ps(side, checked);
    return i;
}

size_t udm1_noise_eval_group_f32(const udm1_noise *n, uint32_t dims, const float *const *axes, size_t stride,
                                 const float *value, const float *gradient)
{
    (void)axes, (void)value, (void)gradient;
    if (n->kind != UDM1_NOISE_IMPROVED || n->period[0] || n->period[1] || n->period[2]) return 0;
    if (dims < 2 || dims > 3 || stride > (1u << 26)) return 0; /* (a gather's offsets must fit an int) */
    return udm1_isa_vbmi() ? 16 : udm1_isa_level() >= UDM1_ISA_AVX2 ? 8 : 0;
}

size_t udm1_noise_eval_fast_f32(const udm1_noise *n, uint32_t dims, const float *const *axes, size_t stride,
                                size_t count, float *value, float *gradient, udm1_side_check *side)
{
    udm1_side_check none = {{NULL}, 0, 0, 0, 0};
    if (!side) side = &none;
    size_t group = udm1_noise_eval_group_f32(n, dims, axes, stride, value, gradient);
    if (group == 16)
        return dims == 3 ? noise3_avx512(n, axes, stride, count, value, gradient, side)
                         : noise2_avx512(n, axes, stride, count, value, gradient, side);
    if (group == 8) /* (AVX-512 without VBMI takes the AVX2 kernel) */
        return dims == 3 ? noise3_avx2(n, axes, stride, count, value, gradient, side)
                         : noise2_avx2(n, axes, stride, count, value, gradient, side);
    return 0;
}

#elif !defined(UDM1_HAVE_NEON_KERNELS) /* (noise_neon_f32.c has them) */
size_t udm1_noise_eval_group_f32(const udm1_noise *n, uint32_t dims, const float *const *axes, size_t stride,
                                 const float *value, const float *gradient)
{
    (void)n, (void)dims, (void)axes, (void)stride, (void)value, (void)gradient;
    return 0;
}

size_t udm1_noise_eval_fast_f32(const udm1_noise *n, uint32_t dims, const float *const *axes, size_t stride,
                                size_t count, float *value, float *gradient, udm1_side_check *side)
{
    (void)n, (void)dims, (void)axes, (void)stride, (void)count, (void)value, (void)gradient, (void)side;
    return 0;
}
#endif
