/* core/internal.h - what every libudm1 source shares: visibility and branch hints, the error report,
 * 64x64 -> 128-bit multiplication and the conversions of a raw 0.64 value. Not installed. */
#ifndef UDM1_INTERNAL_H
#define UDM1_INTERNAL_H

#include "udm1/udm1.h"

#include <stddef.h>
#include <stdint.h>

#if defined(__GNUC__)
#  define UDM1_HIDDEN __attribute__((visibility("hidden")))
#  define UDM1_LIKELY(x) __builtin_expect(!!(x), 1)
#  define UDM1_UNLIKELY(x) __builtin_expect(!!(x), 0)
#  define UDM1_NOINLINE_COLD __attribute__((noinline, cold))
#else
#  define UDM1_HIDDEN
#  define UDM1_LIKELY(x) (x)
#  define UDM1_UNLIKELY(x) (x)
#  define UDM1_NOINLINE_COLD
#endif

/* ---- error reporting (status.c) ---- */
/* Record a one-line message for udm1_last_error() and return status. */
UDM1_HIDDEN udm1_status udm1_fail(udm1_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* ---- versioned descriptors (struct_size.c) ---- */
/* Read a caller's descriptor whose first field is its uint32_t struct_size into dst (this library's
 * layout, dst_size bytes): the caller's first min(struct_size, dst_size) bytes, zeros after them.
 * A struct_size below v1_size (the first release's layout) is refused; one above dst_size (a caller
 * built against a newer udm1) is accepted when every byte this library does not know is zero, and
 * refused otherwise. `what` names the argument in the message ("desc"). */
UDM1_HIDDEN udm1_status udm1_read_struct(const char *fn, const char *what, const char *init_fn, const void *src,
                                         size_t v1_size, void *dst, size_t dst_size);

/* ---- work limits of the metrics (metrics.h) ---- */
/* Whether a x b x c (each up to 2^64; the product in double, so it cannot overflow) is above limit. */
static inline int udm1_work_above(uint64_t a, uint64_t b, uint64_t c, uint64_t limit)
{
    return (double)a * (double)b * (double)c > (double)limit;
}

/* ---- 64x64 -> 128 multiply ---- */
static inline void udm1_mul64(uint64_t a, uint64_t b, uint64_t *hi, uint64_t *lo)
{
#if defined(__SIZEOF_INT128__)
    __extension__ typedef unsigned __int128 u128;
    u128 p = (u128)a * b;
    *hi = (uint64_t)(p >> 64);
    *lo = (uint64_t)p;
#else
    uint64_t a0 = a & 0xffffffffu, a1 = a >> 32, b0 = b & 0xffffffffu, b1 = b >> 32;
    uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
    *lo = (mid << 32) | (p00 & 0xffffffffu);
    *hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
#endif
}

/* Conversions of a raw 0.64 value. Both are < 1 for every input. */
static inline double udm1_to_f64(uint64_t u) { return (double)(int64_t)(u >> 11) * 0x1p-53; }
static inline float udm1_to_f32(uint64_t u) { return (float)(int32_t)(u >> 40) * 0x1p-24f; }

#endif /* UDM1_INTERNAL_H */
