/* status.c - status strings, the per-thread last-error message, version. */
#include "core/internal.h"

#include <stdarg.h>
#include <stdio.h>

#if defined(_MSC_VER)
#  define UDM1_THREAD_LOCAL __declspec(thread)
#else
#  define UDM1_THREAD_LOCAL _Thread_local
#endif

static UDM1_THREAD_LOCAL char last_error[512];

udm1_status udm1_fail(udm1_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_error, sizeof last_error, fmt, ap);
    va_end(ap);
    return status;
}

const char *udm1_last_error(void) { return last_error; }

const char *udm1_status_string(udm1_status status)
{
    switch (status) {
    case UDM1_OK: return "ok";
    case UDM1_ERROR_NULL_ARGUMENT: return "null argument";
    case UDM1_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case UDM1_ERROR_DIMENSION: return "dimension out of range";
    case UDM1_ERROR_UNKNOWN_PRESET: return "unknown preset";
    case UDM1_ERROR_RATIONAL_ALPHA: return "rational generator";
    case UDM1_ERROR_POINT_COUNT: return "invalid point count";
    case UDM1_ERROR_INDEX_RANGE: return "index out of range";
    case UDM1_ERROR_OUT_OF_MEMORY: return "out of memory";
    }
    return "unknown status";
}

#define UDM1_STR2(x) #x
#define UDM1_STR(x) UDM1_STR2(x)

uint32_t udm1_version(void) { return UDM1_VERSION; }

const char *udm1_version_string(void)
{
    return UDM1_STR(UDM1_VERSION_MAJOR) "." UDM1_STR(UDM1_VERSION_MINOR) "." UDM1_STR(UDM1_VERSION_PATCH);
}
