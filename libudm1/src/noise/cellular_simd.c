/* cellular_simd.c - the cellular noise on 16 points at a time with AVX-512 VBMI (8 with AVX2), in float and double.
 * The 3^dims cells around the points are hashed 16 points x 4 cells at a time: the permutation and the
 * three tables of 8-bit feature offsets are held in registers (four each) and looked up 64 bytes at a
 * time (perm[perm[perm[X] + Y] + Z] with byte additions, the permutation being periodic in 256). Each
 * cell's vector v = fma(c1, b, K), its power sum and the min/max network keeping the k smallest are the
 * scalar search's operations (noise/cellular_impl.h), so the same values. The scalar search is exact by
 * visiting further shells while they could hold a nearer point; here a lane whose next shell could
 * (rare: a feature point may lie anywhere in its cell) is recomputed by that scalar search, so every
 * value is the exact one, bit for bit. Metrics Euclidean, Manhattan and Chebyshev; Minkowski is left to
 * the scalar code. Processors with AVX2 and FMA but not AVX-512 VBMI (or UDM1_ISA=avx2) take the AVX2
 * kernels below, on 8 points at a time, with the same arithmetic. */
#include "core/isa.h"
#include "noise/noise_tables.h"

#include <math.h>
#include <stdlib.h>

#if defined(UDM1_HAVE_ISA_KERNELS)
#include <immintrin.h>

#include "noise/byte_table.h"
#include "noise/strided_loads.h"

#define REAL double
#define R(f) f##_f64
#define RT(f) f##_f64
#define RF(fn) fn
#include "noise/cellular_impl.h"
#undef REAL
#undef R
#undef RT
#undef RF

#define REAL float
#define R(f) f##_f32
#define RT(f) f##_f32
#define RF(fn) fn##f
#include "noise/cellular_impl.h"
#undef REAL
#undef R
#undef RT
#undef RF

#define AVX512 __attribute__((target("avx512f,avx512vl,avx512dq,avx512bw,avx512vbmi,fma")))

AVX512 static inline __m512i pack4(__m128i a, __m128i b, __m128i c, __m128i d)
{
    __m512i z = _mm512_castsi128_si512(a);
    z = _mm512_inserti32x4(z, b, 1);
    z = _mm512_inserti32x4(z, c, 2);
    return _mm512_inserti32x4(z, d, 3);
}

/* The cells around 16 points: ib[a][j] the bytes of the index on axis a of the cells at d = j - 1; out:
 * H[c] the 16 entries of cell c = (dx + 1) + 3 (dy + 1) + 9 (dz + 1), O[a][c] their offsets on axis a. */
typedef struct {
    uint8_t H[28][16];
    uint8_t O[3][28][16];
} cells16;

AVX512 static inline void hash_cells(const udm1_noise *n, const byte_table *perm, uint32_t dims, __m128i ib[3][3],
                                     cells16 *out)
{
    __m512i A = byte_table_lookup(perm, pack4(ib[0][0], ib[0][1], ib[0][2], ib[0][2]));
    __m128i a[3] = {_mm512_castsi512_si128(A), _mm512_extracti32x4_epi32(A, 1), _mm512_extracti32x4_epi32(A, 2)};
    __m128i b[12]; /* (dx, dy) = (j % 3, j / 3): perm[A[dx] + Y[dy]] */
    for (int j = 0; j < 9; ++j) b[j] = _mm_add_epi8(a[j % 3], ib[1][j / 3]);
    b[9] = b[10] = b[11] = b[8];
    __m512i B[3];
    for (int z = 0; z < 3; ++z) B[z] = byte_table_lookup(perm, pack4(b[4 * z], b[4 * z + 1], b[4 * z + 2], b[4 * z + 3]));
    const uint32_t cells = dims == 3 ? 27 : 9;
    __m512i Hz[7];
    int nz;
    if (dims == 2) {
        for (int z = 0; z < 3; ++z) Hz[z] = B[z];
        nz = 3;
    } else {
        _Alignas(64) uint8_t bb[3][64];
        for (int z = 0; z < 3; ++z) _mm512_store_si512((void *)bb[z], B[z]);
        __m128i h[28];
        for (int c = 0; c < 27; ++c) { /* perm[B[dx, dy] + Z[dz]] */
            int j = c % 9;
            h[c] = _mm_add_epi8(_mm_load_si128((const __m128i *)(bb[j / 4] + 16 * (j % 4))), ib[2][c / 9]);
        }
        h[27] = h[26];
        for (int z = 0; z < 7; ++z) Hz[z] = byte_table_lookup(perm, pack4(h[4 * z], h[4 * z + 1], h[4 * z + 2], h[4 * z + 3]));
        nz = 7;
    }
    for (int z = 0; z < nz; ++z) _mm512_storeu_si512((void *)out->H[4 * z], Hz[z]);
    for (uint32_t ax = 0; ax < dims; ++ax) {
        byte_table f = byte_table_load(n->feature[ax]);
        for (int z = 0; z < nz; ++z) _mm512_storeu_si512((void *)out->O[ax][4 * z], byte_table_lookup(&f, Hz[z]));
    }
    (void)cells;
}

/* The lattice index (0..255) of the cells at d = -1, 0, 1 from the floors f of 16 points, as bytes; periodic
 * axes by an exact modulo in double (|f| < 2^31: the caller checks). */
AVX512 static inline void index_bytes(__m512i i0, uint32_t period, __m128i out[3])
{
    const __m512i mask = _mm512_set1_epi32(255);
    __m512i m, p;
    if (period) {
        __m512i P = _mm512_set1_epi32((int)period), one = _mm512_set1_epi32(1), zero = _mm512_setzero_si512();
        m = _mm512_mask_blend_epi32(_mm512_cmpeq_epi32_mask(i0, zero), _mm512_sub_epi32(i0, one),
                                    _mm512_sub_epi32(P, one));
        p = _mm512_add_epi32(i0, one);
        p = _mm512_mask_blend_epi32(_mm512_cmpeq_epi32_mask(p, P), p, zero);
    } else {
        m = _mm512_sub_epi32(i0, _mm512_set1_epi32(1));
        p = _mm512_add_epi32(i0, _mm512_set1_epi32(1));
    }
    out[0] = _mm512_cvtepi32_epi8(_mm512_and_si512(m, mask));
    out[1] = _mm512_cvtepi32_epi8(_mm512_and_si512(i0, mask));
    out[2] = _mm512_cvtepi32_epi8(_mm512_and_si512(p, mask));
}

/* f mod P for 8 integral doubles |f| < 2^31, exactly: q = floor(f / P) may be one off, m = f - q P is exact */
AVX512 static inline __m256i mod8(__m512d f, uint32_t period)
{
    __m512d P = _mm512_set1_pd((double)period);
    __m512d q = _mm512_roundscale_pd(_mm512_div_pd(f, P), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    __m512d m = _mm512_sub_pd(f, _mm512_mul_pd(q, P));
    m = _mm512_mask_add_pd(m, _mm512_cmp_pd_mask(m, _mm512_setzero_pd(), _CMP_LT_OQ), m, P);
    m = _mm512_mask_sub_pd(m, _mm512_cmp_pd_mask(m, P, _CMP_GE_OQ), m, P);
    return _mm512_cvttpd_epi32(m);
}

/* ---- float: 16 lanes ---- */

/* The distance's power of the metric (Euclidean: squared; Manhattan: sum of |v|; Chebyshev: max of |v|) over
 * 2 or 3 components, one copy per vector type: NAME(v, dims, metric). */
#define CELLULAR_POWER(NAME, TARGET, V, FMADD, MUL, ADD, MAX, ABS)                                           \
    TARGET static inline V NAME(const V *v, uint32_t dims, uint32_t metric)                                \
    {                                                                                                       \
        V s;                                                                                                \
        if (metric == UDM1_CELLULAR_EUCLIDEAN) {                                                            \
            s = FMADD(v[1], v[1], MUL(v[0], v[0]));                                                         \
            if (dims == 3) s = FMADD(v[2], v[2], s);                                                        \
        } else if (metric == UDM1_CELLULAR_MANHATTAN) {                                                     \
            s = ADD(ABS(v[0]), ABS(v[1]));                                                                  \
            if (dims == 3) s = ADD(s, ABS(v[2]));                                                           \
        } else {                                                                                            \
            s = MAX(ABS(v[0]), ABS(v[1]));                                                                  \
            if (dims == 3) s = MAX(s, ABS(v[2]));                                                           \
        }                                                                                                   \
        return s;                                                                                           \
    }

/* The kernel NAME: KERNEL compiled for 2 or 3 dimensions, Euclidean or any metric (one copy of each) */
#define CELLULAR_DISPATCH(NAME, TARGET, KERNEL, REAL)                                                          \
    TARGET __attribute__((noinline)) static size_t NAME(const udm1_noise *n, const udm1_cellular_params *p,       \
                                                        uint32_t dims, const REAL *const *axes, size_t stride,    \
                                                        size_t count, REAL *out)                                  \
    {                                                                                                           \
        const uint32_t metric = p->metric == UDM1_CELLULAR_EUCLIDEAN ? UDM1_CELLULAR_EUCLIDEAN : UINT32_MAX;    \
        if (dims == 3)                                                                                          \
            return metric == UINT32_MAX ? KERNEL(n, p, 3, UINT32_MAX, axes, stride, count, out)                  \
                                        : KERNEL(n, p, 3, UDM1_CELLULAR_EUCLIDEAN, axes, stride, count, out);    \
        return metric == UINT32_MAX ? KERNEL(n, p, 2, UINT32_MAX, axes, stride, count, out)                      \
                                    : KERNEL(n, p, 2, UDM1_CELLULAR_EUCLIDEAN, axes, stride, count, out);        \
    }

CELLULAR_POWER(power16, AVX512, __m512, _mm512_fmadd_ps, _mm512_mul_ps, _mm512_add_ps, _mm512_max_ps, _mm512_abs_ps)


AVX512 static inline __m512 gap16(__m512 K, __m512 c1, __m512 zero) /* axis_gap */
{
    __m512 top = _mm512_fmadd_ps(c1, _mm512_set1_ps(255.0f), K);
    __m512 g = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(top, zero, _CMP_LT_OQ), zero, _mm512_sub_ps(zero, top));
    return _mm512_mask_blend_ps(_mm512_cmp_ps_mask(K, zero, _CMP_GT_OQ), g, K);
}

AVX512 static inline __m512 root16(__m512 F, uint32_t metric)
{
    return metric == UDM1_CELLULAR_EUCLIDEAN ? _mm512_sqrt_ps(F) : F;
}

/* specialized as the AVX2 kernels (cellular_f32_avx2_k) */
AVX512 static inline __attribute__((always_inline)) size_t cellular_f32_k(const udm1_noise *n,
                                                                        const udm1_cellular_params *p,
                                                                        const uint32_t dims,
                                                                        const uint32_t metric_k,
                                                                        const float *const *axes, size_t stride,
                                                                        size_t count, float *out)
{
    cellular_setup_f32 u;
    const uint32_t k = p->output == UDM1_CELLULAR_F3 ? 3 : (p->output == UDM1_CELLULAR_F1 || p->output == UDM1_CELLULAR_CELL) ? 1 : 2;
    cellular_setup_init_f32(&u, n, dims, p->metric, k, p->jitter, p->exponent);
    const uint32_t metric = metric_k == UINT32_MAX ? u.metric : metric_k;
    const byte_table perm = byte_table_load(n->perm);
    const strided_loads L = strided_loads_init(stride, 16);
    const __m512 c0 = _mm512_set1_ps(u.c0), c1 = _mm512_set1_ps(u.c1), zero = _mm512_setzero_ps();
    const __m512 inf = _mm512_set1_ps(INFINITY), margin = _mm512_set1_ps(0x1p-20f);
    const int want_cell = p->output == UDM1_CELLULAR_CELL;
    const uint32_t cells = dims == 3 ? 27 : 9;
    _Alignas(64) cells16 C;
    size_t i = 0;
    for (; i + 16 <= count; i += 16) {
        __m512 x[3], t[3], K[3][3];
        __m128i ib[3][3];
        int ok = 1;
        for (uint32_t a = 0; a < dims; ++a) {
            x[a] = strided_load16(&L, axes[a] + i * stride);
            if (_mm512_fpclass_ps_mask(x[a], 0x01 | 0x08 | 0x10 | 0x80)) ok = 0;
        }
        if (!ok) break;
        for (uint32_t a = 0; a < dims && ok; ++a) {
            __m512 f = _mm512_roundscale_ps(x[a], _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
            t[a] = _mm512_add_ps(_mm512_sub_ps(x[a], f), zero);
            __m512i i0;
            if (u.period[a]) {
                if (_mm512_cmp_ps_mask(_mm512_abs_ps(f), _mm512_set1_ps(0x1p31f), _CMP_GE_OQ)) ok = 0;
                __m512d lo = _mm512_cvtps_pd(_mm512_castps512_ps256(f));
                __m512d hi = _mm512_cvtps_pd(_mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(f), 1)));
                i0 = _mm512_inserti64x4(_mm512_castsi256_si512(mod8(lo, u.period[a])), mod8(hi, u.period[a]), 1);
            } else {
                i0 = _mm512_cvttps_epi32(f); /* past 2^31: 0x80000000, and f a multiple of 256 */
            }
            index_bytes(i0, u.period[a], ib[a]);
            for (int j = 0; j < 3; ++j) K[a][j] = _mm512_sub_ps(c0, _mm512_sub_ps(t[a], _mm512_set1_ps((float)(j - 1))));
        }
        if (!ok) break; /* a periodic coordinate past 2^31: the scalar code */
        if (dims == 2) ib[2][0] = ib[2][1] = ib[2][2] = _mm_setzero_si128();
        hash_cells(n, &perm, dims, ib, &C);
        __m512 F0 = inf, F1 = inf, F2 = inf;
        __m512i near = _mm512_set1_epi32(256);
#pragma GCC unroll 27
        for (uint32_t c = 0; c < cells; ++c) {
            const int d[3] = {(int)(c % 3), (int)(c / 3 % 3), (int)(c / 9)};
            __m512 v[3] = {zero, zero, zero};
            for (uint32_t a = 0; a < dims; ++a) {
                __m512 b = _mm512_cvtepi32_ps(_mm512_cvtepu8_epi32(_mm_load_si128((const __m128i *)C.O[a][c])));
                v[a] = _mm512_fmadd_ps(c1, b, K[a][d[a]]);
            }
            __m512 D = power16(v, dims, metric);
            if (want_cell) {
                __m512i h = _mm512_cvtepu8_epi32(_mm_load_si128((const __m128i *)C.H[c]));
                __mmask16 m = _mm512_cmp_ps_mask(D, F0, _CMP_LT_OQ) |
                              (_mm512_cmp_ps_mask(D, F0, _CMP_EQ_OQ) & _mm512_cmplt_epi32_mask(h, near));
                near = _mm512_mask_blend_epi32(m, near, h);
            }
            __m512 lo = _mm512_min_ps(F0, D), hi = _mm512_max_ps(F0, D);
            F0 = lo;
            if (k >= 2) {
                lo = _mm512_min_ps(F1, hi), hi = _mm512_max_ps(F1, hi);
                F1 = lo;
                if (k == 3) F2 = _mm512_min_ps(F2, hi);
            }
        }
        /* lanes whose next shell could hold one of the k nearest: the scalar search */
        __m512 gap = inf;
        for (uint32_t a = 0; a < dims; ++a) {
            gap = _mm512_min_ps(gap, gap16(_mm512_sub_ps(c0, _mm512_sub_ps(t[a], _mm512_set1_ps(2.0f))), c1, zero));
            gap = _mm512_min_ps(gap, gap16(_mm512_sub_ps(c0, _mm512_add_ps(t[a], _mm512_set1_ps(2.0f))), c1, zero));
        }
        __m512 g3[3] = {gap, zero, zero};
        __m512 bound = power16(g3, dims, metric), worst = k == 1 ? F0 : (k == 2 ? F1 : F2);
        __mmask16 redo = _mm512_cmp_ps_mask(bound, _mm512_add_ps(worst, _mm512_mul_ps(worst, margin)), _CMP_LE_OQ);
        __m512 r;
        switch (p->output) {
        case UDM1_CELLULAR_F1: r = root16(F0, metric); break;
        case UDM1_CELLULAR_F2: r = root16(F1, metric); break;
        case UDM1_CELLULAR_F3: r = root16(F2, metric); break;
        case UDM1_CELLULAR_F2_MINUS_F1: r = _mm512_sub_ps(root16(F1, metric), root16(F0, metric)); break;
        default: r = _mm512_div_ps(_mm512_cvtepi32_ps(near), _mm512_set1_ps(255.0f)); break;
        }
        _mm512_storeu_ps(out + i, r);
        while (redo) {
            int l = __builtin_ctz(redo);
            redo &= (__mmask16)(redo - 1);
            float c[3] = {0, 0, 0};
            for (uint32_t a = 0; a < dims; ++a) c[a] = axes[a][(i + (size_t)l) * stride];
            nearest3_f32 s;
            cellular_search_f32(n, &u, c, &s);
            out[i + (size_t)l] = cellular_output_f32(&s, &u, p->output);
        }
    }
    return i;
}

CELLULAR_DISPATCH(cellular_f32, AVX512, cellular_f32_k, float)

/* ---- double: 16 points, the arithmetic in two halves of 8 lanes ---- */

CELLULAR_POWER(power8, AVX512, __m512d, _mm512_fmadd_pd, _mm512_mul_pd, _mm512_add_pd, _mm512_max_pd, _mm512_abs_pd)


AVX512 static inline __m512d gap8(__m512d K, __m512d c1, __m512d zero)
{
    __m512d top = _mm512_fmadd_pd(c1, _mm512_set1_pd(255.0), K);
    __m512d g = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(top, zero, _CMP_LT_OQ), zero, _mm512_sub_pd(zero, top));
    return _mm512_mask_blend_pd(_mm512_cmp_pd_mask(K, zero, _CMP_GT_OQ), g, K);
}

AVX512 static inline __m512d root8(__m512d F, uint32_t metric)
{
    return metric == UDM1_CELLULAR_EUCLIDEAN ? _mm512_sqrt_pd(F) : F;
}

/* specialized as the AVX2 kernels (cellular_f64_avx2_k) */
AVX512 static inline __attribute__((always_inline)) size_t cellular_f64_k(const udm1_noise *n,
                                                                        const udm1_cellular_params *p,
                                                                        const uint32_t dims,
                                                                        const uint32_t metric_k,
                                                                        const double *const *axes, size_t stride,
                                                                        size_t count, double *out)
{
    cellular_setup_f64 u;
    const uint32_t k = p->output == UDM1_CELLULAR_F3 ? 3 : (p->output == UDM1_CELLULAR_F1 || p->output == UDM1_CELLULAR_CELL) ? 1 : 2;
    cellular_setup_init_f64(&u, n, dims, p->metric, k, p->jitter, p->exponent);
    const uint32_t metric = metric_k == UINT32_MAX ? u.metric : metric_k;
    const byte_table perm = byte_table_load(n->perm);
    const strided_loads L = strided_loads_init(stride, 8);
    const __m512d c0 = _mm512_set1_pd(u.c0), c1 = _mm512_set1_pd(u.c1), zero = _mm512_setzero_pd();
    const __m512d inf = _mm512_set1_pd(INFINITY), margin = _mm512_set1_pd(0x1p-20);
    const int want_cell = p->output == UDM1_CELLULAR_CELL;
    const uint32_t cells = dims == 3 ? 27 : 9;
    _Alignas(64) cells16 C;
    size_t i = 0;
    for (; i + 16 <= count; i += 16) {
        __m512d x[3][2], t[3][2], K[3][3][2];
        __m128i ib[3][3];
        int ok = 1;
        for (uint32_t a = 0; a < dims; ++a)
            for (int hf = 0; hf < 2; ++hf) {
                x[a][hf] = strided_load8(&L, axes[a] + (i + 8 * (size_t)hf) * stride);
                if (_mm512_fpclass_pd_mask(x[a][hf], 0x01 | 0x08 | 0x10 | 0x80)) ok = 0;
            }
        if (!ok) break;
        for (uint32_t a = 0; a < dims && ok; ++a) {
            __m256i ih[2];
            for (int hf = 0; hf < 2; ++hf) {
                __m512d f = _mm512_roundscale_pd(x[a][hf], _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
                t[a][hf] = _mm512_add_pd(_mm512_sub_pd(x[a][hf], f), zero);
                if (u.period[a]) {
                    if (_mm512_cmp_pd_mask(_mm512_abs_pd(f), _mm512_set1_pd(0x1p31), _CMP_GE_OQ)) ok = 0;
                    ih[hf] = mod8(f, u.period[a]);
                } else { /* exact below 2^63; past it 0x8000000000000000 and f a multiple of 256 */
                    ih[hf] = _mm512_cvtepi64_epi32(_mm512_and_si512(_mm512_cvttpd_epi64(f), _mm512_set1_epi64(255)));
                }
                for (int j = 0; j < 3; ++j)
                    K[a][j][hf] = _mm512_sub_pd(c0, _mm512_sub_pd(t[a][hf], _mm512_set1_pd((double)(j - 1))));
            }
            index_bytes(_mm512_inserti64x4(_mm512_castsi256_si512(ih[0]), ih[1], 1), u.period[a], ib[a]);
        }
        if (!ok) break;
        if (dims == 2) ib[2][0] = ib[2][1] = ib[2][2] = _mm_setzero_si128();
        hash_cells(n, &perm, dims, ib, &C);
        __mmask16 redo = 0;
        for (int hf = 0; hf < 2; ++hf) {
            __m512d F0 = inf, F1 = inf, F2 = inf;
            __m256i near = _mm256_set1_epi32(256);
#pragma GCC unroll 27
            for (uint32_t c = 0; c < cells; ++c) {
                const int d[3] = {(int)(c % 3), (int)(c / 3 % 3), (int)(c / 9)};
                __m512d v[3] = {zero, zero, zero};
                for (uint32_t a = 0; a < dims; ++a) {
                    __m128i bytes = _mm_loadl_epi64((const __m128i *)(C.O[a][c] + 8 * hf));
                    __m512d b = _mm512_cvtepi32_pd(_mm256_cvtepu8_epi32(bytes));
                    v[a] = _mm512_fmadd_pd(c1, b, K[a][d[a]][hf]);
                }
                __m512d D = power8(v, dims, metric);
                if (want_cell) {
                    __m256i h = _mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i *)(C.H[c] + 8 * hf)));
                    __mmask8 m = _mm512_cmp_pd_mask(D, F0, _CMP_LT_OQ) |
                                 (_mm512_cmp_pd_mask(D, F0, _CMP_EQ_OQ) & _mm256_cmplt_epi32_mask(h, near));
                    near = _mm256_mask_blend_epi32(m, near, h);
                }
                __m512d lo = _mm512_min_pd(F0, D), hi = _mm512_max_pd(F0, D);
                F0 = lo;
                if (k >= 2) {
                    lo = _mm512_min_pd(F1, hi), hi = _mm512_max_pd(F1, hi);
                    F1 = lo;
                    if (k == 3) F2 = _mm512_min_pd(F2, hi);
                }
            }
            __m512d gap = inf;
            for (uint32_t a = 0; a < dims; ++a) {
                gap = _mm512_min_pd(gap, gap8(_mm512_sub_pd(c0, _mm512_sub_pd(t[a][hf], _mm512_set1_pd(2.0))), c1, zero));
                gap = _mm512_min_pd(gap, gap8(_mm512_sub_pd(c0, _mm512_add_pd(t[a][hf], _mm512_set1_pd(2.0))), c1, zero));
            }
            __m512d g3[3] = {gap, zero, zero};
            __m512d bound = power8(g3, dims, metric), worst = k == 1 ? F0 : (k == 2 ? F1 : F2);
            redo |= (__mmask16)((unsigned)_mm512_cmp_pd_mask(bound, _mm512_add_pd(worst, _mm512_mul_pd(worst, margin)),
                                                             _CMP_LE_OQ) << (8 * hf));
            __m512d r;
            switch (p->output) {
            case UDM1_CELLULAR_F1: r = root8(F0, metric); break;
            case UDM1_CELLULAR_F2: r = root8(F1, metric); break;
            case UDM1_CELLULAR_F3: r = root8(F2, metric); break;
            case UDM1_CELLULAR_F2_MINUS_F1: r = _mm512_sub_pd(root8(F1, metric), root8(F0, metric)); break;
            default: r = _mm512_div_pd(_mm512_cvtepi32_pd(near), _mm512_set1_pd(255.0)); break;
            }
            _mm512_storeu_pd(out + i + 8 * (size_t)hf, r);
        }
        while (redo) {
            int l = __builtin_ctz(redo);
            redo &= (__mmask16)(redo - 1);
            double c[3] = {0, 0, 0};
            for (uint32_t a = 0; a < dims; ++a) c[a] = axes[a][(i + (size_t)l) * stride];
            nearest3_f64 s;
            cellular_search_f64(n, &u, c, &s);
            out[i + (size_t)l] = cellular_output_f64(&s, &u, p->output);
        }
    }
    return i;
}

CELLULAR_DISPATCH(cellular_f64, AVX512, cellular_f64_k, double)

/* ---- AVX2 + FMA: 8 points ----
 * The cells' hashes by gathers: perm[X + dx] (3), perm[. + Y + dy] (9 in 3D) and the last level from the
 * table cell4 (noise_tables.h), whose word holds a cell's hash and its feature point's three offsets, so
 * that each cell costs one gather. The arithmetic is the AVX-512 kernels' (the scalar search's
 * operations), in 8 floats or two halves of 4 doubles; lanes whose next shell could hold one of the k
 * nearest are redone by the scalar search. */
#define AVX2 __attribute__((target("avx2,fma")))

/* The lattice index (0..255) of the cells at d = -1, 0, 1 of 8 points from their indices m, which are
 * in 0..P-1 on a periodic axis (P its period) and any integer otherwise */
AVX2 static inline void index8(__m256i m, uint32_t period, __m256i out[3])
{
    const __m256i mask = _mm256_set1_epi32(255), one = _mm256_set1_epi32(1);
    __m256i lo = _mm256_sub_epi32(m, one), hi = _mm256_add_epi32(m, one);
    if (period) {
        __m256i P = _mm256_set1_epi32((int)period);
        lo = _mm256_blendv_epi8(lo, _mm256_sub_epi32(P, one), _mm256_cmpeq_epi32(m, _mm256_setzero_si256()));
        hi = _mm256_andnot_si256(_mm256_cmpeq_epi32(hi, P), hi);
    }
    out[0] = _mm256_and_si256(lo, mask), out[1] = _mm256_and_si256(m, mask), out[2] = _mm256_and_si256(hi, mask);
}

/* f mod P for 4 integral doubles |f| < 2^31, exactly (as cell_axis: q = floor(f / P) may be one off) */
AVX2 static inline __m128i mod4(__m256d f, uint32_t period)
{
    __m256d P = _mm256_set1_pd((double)period), zero = _mm256_setzero_pd();
    __m256d m = _mm256_sub_pd(f, _mm256_mul_pd(_mm256_floor_pd(_mm256_div_pd(f, P)), P));
    m = _mm256_add_pd(m, _mm256_and_pd(_mm256_cmp_pd(m, zero, _CMP_LT_OQ), P));
    m = _mm256_sub_pd(m, _mm256_and_pd(_mm256_cmp_pd(m, P, _CMP_GE_OQ), P));
    return _mm256_cvttpd_epi32(m);
}

/* perm[base + d] for d = -1, 0, 1 of 8 points into h[0..2] (h[j] at stride `step`), base + ib[j] the three
 * indices: on an axis without a period ib[j] = (m - 1 + j) mod 256, so one load of the table `triple` at
 * base + ib[0] holds all three (its indices are mod 256 as perm's); on a periodic axis they wrap at the
 * period, one load each. */
AVX2 static inline void step8(const udm1_noise *n, __m256i base, const __m256i ib[3], int periodic, __m256i *h,
                              int step)
{
    const __m256i m255 = _mm256_set1_epi32(255);
    if (periodic) {
        for (int j = 0; j < 3; ++j)
            h[j * step] = _mm256_and_si256(_mm256_i32gather_epi32((const int *)n->cell4, _mm256_add_epi32(base, ib[j]), 4), m255);
        return;
    }
    __m256i t = _mm256_i32gather_epi32((const int *)n->triple, _mm256_add_epi32(base, ib[0]), 4);
    h[0] = _mm256_and_si256(t, m255);
    h[step] = _mm256_and_si256(_mm256_srli_epi32(t, 8), m255);
    h[2 * step] = _mm256_srli_epi32(t, 16);
}

/* The words cell4[...] of the 3^dims cells around 8 points (c = (dx + 1) + 3 (dy + 1) + 9 (dz + 1)); period[a]
 * the axes' periods (0: none) */
AVX2 static inline void cells8(const udm1_noise *n, uint32_t dims, const uint32_t period[3], const __m256i ib[3][3],
                               __m256i W[27])
{
    const int *c4 = (const int *)n->cell4;
    __m256i a[3], b[9];
    step8(n, _mm256_setzero_si256(), ib[0], period[0] != 0, a, 1);
    if (dims == 2) {
        for (int c = 0; c < 9; ++c) W[c] = _mm256_i32gather_epi32(c4, _mm256_add_epi32(a[c % 3], ib[1][c / 3]), 4);
        return;
    }
    for (int j = 0; j < 3; ++j) step8(n, a[j], ib[1], period[1] != 0, &b[j], 3); /* b[dx + 3 dy] */
    if (period[2]) {
        for (int c = 0; c < 27; ++c) W[c] = _mm256_i32gather_epi32(c4, _mm256_add_epi32(b[c % 9], ib[2][c / 9]), 4);
        return;
    }
    /* z without a period: a column's three cells are cell4[i], cell4[i + 1], cell4[i + 2] at i = b + ib[2][0]; the
     * first two by 64-bit loads (4 lanes a gather), the third by a 32-bit one: 16 elements loaded, not 24 */
    const __m256i evens = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
    for (int c = 0; c < 9; ++c) {
        __m256i i = _mm256_add_epi32(b[c], ib[2][0]);
        __m256i g0 = _mm256_i32gather_epi64((const long long *)c4, _mm256_castsi256_si128(i), 4);
        __m256i g1 = _mm256_i32gather_epi64((const long long *)c4, _mm256_extracti128_si256(i, 1), 4);
        /* g0: lanes 0-3's (cell4[i], cell4[i + 1]) as 32-bit pairs; each split into its words, then joined */
        __m256i s0 = _mm256_permutevar8x32_epi32(g0, evens), s1 = _mm256_permutevar8x32_epi32(g1, evens);
        W[c] = _mm256_permute2x128_si256(s0, s1, 0x20);
        W[c + 9] = _mm256_permute2x128_si256(s0, s1, 0x31);
        W[c + 18] = _mm256_i32gather_epi32(c4, _mm256_add_epi32(i, _mm256_set1_epi32(2)), 4);
    }
}

/* the offset on axis a (0..2) of the cells' feature points in W, as 8 ints */
AVX2 static inline __m256i offset8(__m256i W, uint32_t a)
{
    return _mm256_and_si256(_mm256_srli_epi32(W, 8 * (int)(a + 1)), _mm256_set1_epi32(255));
}

AVX2 static inline __m256 abs8(__m256 x) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), x); }
AVX2 static inline __m256d abs4(__m256d x) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), x); }

CELLULAR_POWER(power8s, AVX2, __m256, _mm256_fmadd_ps, _mm256_mul_ps, _mm256_add_ps, _mm256_max_ps, abs8)

CELLULAR_POWER(power4d, AVX2, __m256d, _mm256_fmadd_pd, _mm256_mul_pd, _mm256_add_pd, _mm256_max_pd, abs4)


AVX2 static inline __m256 gap8s(__m256 K, __m256 c1, __m256 zero) /* axis_gap */
{
    __m256 top = _mm256_fmadd_ps(c1, _mm256_set1_ps(255.0f), K);
    __m256 g = _mm256_blendv_ps(zero, _mm256_sub_ps(zero, top), _mm256_cmp_ps(top, zero, _CMP_LT_OQ));
    return _mm256_blendv_ps(g, K, _mm256_cmp_ps(K, zero, _CMP_GT_OQ));
}

AVX2 static inline __m256d gap4d(__m256d K, __m256d c1, __m256d zero)
{
    __m256d top = _mm256_fmadd_pd(c1, _mm256_set1_pd(255.0), K);
    __m256d g = _mm256_blendv_pd(zero, _mm256_sub_pd(zero, top), _mm256_cmp_pd(top, zero, _CMP_LT_OQ));
    return _mm256_blendv_pd(g, K, _mm256_cmp_pd(K, zero, _CMP_GT_OQ));
}

AVX2 static inline __m256 root8s(__m256 F, uint32_t metric)
{
    return metric == UDM1_CELLULAR_EUCLIDEAN ? _mm256_sqrt_ps(F) : F;
}

AVX2 static inline __m256d root4d(__m256d F, uint32_t metric)
{
    return metric == UDM1_CELLULAR_EUCLIDEAN ? _mm256_sqrt_pd(F) : F;
}

AVX2 static inline int finite8s(__m256 x)
{
    return _mm256_movemask_ps(_mm256_cmp_ps(abs8(x), _mm256_set1_ps(INFINITY), _CMP_LT_OQ)) == 0xFF;
}

AVX2 static inline int finite4d(__m256d x)
{
    return _mm256_movemask_pd(_mm256_cmp_pd(abs4(x), _mm256_set1_pd(INFINITY), _CMP_LT_OQ)) == 0xF;
}

/* specialized by the compiler for 2 and 3 dimensions and the Euclidean metric (metric_k; UINT32_MAX: any, read
 * from p), its loop over the cells unrolled: each cell's axes and components known where it is compiled */
AVX2 static inline __attribute__((always_inline)) size_t cellular_f32_avx2_k(const udm1_noise *n,
                                                                             const udm1_cellular_params *p,
                                                                             const uint32_t dims,
                                                                             const uint32_t metric_k,
                                                                             const float *const *axes, size_t stride,
                                                                             size_t count, float *out)
{
    cellular_setup_f32 u;
    const uint32_t k = p->output == UDM1_CELLULAR_F3 ? 3 : (p->output == UDM1_CELLULAR_F1 || p->output == UDM1_CELLULAR_CELL) ? 1 : 2;
    cellular_setup_init_f32(&u, n, dims, p->metric, k, p->jitter, p->exponent);
    const uint32_t metric = metric_k == UINT32_MAX ? u.metric : metric_k;
    const __m256i vindex = _mm256_mullo_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), _mm256_set1_epi32((int)stride));
    const __m256 c0 = _mm256_set1_ps(u.c0), c1 = _mm256_set1_ps(u.c1), zero = _mm256_setzero_ps();
    const __m256 inf = _mm256_set1_ps(INFINITY), margin = _mm256_set1_ps(0x1p-20f);
    const int want_cell = p->output == UDM1_CELLULAR_CELL;
    const uint32_t cells = dims == 3 ? 27 : 9;
    size_t i = 0;
    for (; i + 8 <= count; i += 8) {
        __m256 x[3], t[3], K[3][3];
        __m256i ib[3][3];
        int ok = 1;
        for (uint32_t a = 0; a < dims; ++a) {
            const float *q = axes[a] + i * stride;
            x[a] = stride == 1 ? _mm256_loadu_ps(q) : _mm256_i32gather_ps(q, vindex, 4);
            ok &= finite8s(x[a]);
        }
        if (!ok) break; /* the caller reports it */
        for (uint32_t a = 0; a < dims && ok; ++a) {
            __m256 f = _mm256_floor_ps(x[a]);
            t[a] = _mm256_add_ps(_mm256_sub_ps(x[a], f), zero);
            __m256i m;
            if (u.period[a]) {
                if (_mm256_movemask_ps(_mm256_cmp_ps(abs8(f), _mm256_set1_ps(0x1p31f), _CMP_GE_OQ))) ok = 0;
                __m128i lo = mod4(_mm256_cvtps_pd(_mm256_castps256_ps128(f)), u.period[a]);
                __m128i hi = mod4(_mm256_cvtps_pd(_mm256_extractf128_ps(f, 1)), u.period[a]);
                m = _mm256_set_m128i(hi, lo);
            } else {
                m = _mm256_cvttps_epi32(f); /* past 2^31: 0x80000000, and f a multiple of 256 */
            }
            index8(m, u.period[a], ib[a]);
            for (int j = 0; j < 3; ++j) K[a][j] = _mm256_sub_ps(c0, _mm256_sub_ps(t[a], _mm256_set1_ps((float)(j - 1))));
        }
        if (!ok) break; /* a periodic coordinate past 2^31: the scalar code */
        __m256i W[27];
        cells8(n, dims, u.period, (const __m256i(*)[3])ib, W);
        __m256 F0 = inf, F1 = inf, F2 = inf;
        __m256i near = _mm256_set1_epi32(256);
#pragma GCC unroll 27
        for (uint32_t c = 0; c < cells; ++c) {
            const int d[3] = {(int)(c % 3), (int)(c / 3 % 3), (int)(c / 9)};
            __m256 v[3] = {zero, zero, zero};
            for (uint32_t a = 0; a < dims; ++a)
                v[a] = _mm256_fmadd_ps(c1, _mm256_cvtepi32_ps(offset8(W[c], a)), K[a][d[a]]);
            __m256 D = power8s(v, dims, metric);
            if (want_cell) {
                __m256i h = _mm256_and_si256(W[c], _mm256_set1_epi32(255));
                __m256 m = _mm256_or_ps(_mm256_cmp_ps(D, F0, _CMP_LT_OQ),
                                        _mm256_and_ps(_mm256_cmp_ps(D, F0, _CMP_EQ_OQ),
                                                      _mm256_castsi256_ps(_mm256_cmpgt_epi32(near, h))));
                near = _mm256_blendv_epi8(near, h, _mm256_castps_si256(m));
            }
            __m256 lo = _mm256_min_ps(F0, D), hi = _mm256_max_ps(F0, D);
            F0 = lo;
            if (k >= 2) {
                lo = _mm256_min_ps(F1, hi), hi = _mm256_max_ps(F1, hi);
                F1 = lo;
                if (k == 3) F2 = _mm256_min_ps(F2, hi);
            }
        }
        /* lanes whose next shell could hold one of the k nearest: the scalar search */
        __m256 gap = inf;
        for (uint32_t a = 0; a < dims; ++a) {
            gap = _mm256_min_ps(gap, gap8s(_mm256_sub_ps(c0, _mm256_sub_ps(t[a], _mm256_set1_ps(2.0f))), c1, zero));
            gap = _mm256_min_ps(gap, gap8s(_mm256_sub_ps(c0, _mm256_add_ps(t[a], _mm256_set1_ps(2.0f))), c1, zero));
        }
        __m256 g3[3] = {gap, zero, zero};
        __m256 bound = power8s(g3, dims, metric), worst = k == 1 ? F0 : (k == 2 ? F1 : F2);
        unsigned redo = (unsigned)_mm256_movemask_ps(
            _mm256_cmp_ps(bound, _mm256_add_ps(worst, _mm256_mul_ps(worst, margin)), _CMP_LE_OQ));
        __m256 r;
        switch (p->output) {
        case UDM1_CELLULAR_F1: r = root8s(F0, metric); break;
        case UDM1_CELLULAR_F2: r = root8s(F1, metric); break;
        case UDM1_CELLULAR_F3: r = root8s(F2, metric); break;
        case UDM1_CELLULAR_F2_MINUS_F1: r = _mm256_sub_ps(root8s(F1, metric), root8s(F0, metric)); break;
        default: r = _mm256_div_ps(_mm256_cvtepi32_ps(near), _mm256_set1_ps(255.0f)); break;
        }
        _mm256_storeu_ps(out + i, r);
        while (redo) {
            int l = __builtin_ctz(redo);
            redo &= redo - 1;
            float c[3] = {0, 0, 0};
            for (uint32_t a = 0; a < dims; ++a) c[a] = axes[a][(i + (size_t)l) * stride];
            nearest3_f32 s;
            cellular_search_f32(n, &u, c, &s);
            out[i + (size_t)l] = cellular_output_f32(&s, &u, p->output);
        }
    }
    return i;
}

CELLULAR_DISPATCH(cellular_f32_avx2, AVX2, cellular_f32_avx2_k, float)

/* specialized by the compiler for 2 and 3 dimensions and the Euclidean metric (metric_k; UINT32_MAX: any, read
 * from p), its loop over the cells unrolled: each cell's axes and components known where it is compiled */
AVX2 static inline __attribute__((always_inline)) size_t cellular_f64_avx2_k(const udm1_noise *n,
                                                                             const udm1_cellular_params *p,
                                                                             const uint32_t dims,
                                                                             const uint32_t metric_k,
                                                                             const double *const *axes, size_t stride,
                                                                             size_t count, double *out)
{
    cellular_setup_f64 u;
    const uint32_t k = p->output == UDM1_CELLULAR_F3 ? 3 : (p->output == UDM1_CELLULAR_F1 || p->output == UDM1_CELLULAR_CELL) ? 1 : 2;
    cellular_setup_init_f64(&u, n, dims, p->metric, k, p->jitter, p->exponent);
    const uint32_t metric = metric_k == UINT32_MAX ? u.metric : metric_k;
    const __m128i vindex = _mm_mullo_epi32(_mm_setr_epi32(0, 1, 2, 3), _mm_set1_epi32((int)stride));
    const __m256d c0 = _mm256_set1_pd(u.c0), c1 = _mm256_set1_pd(u.c1), zero = _mm256_setzero_pd();
    const __m256d inf = _mm256_set1_pd(INFINITY), margin = _mm256_set1_pd(0x1p-20);
    const int want_cell = p->output == UDM1_CELLULAR_CELL;
    const uint32_t cells = dims == 3 ? 27 : 9;
    size_t i = 0;
    for (; i + 8 <= count; i += 8) {
        __m256d x[3][2], t[3][2];
        __m256i ib[3][3];
        int ok = 1;
        for (uint32_t a = 0; a < dims; ++a)
            for (int hf = 0; hf < 2; ++hf) {
                const double *q = axes[a] + (i + 4 * (size_t)hf) * stride;
                x[a][hf] = stride == 1 ? _mm256_loadu_pd(q) : _mm256_i32gather_pd(q, vindex, 8);
                ok &= finite4d(x[a][hf]);
            }
        if (!ok) break;
        for (uint32_t a = 0; a < dims && ok; ++a) {
            __m128i mh[2];
            for (int hf = 0; hf < 2; ++hf) {
                __m256d f = _mm256_floor_pd(x[a][hf]);
                t[a][hf] = _mm256_add_pd(_mm256_sub_pd(x[a][hf], f), zero);
                if (u.period[a]) {
                    if (_mm256_movemask_pd(_mm256_cmp_pd(abs4(f), _mm256_set1_pd(0x1p31), _CMP_GE_OQ))) ok = 0;
                    mh[hf] = mod4(f, u.period[a]);
                } else { /* f mod 256, exact for every finite f (the hashes read the low byte) */
                    __m256d m = _mm256_sub_pd(f, _mm256_mul_pd(_mm256_floor_pd(_mm256_mul_pd(f, _mm256_set1_pd(1.0 / 256))),
                                                               _mm256_set1_pd(256.0)));
                    mh[hf] = _mm256_cvttpd_epi32(m);
                }
            }
            index8(_mm256_set_m128i(mh[1], mh[0]), u.period[a], ib[a]);
        }
        if (!ok) break; /* a periodic coordinate past 2^31: the scalar code */
        __m256i W[27];
        cells8(n, dims, u.period, (const __m256i(*)[3])ib, W);
        unsigned redo = 0;
        for (int hf = 0; hf < 2; ++hf) {
            __m256d K[3][3];
            for (uint32_t a = 0; a < dims; ++a)
                for (int j = 0; j < 3; ++j) K[a][j] = _mm256_sub_pd(c0, _mm256_sub_pd(t[a][hf], _mm256_set1_pd((double)(j - 1))));
            __m256d F0 = inf, F1 = inf, F2 = inf;
            __m256i near = _mm256_set1_epi64x(256);
    #pragma GCC unroll 27
        for (uint32_t c = 0; c < cells; ++c) {
                const int d[3] = {(int)(c % 3), (int)(c / 3 % 3), (int)(c / 9)};
                __m128i w = hf ? _mm256_extracti128_si256(W[c], 1) : _mm256_castsi256_si128(W[c]);
                __m256d v[3] = {zero, zero, zero};
                for (uint32_t a = 0; a < dims; ++a) {
                    __m128i b = _mm_and_si128(_mm_srli_epi32(w, 8 * (int)(a + 1)), _mm_set1_epi32(255));
                    v[a] = _mm256_fmadd_pd(c1, _mm256_cvtepi32_pd(b), K[a][d[a]]);
                }
                __m256d D = power4d(v, dims, metric);
                if (want_cell) {
                    __m256i h = _mm256_cvtepu32_epi64(_mm_and_si128(w, _mm_set1_epi32(255)));
                    __m256d m = _mm256_or_pd(_mm256_cmp_pd(D, F0, _CMP_LT_OQ),
                                             _mm256_and_pd(_mm256_cmp_pd(D, F0, _CMP_EQ_OQ),
                                                           _mm256_castsi256_pd(_mm256_cmpgt_epi64(near, h))));
                    near = _mm256_blendv_epi8(near, h, _mm256_castpd_si256(m));
                }
                __m256d lo = _mm256_min_pd(F0, D), hi = _mm256_max_pd(F0, D);
                F0 = lo;
                if (k >= 2) {
                    lo = _mm256_min_pd(F1, hi), hi = _mm256_max_pd(F1, hi);
                    F1 = lo;
                    if (k == 3) F2 = _mm256_min_pd(F2, hi);
                }
            }
            __m256d gap = inf;
            for (uint32_t a = 0; a < dims; ++a) {
                gap = _mm256_min_pd(gap, gap4d(_mm256_sub_pd(c0, _mm256_sub_pd(t[a][hf], _mm256_set1_pd(2.0))), c1, zero));
                gap = _mm256_min_pd(gap, gap4d(_mm256_sub_pd(c0, _mm256_add_pd(t[a][hf], _mm256_set1_pd(2.0))), c1, zero));
            }
            __m256d g3[3] = {gap, zero, zero};
            __m256d bound = power4d(g3, dims, metric), worst = k == 1 ? F0 : (k == 2 ? F1 : F2);
            redo |= (unsigned)_mm256_movemask_pd(
                        _mm256_cmp_pd(bound, _mm256_add_pd(worst, _mm256_mul_pd(worst, margin)), _CMP_LE_OQ))
                    << (4 * hf);
            __m256d r;
            switch (p->output) {
            case UDM1_CELLULAR_F1: r = root4d(F0, metric); break;
            case UDM1_CELLULAR_F2: r = root4d(F1, metric); break;
            case UDM1_CELLULAR_F3: r = root4d(F2, metric); break;
            case UDM1_CELLULAR_F2_MINUS_F1: r = _mm256_sub_pd(root4d(F1, metric), root4d(F0, metric)); break;
            default: { /* near < 2^31: its low 32-bit halves as ints */
                __m128i n32 = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(near, _mm256_setr_epi32(0, 2, 4, 6, 0, 0, 0, 0)));
                r = _mm256_div_pd(_mm256_cvtepi32_pd(n32), _mm256_set1_pd(255.0));
                break;
            }
            }
            _mm256_storeu_pd(out + i + 4 * (size_t)hf, r);
        }
        while (redo) {
            int l = __builtin_ctz(redo);
            redo &= redo - 1;
            double c[3] = {0, 0, 0};
            for (uint32_t a = 0; a < dims; ++a) c[a] = axes[a][(i + (size_t)l) * stride];
            nearest3_f64 s;
            cellular_search_f64(n, &u, c, &s);
            out[i + (size_t)l] = cellular_output_f64(&s, &u, p->output);
        }
    }
    return i;
}

CELLULAR_DISPATCH(cellular_f64_avx2, AVX2, cellular_f64_avx2_k, double)

/* The kernels of the processor: 0 none (the scalar code), 1 AVX2, 2 AVX-512 with VBMI */
static int vector_case(const udm1_cellular_params *p, uint32_t dims, size_t stride)
{
    if (!(p->metric <= UDM1_CELLULAR_CHEBYSHEV && (dims == 2 || dims == 3) && stride <= (1u << 26))) return 0;
    return udm1_isa_vbmi() ? 2 : udm1_isa_level() >= UDM1_ISA_AVX2 ? 1 : 0;
}

size_t udm1_cellular_fast_f64(const udm1_noise *n, const udm1_cellular_params *p, uint32_t dims,
                              const double *const *axes, size_t stride, size_t count, double *out)
{
    switch (vector_case(p, dims, stride)) {
    case 2: return cellular_f64(n, p, dims, axes, stride, count, out);
    case 1: return cellular_f64_avx2(n, p, dims, axes, stride, count, out);
    default: return 0;
    }
}

size_t udm1_cellular_fast_f32(const udm1_noise *n, const udm1_cellular_params *p, uint32_t dims,
                              const float *const *axes, size_t stride, size_t count, float *out)
{
    switch (vector_case(p, dims, stride)) {
    case 2: return cellular_f32(n, p, dims, axes, stride, count, out);
    case 1: return cellular_f32_avx2(n, p, dims, axes, stride, count, out);
    default: return 0;
    }
}

#else
size_t udm1_cellular_fast_f64(const udm1_noise *n, const udm1_cellular_params *p, uint32_t dims,
                              const double *const *axes, size_t stride, size_t count, double *out)
{
    (void)n, (void)p, (void)dims, (void)axes, (void)stride, (void)count, (void)out;
    return 0;
}

size_t udm1_cellular_fast_f32(const udm1_noise *n, const udm1_cellular_params *p, uint32_t dims,
                              const float *const *axes, size_t stride, size_t count, float *out)
{
    (void)n, (void)p, (void)dims, (void)axes, (void)stride, (void)count, (void)out;
    return 0;
}
#endif
