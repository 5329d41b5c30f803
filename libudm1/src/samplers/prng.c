/* prng.c - the PRNG baselines, seekable so that (stream, index, dim) is
 * random access: value (n, j) of a D-dimensional sequence is output number
 * n*D + j of the stream (positions wrap modulo 2^64).
 *
 *  pcg32:   PCG32 XSH-RR 64/32 (O'Neill 2014). The stream is
 *           pcg32_srandom(seed, initseq) with initseq = 54 (the pcg32 demo's,
 *           so seed 42 reproduces its published output) under
 *           UDM1_RANDOMIZE_NONE, and initseq = the stream key otherwise.
 *           32 random bits per value (the top 32 of the raw 0.64 value).
 *  drand48: the 48-bit LCG of the C library (a = 0x5DEECE66D, c = 11). Under
 *           UDM1_RANDOMIZE_NONE the state starts as srand48(seed) does,
 *           (low 32 bits of seed) << 16 | 0x330E, so values equal drand48()'s
 *           bit for bit; otherwise it starts at the low 48 bits of the stream key.
 * Jumps use the LCG's closed form (Brown 1994) in O(log n): n steps of
 * x -> a x + c are x -> A(n) x + c G(n), A(n) = a^n, G(n) = 1 + a + ... + a^(n-1);
 * a table of A and G at the powers of two, made once per sequence, composes them
 * with two multiplications per set bit of n.
 */
#include <stdlib.h>

#include "samplers/samplers.h"
#include "seq/scramble.h"

#define PCG_MULT 6364136223846793005ull
#define DRAND_A 0x5DEECE66Dull
#define DRAND_C 0xBull
#define DRAND_MASK ((1ull << 48) - 1)

typedef struct lcg_table { uint64_t A[64], G[64]; } lcg_table;

static lcg_table *lcg_table_new(uint64_t a)
{
    lcg_table *t = malloc(sizeof *t);
    if (!t) return NULL;
    uint64_t A = a, G = 1;
    for (int k = 0; k < 64; ++k) {
        t->A[k] = A, t->G[k] = G;
        G = G * A + G; /* G(2m) = G(m) a^m + G(m) */
        A *= A;
    }
    return t;
}

/* (mult, plus) of n steps of x -> a x + c, by the table of a */
static void lcg_jump_table(const lcg_table *t, uint64_t c, uint64_t n, uint64_t *mult, uint64_t *plus)
{
    /* branch-free: each bit selects its factor or the identity (a data-dependent branch per bit
     * mispredicted about half the time, which cost more than the multiplications) */
    uint64_t am = 1, g = 0;
    for (int k = 0; n; ++k, n >>= 1) {
        uint64_t bit = 0 - (n & 1);
        uint64_t a = (t->A[k] & bit) | (1 & ~bit), gk = t->G[k] & bit;
        g = g * a + gk;
        am *= a;
    }
    *mult = am;
    *plus = g * c;
}

static uint32_t pcg_output(uint64_t old)
{
    uint32_t xorshifted = (uint32_t)(((old >> 18) ^ old) >> 27);
    uint32_t rot = (uint32_t)(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

/* the increment of pcg32_srandom(initstate, initseq) */
static uint64_t pcg_inc(const udm1_seq_t *seq, uint64_t stream_key)
{
    uint64_t initseq = seq->mode == UDM1_MODE_NONE ? 54u : stream_key;
    return (initseq << 1) | 1u;
}

/* the state after pcg32_srandom(initstate, initseq), and the increment */
static void pcg_seed(const udm1_seq_t *seq, uint64_t stream_key, uint64_t *state, uint64_t *inc)
{
    *inc = pcg_inc(seq, stream_key);
    uint64_t s = 0;
    s = s * PCG_MULT + *inc;
    s += seq->seed;
    s = s * PCG_MULT + *inc;
    *state = s;
}

static uint64_t pcg_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    uint64_t state, inc, m, p;
    pcg_seed(seq, skey, &state, &inc);
    lcg_jump_table(seq->data, inc, index * seq->dims + dim, &m, &p);
    uint64_t v = (uint64_t)pcg_output(state * m + p) << 32;
    return udm1_randomize_base2(seq->mode, v + seq->offset[dim], udm1_word(seq, skey, dim));
}

static uint64_t drand_start(const udm1_seq_t *seq, uint64_t stream_key)
{
    if (seq->mode == UDM1_MODE_NONE) return ((seq->seed & 0xFFFFFFFFull) << 16) | 0x330Eu;
    return stream_key & DRAND_MASK;
}

static uint64_t drand_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    uint64_t m, p;
    /* drand48() steps first, then returns the new state: value k is state k + 1 */
    lcg_jump_table(seq->data, DRAND_C, index * seq->dims + dim + 1, &m, &p);
    uint64_t x = (drand_start(seq, skey) * m + p) & DRAND_MASK;
    return udm1_randomize_base2(seq->mode, (x << 16) + seq->offset[dim], udm1_word(seq, skey, dim));
}

/* Sequential fills: one jump, then steps. */
static void prng_fill(const udm1_seq_t *seq, uint64_t skey, uint64_t first, size_t count, uint32_t dim0, uint32_t nd,
                      uint64_t *raw, int drand)
{
    uint64_t a = drand ? DRAND_A : PCG_MULT, state, inc, m, p;
    if (drand) {
        state = drand_start(seq, skey);
        inc = DRAND_C;
    } else {
        pcg_seed(seq, skey, &state, &inc);
    }
    uint64_t pos = first * seq->dims + dim0 + (drand ? 1u : 0u);
    lcg_jump_table(seq->data, inc, pos, &m, &p);
    state = state * m + p;
    /* steps from the last dimension of a row to dim0 of the next */
    uint64_t skip_m, skip_p;
    lcg_jump_table(seq->data, inc, (uint64_t)seq->dims - nd + 1, &skip_m, &skip_p);
    for (size_t i = 0; i < count; ++i) {
        for (uint32_t j = 0; j < nd; ++j) {
            uint32_t dim = dim0 + j;
            uint64_t v = drand ? (state & DRAND_MASK) << 16 : (uint64_t)pcg_output(state) << 32;
            raw[i * nd + j] = udm1_randomize_base2(seq->mode, v + seq->offset[dim], udm1_word(seq, skey, dim));
            if (j + 1 < nd) state = state * a + inc;
        }
        state = state * skip_m + skip_p;
    }
}

static void pcg_fill(const udm1_seq_t *seq, uint64_t skey, uint64_t first, size_t count, uint32_t dim0, uint32_t nd,
                     uint64_t *raw)
{
    prng_fill(seq, skey, first, count, dim0, nd, raw, 0);
}

static void drand_fill(const udm1_seq_t *seq, uint64_t skey, uint64_t first, size_t count, uint32_t dim0,
                       uint32_t nd, uint64_t *raw)
{
    prng_fill(seq, skey, first, count, dim0, nd, raw, 1);
}

udm1_status udm1_init_pcg32(udm1_seq_t *seq)
{
    if (!(seq->data = lcg_table_new(PCG_MULT)))
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "udm1_seq_create: out of memory for the pcg32 jump table");
    return UDM1_OK;
}

udm1_status udm1_init_drand48(udm1_seq_t *seq)
{
    if (!(seq->data = lcg_table_new(DRAND_A)))
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "udm1_seq_create: out of memory for the drand48 jump table");
    return UDM1_OK;
}

/* A cursor's steps: the state at position index D + dim, then one LCG step per value (pcg32: the output
 * of the state, then the step; drand48: the step, then its state, as drand48() does). */
static uint64_t pcg_seek(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    uint64_t state, inc, m, p;
    pcg_seed(seq, skey, &state, &inc);
    lcg_jump_table(seq->data, inc, index * seq->dims + dim, &m, &p);
    return state * m + p;
}

static uint64_t pcg_step(const udm1_seq_t *seq, uint64_t skey, uint64_t *state, uint32_t dim)
{
    uint64_t old = *state;
    *state = old * PCG_MULT + pcg_inc(seq, skey);
    uint64_t v = (uint64_t)pcg_output(old) << 32;
    return udm1_randomize_base2(seq->mode, v + seq->offset[dim], udm1_word(seq, skey, dim));
}

static uint64_t drand_seek(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    uint64_t m, p;
    lcg_jump_table(seq->data, DRAND_C, index * seq->dims + dim, &m, &p);
    return (drand_start(seq, skey) * m + p) & DRAND_MASK;
}

static uint64_t drand_step(const udm1_seq_t *seq, uint64_t skey, uint64_t *state, uint32_t dim)
{
    uint64_t x = (*state * DRAND_A + DRAND_C) & DRAND_MASK;
    *state = x;
    return udm1_randomize_base2(seq->mode, (x << 16) + seq->offset[dim], udm1_word(seq, skey, dim));
}

const udm1_kind udm1_pcg32_kind = {.name = "pcg32", .value = pcg_value, .fill = pcg_fill, .seek = pcg_seek, .step = pcg_step};
const udm1_kind udm1_drand48_kind = {.name = "drand48", .value = drand_value, .fill = drand_fill, .seek = drand_seek, .step = drand_step};
