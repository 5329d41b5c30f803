/* byte_table.h - a table of 256 bytes held in four AVX-512 registers, and the lookup of 64 byte indices
 * at once (two VBMI permutations and a blend): the noise kernels' permutation and the cellular
 * kernels' hash and offset tables. Not a public header; include it after <immintrin.h> where
 * UDM1_HAVE_ISA_KERNELS is defined, in kernels compiled for AVX-512 with VBMI. */
#ifndef UDM1_NOISE_BYTE_TABLE_H
#define UDM1_NOISE_BYTE_TABLE_H

#include <stdint.h>

#define UDM1_BYTE_TABLE_TARGET __attribute__((target("avx512f,avx512bw,avx512vbmi")))

typedef struct {
    __m512i t[4]; /* the 256 bytes */
} byte_table;

UDM1_BYTE_TABLE_TARGET static inline byte_table byte_table_load(const uint8_t *bytes)
{
    byte_table r;
    for (int k = 0; k < 4; ++k) r.t[k] = _mm512_loadu_si512((const void *)(bytes + 64 * k));
    return r;
}

/* each byte b of idx -> table[b] */
UDM1_BYTE_TABLE_TARGET static inline __m512i byte_table_lookup(const byte_table *t, __m512i idx)
{
    __m512i lo = _mm512_permutex2var_epi8(t->t[0], idx, t->t[1]), hi = _mm512_permutex2var_epi8(t->t[2], idx, t->t[3]);
    return _mm512_mask_blend_epi8(_mm512_movepi8_mask(idx), lo, hi);
}

/* the low byte of each 32-bit lane of a in every byte of that lane */
UDM1_BYTE_TABLE_TARGET static inline __m512i byte_table_spread4(__m512i a)
{
    return _mm512_shuffle_epi8(a, _mm512_set4_epi32(0x0C0C0C0C, 0x08080808, 0x04040404, 0x00000000));
}

#endif
