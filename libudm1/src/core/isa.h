/* core/isa.h - the instruction set of the library's kernels (the Weyl bulk fills, the noise batches):
 * the best the processor has, capped by the environment variable UDM1_ISA (avx512, avx2, baseline on
 * x86-64; neon, baseline on 64-bit Arm), read once per process. Every kernel gives the same values bit
 * for bit; the cap exists so that the tests run each kernel in turn and benchmarks compare them. */
#ifndef UDM1_ISA_H
#define UDM1_ISA_H

#include "core/internal.h"

/* (x86-64: BASELINE < AVX2 < AVX512, each level including the one below; 64-bit Arm: BASELINE, NEON) */
enum udm1_isa_level { UDM1_ISA_BASELINE = 0, UDM1_ISA_AVX2 = 1, UDM1_ISA_AVX512 = 2, UDM1_ISA_NEON = 3 };

/* The level in use (computed on the first call, then constant). */
UDM1_HIDDEN int udm1_isa_level(void);

/* Whether the AVX-512 kernels that need VBMI's byte permutations (noise, cellular noise) may run: the
 * level in use is AVX512 and the processor has AVX-512 VBMI (computed on the first call). */
UDM1_HIDDEN int udm1_isa_vbmi(void);

#endif /* UDM1_ISA_H */
