/* points.c - many points at once (udm1_seq_fill_points_f64), for renderers that trace many paths
 * together: the per-stream words found once per run of equal streams for the Weyl kind and the base-2
 * kinds, the cursor for the others. */
#include "seq/scramble.h"
#include "seq/value.h"

udm1_status udm1_seq_fill_points_f64(const udm1_seq *seq, size_t n, const uint64_t *streams,
                                     const uint64_t *indices, uint32_t first_dimension, uint32_t n_dims, double *out)
{
    static const char fn[] = "udm1_seq_fill_points_f64";
    if (!seq) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: seq is NULL", fn);
    if (n_dims == 0) return udm1_fail(UDM1_ERROR_DIMENSION, "%s: n_dims is 0", fn);
    if (first_dimension >= UDM1_DIMENSION_INDEX_LIMIT || n_dims > UDM1_DIMENSION_INDEX_LIMIT - first_dimension)
        return udm1_fail(UDM1_ERROR_DIMENSION, "%s: first_dimension %u + n_dims %u passes the dimension index limit 2^32 - 1",
                         fn, first_dimension, n_dims);
    if (n == 0) return UDM1_OK;
    if (!streams || !indices || !out)
        return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, !streams ? "streams" : !indices ? "indices" : "out");
    if (seq->point_count)
        for (size_t k = 0; k < n; ++k)
            if (indices[k] >= seq->point_count)
                return udm1_fail(UDM1_ERROR_INDEX_RANGE, "%s: indices[%zu] = %llu of a %llu-point set", fn, k,
                                 (unsigned long long)indices[k], (unsigned long long)seq->point_count);
    /* Weyl sequences on the plain path (no value function: modes none, shift, screen) and the presets with
     * a base-2 randomization (base2: Sobol, PMJ02): the shifts or random words of a stream's dimensions,
     * and the padding's per-stream words, computed once per run of equal streams */
    if (seq->kind == &udm1_weyl_kind || seq->kind->base2) {
        enum { CHUNK = 64 };
        uint64_t word[CHUNK];
        for (uint32_t d0 = 0; d0 < n_dims; d0 += CHUNK) {
            uint32_t m = n_dims - d0 < CHUNK ? n_dims - d0 : CHUNK;
            uint64_t skey = 0;
            for (size_t k = 0; k < n; ++k) {
                if (k == 0 || streams[k] != streams[k - 1]) {
                    skey = udm1_seq_stream_key(seq, streams[k]);
                    for (uint32_t j = 0; j < m; ++j) {
                        uint32_t dim = first_dimension + d0 + j;
                        word[j] = dim >= seq->dims ? udm1_shift(skey, udm1_dim_key(seq->seed_key, dim))
                                  : seq->kind->base2 ? udm1_word(seq, skey, dim)
                                                   : seq->offset[dim] + udm1_weyl_shift(seq, skey, dim);
                    }
                }
                double *o = out + k * n_dims + d0;
                uint32_t first = first_dimension + d0, inside = first >= seq->dims ? 0 : seq->dims - first;
                if (inside > m) inside = m;
                if (seq->kind->base2_point && inside) {  /* the point's raw values at once, then as below */
                    uint64_t raw[CHUNK];
                    seq->kind->base2_point(seq, skey, indices[k], first, inside, raw);
                    if (seq->mode == UDM1_MODE_PERMUTE)  /* (the common case without a switch per value) */
                        for (uint32_t j = 0; j < inside; ++j) o[j] = udm1_to_f64(raw[j] ^ word[j]);
                    else
                        for (uint32_t j = 0; j < inside; ++j) o[j] = udm1_to_f64(udm1_randomize_base2(seq->mode, raw[j], word[j]));
                    for (uint32_t j = inside; j < m; ++j) o[j] = udm1_to_f64(udm1_pad(word[j], indices[k]));
                    continue;
                }
                for (uint32_t j = 0; j < m; ++j) {
                    uint32_t dim = first + j;
                    uint64_t v = dim >= seq->dims ? udm1_pad(word[j], indices[k])
                                 : seq->kind->base2 ? udm1_randomize_base2(seq->mode, seq->kind->base2(seq, skey, indices[k], dim), word[j])
                                              : udm1_weyl_raw(&seq->gen[dim], word[j], udm1_screen_index(seq, skey, indices[k]));
                    o[j] = udm1_to_f64(v);
                }
            }
        }
        return UDM1_OK;
    }
    for (size_t k = 0; k < n; ++k) {
        udm1_cursor c;
        udm1_cursor_start(&c, seq, streams[k], indices[k], first_dimension);
        udm1_cursor_fill_f64(&c, n_dims, out + k * n_dims);
    }
    return UDM1_OK;
}
