/* core/bits.h - the bit scans the library needs (trailing and leading zeros), through the compiler's
 * builtins where it has them (GCC, Clang: one instruction), MSVC's _BitScanForward/_BitScanReverse
 * (x64, ARM64), and plain C elsewhere: the same results. Each takes a nonzero argument. Not installed. */
#ifndef UDM1_BITS_H
#define UDM1_BITS_H

#include <stdint.h>

#if !defined(__GNUC__) && defined(_MSC_VER) && (defined(_M_X64) || defined(_M_ARM64))
#include <intrin.h>
#define UDM1_BITS_MSVC_ 1
#endif

/* The number of trailing zero bits of x (x != 0). */
static inline int udm1_ctz32(uint32_t x)
{
#if defined(__GNUC__)
    return __builtin_ctz(x);
#elif defined(UDM1_BITS_MSVC_)
    unsigned long i;
    _BitScanForward(&i, x);
    return (int)i;
#else
    int n = 0;
    while (!(x & 1u)) x >>= 1, ++n;
    return n;
#endif
}

static inline int udm1_ctz64(uint64_t x)
{
#if defined(__GNUC__)
    return __builtin_ctzll(x);
#elif defined(UDM1_BITS_MSVC_)
    unsigned long i;
    _BitScanForward64(&i, x);
    return (int)i;
#else
    int n = 0;
    while (!(x & 1u)) x >>= 1, ++n;
    return n;
#endif
}

/* The index of the highest set bit of x (x != 0): 63 - the number of leading zeros. */
static inline int udm1_top_bit64(uint64_t x)
{
#if defined(__GNUC__)
    return 63 - __builtin_clzll(x);
#elif defined(UDM1_BITS_MSVC_)
    unsigned long i;
    _BitScanReverse64(&i, x);
    return (int)i;
#else
    int n = 0;
    for (int s = 32; s; s >>= 1)
        if (x >> s) x >>= s, n += s;
    return n;
#endif
}

#endif
