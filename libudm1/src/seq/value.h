/* seq/value.h - the value of (stream key, index, dimension < D) of any kind: the Weyl kind's integer
 * arithmetic inline, every other kind through its operations table. */
#ifndef UDM1_VALUE_H
#define UDM1_VALUE_H

#include "weyl/weyl.h"

static inline uint64_t udm1_value_of(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    if (seq->kind == &udm1_weyl_kind) return udm1_weyl_shifted_raw(seq, skey, index, dim);
    return seq->kind->value(seq, skey, index, dim);
}

#endif /* UDM1_VALUE_H */
