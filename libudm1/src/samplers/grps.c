/* grps.c - golden ratio point sets (Schretter, Kobbelt, Dehaye, "Golden Ratio
 * Sequences for Low-Discrepancy Sampling", JGT 16(2), 2012).
 *
 * For K points and two offsets s1, s2: g_i = {s1 + i/phi} for i < K; point t is
 * (the t-th smallest g_i, {s2 + t/phi}). The sorted order of {i/phi} comes in
 * O(K) from the Fibonacci walk of the paper (three-distance theorem): from
 * the smallest, step +F_a or -F_b. Adding s1 rotates the circle, so the order
 * for any s1 is the same list started where the values wrap past 1 (a binary
 * search). Values are exact: i/phi is the golden Weyl generator in 0.128.
 * Used in pairs: pair k has its own offsets from (seed, k) and, when
 * randomized, the stream; pairs k >= 1 visit the points in their own order.
 */
#include "samplers/samplers.h"
#include "weyl/weyl.h"
#include "seq/scramble.h"

#include <stdlib.h>

typedef struct grps {
    udm1_generator golden; /* frac(1/phi) = frac(phi) in 0.128, exact: the golden preset's */
    uint32_t order[1];     /* K indices by increasing {i/phi} */
} grps;

static uint64_t g(const grps *t, uint64_t i) { return udm1_weyl_raw(&t->golden, 0, i); }

static uint64_t grps_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    const grps *t = seq->data;
    uint32_t pair = dim / 2;
    uint64_t K = seq->point_count, i = udm1_pair_index(seq, pair, index);
    uint64_t key = seq->mode == UDM1_MODE_NONE ? seq->seed_key : skey;
    uint64_t v;
    if ((dim & 1) == 0) {
        uint64_t s1 = udm1_mix64(key ^ udm1_mix64(0x4752505331ull + pair));
        /* first sorted position whose value wraps: g >= 2^64 - s1 */
        uint64_t lo = 0, hi = K;
        while (lo < hi) {
            uint64_t mid = (lo + hi) / 2;
            if (s1 != 0 && g(t, t->order[mid]) >= (uint64_t)0 - s1)
                hi = mid;
            else
                lo = mid + 1;
        }
        v = g(t, t->order[(lo + i) % K]) + s1;
    } else {
        uint64_t s2 = udm1_mix64(key ^ udm1_mix64(0x4752505332ull + pair));
        v = g(t, i) + s2;
    }
    return udm1_randomize_base2(seq->mode, v + seq->offset[dim], udm1_word(seq, skey, dim));
}

udm1_status udm1_init_grps(udm1_seq_t *seq)
{
    uint64_t K = seq->point_count;
    if (K > (1u << 26))
        return udm1_fail(UDM1_ERROR_POINT_COUNT, "udm1_seq_create: grps takes at most 2^26 points, %llu asked",
                         (unsigned long long)K);
    grps *t = malloc(sizeof(grps) + sizeof(uint32_t) * K);
    if (!t) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "udm1_seq_create: out of memory for %llu points",
                             (unsigned long long)K);
    udm1_gen_quadratic(-1, 1, 5, 2, &t->golden);
    /* Fibonacci walk: F_a + F_b >= K, steps +inc (then -dec if past K) or -dec */
    uint64_t f = 1, fp = 1, parity = 0;
    while (f + fp < K) {
        uint64_t nf = f + fp;
        fp = f;
        f = nf;
        ++parity;
    }
    uint64_t inc = (parity & 1) ? f : fp, dec = (parity & 1) ? fp : f;
    uint64_t idx = 0; /* g_0 = 0 is the smallest */
    t->order[0] = 0;
    for (uint64_t k = 1; k < K; ++k) {
        if (idx < dec) {
            idx += inc;
            if (idx >= K) idx -= dec;
        } else {
            idx -= dec;
        }
        t->order[k] = (uint32_t)idx;
    }
    seq->data = t;
    return UDM1_OK;
}

const udm1_kind udm1_grps_kind = {.name = "grps", .value = grps_value};
