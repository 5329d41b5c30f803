/* scramble_simd.c - the base-2 randomization's kernels over many values: udm1_owen64 (udm1_owen64_many,
 * scramble.h), or only its top 32 bits (all a float needs), and the hash of the words (udm1_mix64_many):
 * four lanes with AVX2
 * or AVX-512 where core/isa.h allows, the scalar function elsewhere and for the tail. Each lane does the
 * scalar code's integer operations - bit reversal (by nibble tables, then byte order), the hash's 32-bit
 * products, the 64-bit mix of the low half - so the values are the same bit for bit (tests/c/test_stream.c
 * under each UDM1_ISA). */
#include "core/isa.h"
#include "seq/scramble.h"

#if defined(UDM1_HAVE_ISA_KERNELS)
#include <immintrin.h>

#define OWEN_KERNEL(NAME, ATTR, MUL64)                                                                   \
    ATTR static void NAME(const uint64_t *v, const uint64_t *r, uint64_t *out, int low_half)             \
    {                                                                                                     \
        const __m256i nib = _mm256_setr_epi8(0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15, 0, 8, 4, 12, 2, \
                                             10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15);                     \
        /* the bytes of each 32-bit word in reverse order, for the 32-bit words at the top of each lane */ \
        const __m256i bytes = _mm256_setr_epi8(7, 6, 5, 4, -1, -1, -1, -1, 15, 14, 13, 12, -1, -1, -1, -1, 7, 6, \
                                               5, 4, -1, -1, -1, -1, 15, 14, 13, 12, -1, -1, -1, -1);  \
        const __m256i lo4 = _mm256_set1_epi8(0x0F);                                                     \
        /* v element by element: the caller has just stored it as scalars, and one wide load of four      \
         * narrow stores would wait for them to reach the cache (no store forwarding) */                 \
        __m256i V = _mm256_set_epi64x((long long)v[3], (long long)v[2], (long long)v[1], (long long)v[0]); \
        __m256i R = _mm256_loadu_si256((const __m256i *)r);                                               \
        /* reverse32 of the top halves: bits within each byte by nibble table, then the byte order */    \
        __m256i x = _mm256_or_si256(_mm256_slli_epi16(_mm256_shuffle_epi8(nib, _mm256_and_si256(V, lo4)), 4), \
                                    _mm256_shuffle_epi8(nib, _mm256_and_si256(_mm256_srli_epi16(V, 4), lo4))); \
        x = _mm256_shuffle_epi8(x, bytes); /* now in the low 32 bits of each lane */                     \
        __m256i seed = _mm256_and_si256(R, _mm256_set1_epi64x(0xFFFFFFFF));                              \
        x = _mm256_xor_si256(x, _mm256_mullo_epi32(x, _mm256_set1_epi32(0x3d20adea)));                  \
        x = _mm256_add_epi32(x, seed);                                                                    \
        x = _mm256_mullo_epi32(x, _mm256_or_si256(_mm256_srli_epi32(seed, 16), _mm256_set1_epi32(1)));  \
        x = _mm256_xor_si256(x, _mm256_mullo_epi32(x, _mm256_set1_epi32(0x05526c56)));                  \
        x = _mm256_xor_si256(x, _mm256_mullo_epi32(x, _mm256_set1_epi32(0x53a22864)));                  \
        x = _mm256_and_si256(x, _mm256_set1_epi64x(0xFFFFFFFF)); /* the low words only */               \
        /* reverse32 back, into the top halves */                                                         \
        x = _mm256_or_si256(_mm256_slli_epi16(_mm256_shuffle_epi8(nib, _mm256_and_si256(x, lo4)), 4),    \
                            _mm256_shuffle_epi8(nib, _mm256_and_si256(_mm256_srli_epi16(x, 4), lo4)));    \
        const __m256i up = _mm256_setr_epi8(-1, -1, -1, -1, 3, 2, 1, 0, -1, -1, -1, -1, 11, 10, 9, 8, -1, -1, -1, \
                                            -1, 3, 2, 1, 0, -1, -1, -1, -1, 11, 10, 9, 8);              \
        __m256i top = _mm256_shuffle_epi8(x, up); /* top << 32 */                                       \
        if (!low_half) {                                                                                  \
            _mm256_storeu_si256((__m256i *)out, top);                                                     \
            return;                                                                                       \
        }                                                                                                 \
        /* low = (uint32) mix64((top << 32 | (uint32)(r >> 32)) ^ "OWEN" << 32) */                        \
        __m256i z = _mm256_xor_si256(_mm256_or_si256(top, _mm256_srli_epi64(R, 32)),                     \
                                     _mm256_set1_epi64x(0x4F57454E00000000ll));                           \
        z = MUL64(_mm256_xor_si256(z, _mm256_srli_epi64(z, 30)), 0xBF58476D1CE4E5B9ull);                 \
        z = MUL64(_mm256_xor_si256(z, _mm256_srli_epi64(z, 27)), 0x94D049BB133111EBull);                 \
        z = _mm256_xor_si256(z, _mm256_srli_epi64(z, 31));                                               \
        _mm256_storeu_si256((__m256i *)out, _mm256_or_si256(top, _mm256_and_si256(z, _mm256_set1_epi64x(0xFFFFFFFF)))); \
    }

/* the low 64 bits of a x c: AVX-512's own product, or AVX2's from 32-bit ones */
__attribute__((target("arch=x86-64-v4"))) static inline __m256i mul64_avx512(__m256i a, uint64_t c)
{
    return _mm256_mullo_epi64(a, _mm256_set1_epi64x((long long)c));
}
__attribute__((target("arch=x86-64-v3"))) static inline __m256i mul64_avx2(__m256i a, uint64_t c)
{
    __m256i lo = _mm256_set1_epi64x((long long)(c & 0xFFFFFFFFu)), hi = _mm256_set1_epi64x((long long)(c >> 32));
    __m256i cross = _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(a, 32), lo), _mm256_mul_epu32(a, hi));
    return _mm256_add_epi64(_mm256_mul_epu32(a, lo), _mm256_slli_epi64(cross, 32));
}

OWEN_KERNEL(owen4_avx512, __attribute__((target("arch=x86-64-v4"))), mul64_avx512)
OWEN_KERNEL(owen4_avx2, __attribute__((target("arch=x86-64-v3"))), mul64_avx2)
#endif

void udm1_owen64_many(const uint64_t *v, const uint64_t *r, uint64_t *out, uint32_t n, int low_half)
{
    uint32_t j = 0;
#if defined(UDM1_HAVE_ISA_KERNELS)
    int level = udm1_isa_level();
    if (level == UDM1_ISA_AVX512)
        for (; j + 4 <= n; j += 4) owen4_avx512(v + j, r + j, out + j, low_half);
    else if (level == UDM1_ISA_AVX2)
        for (; j + 4 <= n; j += 4) owen4_avx2(v + j, r + j, out + j, low_half);
#endif
    for (; j < n; ++j)
        out[j] = low_half ? udm1_owen64(v[j], r[j])
                          : (uint64_t)udm1_owen32((uint32_t)(v[j] >> 32), (uint32_t)r[j]) << 32;
}

#if defined(UDM1_HAVE_ISA_KERNELS)
#define MIX_KERNEL(NAME, ATTR, MUL64)                                                                      \
    ATTR static void NAME(const uint64_t *in, uint64_t add, uint64_t *out)                               \
    {                                                                                                     \
        __m256i z = _mm256_add_epi64(_mm256_loadu_si256((const __m256i *)in), _mm256_set1_epi64x((long long)add)); \
        z = MUL64(_mm256_xor_si256(z, _mm256_srli_epi64(z, 30)), 0xBF58476D1CE4E5B9ull);                 \
        z = MUL64(_mm256_xor_si256(z, _mm256_srli_epi64(z, 27)), 0x94D049BB133111EBull);                 \
        _mm256_storeu_si256((__m256i *)out, _mm256_xor_si256(z, _mm256_srli_epi64(z, 31)));              \
    }
MIX_KERNEL(mix4_avx512, __attribute__((target("arch=x86-64-v4"))), mul64_avx512)
MIX_KERNEL(mix4_avx2, __attribute__((target("arch=x86-64-v3"))), mul64_avx2)
#endif

void udm1_mix64_many(const uint64_t *in, uint64_t add, uint64_t *out, uint32_t n)
{
    uint32_t j = 0;
#if defined(UDM1_HAVE_ISA_KERNELS)
    int level = udm1_isa_level();
    if (level == UDM1_ISA_AVX512)
        for (; j + 4 <= n; j += 4) mix4_avx512(in + j, add, out + j);
    else if (level == UDM1_ISA_AVX2)
        for (; j + 4 <= n; j += 4) mix4_avx2(in + j, add, out + j);
#endif
    for (; j < n; ++j) out[j] = udm1_mix64(in[j] + add);
}
