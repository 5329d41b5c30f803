/* check.h - the few macros the C tests need. A failed CHECK prints the file,
 * line and expression and makes the test exit non-zero; the test goes on so
 * one run shows every failure. */
#ifndef UDM1_TEST_CHECK_H
#define UDM1_TEST_CHECK_H

#include <stdio.h>
#include <stdlib.h>

static int check_failures = 0;

/* A sampled run of a test's matrix (the emulated platforms' quick subset of ./run.sh test): with the
 * environment variable UDM1_TEST_SAMPLE=k, check_sampled() is true for one call in k (calls 0, k, 2k, ...:
 * the cases a loop runs spread over its matrix, the same in every run); without it, for every call. */
static inline int check_sampled(void)
{
    static long every = 0, calls = 0;
    if (every == 0) {
        const char *v = getenv("UDM1_TEST_SAMPLE");
        every = v ? atol(v) : 1;
        if (every < 1) every = 1;
    }
    return calls++ % every == 0;
}

/* Whether this test was compiled for an instruction set (the ISA variants of tests/CMakeLists.txt: GFNI with
 * AVX2, AVX-512 DQ and VL, AVX2) that the processor running it lacks: it prints a SKIP line and returns 1, and
 * the test then exits with 77 (CTest's skip code). */
static inline int check_built_isa_missing(void)
{
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
#if defined(__GFNI__)
    if (!__builtin_cpu_supports("gfni") || !__builtin_cpu_supports("avx2")) {
        printf("SKIP: built for GFNI and AVX2, which this processor lacks\n");
        return 1;
    }
#elif defined(__AVX512DQ__) && defined(__AVX512VL__)
    if (!__builtin_cpu_supports("avx512dq") || !__builtin_cpu_supports("avx512vl")) {
        printf("SKIP: built for AVX-512 (DQ, VL), which this processor lacks\n");
        return 1;
    }
#elif defined(__AVX2__)
    if (!__builtin_cpu_supports("avx2")) {
        printf("SKIP: built for AVX2, which this processor lacks\n");
        return 1;
    }
#endif
#endif
    return 0;
}

#define CHECK(cond)                                                                   \
    do {                                                                              \
        if (!(cond)) {                                                                \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);  \
            ++check_failures;                                                         \
        }                                                                             \
    } while (0)

/* CHECK with a printf-style explanation. */
#define CHECKF(cond, ...)                                                             \
    do {                                                                              \
        if (!(cond)) {                                                                \
            fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond);  \
            fprintf(stderr, __VA_ARGS__);                                             \
            fputc('\n', stderr);                                                      \
            ++check_failures;                                                         \
        }                                                                             \
    } while (0)

#define CHECK_STATUS(call, expected)                                                  \
    do {                                                                              \
        udm1_status check_st_ = (call);                                               \
        if (check_st_ != (expected)) {                                                \
            fprintf(stderr, "%s:%d: %s returned %d (%s), expected %s; last error: %s\n", \
                    __FILE__, __LINE__, #call, (int)check_st_,                        \
                    udm1_status_string(check_st_), #expected, udm1_last_error());     \
            ++check_failures;                                                         \
        }                                                                             \
    } while (0)

#define CHECK_DONE()                                                                  \
    do {                                                                              \
        if (check_failures) fprintf(stderr, "%d check(s) failed\n", check_failures);  \
        return check_failures ? 1 : 0;                                                \
    } while (0)

#endif
