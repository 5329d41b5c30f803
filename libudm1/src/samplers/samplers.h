/* samplers/samplers.h - the sampler kinds other than Weyl: one file each, an init that builds the
 * kind's tables into seq->data (dims, K, seed and mode are set; freed with free()) and the kind's
 * operations (seq/seq.h). */
#ifndef UDM1_SAMPLERS_H
#define UDM1_SAMPLERS_H

#include "seq/seq.h"

UDM1_HIDDEN udm1_status udm1_init_pcg32(udm1_seq_t *seq);      /* prng.c */
UDM1_HIDDEN udm1_status udm1_init_drand48(udm1_seq_t *seq);    /* prng.c */
UDM1_HIDDEN udm1_status udm1_init_halton(udm1_seq_t *seq);     /* halton.c */
UDM1_HIDDEN udm1_status udm1_init_sobol(udm1_seq_t *seq);      /* sobol.c */
UDM1_HIDDEN udm1_status udm1_init_hammersley(udm1_seq_t *seq); /* hammersley.c */
UDM1_HIDDEN udm1_status udm1_init_lp(udm1_seq_t *seq);         /* hammersley.c */
UDM1_HIDDEN udm1_status udm1_init_cmj(udm1_seq_t *seq);        /* cmj.c */
UDM1_HIDDEN udm1_status udm1_init_grps(udm1_seq_t *seq);       /* grps.c */
UDM1_HIDDEN udm1_status udm1_init_pmj02(udm1_seq_t *seq);      /* pmj02.c */
UDM1_HIDDEN udm1_status udm1_init_lattice_seq(udm1_seq_t *seq); /* lattice_sequence.c */
/* Dimensions of lattice-seq: the length of its generating vector (lattice_sequence_table.h). */
#define UDM1_LATTICE_SEQ_DIMS 64u

UDM1_HIDDEN extern const udm1_kind udm1_pcg32_kind;
/* For udm1_stream (UDM1_STREAM_PMJ02): pmj02's table ([blocks of 4 dimensions][K][4], every pair in the order it is read)
 * and its index bits ceil(log2 K); NULL for another kind. */
UDM1_HIDDEN const uint32_t *udm1_pmj02_stream_table(const udm1_seq_t *seq, uint32_t *bits);
/* For udm1_stream (UDM1_STREAM_SOBOL): Sobol's byte tables of its first *byte_dims dimensions, [dim][4][256]
 * (entry [d][k][b] the XOR of the direction numbers 8k + i for the set bits i of b), 64-bit, or with
 * `reversed` the bit reversal of their top 32 bits; NULL for another kind. */
UDM1_HIDDEN const void *udm1_sobol_stream_table(const udm1_seq_t *seq, int reversed, uint32_t *byte_dims);
UDM1_HIDDEN extern const udm1_kind udm1_drand48_kind;
UDM1_HIDDEN extern const udm1_kind udm1_halton_kind;
UDM1_HIDDEN extern const udm1_kind udm1_sobol_kind;
UDM1_HIDDEN extern const udm1_kind udm1_hammersley_kind;
UDM1_HIDDEN extern const udm1_kind udm1_lp_kind;
UDM1_HIDDEN extern const udm1_kind udm1_cmj_kind;
UDM1_HIDDEN extern const udm1_kind udm1_grps_kind;
UDM1_HIDDEN extern const udm1_kind udm1_pmj02_kind;
UDM1_HIDDEN extern const udm1_kind udm1_lattice_seq_kind;

#endif /* UDM1_SAMPLERS_H */
