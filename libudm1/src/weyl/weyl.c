/* weyl.c - the Weyl kinds: values, and bulk fills of index ranges (the hot path).
 *
 * Each output value has its own 128-bit state (O_j 2^64 + n A_j) that advances
 * by P A_j per block of P points. The additions are exact integer arithmetic
 * modulo 2^128, so the result equals udm1_weyl_raw() of every (n, j) bit for
 * bit: bulk and per-sample calls, and any split of a range, agree. The inner
 * loop is a plain loop over arrays that compilers vectorize; on x86-64 it is
 * compiled for AVX-512, AVX2 and baseline, on 64-bit Arm its flat kernel also
 * written with NEON (weyl/weyl_neon.h), and core/isa.h picks one (UDM1_ISA
 * caps it, so that the tests run each).
 */
#include "weyl/weyl.h"

#include "core/isa.h"
#include "seq/scramble.h"

#include <string.h>

/* States per block: 4 arrays of 8 bytes each = 15 KiB of stack. Not a power of
 * two on purpose: the flat kernel stores one vector per block at a stride of
 * BLOCK values, and a 4 KiB stride (512 doubles) maps every store to the same
 * L1 set; 480 measured 2x faster than 512 for f64 (BENCHMARKS.md). */
#define BLOCK 480u
/* Blocks per tile of the flat kernel: 16 x 480 doubles = 60 KiB, written while
 * the states of a group stay in registers, then the next group. */
#define TILE 16u


#define CONV_U64(h) (h)
#define CONV_F64(h) ((double)(int64_t)((h) >> 11) * 0x1p-53)
#define CONV_F32(h) ((float)(int32_t)((h) >> 40) * 0x1p-24f)

/* Write len values from the states and advance each state by its increment. */
#define DEFINE_KERNEL(NAME, T, CONV, ATTR)                                                             \
    ATTR static void NAME(void *out_, size_t len, uint64_t *restrict lo, uint64_t *restrict hi,           \
                          const uint64_t *restrict inc_lo, const uint64_t *restrict inc_hi)               \
    {                                                                                                  \
        T *restrict out = out_;                                                                        \
        for (size_t e = 0; e < len; ++e) {                                                             \
            uint64_t h = hi[e];                                                                        \
            out[e] = CONV(h);                                                                          \
            uint64_t l = lo[e] + inc_lo[e];                                                            \
            hi[e] = h + inc_hi[e] + (uint64_t)(l < inc_lo[e]);                                         \
            lo[e] = l;                                                                                 \
        }                                                                                              \
    }

/* Contiguous output of `total` values whose states repeat with period L (one
 * block of rows). Each group of 8 states stays in vector registers while it
 * writes its lanes of every block, instead of going through memory for each
 * value. Vector extensions of GCC and Clang; a scalar loop elsewhere. */
#if defined(__GNUC__)
#  define UDM1_VECTORS 1
typedef uint64_t u64x8 __attribute__((vector_size(64)));
typedef int64_t i64x8 __attribute__((vector_size(64)));
typedef int32_t i32x8 __attribute__((vector_size(32)));
typedef float f32x8 __attribute__((vector_size(32)));
typedef double f64x8 __attribute__((vector_size(64)));
#  define VCONV_U64(h) (h)
#  define VCONV_F64(h) (__builtin_convertvector((i64x8)((h) >> 11), f64x8) * 0x1p-53)
#  define VCONV_F32(h) (__builtin_convertvector(__builtin_convertvector((h) >> 40, i32x8), f32x8) * 0x1p-24f)
#  define DEFINE_FLAT_KERNEL(NAME, T, VT, VCONV, CONV, ATTR)                                          \
    ATTR static void NAME(void *out_, size_t total, size_t L, uint64_t *restrict lo0,                     \
                          uint64_t *restrict hi0, const uint64_t *restrict ilo0,                          \
                          const uint64_t *restrict ihi0)                                                  \
    {                                                                                                  \
        T *restrict out = out_;                                                                        \
        for (size_t c0 = 0; c0 < total; c0 += TILE * L) { /* a tile of blocks stays in cache */        \
            size_t cend = total - c0 < TILE * L ? total : c0 + TILE * L;                               \
            size_t e0 = 0;                                                                             \
            for (; e0 + 16 <= L; e0 += 16) { /* two groups at once: independent chains overlap */      \
                u64x8 lo_a, hi_a, ilo_a, ihi_a, lo_b, hi_b, ilo_b, ihi_b;                              \
                memcpy(&lo_a, lo0 + e0, 64); memcpy(&lo_b, lo0 + e0 + 8, 64);                          \
                memcpy(&hi_a, hi0 + e0, 64); memcpy(&hi_b, hi0 + e0 + 8, 64);                          \
                memcpy(&ilo_a, ilo0 + e0, 64); memcpy(&ilo_b, ilo0 + e0 + 8, 64);                      \
                memcpy(&ihi_a, ihi0 + e0, 64); memcpy(&ihi_b, ihi0 + e0 + 8, 64);                      \
                size_t base = c0 + e0;                                                                 \
                for (; base + 16 <= cend; base += L) {                                                 \
                    VT va = VCONV(hi_a), vb = VCONV(hi_b);                                             \
                    memcpy(out + base, &va, sizeof va);                                                \
                    memcpy(out + base + 8, &vb, sizeof vb);                                            \
                    u64x8 la = lo_a + ilo_a, lb = lo_b + ilo_b;                                        \
                    hi_a = hi_a + ihi_a - (u64x8)(la < ilo_a); /* a true lane compares as -1 */        \
                    hi_b = hi_b + ihi_b - (u64x8)(lb < ilo_b);                                         \
                    lo_a = la;                                                                         \
                    lo_b = lb;                                                                         \
                }                                                                                      \
                if (base < cend) { /* the last, partial block */                                       \
                    uint64_t h[16];                                                                    \
                    memcpy(h, &hi_a, 64);                                                              \
                    memcpy(h + 8, &hi_b, 64);                                                          \
                    for (size_t k = 0; base + k < cend && k < 16; ++k) out[base + k] = CONV(h[k]);     \
                }                                                                                      \
                memcpy(lo0 + e0, &lo_a, 64); memcpy(lo0 + e0 + 8, &lo_b, 64);                          \
                memcpy(hi0 + e0, &hi_a, 64); memcpy(hi0 + e0 + 8, &hi_b, 64);                          \
            }                                                                                          \
            for (; e0 < L; ++e0) { /* states left over when L is not a multiple of 16 */               \
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
#else
#  define DEFINE_FLAT_KERNEL(NAME, T, VT, VCONV, CONV, ATTR)                                          \
    static void NAME(void *out_, size_t total, size_t L, uint64_t *restrict lo0, uint64_t *restrict hi0,   \
                     const uint64_t *restrict ilo0, const uint64_t *restrict ihi0)                        \
    {                                                                                                  \
        T *restrict out = out_;                                                                        \
        for (size_t e0 = 0; e0 < L; ++e0) {                                                            \
            uint64_t lo = lo0[e0], hi = hi0[e0];                                                       \
            for (size_t base = e0; base < total; base += L) {                                          \
                out[base] = CONV(hi);                                                                  \
                uint64_t l = lo + ilo0[e0];                                                            \
                hi = hi + ihi0[e0] + (uint64_t)(l < ilo0[e0]);                                         \
                lo = l;                                                                                \
            }                                                                                          \
        }                                                                                              \
    }
#endif

/* The kernels of one instruction set, and their table */
typedef struct kernels {
    void (*row[3])(void *out, size_t len, uint64_t *lo, uint64_t *hi, const uint64_t *ilo, const uint64_t *ihi);
    void (*flat[3])(void *out, size_t total, size_t L, uint64_t *lo, uint64_t *hi, const uint64_t *ilo,
                    const uint64_t *ihi);
} kernels;

#define DEFINE_KERNELS(SUFFIX, ATTR)                                                                   \
    DEFINE_KERNEL(kernel_u64_##SUFFIX, uint64_t, CONV_U64, ATTR)                                       \
    DEFINE_KERNEL(kernel_f64_##SUFFIX, double, CONV_F64, ATTR)                                         \
    DEFINE_KERNEL(kernel_f32_##SUFFIX, float, CONV_F32, ATTR)                                          \
    DEFINE_FLAT_KERNEL(flat_u64_##SUFFIX, uint64_t, u64x8, VCONV_U64, CONV_U64, ATTR)                  \
    DEFINE_FLAT_KERNEL(flat_f64_##SUFFIX, double, f64x8, VCONV_F64, CONV_F64, ATTR)                    \
    DEFINE_FLAT_KERNEL(flat_f32_##SUFFIX, float, f32x8, VCONV_F32, CONV_F32, ATTR)                     \
    static const kernels kernels_##SUFFIX = {{kernel_u64_##SUFFIX, kernel_f64_##SUFFIX, kernel_f32_##SUFFIX},      \
                                              {flat_u64_##SUFFIX, flat_f64_##SUFFIX, flat_f32_##SUFFIX}};

DEFINE_KERNELS(baseline, )
#if defined(UDM1_HAVE_ISA_KERNELS)
DEFINE_KERNELS(avx2, __attribute__((target("arch=x86-64-v3"))))
DEFINE_KERNELS(avx512, __attribute__((target("arch=x86-64-v4"))))
#endif

#if defined(UDM1_HAVE_NEON_KERNELS)
#include "weyl/weyl_neon.h"
static const kernels kernels_neon = {{kernel_u64_baseline, kernel_f64_baseline, kernel_f32_baseline},
                                     {flat_u64_neon, flat_f64_neon, flat_f32_neon}};
#endif

static const kernels *kernels_in_use(void)
{
#if defined(UDM1_HAVE_NEON_KERNELS)
    if (udm1_isa_level() == UDM1_ISA_NEON) return &kernels_neon;
#endif
#if defined(UDM1_HAVE_ISA_KERNELS)
    switch (udm1_isa_level()) {
    case UDM1_ISA_AVX512: return &kernels_avx512;
    case UDM1_ISA_AVX2: return &kernels_avx2;
    default: break;
    }
#endif
    return &kernels_baseline;
}

static void run_flat(const kernels *k, int kind, void *out, size_t total, size_t L, uint64_t *lo, uint64_t *hi,
                     const uint64_t *ilo, const uint64_t *ihi)
{
    k->flat[kind](out, total, L, lo, hi, ilo, ihi);
}

static void run_kernel(const kernels *k, int kind, void *out, size_t offset, size_t len, uint64_t *lo, uint64_t *hi,
                       const uint64_t *ilo, const uint64_t *ihi)
{
    size_t size = kind == UDM1_OUT_F32 ? sizeof(float) : sizeof(uint64_t);
    k->row[kind]((char *)out + offset * size, len, lo, hi, ilo, ihi);
}

void udm1_weyl_fill(int kind, const udm1_seq_t *seq, uint64_t skey, uint64_t first, size_t count, uint32_t dim0,
                    uint32_t ndims, void *out, size_t stride)
{
    uint64_t lo[BLOCK], hi[BLOCK], inc_lo[BLOCK], inc_hi[BLOCK];
    const kernels *k = kernels_in_use();
    first = udm1_screen_index(seq, skey, first); /* a pixel's segment of one sequence in screen mode */

    for (uint32_t c0 = 0; c0 < ndims; c0 += BLOCK) {
        uint32_t cw = ndims - c0 < BLOCK ? ndims - c0 : BLOCK;
        int flat = cw == ndims && stride == ndims; /* rows are contiguous: one run */
        size_t rows_per_block = BLOCK / cw;
        if (flat) { /* make a block a whole number of 8-lane vectors when it fits */
            size_t m = 16;
            while (m > 1 && cw % (16 / m * 2) == 0) m /= 2; /* m = 16 / gcd(cw, 16) */
            if (m * cw <= BLOCK) rows_per_block -= rows_per_block % m;
        }
        if (rows_per_block > count) rows_per_block = count;

        for (uint32_t jj = 0; jj < cw; ++jj) {
            uint32_t dim = dim0 + c0 + jj;
            const udm1_generator *g = &seq->gen[dim];
            uint64_t o = seq->offset[dim];
            o += udm1_weyl_shift(seq, skey, dim);
            /* increment P A (mod 2^128) */
            uint64_t phi, plo;
            udm1_mul64((uint64_t)rows_per_block, g->lo, &phi, &plo);
            uint64_t step_hi = (uint64_t)rows_per_block * g->hi + phi;
            for (size_t q = 0; q < rows_per_block; ++q) {
                uint64_t n = first + q;
                uint64_t mhi, mlo;
                udm1_mul64(n, g->lo, &mhi, &mlo);
                size_t e = q * cw + jj;
                lo[e] = mlo;
                hi[e] = n * g->hi + mhi + o;
                inc_lo[e] = plo;
                inc_hi[e] = step_hi;
            }
        }

        if (flat) {
            run_flat(k, kind, out, count * cw, rows_per_block * cw, lo, hi, inc_lo, inc_hi);
            continue;
        }
        for (size_t i = 0; i < count; i += rows_per_block) {
            size_t rows = count - i < rows_per_block ? count - i : rows_per_block;
            {
                for (size_t q = 0; q < rows; ++q)
                    run_kernel(k, kind, out, (i + q) * stride + c0, cw, lo + q * cw, hi + q * cw, inc_lo + q * cw,
                               inc_hi + q * cw);
            }
        }
    }
}

static uint64_t weyl_shifted_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    return udm1_weyl_shifted_raw(seq, skey, index, dim);
}

static uint64_t weyl_scrambled_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    uint64_t r = seq->mode == UDM1_MODE_NONE ? 0 : udm1_shift(skey, seq->dim_key[dim]);
    return udm1_randomize_base2(seq->mode, udm1_weyl_raw(&seq->gen[dim], seq->offset[dim], index), r);
}

const udm1_kind udm1_weyl_kind = {.name = "weyl", .value = weyl_shifted_value};
const udm1_kind udm1_weyl_scrambled_kind = {.name = "weyl-scrambled", .value = weyl_scrambled_value};
