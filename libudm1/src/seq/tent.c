/* tent.c - "NAME+tent": the tent (baker's) transform 1 - |2x - 1| of every value of the wrapped kind
 * seq->inner, exact on the raw 0.64 value. */
#include "seq/value.h"

static uint64_t inner_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    if (seq->inner == &udm1_weyl_kind) return udm1_weyl_shifted_raw(seq, skey, index, dim);
    return seq->inner->value(seq, skey, index, dim);
}

static uint64_t tent_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    return udm1_tent(inner_value(seq, skey, index, dim));
}

static void tent_fill(const udm1_seq_t *seq, uint64_t skey, uint64_t first, size_t count, uint32_t dim0, uint32_t nd,
                      uint64_t *raw)
{
    if (seq->inner->fill) {
        seq->inner->fill(seq, skey, first, count, dim0, nd, raw);
    } else {
        for (size_t i = 0; i < count; ++i)
            for (uint32_t j = 0; j < nd; ++j) raw[i * nd + j] = inner_value(seq, skey, first + i, dim0 + j);
    }
    for (size_t i = 0; i < count * nd; ++i) raw[i] = udm1_tent(raw[i]);
}

/* no base2: the tent is not a base-2 randomization of a base-2 value */
const udm1_kind udm1_tent_kind = {.name = "tent", .value = tent_value, .fill = tent_fill};
