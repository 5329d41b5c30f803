/* hash.h - the counter-based hash behind per-stream random shifts and padding.
 *
 * Every constant and step here is part of the ABI: the shifts of a given
 * (seed, stream, dimension) must never change, so that images rendered with
 * one version can be extended or compared with another. Golden values in
 * tests/c/test_golden.c pin them.
 *
 *   mix(z)          Stafford's "Mix13" 64-bit finalizer (as in SplitMix64)
 *   S  = mix(seed ^ "udm1SEED")                         per sequence
 *   K_j = mix(S + (j + 1) * G)                          per dimension, G = 2^64/phi
 *   T(stream) = mix(S ^ mix(stream + G))                per stream
 *   r_j(stream) = mix(T + K_j)                          the shift of dimension j
 *   pad(stream, index, j) = mix(r_j + (index + 1) * G)  a draw past the last dimension
 */
#ifndef UDM1_HASH_H
#define UDM1_HASH_H

#include "udm1/domain.h" /* udm1_mix64 and UDM1_GOLDEN_GAMMA: public, the domains' keys use them */

#include <stdint.h>

#define UDM1_SEED_SALT 0x75646D3153454544ull /* "udm1SEED" */

static inline uint64_t udm1_seed_key(uint64_t seed) { return udm1_mix64(seed ^ UDM1_SEED_SALT); }

static inline uint64_t udm1_dim_key(uint64_t seed_key, uint32_t dim)
{
    return udm1_mix64(seed_key + ((uint64_t)dim + 1u) * UDM1_GOLDEN_GAMMA);
}

static inline uint64_t udm1_stream_key(uint64_t seed_key, uint64_t stream)
{
    return udm1_mix64(seed_key ^ udm1_mix64(stream + UDM1_GOLDEN_GAMMA));
}

static inline uint64_t udm1_shift(uint64_t stream_key, uint64_t dim_key) { return udm1_mix64(stream_key + dim_key); }

static inline uint64_t udm1_pad(uint64_t shift, uint64_t index)
{
    return udm1_mix64(shift + (index + 1u) * UDM1_GOLDEN_GAMMA);
}

#endif /* UDM1_HASH_H */
