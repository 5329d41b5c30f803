/* core/internal.h - what every libudm1 source shares: visibility and branch hints, the error report,
 * the conversions of a raw 0.64 value, and (core/u128.h) the 128-bit arithmetic. Not installed. */
#ifndef UDM1_INTERNAL_H
#define UDM1_INTERNAL_H

#include "core/u128.h"
#include "udm1/udm1.h"

#include <stddef.h>
#include <stdint.h>

#if defined(__GNUC__)
#  if defined(_WIN32) /* (a DLL exports only what is dllexport: nothing to hide) */
#    define UDM1_HIDDEN
#  else
#    define UDM1_HIDDEN __attribute__((visibility("hidden")))
#  endif
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
#if defined(__MINGW32__) /* (its C99 formatting, __USE_MINGW_ANSI_STDIO: CMakeLists.txt) */
    __attribute__((format(gnu_printf, 2, 3)))
#elif defined(__GNUC__)
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

/* Conversions of a raw 0.64 value. Both are < 1 for every input. */
static inline double udm1_to_f64(uint64_t u) { return (double)(int64_t)(u >> 11) * 0x1p-53; }
static inline float udm1_to_f32(uint64_t u) { return (float)(int32_t)(u >> 40) * 0x1p-24f; }

#endif /* UDM1_INTERNAL_H */
