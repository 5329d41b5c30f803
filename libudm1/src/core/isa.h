/* core/isa.h - the instruction set of the library's kernels (the Weyl bulk fills, the noise batches):
 * the best the processor has, capped by the environment variable UDM1_ISA (avx512, avx2, baseline),
 * read once per process. Every kernel gives the same values bit for bit; the cap exists so that the
 * tests run each kernel in turn and benchmarks compare them. */
#ifndef UDM1_ISA_H
#define UDM1_ISA_H

#include "core/internal.h"

enum udm1_isa_level { UDM1_ISA_BASELINE = 0, UDM1_ISA_AVX2 = 1, UDM1_ISA_AVX512 = 2 };

/* The level in use (computed on the first call, then constant). */
UDM1_HIDDEN int udm1_isa_level(void);

/* Whether the AVX-512 kernels that need VBMI's byte permutations (noise, cellular noise) may run: the
 * level in use is AVX512 and the processor has AVX-512 VBMI (computed on the first call). */
UDM1_HIDDEN int udm1_isa_vbmi(void);

#endif /* UDM1_ISA_H */
