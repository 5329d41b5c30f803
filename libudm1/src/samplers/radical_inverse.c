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
 *
 * Many values of one (base, word), without Owen scrambling, split the digits at a position s with
 * n < b^s: the digits k >= s of every such n are zeros, so with PERMUTE their permuted digits are the
 * same for all of them. Their part of the value, the tail Y_s = floor(2^64 sum_{k >= s} d_k b^(s-1-k)),
 * is found once (Horner's rule from the last digit, each step Y_k = floor((d_k 2^64 + Y_{k+1}) / b):
 * floor(x / b) = floor(floor(x) / b) for an integer b), and each value is then
 * floor((H 2^64 + Y_s) / b^s), H the integer of its s leading digits: the same floor of the same
 * rational R 2^64 / b^K. A fill splits at the digits of its last index (and with PERMUTE, where the
 * base is small against its count, writes the s positions' permutations out as a table), a stream
 * (udm1/stream.h) at two fixed positions (radical_inverse.h). The divisions by b and b^s are
 * multiplications by their reciprocals (core/divisor.h).
 */
#include "samplers/radical_inverse.h"
#include "seq/scramble.h"

void udm1_radix_init(udm1_radix *rx, uint32_t base)
{
    static const unsigned split_bits[UDM1_RADIX_SPLITS] = {10, 20};
    rx->base = base;
    rx->mask = udm1_permute_mask(base);
    rx->magic = base > 1 ? udm1_mod32_magic(base) : 0;
    rx->divisor = udm1_divisor_make(base);
    uint32_t k = 1;
    for (uint64_t p = base; p <= UINT64_MAX / base; p *= base) ++k; /* b^k <= 2^64 - 1 */
    rx->digits = k + 1; /* (base 2: 2^63 is the last power below 2^64) */
    for (int i = 0; i < UDM1_RADIX_SPLITS; ++i) {
        uint32_t s = 1;
        uint64_t p = base;
        while (p < (1ull << split_bits[i])) p *= base, ++s;
        rx->split[i] = s;
        rx->limit[i] = p;
        rx->power[i] = udm1_divisor_make(p);
    }
}

/* The permutation key of digit position k: r's low word stepped by a Weyl
 * constant per position (udm1_permute hashes its key thoroughly); for Owen
 * scrambling also a hash of the scrambled digits above (the prefix). */
static inline uint32_t digit_key(uint64_t r, uint32_t k, udm1_u128 prefix, int nested)
{
    uint32_t key = (uint32_t)r + (k + 1u) * 0x9E3779B9u;
    if (nested) key ^= (uint32_t)(((udm1_u128_lo(prefix) ^ udm1_u128_hi(prefix)) * 0xD6E8FEB86659FD93ull) >> 32);
    return key;
}

/* udm1_permute(d, b, key), its final remainder by multiplication */
static inline uint32_t permute_digit(const udm1_radix *rx, uint32_t d, uint32_t key)
{
    /* the walk's first two steps both taken, the one that lands below b kept without a branch (a walk of
     * one step or two is the common case: a branch on which would be mispredicted often) */
    uint32_t h1 = udm1_permute_step(d, rx->mask, key), h2 = udm1_permute_step(h1, rx->mask, key);
    uint64_t i = h1 < rx->base ? h1 : h2;
    if (i >= rx->base) i = udm1_permute_walk((uint32_t)i, rx->base, rx->mask, key);
    i += udm1_mod32(key, rx->base, rx->magic); /* (i + key) mod b, i < b */
    return (uint32_t)(i >= rx->base ? i - rx->base : i);
}

/* The lowest digit of *n, which loses it */
static inline uint32_t next_digit(uint64_t *n, const udm1_radix *rx)
{
    uint64_t q;
    if (*n <= UINT32_MAX) /* by multiplication */
        q = udm1_div32((uint32_t)*n, rx->magic);
    else
        q = *n / rx->base;
    uint32_t d = (uint32_t)(*n - q * rx->base);
    *n = q;
    return d;
}

uint64_t udm1_radical_inverse(uint64_t n, const udm1_radix *rx, uint32_t mode, uint64_t r)
{
    uint32_t b = rx->base;
    if (b == 2) return udm1_randomize_base2(mode, udm1_reverse64(n), r);
    int scramble = mode == UDM1_MODE_PERMUTE || mode == UDM1_MODE_OWEN;
    udm1_u128 R = udm1_u128_make(0, 0), D = udm1_u128_make(0, 1);
    for (uint32_t k = 0; udm1_u128_hi(D) == 0; ++k) { /* until D = b^k reaches 2^64 */
        uint32_t d = 0;
        if (n) {
            d = next_digit(&n, rx);
        } else if (!scramble) {
            break; /* the remaining digits are zeros */
        }
        if (scramble) d = permute_digit(rx, d, digit_key(r, k, R, mode == UDM1_MODE_OWEN));
        R = udm1_u128_muladd64(R, b, d);
        D = udm1_u128_muladd64(D, b, 0);
    }
    uint64_t v = udm1_frac64(R, D);
    return mode == UDM1_MODE_SHIFT ? v + r : v;
}

/* PERMUTE's tail Y_s (see the top), from Y_from of a deeper position from > s (Y_K = 0) */
static uint64_t tail_at(const udm1_radix *rx, uint64_t r, uint32_t s, uint32_t from, uint64_t y)
{
    const udm1_u128 none = udm1_u128_make(0, 0);
    for (uint32_t k = from; k-- > s;)
        y = udm1_divide_by(&rx->divisor, permute_digit(rx, 0, digit_key(r, k, none, 0)), y);
    return y;
}

/* The value of n < b^s (power: b^s) with the tail Y_s (0 without PERMUTE), b > 2, mode not OWEN */
static inline uint64_t head_value(uint64_t n, const udm1_radix *rx, uint32_t s, const udm1_divisor *power,
                                  uint32_t mode, uint64_t r, uint64_t tail)
{
    const udm1_u128 none = udm1_u128_make(0, 0);
    uint64_t h = 0;
    if (mode == UDM1_MODE_PERMUTE) {
        for (uint32_t k = 0; k < s; ++k)
            h = h * rx->base + permute_digit(rx, next_digit(&n, rx), digit_key(r, k, none, 0));
    } else {
        for (uint32_t k = 0; k < s; ++k) h = h * rx->base + next_digit(&n, rx);
    }
    uint64_t v = udm1_divide_by(power, h, tail);
    return mode == UDM1_MODE_SHIFT ? v + r : v;
}

/* Owen-scrambled values of indices first + i, i < count, plus add: OWEN_LANES at a time, their digits in
 * step, so that the processor overlaps their hashes (one value's digits wait for each other: its prefix) */
enum { OWEN_LANES = 4 };
static void owen_fill(const udm1_radix *rx, uint64_t r, uint64_t first, size_t count, uint64_t add, uint64_t *out,
                      size_t stride)
{
    uint32_t b = rx->base;
    udm1_u128 D = udm1_u128_make(0, 1);
    for (uint32_t k = 0; k < rx->digits; ++k) D = udm1_u128_muladd64(D, b, 0);
    size_t i = 0;
    for (; i + OWEN_LANES <= count; i += OWEN_LANES) {
        uint64_t n[OWEN_LANES];
        udm1_u128 R[OWEN_LANES];
        for (int l = 0; l < OWEN_LANES; ++l) n[l] = first + i + (size_t)l, R[l] = udm1_u128_make(0, 0);
        for (uint32_t k = 0; k < rx->digits; ++k)
            for (int l = 0; l < OWEN_LANES; ++l) {
                uint32_t d = n[l] ? next_digit(&n[l], rx) : 0;
                R[l] = udm1_u128_muladd64(R[l], b, permute_digit(rx, d, digit_key(r, k, R[l], 1)));
            }
        for (int l = 0; l < OWEN_LANES; ++l) out[(i + (size_t)l) * stride] = udm1_frac64(R[l], D) + add;
    }
    for (; i < count; ++i) out[i * stride] = udm1_radical_inverse(first + i, rx, UDM1_MODE_OWEN, r) + add;
}

/* The largest permutation table of a PERMUTE fill: s positions x b digits (b at most half the fill's count) */
enum { PERMUTATION_TABLE = 2048 };

void udm1_radical_fill(const udm1_radix *rx, uint32_t mode, uint64_t r, uint64_t first, size_t count,
                       uint64_t add, uint64_t *out, size_t stride)
{
    uint64_t last = first + (count - 1);
    uint32_t s = 0; /* the digits of the last index: b^s > last */
    uint64_t p = 1;
    while (p <= last && p <= UINT64_MAX / rx->base) p *= rx->base, ++s;
    if (mode == UDM1_MODE_OWEN && rx->base > 2) {
        owen_fill(rx, r, first, count, add, out, stride);
        return;
    }
    if (rx->base == 2 || mode == UDM1_MODE_OWEN || p <= last || count == 1) { /* (p <= last: b^s passes 2^64) */
        for (size_t i = 0; i < count; ++i) out[i * stride] = udm1_radical_inverse(first + i, rx, mode, r) + add;
        return;
    }
    udm1_divisor power = udm1_divisor_make(p);
    uint64_t tail = mode == UDM1_MODE_PERMUTE ? tail_at(rx, r, s, rx->digits, 0) : 0;
    uint32_t b = rx->base;
    if (mode == UDM1_MODE_PERMUTE && s * b <= PERMUTATION_TABLE && 2 * (size_t)b <= count) {
        /* the s positions' permutations written out once, looked up by every value */
        const udm1_u128 none = udm1_u128_make(0, 0);
        uint32_t table[PERMUTATION_TABLE];
        for (uint32_t k = 0; k < s; ++k)
            for (uint32_t d = 0; d < b; ++d) table[k * b + d] = permute_digit(rx, d, digit_key(r, k, none, 0));
        for (size_t i = 0; i < count; ++i) {
            uint64_t n = first + i, h = 0;
            for (uint32_t k = 0; k < s; ++k) h = h * b + table[k * b + next_digit(&n, rx)];
            out[i * stride] = udm1_divide_by(&power, h, tail) + add;
        }
        return;
    }
    for (size_t i = 0; i < count; ++i) out[i * stride] = head_value(first + i, rx, s, &power, mode, r, tail) + add;
}

void udm1_radical_pin(const udm1_radix *rx, uint32_t mode, uint64_t r, uint64_t *w0, uint64_t *w1)
{
    *w0 = *w1 = 0;
    if (rx->base == 2 || mode != UDM1_MODE_PERMUTE) return;
    *w1 = tail_at(rx, r, rx->split[1], rx->digits, 0);
    *w0 = tail_at(rx, r, rx->split[0], rx->split[1], *w1);
}

uint64_t udm1_radical_pinned(uint64_t n, const udm1_radix *rx, uint32_t mode, uint64_t r, uint64_t w0, uint64_t w1)
{
    if (rx->base == 2 || mode == UDM1_MODE_OWEN) return udm1_radical_inverse(n, rx, mode, r);
    if (n < rx->limit[0]) return head_value(n, rx, rx->split[0], &rx->power[0], mode, r, w0);
    if (n < rx->limit[1]) return head_value(n, rx, rx->split[1], &rx->power[1], mode, r, w1);
    return udm1_radical_inverse(n, rx, mode, r);
}
