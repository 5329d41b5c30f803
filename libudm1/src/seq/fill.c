/* fill.c - bulk fills of index ranges: the checks, then the Weyl kind's kernels (weyl/weyl.c) or, for
 * every other kind, its own fill of rows (or one value call each) converted and written with the stride. */
#include "weyl/weyl.h"

#include <stdlib.h>
#include <string.h>

#define CONV_F64(h) ((double)(int64_t)((h) >> 11) * 0x1p-53)
#define CONV_F32(h) ((float)(int32_t)((h) >> 40) * 0x1p-24f)

/* Any sampler kind: raw values in chunks of rows (its own fill, or one value
 * call each), then converted and written with the stride. */
static udm1_status fill_generic(const char *fn, int kind, const udm1_seq *seq, uint64_t stream, uint64_t first,
                                size_t count, uint32_t dim0, uint32_t ndims, void *out, size_t stride)
{
    enum { CHUNK_VALUES = 2048 };
    size_t rows = ndims >= CHUNK_VALUES ? 1 : CHUNK_VALUES / ndims;
    uint64_t stack_buf[CHUNK_VALUES];
    uint64_t *raw = ndims > CHUNK_VALUES ? malloc(sizeof(uint64_t) * ndims) : stack_buf;
    if (!raw) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory for %u dimensions", fn, ndims);
    uint64_t skey = udm1_seq_stream_key(seq, stream);
    for (size_t i0 = 0; i0 < count; i0 += rows) {
        size_t n = count - i0 < rows ? count - i0 : rows;
        if (seq->kind->fill) {
            seq->kind->fill(seq, skey, first + i0, n, dim0, ndims, raw);
        } else {
            for (size_t i = 0; i < n; ++i)
                for (uint32_t j = 0; j < ndims; ++j)
                    raw[i * ndims + j] = seq->kind->value(seq, skey, first + i0 + i, dim0 + j);
        }
        if (stride == ndims && kind == UDM1_OUT_F64) { /* rows back to back: one loop, no switch per row */
            double *dst = (double *)out + i0 * stride;
            for (size_t k = 0; k < n * ndims; ++k) dst[k] = CONV_F64(raw[k]);
            continue;
        }
        for (size_t i = 0; i < n; ++i) {
            const uint64_t *src = raw + i * ndims;
            size_t at = (i0 + i) * stride;
            switch (kind) {
            case UDM1_OUT_U64: memcpy((uint64_t *)out + at, src, sizeof(uint64_t) * ndims); break;
            case UDM1_OUT_F64:
                for (uint32_t j = 0; j < ndims; ++j) ((double *)out)[at + j] = CONV_F64(src[j]);
                break;
            default:
                for (uint32_t j = 0; j < ndims; ++j) ((float *)out)[at + j] = CONV_F32(src[j]);
                break;
            }
        }
    }
    if (raw != stack_buf) free(raw);
    return UDM1_OK;
}

static udm1_status fill(const char *fn, int kind, const udm1_seq *seq, uint64_t stream, uint64_t first, size_t count,
                        uint32_t dim0, uint32_t ndims, void *out, size_t stride)
{
    if (!seq) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: seq is NULL", fn);
    if (ndims == 0) return udm1_fail(UDM1_ERROR_DIMENSION, "%s: ndims is 0", fn);
    if (dim0 >= seq->dims || ndims > seq->dims - dim0)
        return udm1_fail(UDM1_ERROR_DIMENSION, "%s: dimensions [%u, %llu) of a %u-dimensional sequence", fn, dim0,
                         (unsigned long long)dim0 + ndims, seq->dims);
    if (stride < ndims) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: stride %zu < ndims %u", fn, stride, ndims);
    if (count > 0 && count - 1 > UINT64_MAX - first)
        return udm1_fail(UDM1_ERROR_INDEX_RANGE, "%s: first %llu + count %zu passes 2^64", fn,
                         (unsigned long long)first, count);
    if (seq->point_count && (first >= seq->point_count || count > seq->point_count - first) && count > 0)
        return udm1_fail(UDM1_ERROR_INDEX_RANGE, "%s: indices [%llu, %llu + %zu) of a %llu-point set", fn,
                         (unsigned long long)first, (unsigned long long)first, count,
                         (unsigned long long)seq->point_count);
    if (count > 0 && count - 1 > (SIZE_MAX - ndims) / stride)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: count %zu x stride %zu overflows the buffer size", fn,
                         count, stride);
    if (count == 0) return UDM1_OK;
    if (!out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: out is NULL", fn);
    if (seq->kind != &udm1_weyl_kind) return fill_generic(fn, kind, seq, stream, first, count, dim0, ndims, out, stride);
    udm1_weyl_fill(kind, seq, udm1_seq_stream_key(seq, stream), first, count, dim0, ndims, out, stride);
    return UDM1_OK;
}

udm1_status udm1_seq_fill_u64(const udm1_seq *seq, uint64_t stream, uint64_t first, size_t count, uint32_t dim0,
                              uint32_t ndims, uint64_t *out, size_t stride)
{
    return fill("udm1_seq_fill_u64", UDM1_OUT_U64, seq, stream, first, count, dim0, ndims, out, stride);
}

udm1_status udm1_seq_fill_f64(const udm1_seq *seq, uint64_t stream, uint64_t first, size_t count, uint32_t dim0,
                              uint32_t ndims, double *out, size_t stride)
{
    return fill("udm1_seq_fill_f64", UDM1_OUT_F64, seq, stream, first, count, dim0, ndims, out, stride);
}

udm1_status udm1_seq_fill_f32(const udm1_seq *seq, uint64_t stream, uint64_t first, size_t count, uint32_t dim0,
                              uint32_t ndims, float *out, size_t stride)
{
    return fill("udm1_seq_fill_f32", UDM1_OUT_F32, seq, stream, first, count, dim0, ndims, out, stride);
}
