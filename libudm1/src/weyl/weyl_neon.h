/* weyl/weyl_neon.h - the flat kernel of the Weyl bulk fill (weyl.c) with NEON, for 64-bit Arm: the same
 * 128-bit states and additions as the generic kernel, eight states at a time in sixteen 128-bit registers
 * (the generic kernel's 16 lanes of 512-bit vectors, which AArch64's 32 registers cannot hold, go through
 * the stack), and the same conversions (exact: a 24- or 53-bit integer scaled by a power of two), so the
 * same values bit for bit. Included by weyl.c where UDM1_HAVE_NEON_KERNELS is defined; core/isa.h
 * chooses it (UDM1_ISA=baseline takes the generic kernel, so that the tests compare the two). */
#ifndef UDM1_WEYL_NEON_H
#define UDM1_WEYL_NEON_H

#include <arm_neon.h>

/* Store the eight values of states h[0..3] (two per register) at out, converted. */
static inline void neon_put8_u64(uint64_t *out, const uint64x2_t h[4])
{
    for (int k = 0; k < 4; ++k) vst1q_u64(out + 2 * k, h[k]);
}

static inline void neon_put8_f64(double *out, const uint64x2_t h[4])
{
    for (int k = 0; k < 4; ++k)
        vst1q_f64(out + 2 * k, vmulq_n_f64(vcvtq_f64_s64(vreinterpretq_s64_u64(vshrq_n_u64(h[k], 11))), 0x1p-53));
}

static inline void neon_put8_f32(float *out, const uint64x2_t h[4])
{
    for (int k = 0; k < 4; k += 2) {
        uint32x4_t top = vcombine_u32(vmovn_u64(vshrq_n_u64(h[k], 40)), vmovn_u64(vshrq_n_u64(h[k + 1], 40)));
        vst1q_f32(out + 2 * k, vmulq_n_f32(vcvtq_f32_s32(vreinterpretq_s32_u32(top)), 0x1p-24f));
    }
}

/* The flat kernel of weyl.c (its contract and loop order) with groups of 8 states. */
#define DEFINE_NEON_FLAT_KERNEL(NAME, T, PUT8, CONV)                                                   \
    static void NAME(void *out_, size_t total, size_t L, uint64_t *restrict lo0, uint64_t *restrict hi0,   \
                     const uint64_t *restrict ilo0, const uint64_t *restrict ihi0)                        \
    {                                                                                                  \
        T *restrict out = out_;                                                                        \
        for (size_t c0 = 0; c0 < total; c0 += TILE * L) {                                              \
            size_t cend = total - c0 < TILE * L ? total : c0 + TILE * L;                               \
            size_t e0 = 0;                                                                             \
            for (; e0 + 8 <= L; e0 += 8) {                                                             \
                uint64x2_t lo[4], hi[4], ilo[4], ihi[4];                                               \
                for (int k = 0; k < 4; ++k) {                                                          \
                    lo[k] = vld1q_u64(lo0 + e0 + 2 * k), hi[k] = vld1q_u64(hi0 + e0 + 2 * k);          \
                    ilo[k] = vld1q_u64(ilo0 + e0 + 2 * k), ihi[k] = vld1q_u64(ihi0 + e0 + 2 * k);      \
                }                                                                                      \
                size_t base = c0 + e0;                                                                 \
                for (; base + 8 <= cend; base += L) {                                                  \
                    PUT8(out + base, hi);                                                              \
                    for (int k = 0; k < 4; ++k) {                                                      \
                        uint64x2_t l = vaddq_u64(lo[k], ilo[k]);                                       \
                        /* a carry lane compares as all ones: minus it adds 1 */                       \
                        hi[k] = vsubq_u64(vaddq_u64(hi[k], ihi[k]), vcltq_u64(l, ilo[k]));             \
                        lo[k] = l;                                                                     \
                    }                                                                                  \
                }                                                                                      \
                if (base < cend) { /* the last, partial block */                                      \
                    uint64_t h[8];                                                                     \
                    for (int k = 0; k < 4; ++k) vst1q_u64(h + 2 * k, hi[k]);                           \
                    for (size_t k = 0; base + k < cend && k < 8; ++k) out[base + k] = CONV(h[k]);      \
                }                                                                                      \
                for (int k = 0; k < 4; ++k) {                                                          \
                    vst1q_u64(lo0 + e0 + 2 * k, lo[k]);                                                \
                    vst1q_u64(hi0 + e0 + 2 * k, hi[k]);                                                \
                }                                                                                      \
            }                                                                                          \
            for (; e0 < L; ++e0) { /* states left over when L is not a multiple of 8 */                \
                uint64_t lo = lo0[e0], hi = hi0[e0];                                                   \
                for (size_t base = c0 + e0; base < cend; base += L) {                                  \
                    out[base] = CONV(hi);                                                              \
                    uint64_t l = lo + ilo0[e0];                                                        \
                    hi = hi + ihi0[e0] + (uint64_t)(l < ilo0[e0]);                                     \
                    lo = l;                                                                            \
                }                                                                                      \
                lo0[e0] = lo;                                                                          \
                hi0[e0] = hi;                                                                          \
            }                                                                                          \
        }                                                                                              \
    }

DEFINE_NEON_FLAT_KERNEL(flat_u64_neon, uint64_t, neon_put8_u64, CONV_U64)
DEFINE_NEON_FLAT_KERNEL(flat_f64_neon, double, neon_put8_f64, CONV_F64)
DEFINE_NEON_FLAT_KERNEL(flat_f32_neon, float, neon_put8_f32, CONV_F32)

#endif /* UDM1_WEYL_NEON_H */
