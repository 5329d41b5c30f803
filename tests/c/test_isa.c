/* test_isa.c - the instruction set forced by UDM1_ISA is the one the library's kernels use:
 * test_isa LEVEL checks that udm1_isa() is LEVEL, or skips (exit 77, with the reason) where this
 * processor or build lacks it. CTest runs it beside test_fill and test_noise under each UDM1_ISA, so
 * that every kernel is shown to have run and to equal the scalar reference. */
#include <udm1/udm1.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: test_isa avx512|avx2|neon|baseline (with UDM1_ISA set to the same)\n");
        return 2;
    }
    const char *want = argv[1], *env = getenv("UDM1_ISA"), *got = udm1_isa();
    if (!env || strcmp(env, want) != 0) {
        fprintf(stderr, "test_isa: UDM1_ISA is '%s', expected '%s'\n", env ? env : "(unset)", want);
        return 1;
    }
    if (strcmp(got, want) == 0) {
        printf("kernels in use: %s\n", got);
        return 0;
    }
    /* a lower level than asked: only where the processor (or a build without the copies) lacks it */
    static const char *order[] = {"baseline", "neon", "avx2", "avx512"}; /* (neon: on Arm, above baseline) */
    int w = 0, g = 0;
    for (int i = 0; i < 4; ++i) {
        if (strcmp(order[i], want) == 0) w = i;
        if (strcmp(order[i], got) == 0) g = i;
    }
    if (g < w) {
        printf("SKIP: this processor or build has no %s kernels (the library uses %s)\n", want, got);
        return 77;
    }
    fprintf(stderr, "test_isa: UDM1_ISA=%s but the library uses %s\n", want, got);
    return 1;
}
