/* radical_inverse.c - exact base-b radical inverses with digit scrambling,
 * for Halton and Hammersley.
 *
 * The value is floor(phi_b(n) * 2^64) computed from the integer R of the
 * reversed (and permuted) digits over b^K, so it is exact: no floating point.
 * K covers 64 bits (b^K >= 2^64); without scrambling trailing zero digits are
 * skipped. Scrambling per digit position k (0 = most significant digit of the
 * result):
 *  PERMUTE  digit d -> permute(d, b, key(r, k)): one random permutation per
 *           position, the same for every prefix (random digit permutations);
 *  OWEN     digit d -> permute(d, b, key(r, k, prefix)), the prefix being the
 *           scrambled digits above: a nested (Owen) scramble in base b;
 *  SHIFT    the exact value plus r modulo 1.
 * Base 2 uses bit reversal and the base-2 scramblings directly.
 */
#include "samplers/samplers.h"
#include "seq/scramble.h"

/* The permutation key of digit position k: r's low word stepped by a Weyl
 * constant per position (udm1_permute hashes its key thoroughly); for Owen
 * scrambling also a hash of the scrambled digits above (the prefix). */
static inline uint32_t digit_key(uint64_t r, uint32_t k, udm1_u128 prefix, int nested)
{
    uint32_t key = (uint32_t)r + (k + 1u) * 0x9E3779B9u;
    if (nested) key ^= (uint32_t)(((udm1_u128_lo(prefix) ^ udm1_u128_hi(prefix)) * 0xD6E8FEB86659FD93ull) >> 32);
    return key;
}

uint64_t udm1_radical_inverse(uint64_t n, uint32_t b, uint32_t mode, uint64_t r)
{
    if (b == 2) return udm1_randomize_base2(mode, udm1_reverse64(n), r);
    int scramble = mode == UDM1_MODE_PERMUTE || mode == UDM1_MODE_OWEN;
    udm1_u128 R = udm1_u128_make(0, 0), D = udm1_u128_make(0, 1);
    for (uint32_t k = 0; udm1_u128_hi(D) == 0; ++k) { /* until D = b^k reaches 2^64 */
        uint32_t d = 0;
        if (n) {
            if (n <= UINT32_MAX) { /* 32-bit division is several times faster */
                d = (uint32_t)n % b;
                n = (uint32_t)n / b;
            } else {
                d = (uint32_t)(n % b);
                n /= b;
            }
        } else if (!scramble) {
            break; /* the remaining digits are zeros */
        }
        if (scramble) d = udm1_permute(d, b, digit_key(r, k, R, mode == UDM1_MODE_OWEN));
        R = udm1_u128_muladd64(R, b, d);
        D = udm1_u128_muladd64(D, b, 0);
    }
    uint64_t v = udm1_frac64(R, D);
    return mode == UDM1_MODE_SHIFT ? v + r : v;
}
