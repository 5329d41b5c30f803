/* fuzz_bytes.h - what the C fuzz targets share: reading fuzzer bytes as numbers, and an invariant check
 * that aborts (so that libFuzzer and the replay test both report it) with the failed condition. */
#ifndef UDM1_FUZZ_BYTES_H
#define UDM1_FUZZ_BYTES_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#define REQUIRE(cond)                                                                                        \
    do {                                                                                                     \
        if (!(cond)) {                                                                                       \
            fprintf(stderr, "%s: invariant failed at line %d: %s\n", __FILE__, __LINE__, #cond);            \
            abort();                                                                                         \
        }                                                                                                    \
    } while (0)

typedef struct bytes {
    const uint8_t *p;
    size_t n;
} bytes;

/* k bytes as a little-endian number; zeros past the end */
static inline uint64_t take(bytes *b, int k)
{
    uint64_t v = 0;
    for (int i = 0; i < k; ++i) v |= (uint64_t)(b->n ? (--b->n, *b->p++) : 0) << (8 * i);
    return v;
}

#endif
