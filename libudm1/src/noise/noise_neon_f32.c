/* noise_neon_f32.c - the float noise of udm1_noise_eval_f32 on 4 points at a time with NEON (64-bit Arm),
 * with the scalar float code's operations in the same order (noise/lattice_impl.h), so the same bits: the
 * exact floor and offset, the quintic fade, Perlin's gradients as selections and sign flips, the nested
 * lerps, and for the gradient the same derivative. Improved noise in 2D and 3D, not periodic; everything
 * else (1D, 4D, classic, periodic) is left to the scalar code. The hashes are read lane by lane from the
 * combined tables hash4 and pair of noise_tables.h (NEON has no gathers): a cell's four column hashes in
 * one load, each column's hashes at z and z + 1 in another. Chosen by core/isa.h ("neon"; UDM1_ISA=baseline
 * leaves the scalar code). Where UDM1_HAVE_NEON_KERNELS is not defined, noise_simd_f32.c defines these
 * functions. */
#include "core/isa.h"
#include "noise/noise_tables.h"

#if defined(UDM1_HAVE_NEON_KERNELS)
#include <arm_neon.h>
#include <math.h>

/* ---- the side check (noise/side_check.h's, with 128-bit vectors): x - x is +0 for a finite x ---- */
static inline uint32x4_t side_step(udm1_side_check *s, uint32x4_t acc)
{
    if (s->steps) {
        --s->steps;
        for (unsigned r = 0; r < s->runs; ++r) {
            const char *p = s->at[r];
            for (unsigned v = 0; v < 4 * s->vectors; ++v) {
                float32x4_t x = vld1q_f32((const float *)(const void *)(p + 16 * v));
                acc = vorrq_u32(acc, vreinterpretq_u32_f32(vsubq_f32(x, x)));
            }
            s->at[r] = p + 64 * (size_t)s->vectors;
        }
    }
    return acc;
}

static inline void side_end(udm1_side_check *s, uint32x4_t acc) { s->bad |= vmaxvq_u32(acc) != 0; }

/* four coordinates at a stride */
static inline float32x4_t load4(const float *p, size_t stride)
{
    if (stride == 1) return vld1q_f32(p);
    float v[4] = {p[0], p[stride], p[2 * stride], p[3 * stride]};
    return vld1q_f32(v);
}

static inline int finite4(float32x4_t x) /* every lane finite */
{
    return vminvq_u32(vcltq_f32(vabsq_f32(x), vdupq_n_f32(INFINITY))) == 0xFFFFFFFFu;
}

/* floor, the offset in the cell (exact, -0 made +0) and the lower corner's index mod 256: from the floor
 * converted where it is below 2^31 in magnitude (exact: a whole number that fits an int32), else 0 (past
 * 2^31 a float is a multiple of 256, as the scalar code's index; the conversion would saturate to
 * 0x7FFFFFFF, whose low byte is not 0) */
static inline float32x4_t axis4(float32x4_t x, int32x4_t *i0)
{
    float32x4_t f = vrndmq_f32(x);
    float32x4_t small = vbslq_f32(vcltq_f32(vabsq_f32(f), vdupq_n_f32(0x1p31f)), f, vdupq_n_f32(0.0f));
    *i0 = vandq_s32(vcvtq_s32_f32(small), vdupq_n_s32(255));
    return vaddq_f32(vsubq_f32(x, f), vdupq_n_f32(0.0f));
}

static inline float32x4_t fade4(float32x4_t t) /* t t t (t (t 6 - 15) + 10) */
{
    float32x4_t a = vmulq_f32(vmulq_f32(t, t), t);
    float32x4_t b = vsubq_f32(vmulq_f32(t, vdupq_n_f32(6.0f)), vdupq_n_f32(15.0f));
    b = vaddq_f32(vmulq_f32(t, b), vdupq_n_f32(10.0f));
    return vmulq_f32(a, b);
}

static inline float32x4_t dfade4(float32x4_t t) /* 30 t t (t (t - 2) + 1) */
{
    float32x4_t a = vmulq_f32(vmulq_f32(vdupq_n_f32(30.0f), t), t);
    float32x4_t b = vaddq_f32(vmulq_f32(t, vsubq_f32(t, vdupq_n_f32(2.0f))), vdupq_n_f32(1.0f));
    return vmulq_f32(a, b);
}

static inline float32x4_t lerp4(float32x4_t t, float32x4_t a, float32x4_t b)
{
    return vaddq_f32(a, vmulq_f32(t, vsubq_f32(b, a)));
}

static inline uint32x4_t mask4(uint32x4_t h, uint32_t bits, uint32_t equal) /* (h & bits) == equal */
{
    return vceqq_u32(vandq_u32(h, vdupq_n_u32(bits)), vdupq_n_u32(equal));
}

static inline float32x4_t flip4(float32x4_t v, uint32x4_t h, uint32_t bit) /* negated where h & bit */
{
    uint32x4_t sign = vandq_u32(vtstq_u32(h, vdupq_n_u32(bit)), vdupq_n_u32(0x80000000u));
    return vreinterpretq_f32_u32(veorq_u32(vreinterpretq_u32_f32(v), sign));
}

/* Perlin's gradient of the hash h (low 4 bits; the others ignored): +-u +-v, and + 0 (a zero +0) */
static inline float32x4_t grad3_4(uint32x4_t h, float32x4_t x, float32x4_t y, float32x4_t z)
{
    uint32x4_t below8 = mask4(h, 8, 0), below4 = mask4(h, 12, 0), is12or14 = mask4(h, 13, 12);
    float32x4_t u = vbslq_f32(below8, x, y);
    float32x4_t v = vbslq_f32(below4, y, vbslq_f32(is12or14, x, z));
    return vaddq_f32(vaddq_f32(flip4(u, h, 1), flip4(v, h, 2)), vdupq_n_f32(0.0f));
}

static inline void gvec3_4(uint32x4_t h, float32x4_t g[3])
{
    uint32x4_t below8 = mask4(h, 8, 0), below4 = mask4(h, 12, 0), is12or14 = mask4(h, 13, 12);
    float32x4_t one = vdupq_n_f32(1.0f), zero = vdupq_n_f32(0.0f);
    float32x4_t su = flip4(one, h, 1), sv = flip4(one, h, 2);
    uint32x4_t v_on_x = vbicq_u32(is12or14, below4), v_on_z = vbicq_u32(vmvnq_u32(is12or14), below4);
    g[0] = vbslq_f32(below8, su, vbslq_f32(v_on_x, sv, zero));
    g[1] = vbslq_f32(below8, vbslq_f32(below4, sv, zero), su);
    g[2] = vbslq_f32(v_on_z, sv, zero);
}

/* noise1234's 2D gradient: +-u +-2v, u = x where h & 4 is 0, else y */
static inline float32x4_t grad2_4(uint32x4_t h, float32x4_t x, float32x4_t y)
{
    uint32x4_t below4 = mask4(h, 4, 0);
    float32x4_t u = vbslq_f32(below4, x, y);
    float32x4_t v = vmulq_f32(vdupq_n_f32(2.0f), vbslq_f32(below4, y, x));
    return vaddq_f32(flip4(u, h, 1), flip4(v, h, 2));
}

static inline void gvec2_4(uint32x4_t h, float32x4_t g[2])
{
    uint32x4_t below4 = mask4(h, 4, 0);
    float32x4_t su = flip4(vdupq_n_f32(1.0f), h, 1), sv = flip4(vdupq_n_f32(2.0f), h, 2);
    g[0] = vbslq_f32(below4, su, sv);
    g[1] = vbslq_f32(below4, sv, su);
}

/* The cell's four column hashes [p[A], p[A1], p[B], p[B1]] (2D: its corner hashes) of each lane. */
static inline uint32x4_t column_hashes(const udm1_noise *n, int32x4_t X0, int32x4_t Y0)
{
    uint32_t at[4], c[4];
    vst1q_u32(at, vreinterpretq_u32_s32(vorrq_s32(vshlq_n_s32(X0, 8), Y0)));
    for (int l = 0; l < 4; ++l) c[l] = n->hash4[at[l]];
    return vld1q_u32(c);
}

/* The hashes at z and z + 1 (low two bytes) of the column hash in byte `byte` of each lane of c. */
static inline uint32x4_t pair_hashes(const udm1_noise *n, uint32x4_t c, const int byte, int32x4_t Z0)
{
    uint32_t at[4], q[4];
    uint32x4_t b = vshlq_u32(c, vdupq_n_s32(-8 * byte)); /* (a negative shift is to the right) */
    if (byte < 3) b = vandq_u32(b, vdupq_n_u32(255));
    vst1q_u32(at, vaddq_u32(b, vreinterpretq_u32_s32(Z0)));
    for (int l = 0; l < 4; ++l) q[l] = (uint32_t)n->pair[at[l]];
    return vld1q_u32(q);
}

/* g[0..k-1] (4 lanes each) into out[k j + c] */
static inline void store_interleaved4(float *out, const float32x4_t *g, int k)
{
    if (k == 2) {
        float32x4x2_t v = {{g[0], g[1]}};
        vst2q_f32(out, v);
    } else {
        float32x4x3_t v = {{g[0], g[1], g[2]}};
        vst3q_f32(out, v);
    }
}

static size_t noise3_neon(const udm1_noise *n, const float *const *axes, size_t stride, size_t count, float *value,
                          float *gradient, udm1_side_check *side)
{
    const float32x4_t onef = vdupq_n_f32(1.0f);
    uint32x4_t checked = vdupq_n_u32(0);
    size_t i = 0;
    for (; i + 4 <= count; i += 4) {
        checked = side_step(side, checked);
        float32x4_t x = load4(axes[0] + i * stride, stride), y = load4(axes[1] + i * stride, stride);
        float32x4_t z = load4(axes[2] + i * stride, stride);
        if (!(finite4(x) && finite4(y) && finite4(z))) break; /* the caller reports it */
        int32x4_t X0, Y0, Z0;
        x = axis4(x, &X0), y = axis4(y, &Y0), z = axis4(z, &Z0);
        uint32x4_t c = column_hashes(n, X0, Y0);
        uint32x4_t qA = pair_hashes(n, c, 0, Z0), qA1 = pair_hashes(n, c, 1, Z0);
        uint32x4_t qB = pair_hashes(n, c, 2, Z0), qB1 = pair_hashes(n, c, 3, Z0);
        float32x4_t x1 = vsubq_f32(x, onef), y1 = vsubq_f32(y, onef), z1 = vsubq_f32(z, onef);
        float32x4_t u = fade4(x), v = fade4(y), w = fade4(z);
        uint32x4_t hA1 = vshrq_n_u32(qA, 8), hB1 = vshrq_n_u32(qB, 8), hA11 = vshrq_n_u32(qA1, 8), hB11 = vshrq_n_u32(qB1, 8);
        float32x4_t c000 = grad3_4(qA, x, y, z), c100 = grad3_4(qB, x1, y, z);
        float32x4_t c010 = grad3_4(qA1, x, y1, z), c110 = grad3_4(qB1, x1, y1, z);
        float32x4_t c001 = grad3_4(hA1, x, y, z1), c101 = grad3_4(hB1, x1, y, z1);
        float32x4_t c011 = grad3_4(hA11, x, y1, z1), c111 = grad3_4(hB11, x1, y1, z1);
        if (value)
            vst1q_f32(value + i, lerp4(w, lerp4(v, lerp4(u, c000, c100), lerp4(u, c010, c110)),
                                       lerp4(v, lerp4(u, c001, c101), lerp4(u, c011, c111))));
        if (gradient) {
            float32x4_t G[8][3], g[3];
            gvec3_4(qA, G[0]), gvec3_4(qB, G[1]), gvec3_4(qA1, G[2]), gvec3_4(qB1, G[3]);
            gvec3_4(hA1, G[4]), gvec3_4(hB1, G[5]), gvec3_4(hA11, G[6]), gvec3_4(hB11, G[7]);
            for (int k = 0; k < 3; ++k)
                g[k] = lerp4(w, lerp4(v, lerp4(u, G[0][k], G[1][k]), lerp4(u, G[2][k], G[3][k])),
                             lerp4(v, lerp4(u, G[4][k], G[5][k]), lerp4(u, G[6][k], G[7][k])));
            float32x4_t du = dfade4(x), dv = dfade4(y), dw = dfade4(z);
            float32x4_t k1 = vsubq_f32(c100, c000), k2 = vsubq_f32(c010, c000), k3 = vsubq_f32(c001, c000);
            float32x4_t k4 = vsubq_f32(vsubq_f32(c110, c010), k1), k5 = vsubq_f32(vsubq_f32(c011, c001), k2);
            float32x4_t k6 = vsubq_f32(vsubq_f32(c101, c001), k1);
            float32x4_t k7 = vsubq_f32(vsubq_f32(vsubq_f32(c111, c011), vsubq_f32(c101, c001)), k4);
            float32x4_t k67 = vaddq_f32(k6, vmulq_f32(k7, v));
            float32x4_t pu = vaddq_f32(vaddq_f32(k1, vmulq_f32(k4, v)), vmulq_f32(k67, w));
            float32x4_t pv = vaddq_f32(vaddq_f32(k2, vmulq_f32(k4, u)), vmulq_f32(vaddq_f32(k5, vmulq_f32(k7, u)), w));
            float32x4_t pw = vaddq_f32(vaddq_f32(k3, vmulq_f32(k5, v)), vmulq_f32(k67, u));
            g[0] = vaddq_f32(g[0], vmulq_f32(du, pu));
            g[1] = vaddq_f32(g[1], vmulq_f32(dv, pv));
            g[2] = vaddq_f32(g[2], vmulq_f32(dw, pw));
            store_interleaved4(gradient + 3 * i, g, 3);
        }
    }
    side_end(side, checked);
    return i;
}

static size_t noise2_neon(const udm1_noise *n, const float *const *axes, size_t stride, size_t count, float *value,
                          float *gradient, udm1_side_check *side)
{
    const float32x4_t onef = vdupq_n_f32(1.0f), scale = vdupq_n_f32(0.507f);
    uint32x4_t checked = vdupq_n_u32(0);
    size_t i = 0;
    for (; i + 4 <= count; i += 4) {
        checked = side_step(side, checked);
        float32x4_t x = load4(axes[0] + i * stride, stride), y = load4(axes[1] + i * stride, stride);
        if (!(finite4(x) && finite4(y))) break;
        int32x4_t X0, Y0;
        x = axis4(x, &X0), y = axis4(y, &Y0);
        uint32x4_t c = column_hashes(n, X0, Y0); /* [h00, h01, h10, h11] */
        float32x4_t x1 = vsubq_f32(x, onef), y1 = vsubq_f32(y, onef);
        float32x4_t u = fade4(x), v = fade4(y);
        uint32x4_t h01 = vshrq_n_u32(c, 8), h10 = vshrq_n_u32(c, 16), h11 = vshrq_n_u32(c, 24);
        float32x4_t a = grad2_4(c, x, y), b = grad2_4(h10, x1, y), cc = grad2_4(h01, x, y1), d = grad2_4(h11, x1, y1);
        if (value) vst1q_f32(value + i, vmulq_f32(scale, lerp4(v, lerp4(u, a, b), lerp4(u, cc, d))));
        if (gradient) {
            float32x4_t G[4][2], g[2];
            gvec2_4(c, G[0]), gvec2_4(h10, G[1]), gvec2_4(h01, G[2]), gvec2_4(h11, G[3]);
            for (int k = 0; k < 2; ++k) g[k] = lerp4(v, lerp4(u, G[0][k], G[1][k]), lerp4(u, G[2][k], G[3][k]));
            float32x4_t du = dfade4(x), dv = dfade4(y);
            g[0] = vmulq_f32(scale, vaddq_f32(vmulq_f32(du, lerp4(v, vsubq_f32(b, a), vsubq_f32(d, cc))), g[0]));
            g[1] = vmulq_f32(scale, vaddq_f32(vmulq_f32(dv, lerp4(u, vsubq_f32(cc, a), vsubq_f32(d, b))), g[1]));
            store_interleaved4(gradient + 2 * i, g, 2);
        }
    }
    side_end(side, checked);
    return i;
}

size_t udm1_noise_eval_group_f32(const udm1_noise *n, uint32_t dims, const float *const *axes, size_t stride,
                                 const float *value, const float *gradient)
{
    (void)axes, (void)stride, (void)value, (void)gradient;
    if (n->kind != UDM1_NOISE_IMPROVED || n->period[0] || n->period[1] || n->period[2]) return 0;
    if (dims < 2 || dims > 3) return 0;
    return udm1_isa_level() == UDM1_ISA_NEON ? 4 : 0;
}

size_t udm1_noise_eval_fast_f32(const udm1_noise *n, uint32_t dims, const float *const *axes, size_t stride,
                                size_t count, float *value, float *gradient, udm1_side_check *side)
{
    udm1_side_check none = {{NULL}, 0, 0, 0, 0};
    if (!side) side = &none;
    if (!udm1_noise_eval_group_f32(n, dims, axes, stride, value, gradient)) return 0;
    return dims == 3 ? noise3_neon(n, axes, stride, count, value, gradient, side)
                     : noise2_neon(n, axes, stride, count, value, gradient, side);
}
#endif
