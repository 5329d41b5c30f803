/* weyl/generators.h - a Weyl sequence's generators: the exact 0.128 fixed-point fraction of each
 * dimension's alpha, what is known of its arithmetic nature, and how the presets' sets are made. */
#ifndef UDM1_GENERATORS_H
#define UDM1_GENERATORS_H

#include "core/internal.h"

/* What is known about a generator's arithmetic nature (for udm1_alpha_check). */
enum udm1_alpha_nature {
    UDM1_NATURE_UNKNOWN = 0,   /* a fixed-point or double value: only numeric checks */
    UDM1_NATURE_RATIONAL = 1,  /* rational: useless as a generator */
    UDM1_NATURE_QUADRATIC = 2, /* a + b sqrt(m), m square-free >= 2, stored in `radical` */
    UDM1_NATURE_INDEPENDENT = 3, /* independent of every other generator of its set and of 1
                                    by construction (e, e^2; R_d) */
    UDM1_NATURE_POINT_SET = 4    /* rational by design: the n/K axis of a point set (EPIS) */
};

/* One dimension's generator: the 0.128 fixed-point fraction and its nature. */
typedef struct udm1_generator {
    uint64_t hi, lo;
    uint32_t nature;   /* enum udm1_alpha_nature */
    uint64_t radical;  /* square-free m for UDM1_NATURE_QUADRATIC */
} udm1_generator;

/* frac(sqrt(k)) for k >= 2 not a perfect square; returns 0 if k is a square. */
UDM1_HIDDEN int udm1_gen_sqrt(uint64_t k, udm1_generator *g);
/* frac((a + b sqrt(k)) / c), small a, b >= 1, c in {1, 2}; k not a square. */
UDM1_HIDDEN int udm1_gen_quadratic(int64_t a, uint64_t b, uint64_t k, uint64_t c, udm1_generator *g);
/* R_d generators phi_d^-1 .. phi_d^-d into g[0..d-1]; d >= 1. Returns 0 on out of memory. */
UDM1_HIDDEN int udm1_gen_rd(uint32_t d, udm1_generator *g);
/* Square-free part of k (k >= 1). */
UDM1_HIDDEN uint64_t udm1_squarefree_part(uint64_t k);
/* The first `count` primes into out. Returns 0 on out of memory. */
UDM1_HIDDEN int udm1_first_primes(uint32_t count, uint64_t *out);

/* ---- user generators (seq/seq.c) ---- */
/* Resolve alphas[j]; with check != 0 a rational one is marked, not refused. */
UDM1_HIDDEN udm1_status udm1_user_generator(const char *fn, uint32_t j, const udm1_alpha *a, udm1_generator *g,
                                            int check);

/* ---- the constant-set check (alpha_check.c) ---- */
/* The report of udm1_seq_check and udm1_alpha_check (fn, their name, for the messages); *report is written
 * only on success. */
UDM1_HIDDEN udm1_status udm1_check_generators(const char *fn, const udm1_generator *gen, uint32_t dims, uint64_t n,
                                              udm1_alpha_report *report);

#endif /* UDM1_GENERATORS_H */
