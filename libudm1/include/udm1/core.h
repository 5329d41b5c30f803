/*
 * udm1/core.h - what every part of libudm1's interface shares: the version, the export macro, status
 * codes and the per-thread error message.
 * Part of libudm1's public interface; udm1/udm1.h includes every part.
 */
#ifndef UDM1_CORE_H
#define UDM1_CORE_H

#include <stddef.h>
#include <stdint.h>

#define UDM1_VERSION_MAJOR 1
#define UDM1_VERSION_MINOR 11
#define UDM1_VERSION_PATCH 0
/* MAJOR * 10000 + MINOR * 100 + PATCH, as returned by udm1_version(). */
#define UDM1_VERSION (UDM1_VERSION_MAJOR * 10000 + UDM1_VERSION_MINOR * 100 + UDM1_VERSION_PATCH)

#if defined(UDM1_STATIC_DEFINE)
#  define UDM1_API
#elif defined(_WIN32)
#  if defined(UDM1_BUILDING)
#    define UDM1_API __declspec(dllexport)
#  else
#    define UDM1_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__) && defined(UDM1_BUILDING)
#  define UDM1_API __attribute__((visibility("default")))
#else
#  define UDM1_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* Status codes and version                                                  */
/* ------------------------------------------------------------------------ */

typedef enum udm1_status {
    UDM1_OK = 0,
    UDM1_ERROR_NULL_ARGUMENT = 1,    /* a required pointer argument was NULL */
    UDM1_ERROR_INVALID_ARGUMENT = 2, /* a value outside its documented range */
    UDM1_ERROR_DIMENSION = 3,        /* 0 dimensions, too many, or a dimension index out of range */
    UDM1_ERROR_UNKNOWN_PRESET = 4,   /* no preset has that name */
    UDM1_ERROR_RATIONAL_ALPHA = 5,   /* a generator is rational (e.g. sqrt of a perfect square) */
    UDM1_ERROR_POINT_COUNT = 6,      /* a point set without a valid point count K, or K given to a sequence */
    UDM1_ERROR_INDEX_RANGE = 7,      /* index past the point count, or first + count past 2^64 */
    UDM1_ERROR_OUT_OF_MEMORY = 8
} udm1_status;

/*
 * A function that returns a udm1_status and fails writes nothing into the caller's memory: every output
 * array, struct and pointer it was given keeps every byte it had (the creators - udm1_seq_create,
 * udm1_noise_create, udm1_lattice_bound_create - set *out to NULL and nothing else), and
 * udm1_last_error() names the function and the input. A batch checks all of its input (every point,
 * index and dimension) before it writes its first output.
 *
 * Functions without a status (queries, the cursor's draws, the scalar noise and pattern calls, the
 * initializers and destroyers) follow one rule for inputs they cannot use, a NULL handle or pointer
 * first: they never crash, they do nothing or return a neutral value - 0, NULL, or NaN where the
 * result is a number - and, except the destroyers and initializers (for which NULL is a no-op), set
 * udm1_last_error() to a line naming the function and the input. Where a number is drawn or
 * evaluated (the cursor, noise, patterns) the neutral value is NaN, which no valid call returns.
 */

/* Version of the library actually loaded: UDM1_VERSION of its build. */
UDM1_API uint32_t udm1_version(void);
/* "1.0.0". Static storage; never NULL. */
UDM1_API const char *udm1_version_string(void);
/* A short fixed English text for a status ("invalid argument"). Static
 * storage; never NULL, also for unknown codes. */
UDM1_API const char *udm1_status_string(udm1_status status);
/* The instruction set of the library's kernels in this process - the Weyl bulk fills and the noise
 * batches: "avx512", "avx2" or "baseline" on x86-64, "neon" or "baseline" on 64-bit Arm ("baseline"
 * elsewhere). The best the processor has, capped by the environment variable UDM1_ISA=avx512|avx2|baseline
 * (neon|baseline on Arm), read once, when a kernel is first needed. Every kernel gives the same values bit
 * for bit; the cap lets tests run each one and benchmarks compare them. Static storage. (1.6) */
UDM1_API const char *udm1_isa(void);
/* The one-line message of the last failing udm1 call on this thread, such as
 * "udm1_seq_create: unknown preset 'wrr'". Empty if none failed yet.
 * Valid until the next failing udm1 call on this thread. */
UDM1_API const char *udm1_last_error(void);

#ifdef __cplusplus
}
#endif

#endif /* UDM1_CORE_H */
