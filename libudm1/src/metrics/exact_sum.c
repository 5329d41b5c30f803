/* exact_sum.c - the exact sum of doubles in a 2304-bit fixed point integer (see udm1/exact_sum.h).
 *
 * A finite double is m 2^(e - 1075) with its 53-bit integer mantissa m and biased exponent e (e = 1 for
 * subnormals, whose m has no implicit bit): times 2^1074 it is m 2^(e - 1), an integer. The values are
 * added as 32-bit digits into signed 64-bit counters (three digits a value), whose carries are only
 * propagated every 2^30 values - each digit is below 2^32, so no counter can overflow - and once at the
 * end, into the caller's words. */
#include "core/internal.h"

#include <string.h>

enum { DIGITS = UDM1_EXACT_SUM_WORDS * 2, BATCH = 1 << 30 };

static void digits_to_words(int64_t *digit, uint64_t *words)
{
    /* the counters as one signed integer: carry each into the next, keeping 0 <= digit < 2^32 */
    int64_t carry = 0;
    for (int i = 0; i < DIGITS; ++i) {
        int64_t v = digit[i] + carry;
        int64_t low = (int64_t)((uint64_t)v & 0xffffffffu);
        carry = (v - low) / 4294967296; /* exact: v - low is a multiple of 2^32 */
        digit[i] = low;
    }
    /* a carry left over is the sign, beyond 2304 bits: dropped (arithmetic modulo 2^2304) */
    uint64_t c = 0;
    for (int w = 0; w < UDM1_EXACT_SUM_WORDS; ++w) {
        uint64_t add = (uint64_t)digit[2 * w] | (uint64_t)digit[2 * w + 1] << 32;
        uint64_t s = words[w] + add;
        uint64_t c1 = s < add;
        uint64_t t = s + c;
        c = c1 | (t < s);
        words[w] = t;
    }
    memset(digit, 0, DIGITS * sizeof *digit);
}

udm1_status udm1_exact_sum_add(const double *x, size_t n, uint64_t words[UDM1_EXACT_SUM_WORDS])
{
    if (!words || (!x && n))
        return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_exact_sum_add: %s is NULL", words ? "x" : "words");
    for (size_t i = 0; i < n; ++i) {
        uint64_t bits;
        memcpy(&bits, &x[i], sizeof bits);
        if (UDM1_UNLIKELY((bits >> 52 & 0x7ff) == 0x7ff))
            return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "udm1_exact_sum_add: x[%zu] is %s", i,
                             bits << 12 ? "NaN" : "infinite");
    }
    int64_t digit[DIGITS]; /* the largest double's three digits are 63 .. 65 */
    memset(digit, 0, sizeof digit);
    for (size_t i = 0; i < n; ++i) {
        uint64_t bits;
        memcpy(&bits, &x[i], sizeof bits);
        uint32_t e = (uint32_t)(bits >> 52 & 0x7ff);
        uint64_t m = bits & 0xfffffffffffffull;
        if (e)
            m |= 1ull << 52;
        else
            e = 1;
        uint32_t shift = e - 1, at = shift >> 5, o = shift & 31;
        uint64_t lo = m << o, hi = o ? m >> (64 - o) : 0;
        int64_t sign = -(int64_t)(bits >> 63); /* 0 or -1: (d ^ sign) - sign is d or -d, without a branch */
        int64_t d0 = (int64_t)(lo & 0xffffffffu), d1 = (int64_t)(lo >> 32), d2 = (int64_t)hi;
        digit[at] += (d0 ^ sign) - sign;
        digit[at + 1] += (d1 ^ sign) - sign;
        digit[at + 2] += (d2 ^ sign) - sign;
        if (UDM1_UNLIKELY((i + 1) % BATCH == 0))
            digits_to_words(digit, words);
    }
    digits_to_words(digit, words);
    return UDM1_OK;
}
