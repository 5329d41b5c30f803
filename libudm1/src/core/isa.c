/* isa.c - see isa.h. */
#include "core/isa.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

/* What the processor and this build support: the kernels exist for x86-64 with GCC or Clang when the
 * build compiles them (UDM1_MULTIVERSION, UDM1_HAVE_ISA_KERNELS), and for 64-bit Arm, where NEON is part
 * of the architecture (UDM1_HAVE_NEON_KERNELS). */
static int supported(void)
{
#if defined(UDM1_HAVE_NEON_KERNELS)
    return UDM1_ISA_NEON;
#endif
#if defined(UDM1_HAVE_ISA_KERNELS) && defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    /* each level includes the one below (the AVX-512 level may run AVX2 + FMA code) */
    if (!(__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2")))
        return UDM1_ISA_BASELINE;
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
        __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw"))
        return UDM1_ISA_AVX512;
    return UDM1_ISA_AVX2;
#endif
    return UDM1_ISA_BASELINE;
}

static int cap(void)
{
    const char *v = getenv("UDM1_ISA");
    if (!v || !*v) return UDM1_ISA_AVX512;
    if (strcmp(v, "avx2") == 0) return UDM1_ISA_AVX2;
    if (strcmp(v, "baseline") == 0 || strcmp(v, "scalar") == 0) return UDM1_ISA_BASELINE;
    return UDM1_ISA_AVX512; /* "avx512" or anything else: no cap */
}

static atomic_int level = -1;

int udm1_isa_level(void)
{
    int l = atomic_load_explicit(&level, memory_order_relaxed);
    if (UDM1_LIKELY(l >= 0)) return l;
    int s = supported(), c = cap();
    l = s == UDM1_ISA_NEON ? (c == UDM1_ISA_BASELINE ? c : s) : s < c ? s : c; /* (NEON: "baseline" caps it) */
    atomic_store_explicit(&level, l, memory_order_relaxed); /* every thread computes the same value */
    return l;
}

static atomic_int vbmi = -1;

int udm1_isa_vbmi(void)
{
    int v = atomic_load_explicit(&vbmi, memory_order_relaxed);
    if (UDM1_LIKELY(v >= 0)) return v;
    v = 0;
#if defined(UDM1_HAVE_ISA_KERNELS) && defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    v = udm1_isa_level() == UDM1_ISA_AVX512 && __builtin_cpu_supports("avx512vbmi");
#endif
    atomic_store_explicit(&vbmi, v, memory_order_relaxed);
    return v;
}

const char *udm1_isa(void)
{
    static const char *const names[] = {"baseline", "avx2", "avx512", "neon"};
    return names[udm1_isa_level()];
}
