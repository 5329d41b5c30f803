/* test_no_write_on_error.c - a call that fails writes nothing: for every public function that writes into
 * the caller's memory and returns a status, and every error status it can return, one row of the table
 * below makes the failing call with every output buffer filled with a byte pattern and checks the status,
 * the one-line message naming the function, and that every byte of every buffer is unchanged. The buffers
 * are large (more than any internal chunk: the fills' rows of 2048 values, the streams' 64 dimensions,
 * the noise kernels' blocks) and the bad input sits where a function that checked as it went would have
 * written first: the last point, the last chunk, a later row.
 *
 * Two other kinds of rows: the creators, which set *out to NULL on failure and write nothing else; and
 * the inline draws of udm1/stream.h and udm1/domain.h and the cursor's, which return no status: a refused
 * draw writes its documented NaN (0 for raw values) into its n outputs, nothing else, and sets
 * udm1_last_error(). */
#include "check.h"

#include <udm1/udm1.h>

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define BUF_BYTES (384u * 1024u) /* each output buffer: more than any row would write */
#define NPTS 5000u               /* points of the batch calls: many kernel blocks */
#define LIMIT UDM1_DIMENSION_INDEX_LIMIT

/* What the rows use: sequences, streams, noises, inputs (finite, and with one bad value late), and the
 * three output buffers every row gets. */
typedef struct fixture {
    udm1_seq *wr4, *sobol4, *pcg3, *hamm2, *epis1, *pmj2, *wr1, *wr2000;
    udm1_stream st_wr, st_limit, st_hamm, st_zero, st_pmj;
    udm1_noise *perlin, *classic, *periodic, *seqnoise;
    udm1_lattice_bound *lb, *lb_empty;
    udm1_pattern_params fbm, fbm_overflow, ridged_overflow, marble, bad_params, noise_pattern;
    udm1_cellular_params cell, cell_minkowski;
    udm1_color_entry colors[3], unsorted[3], nan_entry[2];
    udm1_alpha alphas[3];
    udm1_seq_desc desc;
    uint64_t streams[NPTS], indices[NPTS], indices_bad_last[NPTS];
    double x[NPTS], y[NPTS], z[NPTS], w[NPTS], x_nan_last[NPTS], y_inf_mid[NPTS], z_ninf_early[NPTS];
    float xf[NPTS], yf[NPTS], zf[NPTS], wf[NPTS], xf_nan_last[NPTS], yf_inf_mid[NPTS], zf_ninf_early[NPTS];
    double xyz[3 * NPTS], xyz_nan_last[3 * NPTS], xyz_big_last[3 * NPTS]; /* packed points */
    double unit[2 * NPTS], unit_out_last[2 * NPTS];                          /* points in [0, 1]^2 */
    double transform[2 * 65];                                                /* 128 values' transform */
    double origin[3], step_x[3], step_y[3], step_y_big[3], step_y_huge[3], nan3[3];
    const double *ax[4], *ax_nan[4], *ax_inf[4], *ax_ninf[4], *ax_null1[4];
    const float *axf[4], *axf_nan[4], *axf_inf[4], *axf_ninf[4], *axf_null1[4];
    void *out[3];
} fixture;

#define O8(k) ((uint8_t *)f->out[k])
#define U64(k) ((uint64_t *)f->out[k])
#define F64(k) ((double *)f->out[k])
#define F32(k) ((float *)f->out[k])

/* Row kinds. STATUS: the call fails with the expected status and writes nothing. CREATOR: the same, except
 * the handle it was to create, at the start of buffer 0, which it sets to NULL. DRAW_*: a status-less draw
 * into buffer 0 writes its n outputs as NaN (F32, F64) or 0 (RAW) and nothing else. */
enum { STATUS, CREATOR, DRAW_F32, DRAW_F64, DRAW_RAW };

typedef struct row {
    const char *id;
    const char *fn; /* the message starts with "fn:" (for the draws: the message is set) */
    int kind;
    udm1_status expected; /* STATUS, CREATOR */
    uint32_t n;           /* DRAW_*: the outputs written */
    udm1_status (*call)(fixture *f);
} row;

#define E(s) UDM1_ERROR_##s

/* X(id, kind, fn, expected status, draw count, call) */
#define ROWS(X)                                                                                                         \
    /* presets */                                                                                                       \
    X(preset_get_null, STATUS, udm1_preset_get, E(NULL_ARGUMENT), 0, udm1_preset_get(0, NULL))                          \
    X(preset_get_past, STATUS, udm1_preset_get, E(INVALID_ARGUMENT), 0,                                                 \
      udm1_preset_get(udm1_preset_count(), (udm1_preset_info *)f->out[0]))                                              \
    X(preset_get_max, STATUS, udm1_preset_get, E(INVALID_ARGUMENT), 0,                                                  \
      udm1_preset_get(SIZE_MAX, (udm1_preset_info *)f->out[0]))                                                         \
    X(preset_find_null_name, STATUS, udm1_preset_find, E(NULL_ARGUMENT), 0,                                             \
      udm1_preset_find(NULL, (udm1_preset_info *)f->out[0]))                                                            \
    X(preset_find_null_info, STATUS, udm1_preset_find, E(NULL_ARGUMENT), 0, udm1_preset_find("wr", NULL))               \
    X(preset_find_unknown, STATUS, udm1_preset_find, E(UNKNOWN_PRESET), 0,                                              \
      udm1_preset_find("WR", (udm1_preset_info *)f->out[0]))                                                            \
    /* creators */                                                                                                      \
    X(create_null_preset, CREATOR, udm1_seq_create, E(NULL_ARGUMENT), 0,                                                \
      udm1_seq_create(NULL, 2, 0, 0, (udm1_seq **)f->out[0]))                                                           \
    X(create_unknown, CREATOR, udm1_seq_create, E(UNKNOWN_PRESET), 0,                                                   \
      udm1_seq_create("nope", 2, 0, 0, (udm1_seq **)f->out[0]))                                                         \
    X(create_dims0, CREATOR, udm1_seq_create, E(DIMENSION), 0, udm1_seq_create("wr", 0, 0, 0, (udm1_seq **)f->out[0]))  \
    X(create_dims_many, CREATOR, udm1_seq_create, E(DIMENSION), 0,                                                      \
      udm1_seq_create("wr-ao", 3, 0, 0, (udm1_seq **)f->out[0]))                                                        \
    X(create_no_k, CREATOR, udm1_seq_create, E(POINT_COUNT), 0,                                                         \
      udm1_seq_create("epis", 1, 0, 0, (udm1_seq **)f->out[0]))                                                         \
    X(create_k_for_seq, CREATOR, udm1_seq_create, E(POINT_COUNT), 0,                                                    \
      udm1_seq_create("wr", 1, 8, 0, (udm1_seq **)f->out[0]))                                                           \
    X(create_desc_null, CREATOR, udm1_seq_create, E(NULL_ARGUMENT), 0,                                                  \
      udm1_seq_create_desc(NULL, (udm1_seq **)f->out[0]))                                                               \
    X(create_desc_rational, CREATOR, udm1_seq_create, E(RATIONAL_ALPHA), 0, create_rational(f))                         \
    X(create_desc_randomize, CREATOR, udm1_seq_create, E(INVALID_ARGUMENT), 0, create_bad_randomize(f))                 \
    X(create_desc_struct_size, CREATOR, udm1_seq_create, E(INVALID_ARGUMENT), 0, create_bad_size(f))                    \
    X(noise_create_null, CREATOR, udm1_noise_create, E(NULL_ARGUMENT), 0,                                               \
      udm1_noise_create(NULL, (udm1_noise **)f->out[0]))                                                                \
    X(noise_create_kind, CREATOR, udm1_noise_create, E(INVALID_ARGUMENT), 0, noise_create_bad(f, 0))                    \
    X(noise_create_period, CREATOR, udm1_noise_create, E(INVALID_ARGUMENT), 0, noise_create_bad(f, 1))                  \
    X(noise_create_table, CREATOR, udm1_noise_create, E(UNKNOWN_PRESET), 0, noise_create_bad(f, 2))                     \
    X(bound_create_lag, CREATOR, udm1_lattice_bound_create, E(INVALID_ARGUMENT), 0,                                     \
      udm1_lattice_bound_create(0, 5.0, 0, (udm1_lattice_bound **)f->out[0]))                                           \
    X(bound_create_lag31, CREATOR, udm1_lattice_bound_create, E(INVALID_ARGUMENT), 0,                                   \
      udm1_lattice_bound_create(31, 5.0, 0, (udm1_lattice_bound **)f->out[0]))                                          \
    X(bound_create_fudge, CREATOR, udm1_lattice_bound_create, E(INVALID_ARGUMENT), 0,                                   \
      udm1_lattice_bound_create(4, NAN, 0, (udm1_lattice_bound **)f->out[0]))                                           \
    X(bound_create_capacity, CREATOR, udm1_lattice_bound_create, E(INVALID_ARGUMENT), 0,                                \
      udm1_lattice_bound_create(4, 5.0, (1ull << 32) + 1, (udm1_lattice_bound **)f->out[0]))                            \
    /* generators and offsets */                                                                                        \
    X(alpha_null_seq, STATUS, udm1_seq_alpha, E(NULL_ARGUMENT), 0, udm1_seq_alpha(NULL, 0, U64(0), U64(1)))             \
    X(alpha_null_lo, STATUS, udm1_seq_alpha, E(NULL_ARGUMENT), 0, udm1_seq_alpha(f->wr4, 0, U64(0), NULL))              \
    X(alpha_null_hi, STATUS, udm1_seq_alpha, E(NULL_ARGUMENT), 0, udm1_seq_alpha(f->wr4, 0, NULL, U64(1)))              \
    X(alpha_dim, STATUS, udm1_seq_alpha, E(DIMENSION), 0, udm1_seq_alpha(f->wr4, 4, U64(0), U64(1)))                    \
    X(alpha_not_weyl, STATUS, udm1_seq_alpha, E(INVALID_ARGUMENT), 0, udm1_seq_alpha(f->sobol4, 0, U64(0), U64(1)))     \
    X(offset_null_seq, STATUS, udm1_seq_offset, E(NULL_ARGUMENT), 0, udm1_seq_offset(NULL, 0, 0, U64(0)))               \
    X(offset_null_out, STATUS, udm1_seq_offset, E(NULL_ARGUMENT), 0, udm1_seq_offset(f->wr4, 0, 0, NULL))               \
    X(offset_dim, STATUS, udm1_seq_offset, E(DIMENSION), 0, udm1_seq_offset(f->wr4, 0, 4, U64(0)))                      \
    /* one value */                                                                                                     \
    X(sample_u64_null_seq, STATUS, udm1_seq_sample_u64, E(NULL_ARGUMENT), 0,                                            \
      udm1_seq_sample_u64(NULL, 0, 0, 0, U64(0)))                                                                       \
    X(sample_u64_null_out, STATUS, udm1_seq_sample_u64, E(NULL_ARGUMENT), 0,                                            \
      udm1_seq_sample_u64(f->wr4, 0, 0, 0, NULL))                                                                       \
    X(sample_u64_dim, STATUS, udm1_seq_sample_u64, E(DIMENSION), 0, udm1_seq_sample_u64(f->wr4, 0, 0, 4, U64(0)))       \
    X(sample_u64_index, STATUS, udm1_seq_sample_u64, E(INDEX_RANGE), 0,                                                 \
      udm1_seq_sample_u64(f->hamm2, 0, 64, 0, U64(0)))                                                                  \
    X(sample_f64_dim, STATUS, udm1_seq_sample_f64, E(DIMENSION), 0, udm1_seq_sample_f64(f->sobol4, 0, 0, 9, F64(0)))    \
    X(sample_f64_index, STATUS, udm1_seq_sample_f64, E(INDEX_RANGE), 0,                                                 \
      udm1_seq_sample_f64(f->epis1, 0, 64, 0, F64(0)))                                                                  \
    X(sample_f64_null, STATUS, udm1_seq_sample_f64, E(NULL_ARGUMENT), 0, udm1_seq_sample_f64(NULL, 0, 0, 0, F64(0)))    \
    X(sample_f32_dim, STATUS, udm1_seq_sample_f32, E(DIMENSION), 0, udm1_seq_sample_f32(f->pcg3, 0, 0, 3, F32(0)))      \
    X(sample_f32_index, STATUS, udm1_seq_sample_f32, E(INDEX_RANGE), 0,                                                 \
      udm1_seq_sample_f32(f->pmj2, 0, 256, 0, F32(0)))                                                                  \
    X(sample_f32_null, STATUS, udm1_seq_sample_f32, E(NULL_ARGUMENT), 0, udm1_seq_sample_f32(f->wr4, 0, 0, 0, NULL))    \
    /* bulk fills: Weyl kernels and the generic rows */                                                                 \
    X(fill_u64_null_seq, STATUS, udm1_seq_fill_u64, E(NULL_ARGUMENT), 0,                                                \
      udm1_seq_fill_u64(NULL, 0, 0, 100, 0, 1, U64(0), 1))                                                              \
    X(fill_u64_null_out, STATUS, udm1_seq_fill_u64, E(NULL_ARGUMENT), 0,                                                \
      udm1_seq_fill_u64(f->wr4, 0, 0, 100, 0, 1, NULL, 1))                                                              \
    X(fill_u64_ndims0, STATUS, udm1_seq_fill_u64, E(DIMENSION), 0,                                                      \
      udm1_seq_fill_u64(f->wr4, 0, 0, 100, 0, 0, U64(0), 1))                                                            \
    X(fill_u64_dims_past, STATUS, udm1_seq_fill_u64, E(DIMENSION), 0,                                                   \
      udm1_seq_fill_u64(f->wr4, 0, 0, 10000, 2, 3, U64(0), 3))                                                          \
    X(fill_u64_dim0_past, STATUS, udm1_seq_fill_u64, E(DIMENSION), 0,                                                   \
      udm1_seq_fill_u64(f->sobol4, 0, 0, 100, 4, 1, U64(0), 1))                                                         \
    X(fill_u64_stride, STATUS, udm1_seq_fill_u64, E(INVALID_ARGUMENT), 0,                                               \
      udm1_seq_fill_u64(f->wr4, 0, 0, 100, 0, 4, U64(0), 3))                                                            \
    X(fill_u64_wrap, STATUS, udm1_seq_fill_u64, E(INDEX_RANGE), 0,                                                      \
      udm1_seq_fill_u64(f->wr4, 0, UINT64_MAX - 10, 100, 0, 1, U64(0), 1))                                              \
    X(fill_u64_past_k, STATUS, udm1_seq_fill_u64, E(INDEX_RANGE), 0,                                                    \
      udm1_seq_fill_u64(f->hamm2, 0, 10, 55, 0, 2, U64(0), 2))                                                          \
    X(fill_u64_first_k, STATUS, udm1_seq_fill_u64, E(INDEX_RANGE), 0,                                                   \
      udm1_seq_fill_u64(f->epis1, 0, 64, 1, 0, 1, U64(0), 1))                                                           \
    X(fill_u64_overflow, STATUS, udm1_seq_fill_u64, E(INVALID_ARGUMENT), 0,                                             \
      udm1_seq_fill_u64(f->wr4, 0, 0, SIZE_MAX / 2, 0, 1, U64(0), 4))                                                   \
    X(fill_f64_dims_past, STATUS, udm1_seq_fill_f64, E(DIMENSION), 0,                                                   \
      udm1_seq_fill_f64(f->pcg3, 0, 0, 10000, 0, 4, F64(0), 4))                                                         \
    X(fill_f64_past_k, STATUS, udm1_seq_fill_f64, E(INDEX_RANGE), 0,                                                    \
      udm1_seq_fill_f64(f->pmj2, 0, 0, 257, 0, 2, F64(0), 2))                                                           \
    X(fill_f64_stride, STATUS, udm1_seq_fill_f64, E(INVALID_ARGUMENT), 0,                                               \
      udm1_seq_fill_f64(f->sobol4, 0, 0, 100, 0, 2, F64(0), 1))                                                         \
    X(fill_f64_null, STATUS, udm1_seq_fill_f64, E(NULL_ARGUMENT), 0,                                                    \
      udm1_seq_fill_f64(f->wr4, 0, 0, 1, 0, 1, NULL, 1))                                                                \
    X(fill_f32_dims_past, STATUS, udm1_seq_fill_f32, E(DIMENSION), 0,                                                   \
      udm1_seq_fill_f32(f->wr4, 0, 0, 20000, 1, 4, F32(0), 4))                                                          \
    X(fill_f32_past_k, STATUS, udm1_seq_fill_f32, E(INDEX_RANGE), 0,                                                    \
      udm1_seq_fill_f32(f->hamm2, 0, 0, 65, 0, 2, F32(0), 2))                                                           \
    X(fill_f32_wrap, STATUS, udm1_seq_fill_f32, E(INDEX_RANGE), 0,                                                      \
      udm1_seq_fill_f32(f->sobol4, 0, UINT64_MAX, 2, 0, 1, F32(0), 1))                                                  \
    X(fill_f32_ndims0, STATUS, udm1_seq_fill_f32, E(DIMENSION), 0,                                                      \
      udm1_seq_fill_f32(f->pcg3, 0, 0, 10, 0, 0, F32(0), 0))                                                            \
    /* the cursor */                                                                                                    \
    X(cursor_null, STATUS, udm1_cursor_start, E(NULL_ARGUMENT), 0, udm1_cursor_start(NULL, f->wr4, 0, 0, 0))            \
    X(cursor_null_seq, STATUS, udm1_cursor_start, E(NULL_ARGUMENT), 0,                                                  \
      udm1_cursor_start((udm1_cursor *)f->out[0], NULL, 0, 0, 0))                                                       \
    X(cursor_index, STATUS, udm1_cursor_start, E(INDEX_RANGE), 0,                                                       \
      udm1_cursor_start((udm1_cursor *)f->out[0], f->hamm2, 0, 64, 0))                                                  \
    X(cursor_dim, STATUS, udm1_cursor_start, E(DIMENSION), 0,                                                           \
      udm1_cursor_start((udm1_cursor *)f->out[0], f->wr4, 0, 0, LIMIT))                                                 \
    /* many points */                                                                                                   \
    X(points_null_seq, STATUS, udm1_seq_fill_points_f64, E(NULL_ARGUMENT), 0,                                           \
      udm1_seq_fill_points_f64(NULL, 10, f->streams, f->indices, 0, 2, F64(0)))                                         \
    X(points_ndims0, STATUS, udm1_seq_fill_points_f64, E(DIMENSION), 0,                                                 \
      udm1_seq_fill_points_f64(f->wr4, 10, f->streams, f->indices, 0, 0, F64(0)))                                       \
    X(points_limit, STATUS, udm1_seq_fill_points_f64, E(DIMENSION), 0,                                                  \
      udm1_seq_fill_points_f64(f->wr4, 10, f->streams, f->indices, LIMIT - 4, 8, F64(0)))                               \
    X(points_limit_n0, STATUS, udm1_seq_fill_points_f64, E(DIMENSION), 0,                                               \
      udm1_seq_fill_points_f64(f->wr4, 0, f->streams, f->indices, LIMIT, 1, F64(0)))                                    \
    X(points_null_streams, STATUS, udm1_seq_fill_points_f64, E(NULL_ARGUMENT), 0,                                       \
      udm1_seq_fill_points_f64(f->wr4, 10, NULL, f->indices, 0, 2, F64(0)))                                             \
    X(points_null_indices, STATUS, udm1_seq_fill_points_f64, E(NULL_ARGUMENT), 0,                                       \
      udm1_seq_fill_points_f64(f->wr4, 10, f->streams, NULL, 0, 2, F64(0)))                                             \
    X(points_null_out, STATUS, udm1_seq_fill_points_f64, E(NULL_ARGUMENT), 0,                                           \
      udm1_seq_fill_points_f64(f->wr4, 10, f->streams, f->indices, 0, 2, NULL))                                         \
    X(points_index_last_hamm, STATUS, udm1_seq_fill_points_f64, E(INDEX_RANGE), 0,                                      \
      udm1_seq_fill_points_f64(f->hamm2, 4000, f->streams, f->indices_bad_last, 0, 8, F64(0)))                          \
    X(points_index_last_epis, STATUS, udm1_seq_fill_points_f64, E(INDEX_RANGE), 0,                                      \
      udm1_seq_fill_points_f64(f->epis1, 4000, f->streams, f->indices_bad_last, 0, 3, F64(0)))                          \
    X(points_index_last_pmj, STATUS, udm1_seq_fill_points_f64, E(INDEX_RANGE), 0,                                       \
      udm1_seq_fill_points_f64(f->pmj2, 4000, f->streams, f->indices_bad_last, 1, 4, F64(0)))                           \
    /* the generator check */                                                                                           \
    X(seq_check_null, STATUS, udm1_seq_check, E(NULL_ARGUMENT), 0,                                                      \
      udm1_seq_check(NULL, 64, (udm1_alpha_report *)f->out[0]))                                                         \
    X(seq_check_null_report, STATUS, udm1_seq_check, E(NULL_ARGUMENT), 0, udm1_seq_check(f->wr4, 64, NULL))             \
    X(seq_check_not_weyl, STATUS, udm1_seq_check, E(INVALID_ARGUMENT), 0,                                               \
      udm1_seq_check(f->sobol4, 64, (udm1_alpha_report *)f->out[0]))                                                    \
    X(seq_check_n1, STATUS, udm1_seq_check, E(INVALID_ARGUMENT), 0,                                                     \
      udm1_seq_check(f->wr4, 1, (udm1_alpha_report *)f->out[0]))                                                        \
    X(seq_check_n_big, STATUS, udm1_seq_check, E(INVALID_ARGUMENT), 0,                                                  \
      udm1_seq_check(f->wr4, 65537, (udm1_alpha_report *)f->out[0]))                                                    \
    X(seq_check_work, STATUS, udm1_seq_check, E(INVALID_ARGUMENT), 0,                                                   \
      udm1_seq_check(f->wr2000, 65536, (udm1_alpha_report *)f->out[0]))                                                 \
    X(alpha_check_null, STATUS, udm1_alpha_check, E(NULL_ARGUMENT), 0,                                                  \
      udm1_alpha_check(NULL, 2, 64, (udm1_alpha_report *)f->out[0]))                                                    \
    X(alpha_check_null_report, STATUS, udm1_alpha_check, E(NULL_ARGUMENT), 0,                                           \
      udm1_alpha_check(f->alphas, 2, 64, NULL))                                                                         \
    X(alpha_check_count0, STATUS, udm1_alpha_check, E(INVALID_ARGUMENT), 0,                                             \
      udm1_alpha_check(f->alphas, 0, 64, (udm1_alpha_report *)f->out[0]))                                               \
    X(alpha_check_count_big, STATUS, udm1_alpha_check, E(INVALID_ARGUMENT), 0,                                          \
      udm1_alpha_check(f->alphas, UDM1_MAX_DIMENSIONS + 1, 64, (udm1_alpha_report *)f->out[0]))                         \
    X(alpha_check_bad_alpha, STATUS, udm1_alpha_check, E(INVALID_ARGUMENT), 0,                                          \
      udm1_alpha_check(f->alphas, 3, 64, (udm1_alpha_report *)f->out[0]))                                               \
    X(alpha_check_n, STATUS, udm1_alpha_check, E(INVALID_ARGUMENT), 0,                                                  \
      udm1_alpha_check(f->alphas, 2, 1, (udm1_alpha_report *)f->out[0]))                                                \
    /* streams */                                                                                                       \
    X(stream_init_null, STATUS, udm1_stream_init, E(NULL_ARGUMENT), 0, udm1_stream_init(NULL, f->wr4, 0, 0, 4))         \
    X(stream_init_null_seq, STATUS, udm1_stream_init, E(NULL_ARGUMENT), 0,                                              \
      udm1_stream_init((udm1_stream *)f->out[0], NULL, 0, 0, 4))                                                        \
    X(stream_init_count0, STATUS, udm1_stream_init, E(DIMENSION), 0,                                                    \
      udm1_stream_init((udm1_stream *)f->out[0], f->wr4, 0, 0, 0))                                                      \
    X(stream_init_count65, STATUS, udm1_stream_init, E(DIMENSION), 0,                                                   \
      udm1_stream_init((udm1_stream *)f->out[0], f->wr4, 0, 0, UDM1_STREAM_DIMS + 1))                                   \
    X(stream_init_limit, STATUS, udm1_stream_init, E(DIMENSION), 0,                                                     \
      udm1_stream_init((udm1_stream *)f->out[0], f->sobol4, 0, LIMIT - 3, 4))                                           \
    X(stream_raw_null, STATUS, udm1_stream_fill_raw, E(NULL_ARGUMENT), 0, udm1_stream_fill_raw(NULL, 0, 0, 4, U64(0)))  \
    X(stream_raw_null_out, STATUS, udm1_stream_fill_raw, E(NULL_ARGUMENT), 0,                                           \
      udm1_stream_fill_raw(&f->st_wr, 0, 0, 4, NULL))                                                                   \
    X(stream_raw_zeroed, STATUS, udm1_stream_fill_raw, E(NULL_ARGUMENT), 0,                                             \
      udm1_stream_fill_raw(&f->st_zero, 0, 0, 4, U64(0)))                                                               \
    X(stream_raw_index, STATUS, udm1_stream_fill_raw, E(INDEX_RANGE), 0,                                                \
      udm1_stream_fill_raw(&f->st_hamm, 64, 0, 200, U64(0)))                                                            \
    X(stream_raw_limit, STATUS, udm1_stream_fill_raw, E(DIMENSION), 0,                                                  \
      udm1_stream_fill_raw(&f->st_limit, 0, 0, 1000, U64(0)))                                                           \
    X(stream_raw_dim_max, STATUS, udm1_stream_fill_raw, E(DIMENSION), 0,                                                \
      udm1_stream_fill_raw(&f->st_wr, 0, LIMIT, 1, U64(0)))                                                             \
    X(stream_f32_null, STATUS, udm1_stream_fill_f32, E(NULL_ARGUMENT), 0, udm1_stream_fill_f32(NULL, 0, 0, 4, F32(0)))  \
    X(stream_f32_null_out, STATUS, udm1_stream_fill_f32, E(NULL_ARGUMENT), 0,                                           \
      udm1_stream_fill_f32(&f->st_wr, 0, 0, 4, NULL))                                                                   \
    X(stream_f32_zeroed, STATUS, udm1_stream_fill_f32, E(NULL_ARGUMENT), 0,                                             \
      udm1_stream_fill_f32(&f->st_zero, 0, 0, 100, F32(0)))                                                             \
    X(stream_f32_index, STATUS, udm1_stream_fill_f32, E(INDEX_RANGE), 0,                                                \
      udm1_stream_fill_f32(&f->st_pmj, 256, 0, 300, F32(0)))                                                            \
    X(stream_f32_limit, STATUS, udm1_stream_fill_f32, E(DIMENSION), 0,                                                  \
      udm1_stream_fill_f32(&f->st_limit, 0, 0, 1000, F32(0)))                                                           \
    X(stream_f32_limit_4, STATUS, udm1_stream_fill_f32, E(DIMENSION), 0,                                                \
      udm1_stream_fill_f32(&f->st_limit, 0, 62, 4, F32(0)))                                                             \
    X(stream_f32_limit_65, STATUS, udm1_stream_fill_f32, E(DIMENSION), 0,                                               \
      udm1_stream_fill_f32(&f->st_limit, 0, 0, 65, F32(0)))                                                             \
    /* domains */                                                                                                       \
    X(domain_raw_null, STATUS, udm1_domain_fill_raw, E(NULL_ARGUMENT), 0, udm1_domain_fill_raw(NULL, 4, U64(0)))        \
    X(domain_raw_null_out, STATUS, udm1_domain_fill_raw, E(NULL_ARGUMENT), 0, domain_fill(f, 0, 1, 0, 4, 0))            \
    X(domain_raw_no_stream, STATUS, udm1_domain_fill_raw, E(NULL_ARGUMENT), 0, domain_fill(f, 1, 1, 0, 4, 1))           \
    X(domain_raw_zeroed, STATUS, udm1_domain_fill_raw, E(NULL_ARGUMENT), 0, domain_fill(f, 2, 1, 0, 4, 1))              \
    X(domain_raw_n0, STATUS, udm1_domain_fill_raw, E(DIMENSION), 0, domain_fill(f, 3, 1, 0, 0, 1))                      \
    X(domain_raw_n5, STATUS, udm1_domain_fill_raw, E(DIMENSION), 0, domain_fill(f, 3, 1, 0, 5, 1))                      \
    X(domain_raw_root_n5, STATUS, udm1_domain_fill_raw, E(DIMENSION), 0, domain_fill(f, 3, 0, 0, 5, 1))                 \
    X(domain_raw_index, STATUS, udm1_domain_fill_raw, E(INDEX_RANGE), 0, domain_fill(f, 4, 1, 64, 4, 1))                \
    X(domain_raw_root_index, STATUS, udm1_domain_fill_raw, E(INDEX_RANGE), 0, domain_fill(f, 4, 0, 64, 4, 1))           \
    X(domain_raw_limit, STATUS, udm1_domain_fill_raw, E(DIMENSION), 0, domain_fill(f, 5, 1, 0, 4, 1))                   \
    X(domain_raw_root_limit, STATUS, udm1_domain_fill_raw, E(DIMENSION), 0, domain_fill(f, 5, 0, 0, 4, 1))              \
    X(domain_f32_null, STATUS, udm1_domain_fill_f32, E(NULL_ARGUMENT), 0, udm1_domain_fill_f32(NULL, 4, F32(0)))        \
    X(domain_f32_null_out, STATUS, udm1_domain_fill_f32, E(NULL_ARGUMENT), 0, domain_fill(f, 0, 1, 0, 4, 2))            \
    X(domain_f32_n5, STATUS, udm1_domain_fill_f32, E(DIMENSION), 0, domain_fill(f, 3, 1, 0, 5, 3))                      \
    X(domain_f32_index, STATUS, udm1_domain_fill_f32, E(INDEX_RANGE), 0, domain_fill(f, 4, 1, 64, 2, 3))                \
    X(domain_f32_limit, STATUS, udm1_domain_fill_f32, E(DIMENSION), 0, domain_fill(f, 5, 1, 0, 3, 3))                   \
    /* the inline draws and the cursor's: NaN (0 raw) in the n outputs, nothing else */                                 \
    X(draw_f32_limit, DRAW_F32, draw, 0, 1000, draw_stream(f, &f->st_limit, 0, 0, 1000, 1))                             \
    X(draw_f64_limit, DRAW_F64, draw, 0, 1000, draw_stream(f, &f->st_limit, 0, 0, 1000, 2))                             \
    X(draw_raw_limit, DRAW_RAW, draw, 0, 1000, draw_stream(f, &f->st_limit, 0, 0, 1000, 0))                             \
    X(draw_f64_limit_65, DRAW_F64, draw, 0, 65, draw_stream(f, &f->st_limit, 0, 0, 65, 2))                              \
    X(draw_f32_index, DRAW_F32, draw, 0, 200, draw_stream(f, &f->st_hamm, 64, 0, 200, 1))                               \
    X(draw_f64_index, DRAW_F64, draw, 0, 2, draw_stream(f, &f->st_pmj, 256, 0, 2, 2))                                   \
    X(draw_raw_index, DRAW_RAW, draw, 0, 3, draw_stream(f, &f->st_hamm, 65, 0, 3, 0))                                   \
    X(draw_f32_zeroed, DRAW_F32, draw, 0, 4, draw_stream(f, &f->st_zero, 0, 0, 4, 1))                                   \
    X(draw_f64_zeroed, DRAW_F64, draw, 0, 130, draw_stream(f, &f->st_zero, 0, 0, 130, 2))                               \
    X(draw_f32_null, DRAW_F32, draw, 0, 4, draw_stream(f, NULL, 0, 0, 4, 1))                                            \
    X(domain_draw_root_n5, DRAW_F32, draw, 0, 4, draw_domain(f, 0, 0, 0, 5, 1))                                         \
    X(domain_draw_root_n5_f64, DRAW_F64, draw, 0, 4, draw_domain(f, 0, 0, 0, 5, 2))                                     \
    X(domain_draw_root_n5_raw, DRAW_RAW, draw, 0, 4, draw_domain(f, 0, 0, 0, 5, 0))                                     \
    X(domain_draw_child_n5, DRAW_F64, draw, 0, 4, draw_domain(f, 0, 1, 0, 5, 2))                                        \
    X(domain_draw_root_n0, DRAW_F32, draw, 0, 0, draw_domain(f, 0, 0, 0, 0, 1))                                         \
    X(domain_draw_child_n0, DRAW_RAW, draw, 0, 0, draw_domain(f, 0, 1, 0, 0, 0))                                        \
    X(domain_draw_index, DRAW_F32, draw, 0, 4, draw_domain(f, 1, 1, 64, 4, 1))                                          \
    X(domain_draw_root_index, DRAW_F64, draw, 0, 4, draw_domain(f, 1, 0, 64, 4, 2))                                     \
    X(domain_draw_pmj_index, DRAW_F32, draw, 0, 2, draw_domain(f, 2, 1, 256, 2, 1))                                     \
    X(domain_draw_limit, DRAW_F32, draw, 0, 2, draw_domain(f, 3, 1, 0, 2, 1))                                           \
    X(domain_draw_limit_raw, DRAW_RAW, draw, 0, 2, draw_domain(f, 3, 0, 0, 2, 0))                                       \
    X(domain_draw_no_stream, DRAW_F64, draw, 0, 3, draw_domain(f, 4, 1, 0, 3, 2))                                       \
    X(cursor_fill_zeroed, DRAW_F32, draw, 0, 100, draw_cursor(f, 100, 1))                                               \
    X(cursor_fill_f64_zeroed, DRAW_F64, draw, 0, 100, draw_cursor(f, 100, 2))                                           \
    X(cursor_2d_zeroed, DRAW_F32, draw, 0, 2, draw_cursor(f, 2, 3))                                                     \
    X(cursor_2d_f64_zeroed, DRAW_F64, draw, 0, 2, draw_cursor(f, 2, 4))                                                 \
    /* metrics */                                                                                                       \
    X(discrepancy_null, STATUS, udm1_discrepancy, E(NULL_ARGUMENT), 0, udm1_discrepancy(NULL, 10, 2, 2, 1, F64(0)))     \
    X(discrepancy_null_out, STATUS, udm1_discrepancy, E(NULL_ARGUMENT), 0,                                              \
      udm1_discrepancy(f->unit, 10, 2, 2, 1, NULL))                                                                     \
    X(discrepancy_n0, STATUS, udm1_discrepancy, E(INVALID_ARGUMENT), 0, udm1_discrepancy(f->unit, 0, 2, 2, 1, F64(0)))  \
    X(discrepancy_d0, STATUS, udm1_discrepancy, E(INVALID_ARGUMENT), 0,                                                 \
      udm1_discrepancy(f->unit, 10, 0, 2, 1, F64(0)))                                                                   \
    X(discrepancy_stride, STATUS, udm1_discrepancy, E(INVALID_ARGUMENT), 0,                                             \
      udm1_discrepancy(f->unit, 10, 2, 1, 1, F64(0)))                                                                   \
    X(discrepancy_kind, STATUS, udm1_discrepancy, E(INVALID_ARGUMENT), 0,                                               \
      udm1_discrepancy(f->unit, 10, 2, 2, 5, F64(0)))                                                                   \
    X(discrepancy_outside, STATUS, udm1_discrepancy, E(INVALID_ARGUMENT), 0,                                            \
      udm1_discrepancy(f->unit_out_last, NPTS, 2, 2, 3, F64(0)))                                                        \
    X(discrepancy_random_null, STATUS, udm1_discrepancy_random, E(NULL_ARGUMENT), 0,                                    \
      udm1_discrepancy_random(10, 2, 1, NULL))                                                                          \
    X(discrepancy_random_n0, STATUS, udm1_discrepancy_random, E(INVALID_ARGUMENT), 0,                                   \
      udm1_discrepancy_random(0, 2, 1, F64(0)))                                                                         \
    X(discrepancy_random_d0, STATUS, udm1_discrepancy_random, E(INVALID_ARGUMENT), 0,                                   \
      udm1_discrepancy_random(10, 0, 1, F64(0)))                                                                        \
    X(discrepancy_random_kind, STATUS, udm1_discrepancy_random, E(INVALID_ARGUMENT), 0,                                 \
      udm1_discrepancy_random(10, 2, 0, F64(0)))                                                                        \
    X(star_null, STATUS, udm1_star_discrepancy_2d, E(NULL_ARGUMENT), 0, udm1_star_discrepancy_2d(NULL, 10, 2, F64(0)))  \
    X(star_n0, STATUS, udm1_star_discrepancy_2d, E(INVALID_ARGUMENT), 0,                                                \
      udm1_star_discrepancy_2d(f->unit, 0, 2, F64(0)))                                                                  \
    X(star_n_big, STATUS, udm1_star_discrepancy_2d, E(INVALID_ARGUMENT), 0,                                             \
      udm1_star_discrepancy_2d(f->unit, 16385, 2, F64(0)))                                                              \
    X(star_stride, STATUS, udm1_star_discrepancy_2d, E(INVALID_ARGUMENT), 0,                                            \
      udm1_star_discrepancy_2d(f->unit, 10, 1, F64(0)))                                                                 \
    X(star_outside, STATUS, udm1_star_discrepancy_2d, E(INVALID_ARGUMENT), 0,                                           \
      udm1_star_discrepancy_2d(f->unit_out_last, NPTS, 2, F64(0)))                                                      \
    X(min_distance_null, STATUS, udm1_min_distance, E(NULL_ARGUMENT), 0,                                                \
      udm1_min_distance(f->unit, 10, 2, 2, 0, NULL))                                                                    \
    X(min_distance_n1, STATUS, udm1_min_distance, E(INVALID_ARGUMENT), 0,                                               \
      udm1_min_distance(f->unit, 1, 2, 2, 0, F64(0)))                                                                   \
    X(min_distance_d0, STATUS, udm1_min_distance, E(INVALID_ARGUMENT), 0,                                               \
      udm1_min_distance(f->unit, 10, 0, 2, 0, F64(0)))                                                                  \
    X(min_distance_stride, STATUS, udm1_min_distance, E(INVALID_ARGUMENT), 0,                                           \
      udm1_min_distance(f->unit, 10, 3, 2, 1, F64(0)))                                                                  \
    X(min_distance_nan, STATUS, udm1_min_distance, E(INVALID_ARGUMENT), 0,                                              \
      udm1_min_distance(f->xyz_nan_last, NPTS, 3, 3, 0, F64(0)))                                                        \
    X(integrand_eval_null, STATUS, udm1_integrand_eval, E(NULL_ARGUMENT), 0,                                            \
      udm1_integrand_eval(4, 2, NULL, 10, 2, F64(0)))                                                                   \
    X(integrand_eval_null_out, STATUS, udm1_integrand_eval, E(NULL_ARGUMENT), 0,                                        \
      udm1_integrand_eval(4, 2, f->unit, 10, 2, NULL))                                                                  \
    X(integrand_eval_kind, STATUS, udm1_integrand_eval, E(INVALID_ARGUMENT), 0,                                         \
      udm1_integrand_eval(99, 2, f->unit, 10, 2, F64(0)))                                                               \
    X(integrand_eval_d2, STATUS, udm1_integrand_eval, E(INVALID_ARGUMENT), 0,                                           \
      udm1_integrand_eval(4, 3, f->xyz, 10, 3, F64(0)))                                                                 \
    X(integrand_eval_corner_d, STATUS, udm1_integrand_eval, E(INVALID_ARGUMENT), 0,                                     \
      udm1_integrand_eval(UDM1_INTEGRAND_GENZ_CORNER_PEAK, 21, f->xyz, 10, 21, F64(0)))                                 \
    X(integrand_eval_disc_d1, STATUS, udm1_integrand_eval, E(INVALID_ARGUMENT), 0,                                      \
      udm1_integrand_eval(UDM1_INTEGRAND_GENZ_DISCONTINUOUS, 1, f->unit, 10, 1, F64(0)))                                \
    X(integrand_eval_stride, STATUS, udm1_integrand_eval, E(INVALID_ARGUMENT), 0,                                       \
      udm1_integrand_eval(8, 3, f->xyz, 10, 2, F64(0)))                                                                 \
    X(integrand_eval_nan, STATUS, udm1_integrand_eval, E(INVALID_ARGUMENT), 0,                                          \
      udm1_integrand_eval(UDM1_INTEGRAND_GENZ_GAUSSIAN, 3, f->xyz_nan_last, NPTS, 3, F64(0)))                           \
    X(integrand_exact_null, STATUS, udm1_integrand_exact, E(NULL_ARGUMENT), 0, udm1_integrand_exact(4, 2, NULL))        \
    X(integrand_exact_kind, STATUS, udm1_integrand_exact, E(INVALID_ARGUMENT), 0, udm1_integrand_exact(0, 2, F64(0)))   \
    X(integrand_exact_d, STATUS, udm1_integrand_exact, E(INVALID_ARGUMENT), 0, udm1_integrand_exact(1, 5, F64(0)))      \
    X(integration_null, STATUS, udm1_integration_error, E(NULL_ARGUMENT), 0,                                            \
      udm1_integration_error(NULL, 1, 2, 16, 2, F64(0), F64(1)))                                                        \
    X(integration_null_rmse, STATUS, udm1_integration_error, E(NULL_ARGUMENT), 0,                                       \
      udm1_integration_error(f->wr4, 1, 2, 16, 2, NULL, F64(1)))                                                        \
    X(integration_kind, STATUS, udm1_integration_error, E(INVALID_ARGUMENT), 0,                                         \
      udm1_integration_error(f->wr4, 0, 2, 16, 2, F64(0), F64(1)))                                                      \
    X(integration_d, STATUS, udm1_integration_error, E(DIMENSION), 0,                                                   \
      udm1_integration_error(f->wr4, 8, 5, 16, 2, F64(0), F64(1)))                                                      \
    X(integration_n0, STATUS, udm1_integration_error, E(INVALID_ARGUMENT), 0,                                           \
      udm1_integration_error(f->wr4, 1, 2, 0, 2, F64(0), F64(1)))                                                       \
    X(integration_r0, STATUS, udm1_integration_error, E(INVALID_ARGUMENT), 0,                                           \
      udm1_integration_error(f->wr4, 1, 2, 16, 0, F64(0), F64(1)))                                                      \
    X(integration_work, STATUS, udm1_integration_error, E(INVALID_ARGUMENT), 0,                                         \
      udm1_integration_error(f->wr4, 8, 4, 1ull << 40, 2, F64(0), F64(1)))                                              \
    X(integration_past_k, STATUS, udm1_integration_error, E(INDEX_RANGE), 0,                                            \
      udm1_integration_error(f->hamm2, 1, 2, 65, 2, F64(0), F64(1)))                                                    \
    X(spectrum_null, STATUS, udm1_spectrum_2d, E(NULL_ARGUMENT), 0, udm1_spectrum_2d(NULL, 0, 16, 1, 64, F64(0)))       \
    X(spectrum_null_out, STATUS, udm1_spectrum_2d, E(NULL_ARGUMENT), 0, udm1_spectrum_2d(f->wr4, 0, 16, 1, 64, NULL))   \
    X(spectrum_dims, STATUS, udm1_spectrum_2d, E(DIMENSION), 0, udm1_spectrum_2d(f->wr4, 3, 16, 1, 64, F64(0)))         \
    X(spectrum_1d, STATUS, udm1_spectrum_2d, E(DIMENSION), 0, udm1_spectrum_2d(f->epis1, 0, 16, 1, 64, F64(0)))         \
    X(spectrum_n0, STATUS, udm1_spectrum_2d, E(INVALID_ARGUMENT), 0, udm1_spectrum_2d(f->wr4, 0, 0, 1, 64, F64(0)))     \
    X(spectrum_r0, STATUS, udm1_spectrum_2d, E(INVALID_ARGUMENT), 0, udm1_spectrum_2d(f->wr4, 0, 16, 0, 64, F64(0)))    \
    X(spectrum_size_odd, STATUS, udm1_spectrum_2d, E(INVALID_ARGUMENT), 0,                                              \
      udm1_spectrum_2d(f->wr4, 0, 16, 1, 63, F64(0)))                                                                   \
    X(spectrum_size_big, STATUS, udm1_spectrum_2d, E(INVALID_ARGUMENT), 0,                                              \
      udm1_spectrum_2d(f->wr4, 0, 16, 1, 1026, F64(0)))                                                                 \
    X(spectrum_work, STATUS, udm1_spectrum_2d, E(INVALID_ARGUMENT), 0,                                                  \
      udm1_spectrum_2d(f->wr4, 0, 1ull << 30, 4, 256, F64(0)))                                                          \
    X(spectrum_past_k, STATUS, udm1_spectrum_2d, E(INDEX_RANGE), 0, udm1_spectrum_2d(f->hamm2, 0, 65, 1, 64, F64(0)))   \
    X(zoneplate_null, STATUS, udm1_zoneplate, E(NULL_ARGUMENT), 0, udm1_zoneplate(NULL, 0, 64, 64, 1, F32(0)))          \
    X(zoneplate_null_out, STATUS, udm1_zoneplate, E(NULL_ARGUMENT), 0, udm1_zoneplate(f->wr4, 0, 64, 64, 1, NULL))      \
    X(zoneplate_dims, STATUS, udm1_zoneplate, E(DIMENSION), 0, udm1_zoneplate(f->wr4, 3, 64, 64, 1, F32(0)))            \
    X(zoneplate_width0, STATUS, udm1_zoneplate, E(INVALID_ARGUMENT), 0, udm1_zoneplate(f->wr4, 0, 0, 64, 1, F32(0)))    \
    X(zoneplate_height_big, STATUS, udm1_zoneplate, E(INVALID_ARGUMENT), 0,                                             \
      udm1_zoneplate(f->wr4, 0, 64, 16385, 1, F32(0)))                                                                  \
    X(zoneplate_spp0, STATUS, udm1_zoneplate, E(INVALID_ARGUMENT), 0, udm1_zoneplate(f->wr4, 0, 64, 64, 0, F32(0)))     \
    X(zoneplate_work, STATUS, udm1_zoneplate, E(INVALID_ARGUMENT), 0,                                                   \
      udm1_zoneplate(f->wr4, 0, 16384, 16384, 64, F32(0)))                                                              \
    X(zoneplate_past_k, STATUS, udm1_zoneplate, E(INDEX_RANGE), 0, udm1_zoneplate(f->hamm2, 0, 64, 64, 65, F32(0)))     \
    X(exact_sum_null_words, STATUS, udm1_exact_sum_add, E(NULL_ARGUMENT), 0, udm1_exact_sum_add(f->x, 10, NULL))        \
    X(exact_sum_null_x, STATUS, udm1_exact_sum_add, E(NULL_ARGUMENT), 0, udm1_exact_sum_add(NULL, 10, U64(0)))          \
    X(exact_sum_nan_last, STATUS, udm1_exact_sum_add, E(INVALID_ARGUMENT), 0,                                           \
      udm1_exact_sum_add(f->x_nan_last, NPTS, U64(0)))                                                                  \
    X(exact_sum_inf, STATUS, udm1_exact_sum_add, E(INVALID_ARGUMENT), 0,                                                \
      udm1_exact_sum_add(f->y_inf_mid, NPTS, U64(0)))                                                                   \
    /* the lattice bound's reads */                                                                                     \
    X(bound_error_null, STATUS, udm1_lattice_bound_error, E(NULL_ARGUMENT), 0, udm1_lattice_bound_error(NULL, F64(0)))  \
    X(bound_error_null_out, STATUS, udm1_lattice_bound_error, E(NULL_ARGUMENT), 0,                                      \
      udm1_lattice_bound_error(f->lb, NULL))                                                                            \
    X(bound_error_empty, STATUS, udm1_lattice_bound_error, E(INVALID_ARGUMENT), 0,                                      \
      udm1_lattice_bound_error(f->lb_empty, F64(0)))                                                                    \
    X(bound_coef_null, STATUS, udm1_lattice_bound_coefficients, E(NULL_ARGUMENT), 0,                                    \
      udm1_lattice_bound_coefficients(NULL, 0, 4, F64(0)))                                                              \
    X(bound_coef_null_out, STATUS, udm1_lattice_bound_coefficients, E(NULL_ARGUMENT), 0,                                \
      udm1_lattice_bound_coefficients(f->lb, 0, 4, NULL))                                                               \
    X(bound_coef_past, STATUS, udm1_lattice_bound_coefficients, E(INDEX_RANGE), 0,                                      \
      udm1_lattice_bound_coefficients(f->lb, 100, 29, F64(0)))                                                          \
    X(bound_coef_first, STATUS, udm1_lattice_bound_coefficients, E(INDEX_RANGE), 0,                                     \
      udm1_lattice_bound_coefficients(f->lb, 129, 0, F64(0)))                                                           \
    X(bound_coef_wrap, STATUS, udm1_lattice_bound_coefficients, E(INDEX_RANGE), 0,                                      \
      udm1_lattice_bound_coefficients(f->lb, 1, UINT64_MAX, F64(0)))                                                    \
    X(bound_coef_empty, STATUS, udm1_lattice_bound_coefficients, E(INDEX_RANGE), 0,                                     \
      udm1_lattice_bound_coefficients(f->lb_empty, 0, 1, F64(0)))                                                       \
    X(bound_order_null, STATUS, udm1_lattice_bound_order, E(NULL_ARGUMENT), 0,                                          \
      udm1_lattice_bound_order(NULL, 0, 4, U64(0)))                                                                     \
    X(bound_order_null_out, STATUS, udm1_lattice_bound_order, E(NULL_ARGUMENT), 0,                                      \
      udm1_lattice_bound_order(f->lb, 0, 4, NULL))                                                                      \
    X(bound_order_past, STATUS, udm1_lattice_bound_order, E(INDEX_RANGE), 0,                                            \
      udm1_lattice_bound_order(f->lb, 0, 129, U64(0)))                                                                  \
    X(bound_order_wrap, STATUS, udm1_lattice_bound_order, E(INDEX_RANGE), 0,                                            \
      udm1_lattice_bound_order(f->lb, UINT64_MAX, 2, U64(0)))                                                           \
    /* noise tables */                                                                                                  \
    X(noise_tables_null, STATUS, udm1_noise_tables, E(NULL_ARGUMENT), 0, udm1_noise_tables(NULL, O8(0), F64(1)))        \
    X(cellular_offsets_null, STATUS, udm1_cellular_offsets, E(NULL_ARGUMENT), 0, udm1_cellular_offsets(NULL, O8(0)))    \
    X(cellular_offsets_null_out, STATUS, udm1_cellular_offsets, E(NULL_ARGUMENT), 0,                                    \
      udm1_cellular_offsets(f->perlin, NULL))                                                                           \
    /* noise batches, double */                                                                                         \
    X(eval_null_noise, STATUS, udm1_noise_eval, E(NULL_ARGUMENT), 0,                                                    \
      udm1_noise_eval(NULL, 3, f->ax, 1, NPTS, F64(0), F64(1)))                                                         \
    X(eval_null_axes, STATUS, udm1_noise_eval, E(NULL_ARGUMENT), 0,                                                     \
      udm1_noise_eval(f->perlin, 3, NULL, 1, NPTS, F64(0), F64(1)))                                                     \
    X(eval_null_axis, STATUS, udm1_noise_eval, E(NULL_ARGUMENT), 0,                                                     \
      udm1_noise_eval(f->perlin, 3, f->ax_null1, 1, NPTS, F64(0), F64(1)))                                              \
    X(eval_null_outputs, STATUS, udm1_noise_eval, E(NULL_ARGUMENT), 0,                                                  \
      udm1_noise_eval(f->perlin, 3, f->ax, 1, NPTS, NULL, NULL))                                                        \
    X(eval_dims0, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                                      \
      udm1_noise_eval(f->perlin, 0, f->ax, 1, NPTS, F64(0), F64(1)))                                                    \
    X(eval_dims5, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                                      \
      udm1_noise_eval(f->perlin, 5, f->ax, 1, NPTS, F64(0), F64(1)))                                                    \
    X(eval_classic_4d, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                                 \
      udm1_noise_eval(f->classic, 4, f->ax, 1, NPTS, F64(0), F64(1)))                                                   \
    X(eval_stride0, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                                    \
      udm1_noise_eval(f->perlin, 2, f->ax, 0, NPTS, F64(0), F64(1)))                                                    \
    X(eval_nan_last_1d, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                                \
      udm1_noise_eval(f->perlin, 1, f->ax_nan, 1, NPTS, F64(0), F64(1)))                                                \
    X(eval_nan_last_2d, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                                \
      udm1_noise_eval(f->perlin, 2, f->ax_nan, 1, NPTS, F64(0), F64(1)))                                                \
    X(eval_nan_last_3d, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                                \
      udm1_noise_eval(f->perlin, 3, f->ax_nan, 1, NPTS, F64(0), F64(1)))                                                \
    X(eval_nan_last_4d, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                                \
      udm1_noise_eval(f->perlin, 4, f->ax_nan, 1, NPTS, F64(0), F64(1)))                                                \
    X(eval_inf_mid_value, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                              \
      udm1_noise_eval(f->perlin, 3, f->ax_inf, 1, NPTS, F64(0), NULL))                                                  \
    X(eval_ninf_gradient, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                              \
      udm1_noise_eval(f->perlin, 3, f->ax_ninf, 1, NPTS, NULL, F64(1)))                                                 \
    X(eval_nan_classic, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                                \
      udm1_noise_eval(f->classic, 3, f->ax_nan, 1, NPTS, F64(0), F64(1)))                                               \
    X(eval_nan_periodic, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0,                                               \
      udm1_noise_eval(f->periodic, 2, f->ax_nan, 1, NPTS, F64(0), F64(1)))                                              \
    X(eval_nan_strided, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0, eval_packed(f, 3, 3, 0))                       \
    X(eval_nan_strided_2d, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0, eval_packed(f, 2, 3, 0))                    \
    /* noise batches, float */                                                                                          \
    X(eval_f32_null_noise, STATUS, udm1_noise_eval_f32, E(NULL_ARGUMENT), 0,                                            \
      udm1_noise_eval_f32(NULL, 3, f->axf, 1, NPTS, F32(0), F32(1)))                                                    \
    X(eval_f32_null_axis, STATUS, udm1_noise_eval_f32, E(NULL_ARGUMENT), 0,                                             \
      udm1_noise_eval_f32(f->perlin, 2, f->axf_null1, 1, NPTS, F32(0), F32(1)))                                         \
    X(eval_f32_null_outputs, STATUS, udm1_noise_eval_f32, E(NULL_ARGUMENT), 0,                                          \
      udm1_noise_eval_f32(f->perlin, 2, f->axf, 1, NPTS, NULL, NULL))                                                   \
    X(eval_f32_dims, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0,                                               \
      udm1_noise_eval_f32(f->perlin, 0, f->axf, 1, NPTS, F32(0), F32(1)))                                               \
    X(eval_f32_classic_4d, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0,                                         \
      udm1_noise_eval_f32(f->classic, 4, f->axf, 1, NPTS, F32(0), F32(1)))                                              \
    X(eval_f32_stride0, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0,                                            \
      udm1_noise_eval_f32(f->perlin, 3, f->axf, 0, NPTS, F32(0), F32(1)))                                               \
    X(eval_f32_nan_last_1d, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0,                                        \
      udm1_noise_eval_f32(f->perlin, 1, f->axf_nan, 1, NPTS, F32(0), F32(1)))                                           \
    X(eval_f32_nan_last_2d, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0,                                        \
      udm1_noise_eval_f32(f->perlin, 2, f->axf_nan, 1, NPTS, F32(0), F32(1)))                                           \
    X(eval_f32_nan_last_3d, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0,                                        \
      udm1_noise_eval_f32(f->perlin, 3, f->axf_nan, 1, NPTS, F32(0), F32(1)))                                           \
    X(eval_f32_nan_last_4d, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0,                                        \
      udm1_noise_eval_f32(f->seqnoise, 4, f->axf_nan, 1, NPTS, F32(0), F32(1)))                                         \
    X(eval_f32_inf_mid, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0,                                            \
      udm1_noise_eval_f32(f->perlin, 2, f->axf_inf, 1, NPTS, F32(0), NULL))                                             \
    X(eval_f32_ninf_gradient, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0,                                      \
      udm1_noise_eval_f32(f->perlin, 3, f->axf_ninf, 1, NPTS, NULL, F32(1)))                                            \
    X(eval_f32_nan_classic, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0,                                        \
      udm1_noise_eval_f32(f->classic, 2, f->axf_nan, 1, NPTS, F32(0), F32(1)))                                          \
    X(eval_f32_nan_periodic, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0,                                       \
      udm1_noise_eval_f32(f->periodic, 3, f->axf_nan, 1, NPTS, F32(0), F32(1)))                                         \
    /* small batches (all of the kernel's groups into scratch, the last few points checked after) */             \
    X(eval_f32_small_nan_rest, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0, small_batch(f, 0))              \
    X(eval_f32_small_ninf_kernel, STATUS, udm1_noise_eval_f32, E(INVALID_ARGUMENT), 0, small_batch(f, 1))           \
    X(eval_small_nan_rest, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0, small_batch(f, 2))                      \
    X(eval_small_ninf_kernel, STATUS, udm1_noise_eval, E(INVALID_ARGUMENT), 0, small_batch(f, 3))                   \
    X(noise_points_small_nan_rest, STATUS, udm1_noise_points, E(INVALID_ARGUMENT), 0, small_batch(f, 4))            \
    /* noise points */                                                                                                  \
    X(noise_points_null, STATUS, udm1_noise_points, E(NULL_ARGUMENT), 0,                                                \
      udm1_noise_points(NULL, 3, f->xyz, NPTS, 3, F64(0)))                                                              \
    X(noise_points_null_xyz, STATUS, udm1_noise_points, E(NULL_ARGUMENT), 0,                                            \
      udm1_noise_points(f->perlin, 3, NULL, NPTS, 3, F64(0)))                                                           \
    X(noise_points_null_out, STATUS, udm1_noise_points, E(NULL_ARGUMENT), 0,                                            \
      udm1_noise_points(f->perlin, 3, f->xyz, NPTS, 3, NULL))                                                           \
    X(noise_points_dims0, STATUS, udm1_noise_points, E(INVALID_ARGUMENT), 0,                                            \
      udm1_noise_points(f->perlin, 0, f->xyz, NPTS, 3, F64(0)))                                                         \
    X(noise_points_dims4, STATUS, udm1_noise_points, E(INVALID_ARGUMENT), 0,                                            \
      udm1_noise_points(f->perlin, 4, f->xyz, NPTS, 4, F64(0)))                                                         \
    X(noise_points_stride, STATUS, udm1_noise_points, E(INVALID_ARGUMENT), 0,                                           \
      udm1_noise_points(f->perlin, 3, f->xyz, NPTS, 2, F64(0)))                                                         \
    X(noise_points_nan_1d, STATUS, udm1_noise_points, E(INVALID_ARGUMENT), 0,                                           \
      udm1_noise_points(f->perlin, 1, f->xyz_nan_last, NPTS, 3, F64(0)))                                                \
    X(noise_points_nan_2d, STATUS, udm1_noise_points, E(INVALID_ARGUMENT), 0,                                           \
      udm1_noise_points(f->perlin, 2, f->xyz_nan_last, NPTS, 3, F64(0)))                                                \
    X(noise_points_nan_3d, STATUS, udm1_noise_points, E(INVALID_ARGUMENT), 0,                                           \
      udm1_noise_points(f->perlin, 3, f->xyz_nan_last, NPTS, 3, F64(0)))                                                \
    X(noise_points_nan_classic, STATUS, udm1_noise_points, E(INVALID_ARGUMENT), 0,                                      \
      udm1_noise_points(f->classic, 3, f->xyz_nan_last, NPTS, 3, F64(0)))                                               \
    X(noise_points_nan_periodic, STATUS, udm1_noise_points, E(INVALID_ARGUMENT), 0,                                     \
      udm1_noise_points(f->periodic, 2, f->xyz_nan_last, NPTS, 3, F64(0)))                                              \
    /* patterns */                                                                                                      \
    X(grid_null_noise, STATUS, udm1_pattern_grid, E(NULL_ARGUMENT), 0, grid(f, NULL, &f->fbm, 64, 64, 0, 64, 0))        \
    X(grid_null_params, STATUS, udm1_pattern_grid, E(NULL_ARGUMENT), 0, grid(f, f->perlin, NULL, 64, 64, 0, 64, 0))     \
    X(grid_null_out, STATUS, udm1_pattern_grid, E(NULL_ARGUMENT), 0, grid(f, f->perlin, &f->fbm, 64, 64, 0, 64, 1))     \
    X(grid_null_origin, STATUS, udm1_pattern_grid, E(NULL_ARGUMENT), 0, grid(f, f->perlin, &f->fbm, 64, 64, 0, 64, 2))  \
    X(grid_bad_params, STATUS, udm1_pattern_grid, E(INVALID_ARGUMENT), 0,                                               \
      grid(f, f->perlin, &f->bad_params, 64, 64, 0, 64, 0))                                                             \
    X(grid_width0, STATUS, udm1_pattern_grid, E(INVALID_ARGUMENT), 0, grid(f, f->perlin, &f->fbm, 0, 64, 0, 64, 0))     \
    X(grid_height_big, STATUS, udm1_pattern_grid, E(INVALID_ARGUMENT), 0,                                               \
      grid(f, f->perlin, &f->fbm, 4, 65537, 0, 4, 0))                                                                   \
    X(grid_rows_past, STATUS, udm1_pattern_grid, E(INVALID_ARGUMENT), 0,                                                \
      grid(f, f->perlin, &f->fbm, 64, 64, 60, 5, 0))                                                                    \
    X(grid_row0_past, STATUS, udm1_pattern_grid, E(INVALID_ARGUMENT), 0,                                                \
      grid(f, f->perlin, &f->fbm, 64, 64, 64, 0, 0))                                                                    \
    X(grid_origin_nan, STATUS, udm1_pattern_grid, E(INVALID_ARGUMENT), 0,                                               \
      grid(f, f->perlin, &f->fbm, 64, 64, 0, 64, 3))                                                                    \
    X(grid_step_nan, STATUS, udm1_pattern_grid, E(INVALID_ARGUMENT), 0, grid(f, f->perlin, &f->fbm, 64, 64, 0, 64, 4))  \
    X(grid_overflow_fbm, STATUS, udm1_pattern_grid, E(INVALID_ARGUMENT), 0,                                             \
      grid(f, f->perlin, &f->fbm_overflow, 64, 64, 0, 64, 5))                                                           \
    X(grid_overflow_ridged, STATUS, udm1_pattern_grid, E(INVALID_ARGUMENT), 0,                                          \
      grid(f, f->perlin, &f->ridged_overflow, 64, 64, 0, 64, 5))                                                        \
    X(grid_coordinate_overflow, STATUS, udm1_pattern_grid, E(INVALID_ARGUMENT), 0,                                      \
      grid(f, f->perlin, &f->noise_pattern, 64, 64, 0, 64, 6))                                                          \
    X(grid_coordinate_overflow_pov, STATUS, udm1_pattern_grid, E(INVALID_ARGUMENT), 0,                                  \
      grid(f, f->perlin, &f->marble, 64, 64, 0, 64, 6))                                                                 \
    X(pattern_points_null, STATUS, udm1_pattern_points, E(NULL_ARGUMENT), 0,                                            \
      udm1_pattern_points(f->perlin, &f->fbm, NULL, NPTS, 3, F64(0)))                                                   \
    X(pattern_points_null_out, STATUS, udm1_pattern_points, E(NULL_ARGUMENT), 0,                                        \
      udm1_pattern_points(f->perlin, &f->fbm, f->xyz, NPTS, 3, NULL))                                                   \
    X(pattern_points_params, STATUS, udm1_pattern_points, E(INVALID_ARGUMENT), 0,                                       \
      udm1_pattern_points(f->perlin, &f->bad_params, f->xyz, NPTS, 3, F64(0)))                                          \
    X(pattern_points_stride, STATUS, udm1_pattern_points, E(INVALID_ARGUMENT), 0,                                       \
      udm1_pattern_points(f->perlin, &f->fbm, f->xyz, NPTS, 2, F64(0)))                                                 \
    X(pattern_points_nan, STATUS, udm1_pattern_points, E(INVALID_ARGUMENT), 0,                                          \
      udm1_pattern_points(f->perlin, &f->marble, f->xyz_nan_last, NPTS, 3, F64(0)))                                     \
    X(pattern_points_overflow, STATUS, udm1_pattern_points, E(INVALID_ARGUMENT), 0,                                     \
      udm1_pattern_points(f->perlin, &f->fbm_overflow, f->xyz_big_last, 1000, 3, F64(0)))                               \
    X(pattern_points_overflow_ridged, STATUS, udm1_pattern_points, E(INVALID_ARGUMENT), 0,                              \
      udm1_pattern_points(f->perlin, &f->ridged_overflow, f->xyz_big_last, 1000, 3, F64(0)))                            \
    X(pattern_gradient_null, STATUS, udm1_pattern_gradient, E(NULL_ARGUMENT), 0,                                        \
      udm1_pattern_gradient(f->perlin, &f->fbm, f->xyz, NPTS, 3, NULL, NULL))                                           \
    X(pattern_gradient_null_xyz, STATUS, udm1_pattern_gradient, E(NULL_ARGUMENT), 0,                                    \
      udm1_pattern_gradient(f->perlin, &f->fbm, NULL, NPTS, 3, F64(0), F64(1)))                                         \
    X(pattern_gradient_params, STATUS, udm1_pattern_gradient, E(INVALID_ARGUMENT), 0,                                   \
      udm1_pattern_gradient(f->perlin, &f->bad_params, f->xyz, NPTS, 3, F64(0), F64(1)))                                \
    X(pattern_gradient_marble, STATUS, udm1_pattern_gradient, E(INVALID_ARGUMENT), 0,                                   \
      udm1_pattern_gradient(f->perlin, &f->marble, f->xyz, NPTS, 3, F64(0), F64(1)))                                    \
    X(pattern_gradient_stride, STATUS, udm1_pattern_gradient, E(INVALID_ARGUMENT), 0,                                   \
      udm1_pattern_gradient(f->perlin, &f->fbm, f->xyz, NPTS, 1, F64(0), F64(1)))                                       \
    X(pattern_gradient_nan, STATUS, udm1_pattern_gradient, E(INVALID_ARGUMENT), 0,                                      \
      udm1_pattern_gradient(f->perlin, &f->fbm, f->xyz_nan_last, NPTS, 3, F64(0), F64(1)))                              \
    X(pattern_gradient_overflow, STATUS, udm1_pattern_gradient, E(INVALID_ARGUMENT), 0,                                 \
      udm1_pattern_gradient(f->perlin, &f->fbm_overflow, f->xyz_big_last, 1000, 3, F64(0), F64(1)))                     \
    X(pattern_gradient_overflow_value, STATUS, udm1_pattern_gradient, E(INVALID_ARGUMENT), 0,                           \
      udm1_pattern_gradient(f->perlin, &f->ridged_overflow, f->xyz_big_last, 1000, 3, F64(0), NULL))                    \
    X(pattern_gradient_overflow_grad, STATUS, udm1_pattern_gradient, E(INVALID_ARGUMENT), 0,                            \
      udm1_pattern_gradient(f->perlin, &f->fbm_overflow, f->xyz_big_last, 1000, 3, NULL, F64(1)))                       \
    X(color_map_null, STATUS, udm1_color_map_eval, E(NULL_ARGUMENT), 0, udm1_color_map_eval(NULL, 3, 0.5, F32(0)))      \
    X(color_map_null_rgb, STATUS, udm1_color_map_eval, E(NULL_ARGUMENT), 0,                                             \
      udm1_color_map_eval(f->colors, 3, 0.5, NULL))                                                                     \
    X(color_map_count0, STATUS, udm1_color_map_eval, E(INVALID_ARGUMENT), 0,                                            \
      udm1_color_map_eval(f->colors, 0, 0.5, F32(0)))                                                                   \
    X(color_map_unsorted, STATUS, udm1_color_map_eval, E(INVALID_ARGUMENT), 0,                                          \
      udm1_color_map_eval(f->unsorted, 3, 0.5, F32(0)))                                                                 \
    X(color_map_nan_entry, STATUS, udm1_color_map_eval, E(INVALID_ARGUMENT), 0,                                         \
      udm1_color_map_eval(f->nan_entry, 2, 0.5, F32(0)))                                                                \
    X(color_map_nan_value, STATUS, udm1_color_map_eval, E(INVALID_ARGUMENT), 0,                                         \
      udm1_color_map_eval(f->colors, 3, NAN, F32(0)))                                                                   \
    X(default_colors_null, STATUS, udm1_pattern_default_colors, E(NULL_ARGUMENT), 0,                                    \
      udm1_pattern_default_colors(UDM1_PATTERN_BOZO, NULL, (size_t *)f->out[1]))                                        \
    X(default_colors_null_count, STATUS, udm1_pattern_default_colors, E(NULL_ARGUMENT), 0,                              \
      udm1_pattern_default_colors(UDM1_PATTERN_BOZO, (const udm1_color_entry **)f->out[0], NULL))                       \
    X(default_colors_unknown, STATUS, udm1_pattern_default_colors, E(INVALID_ARGUMENT), 0,                              \
      udm1_pattern_default_colors(99, (const udm1_color_entry **)f->out[0], (size_t *)f->out[1]))                       \
    /* cellular noise */                                                                                                \
    X(cell_null_noise, STATUS, udm1_cellular_eval, E(NULL_ARGUMENT), 0,                                                 \
      udm1_cellular_eval(NULL, &f->cell, 3, f->ax, 1, NPTS, F64(0)))                                                    \
    X(cell_null_axes, STATUS, udm1_cellular_eval, E(NULL_ARGUMENT), 0,                                                  \
      udm1_cellular_eval(f->perlin, &f->cell, 3, NULL, 1, NPTS, F64(0)))                                                \
    X(cell_null_axis, STATUS, udm1_cellular_eval, E(NULL_ARGUMENT), 0,                                                  \
      udm1_cellular_eval(f->perlin, &f->cell, 3, f->ax_null1, 1, NPTS, F64(0)))                                         \
    X(cell_null_out, STATUS, udm1_cellular_eval, E(NULL_ARGUMENT), 0,                                                   \
      udm1_cellular_eval(f->perlin, &f->cell, 3, f->ax, 1, NPTS, NULL))                                                 \
    X(cell_dims1, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0,                                                   \
      udm1_cellular_eval(f->perlin, &f->cell, 1, f->ax, 1, NPTS, F64(0)))                                               \
    X(cell_dims4, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0,                                                   \
      udm1_cellular_eval(f->perlin, &f->cell, 4, f->ax, 1, NPTS, F64(0)))                                               \
    X(cell_stride0, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0,                                                 \
      udm1_cellular_eval(f->perlin, &f->cell, 2, f->ax, 0, NPTS, F64(0)))                                               \
    X(cell_params_metric, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0, cellular(f, 0, 3, 0, 0))                  \
    X(cell_params_output, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0, cellular(f, 1, 3, 0, 0))                  \
    X(cell_params_reserved, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0, cellular(f, 2, 3, 0, 0))                \
    X(cell_params_jitter, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0, cellular(f, 3, 3, 0, 0))                  \
    X(cell_params_jitter_nan, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0, cellular(f, 4, 3, 0, 0))              \
    X(cell_params_exponent, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0, cellular(f, 5, 3, 0, 0))                \
    X(cell_params_size, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0, cellular(f, 6, 3, 0, 0))                    \
    X(cell_nan_last_3d, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0, cellular(f, 7, 3, 1, 0))                    \
    X(cell_nan_last_2d, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0, cellular(f, 7, 2, 1, 0))                    \
    X(cell_inf_mid, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0, cellular(f, 7, 3, 2, 0))                        \
    X(cell_nan_minkowski, STATUS, udm1_cellular_eval, E(INVALID_ARGUMENT), 0, cellular(f, 8, 3, 1, 0))                  \
    X(cell_f32_null_noise, STATUS, udm1_cellular_eval_f32, E(NULL_ARGUMENT), 0,                                         \
      udm1_cellular_eval_f32(NULL, &f->cell, 3, f->axf, 1, NPTS, F32(0)))                                               \
    X(cell_f32_null_axis, STATUS, udm1_cellular_eval_f32, E(NULL_ARGUMENT), 0,                                          \
      udm1_cellular_eval_f32(f->perlin, &f->cell, 3, f->axf_null1, 1, NPTS, F32(0)))                                    \
    X(cell_f32_dims, STATUS, udm1_cellular_eval_f32, E(INVALID_ARGUMENT), 0,                                            \
      udm1_cellular_eval_f32(f->perlin, &f->cell, 1, f->axf, 1, NPTS, F32(0)))                                          \
    X(cell_f32_params, STATUS, udm1_cellular_eval_f32, E(INVALID_ARGUMENT), 0, cellular(f, 3, 3, 0, 1))                 \
    X(cell_f32_nan_last_3d, STATUS, udm1_cellular_eval_f32, E(INVALID_ARGUMENT), 0, cellular(f, 7, 3, 1, 1))            \
    X(cell_f32_nan_last_2d, STATUS, udm1_cellular_eval_f32, E(INVALID_ARGUMENT), 0, cellular(f, 7, 2, 1, 1))            \
    X(cell_f32_inf_mid, STATUS, udm1_cellular_eval_f32, E(INVALID_ARGUMENT), 0, cellular(f, 7, 3, 2, 1))                \
    X(cell_f32_nan_minkowski, STATUS, udm1_cellular_eval_f32, E(INVALID_ARGUMENT), 0, cellular(f, 8, 2, 1, 1))

/* ---- helpers the rows call ---------------------------------------------------------------------------- */

static udm1_status create_rational(fixture *f)
{
    udm1_seq_desc d = f->desc;
    static const udm1_alpha a[2] = {{UDM1_ALPHA_SQRT, 0, 3, 0, 0, 0}, {UDM1_ALPHA_SQRT, 0, 16, 0, 0, 0}};
    d.preset = NULL, d.alphas = a, d.dimensions = 2;
    return udm1_seq_create_desc(&d, (udm1_seq **)f->out[0]);
}

static udm1_status create_bad_randomize(fixture *f)
{
    udm1_seq_desc d = f->desc;
    d.randomize = 99;
    return udm1_seq_create_desc(&d, (udm1_seq **)f->out[0]);
}

static udm1_status create_bad_size(fixture *f)
{
    udm1_seq_desc d = f->desc;
    d.struct_size = 4;
    return udm1_seq_create_desc(&d, (udm1_seq **)f->out[0]);
}

static udm1_status noise_create_bad(fixture *f, int which)
{
    udm1_noise_desc d;
    udm1_noise_desc_init(&d);
    if (which == 0) d.kind = 7;
    if (which == 1) d.period[2] = (1u << 30) + 1;
    if (which == 2) d.table = "nope";
    return udm1_noise_create(&d, (udm1_noise **)f->out[0]);
}

/* A domain fill: stream 0 of f (0 st_wr, 1 NULL, 2 st_zero, 3 st_wr, 4 st_hamm, 5 st_limit at its last
 * dimensions); child or root; index; n; output (0 NULL raw, 1 raw, 2 NULL float, 3 float). */
static udm1_status domain_fill(fixture *f, int which, int child, uint64_t index, uint32_t n, int out)
{
    const udm1_stream *st = which == 1 ? NULL : which == 2 ? &f->st_zero : which == 4 ? &f->st_hamm
                            : which == 5 ? &f->st_limit : &f->st_wr;
    udm1_domain d = {st, 0, index, 0, 0};
    if (child) d = udm1_domain_child(d, 3);
    if (which == 5) d.dim = 62; /* dimensions from LIMIT - 2 */
    if (out == 0) return udm1_domain_fill_raw(&d, n, NULL);
    if (out == 1) return udm1_domain_fill_raw(&d, n, U64(0));
    if (out == 2) return udm1_domain_fill_f32(&d, n, NULL);
    return udm1_domain_fill_f32(&d, n, F32(0));
}

/* A stream draw into buffer 0: raw (kind 0), float (1) or double (2). */
static udm1_status draw_stream(fixture *f, const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n, int kind)
{
    if (kind == 0) udm1_stream_draw_raw(st, index, dim, n, U64(0));
    else if (kind == 1) udm1_stream_draw_f32(st, index, dim, n, F32(0));
    else udm1_stream_draw_f64(st, index, dim, n, F64(0));
    return UDM1_OK;
}

/* A domain draw into buffer 0: of stream (0 st_wr, 1 st_hamm, 2 st_pmj, 3 st_limit past its last dimension,
 * 4 none), child or root, index, n, kind as draw_stream. */
static udm1_status draw_domain(fixture *f, int which, int child, uint64_t index, uint32_t n, int kind)
{
    const udm1_stream *st = which == 1 ? &f->st_hamm : which == 2 ? &f->st_pmj : which == 3 ? &f->st_limit
                            : which == 4 ? NULL : &f->st_wr;
    udm1_domain d = udm1_domain_root(st, index);
    if (child) d = udm1_domain_child(d, 5);
    if (which == 3) d.dim = 63; /* dimension LIMIT - 1 and the next: past the limit */
    if (which == 4) d.key = child ? 77 : 0;
    if (kind == 0) udm1_domain_draw_raw(d, n, U64(0));
    else if (kind == 1) udm1_domain_draw_f32(d, n, F32(0));
    else udm1_domain_draw_f64(d, n, F64(0));
    return UDM1_OK;
}

/* The cursor's draws from a cursor never started (zeroed): fill (kind 1), fill_f64 (2), 2d (3), 2d_f64 (4). */
static udm1_status draw_cursor(fixture *f, uint32_t n, int kind)
{
    udm1_cursor c;
    memset(&c, 0, sizeof c);
    if (kind == 1) udm1_cursor_fill(&c, n, F32(0));
    else if (kind == 2) udm1_cursor_fill_f64(&c, n, F64(0));
    else if (kind == 3) udm1_cursor_2d(&c, F32(0));
    else udm1_cursor_2d_f64(&c, F64(0));
    return UDM1_OK;
}

/* noise_eval on packed points (axes p, p + 1, p + 2, stride `stride`), NaN at the last point */
static udm1_status eval_packed(fixture *f, uint32_t dims, size_t stride, int f32)
{
    (void)f32;
    const double *axes[3] = {f->xyz_nan_last, f->xyz_nan_last + 1, f->xyz_nan_last + 2};
    return udm1_noise_eval(f->perlin, dims, axes, stride, NPTS, F64(0), F64(1));
}

/* A batch of 100 points, value only (the small batches' path): 0 float 2D, NaN at the last point (past the
 * kernel's groups); 1 float 3D, -infinity at point 17 (in them); 2, 3 the same in double, 3D; 4 noise_points
 * 3D, NaN at the last point. */
static udm1_status small_batch(fixture *f, int which)
{
    enum { M = 100 };
    size_t at = NPTS - M;
    if (which == 0) {
        const float *axes[2] = {f->xf_nan_last + at, f->yf + at};
        return udm1_noise_eval_f32(f->perlin, 2, axes, 1, M, F32(0), NULL);
    }
    if (which == 1) return udm1_noise_eval_f32(f->perlin, 3, f->axf_ninf, 1, M, F32(0), NULL);
    if (which == 2) {
        const double *axes[3] = {f->x_nan_last + at, f->y + at, f->z + at};
        return udm1_noise_eval(f->perlin, 3, axes, 1, M, F64(0), NULL);
    }
    if (which == 3) return udm1_noise_eval(f->perlin, 3, f->ax_ninf, 1, M, F64(0), NULL);
    return udm1_noise_points(f->perlin, 3, f->xyz_nan_last + 3 * at, M, 3, F64(0));
}

/* pattern_grid over 64 columns: the arguments as given; `bad` 1 NULL out, 2 NULL origin, 3 NaN origin,
 * 4 NaN step, 5 a step along y that makes the octaves' scaled coordinates overflow from row 2 on, 6 one
 * that makes the coordinates themselves overflow from row 5 on. */
static udm1_status grid(fixture *f, const udm1_noise *n, const udm1_pattern_params *p, uint32_t width, uint32_t height,
                        uint32_t row0, uint32_t rows, int bad)
{
    return udm1_pattern_grid(n, p, width, height, row0, rows, bad == 2 ? NULL : bad == 3 ? f->nan3 : f->origin,
                             bad == 4 ? f->nan3 : f->step_x,
                             bad == 5 ? f->step_y_big : bad == 6 ? f->step_y_huge : f->step_y,
                             bad == 1 ? NULL : F32(0));
}

/* cellular_eval (f32 0/1) with params: 0 bad metric, 1 bad output, 2 reserved, 3 jitter 2, 4 jitter NaN,
 * 5 exponent 65, 6 struct_size 4, 7 good, 8 Minkowski e = 3; coordinates: 0 finite, 1 NaN at the last point,
 * 2 infinite in the middle. */
static udm1_status cellular(fixture *f, int params, uint32_t dims, int coords, int f32)
{
    udm1_cellular_params p = params == 8 ? f->cell_minkowski : f->cell;
    if (params == 0) p.metric = 9;
    if (params == 1) p.output = 9;
    if (params == 2) p.reserved = 1;
    if (params == 3) p.jitter = 2.0;
    if (params == 4) p.jitter = NAN;
    if (params == 5) p.exponent = 65.0;
    if (params == 6) p.struct_size = 4;
    if (f32) {
        const float *const *axes = coords == 1 ? f->axf_nan : coords == 2 ? f->axf_inf : f->axf;
        return udm1_cellular_eval_f32(f->perlin, &p, dims, axes, 1, NPTS, F32(0));
    }
    const double *const *axes = coords == 1 ? f->ax_nan : coords == 2 ? f->ax_inf : f->ax;
    return udm1_cellular_eval(f->perlin, &p, dims, axes, 1, NPTS, F64(0));
}

/* ---- the table ----------------------------------------------------------------------------------------- */

#define DEFINE_ROW(id, kind, fn, status, n, expr)                                                                       \
    static udm1_status row_##id(fixture *f)                                                                             \
    {                                                                                                                   \
        (void)f;                                                                                                        \
        return expr;                                                                                                    \
    }
ROWS(DEFINE_ROW)

#define TABLE_ROW(id, kind, fn, status, n, expr) {#id, #fn, kind, status, n, row_##id},
static const row ROW_TABLE[] = {ROWS(TABLE_ROW)};

/* ---- the fixture ---------------------------------------------------------------------------------------- */

/* Buffer k's pattern: no byte is 0 (a zero written shows), and neighbouring bytes differ. */
static uint8_t pattern_byte(int k, size_t i) { return (uint8_t)(0x80u | ((i * 37u + (size_t)k * 11u) & 0x7Fu)); }
static uint8_t *pattern[3];

static udm1_seq *make(const char *preset, uint32_t d, uint64_t k)
{
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create(preset, d, k, 7, &s), UDM1_OK);
    return s;
}

static void fixture_init(fixture *f)
{
    memset(f, 0, sizeof *f);
    f->wr4 = make("wr", 4, 0), f->sobol4 = make("sobol", 4, 0), f->pcg3 = make("pcg32", 3, 0);
    f->hamm2 = make("hammersley", 2, 64), f->epis1 = make("epis", 1, 64), f->pmj2 = make("pmj02", 2, 256);
    f->wr1 = make("wr", 1, 0), f->wr2000 = make("wr", 2000, 0);
    CHECK_STATUS(udm1_stream_init(&f->st_wr, f->wr4, 3, 0, 4), UDM1_OK);
    CHECK_STATUS(udm1_stream_init(&f->st_limit, f->wr4, 3, LIMIT - UDM1_STREAM_DIMS, UDM1_STREAM_DIMS), UDM1_OK);
    CHECK_STATUS(udm1_stream_init(&f->st_hamm, f->hamm2, 3, 0, 2), UDM1_OK);
    CHECK_STATUS(udm1_stream_init(&f->st_pmj, f->pmj2, 3, 0, 2), UDM1_OK);
    udm1_noise_desc nd;
    udm1_noise_desc_init(&nd);
    CHECK_STATUS(udm1_noise_create(&nd, &f->perlin), UDM1_OK);
    nd.kind = UDM1_NOISE_CLASSIC;
    CHECK_STATUS(udm1_noise_create(&nd, &f->classic), UDM1_OK);
    udm1_noise_desc_init(&nd);
    nd.period[0] = nd.period[1] = nd.period[2] = 8;
    CHECK_STATUS(udm1_noise_create(&nd, &f->periodic), UDM1_OK);
    udm1_noise_desc_init(&nd);
    nd.table = "wr";
    CHECK_STATUS(udm1_noise_create(&nd, &f->seqnoise), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_create(4, 5.0, 0, &f->lb), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_create(4, 5.0, 0, &f->lb_empty), UDM1_OK);
    for (int l = 0; l <= 64; ++l) f->transform[2 * l] = 1.0 / (1 + l), f->transform[2 * l + 1] = 0.5 / (1 + l);
    f->transform[1] = f->transform[129] = 0.0;
    CHECK_STATUS(udm1_lattice_bound_add(f->lb, f->transform, 128), UDM1_OK);

    udm1_pattern_params_init(&f->fbm, UDM1_PATTERN_FBM);
    udm1_pattern_params_init(&f->marble, UDM1_PATTERN_MARBLE);
    udm1_pattern_params_init(&f->noise_pattern, UDM1_PATTERN_NOISE);
    /* octave 1's scale 1e200: a coordinate above ~1.8e108 overflows there */
    udm1_pattern_params_init(&f->fbm_overflow, UDM1_PATTERN_FBM);
    f->fbm_overflow.lambda = 1e200, f->fbm_overflow.octaves = 2;
    udm1_pattern_params_init(&f->ridged_overflow, UDM1_PATTERN_RIDGED);
    f->ridged_overflow.lambda = 1e200, f->ridged_overflow.octaves = 2;
    udm1_pattern_params_init(&f->bad_params, UDM1_PATTERN_FBM);
    f->bad_params.octaves = 11;
    udm1_cellular_params_init(&f->cell);
    udm1_cellular_params_init(&f->cell_minkowski);
    f->cell_minkowski.metric = UDM1_CELLULAR_MINKOWSKI, f->cell_minkowski.exponent = 3.0;
    udm1_color_entry c0 = {0.0, {0, 0, 0}}, c1 = {0.5, {1, 0, 0}}, c2 = {1.0, {1, 1, 1}};
    f->colors[0] = c0, f->colors[1] = c1, f->colors[2] = c2;
    f->unsorted[0] = c0, f->unsorted[1] = c2, f->unsorted[2] = c1;
    f->nan_entry[0] = c0, f->nan_entry[1] = c1, f->nan_entry[1].value = NAN;
    udm1_alpha good = {UDM1_ALPHA_SQRT, 0, 2, 0, 0, 0}, bad = {UDM1_ALPHA_DOUBLE, 0, 0, 0, 0, NAN};
    f->alphas[0] = good, f->alphas[1] = good, f->alphas[1].k = 3, f->alphas[2] = bad;
    udm1_seq_desc_init(&f->desc);
    f->desc.preset = "wr", f->desc.dimensions = 2;

    for (uint32_t i = 0; i < NPTS; ++i) {
        f->streams[i] = i / 7, f->indices[i] = i % 64, f->indices_bad_last[i] = i % 64;
        double u = (double)i / NPTS;
        f->x[i] = 17.3 * u - 3.1, f->y[i] = -9.7 * u + 2.2, f->z[i] = 5.5 * u * u + 0.3, f->w[i] = 1.25 - 4.0 * u;
        f->xf[i] = (float)f->x[i], f->yf[i] = (float)f->y[i], f->zf[i] = (float)f->z[i], f->wf[i] = (float)f->w[i];
        f->xyz[3 * i] = f->x[i], f->xyz[3 * i + 1] = f->y[i], f->xyz[3 * i + 2] = f->z[i];
        f->unit[2 * i] = u, f->unit[2 * i + 1] = 1.0 - u;
    }
    f->indices_bad_last[3999] = 256; /* the last of the 4000 points the rows take: past every K here */
    memcpy(f->x_nan_last, f->x, sizeof f->x), f->x_nan_last[NPTS - 1] = NAN;
    memcpy(f->y_inf_mid, f->y, sizeof f->y), f->y_inf_mid[NPTS / 2] = INFINITY;
    memcpy(f->z_ninf_early, f->z, sizeof f->z), f->z_ninf_early[17] = -INFINITY;
    memcpy(f->xf_nan_last, f->xf, sizeof f->xf), f->xf_nan_last[NPTS - 1] = NAN;
    memcpy(f->yf_inf_mid, f->yf, sizeof f->yf), f->yf_inf_mid[NPTS / 2] = INFINITY;
    memcpy(f->zf_ninf_early, f->zf, sizeof f->zf), f->zf_ninf_early[17] = -INFINITY;
    memcpy(f->xyz_nan_last, f->xyz, sizeof f->xyz), f->xyz_nan_last[3 * (NPTS - 1)] = NAN;
    memcpy(f->xyz_big_last, f->xyz, sizeof f->xyz), f->xyz_big_last[3 * 999] = 1e150; /* last of 1000 points */
    memcpy(f->unit_out_last, f->unit, sizeof f->unit), f->unit_out_last[2 * NPTS - 1] = 1.5;
    const double *ax[4] = {f->x, f->y, f->z, f->w};
    const float *axf[4] = {f->xf, f->yf, f->zf, f->wf};
    for (int c = 0; c < 4; ++c) {
        f->ax[c] = f->ax_nan[c] = f->ax_inf[c] = f->ax_ninf[c] = f->ax_null1[c] = ax[c];
        f->axf[c] = f->axf_nan[c] = f->axf_inf[c] = f->axf_ninf[c] = f->axf_null1[c] = axf[c];
    }
    f->ax_nan[0] = f->x_nan_last, f->ax_inf[1] = f->y_inf_mid, f->ax_ninf[2] = f->z_ninf_early, f->ax_null1[1] = NULL;
    f->axf_nan[0] = f->xf_nan_last, f->axf_inf[1] = f->yf_inf_mid, f->axf_ninf[2] = f->zf_ninf_early;
    f->axf_null1[1] = NULL;
    f->origin[0] = 0.25, f->origin[1] = -1.5, f->origin[2] = 0.5;
    f->step_x[0] = 0.125, f->step_y[1] = 0.125;
    f->step_y_big[1] = 1e108; /* row j at (j + 1/2) 1e108, times 1e200: past the double range from row 2 */
    f->step_y_huge[1] = DBL_MAX / 3; /* row j at (j + 1/2) DBL_MAX / 3: past the double range from row 5 */
    f->nan3[0] = f->nan3[1] = f->nan3[2] = NAN;
    for (int k = 0; k < 3; ++k) {
        f->out[k] = malloc(BUF_BYTES), pattern[k] = malloc(BUF_BYTES);
        for (size_t i = 0; i < BUF_BYTES; ++i) pattern[k][i] = pattern_byte(k, i);
    }
}

static void fixture_free(fixture *f)
{
    udm1_seq *seqs[] = {f->wr4, f->sobol4, f->pcg3, f->hamm2, f->epis1, f->pmj2, f->wr1, f->wr2000};
    for (size_t i = 0; i < sizeof seqs / sizeof seqs[0]; ++i) udm1_seq_destroy(seqs[i]);
    udm1_noise_destroy(f->perlin), udm1_noise_destroy(f->classic), udm1_noise_destroy(f->periodic);
    udm1_noise_destroy(f->seqnoise);
    udm1_lattice_bound_destroy(f->lb), udm1_lattice_bound_destroy(f->lb_empty);
    for (int k = 0; k < 3; ++k) free(f->out[k]), free(pattern[k]);
}

/* ---- running a row --------------------------------------------------------------------------------------- */

static void fill_pattern(fixture *f)
{
    for (int k = 0; k < 3; ++k) memcpy(f->out[k], pattern[k], BUF_BYTES);
}

/* The first byte of buffer k at or after `from` that is not the pattern, or BUF_BYTES. */
static size_t first_changed(const fixture *f, int k, size_t from)
{
    if (memcmp(O8(k) + from, pattern[k] + from, BUF_BYTES - from) == 0) return BUF_BYTES;
    for (size_t i = from; i < BUF_BYTES; ++i)
        if (O8(k)[i] != pattern[k][i]) return i;
    return BUF_BYTES;
}

/* Whether output j of a draw of `kind` in buffer 0 is its refusal value. */
static int refused_value(const fixture *f, int kind, uint32_t j)
{
    if (kind == DRAW_F32) return isnan(((const float *)f->out[0])[j]);
    if (kind == DRAW_F64) return isnan(((const double *)f->out[0])[j]);
    return ((const uint64_t *)f->out[0])[j] == 0;
}

static int run_row(fixture *f, const row *r)
{
    int failed = 0;
    fill_pattern(f);
    udm1_preset_find("-marker-", NULL); /* a message that the row's must replace */
    char marker[256];
    snprintf(marker, sizeof marker, "%s", udm1_last_error());
    udm1_status st = r->call(f);
    const char *msg = udm1_last_error();
    if (r->kind == STATUS || r->kind == CREATOR) {
        size_t len = strlen(r->fn);
        if (st != r->expected) {
            fprintf(stderr, "row %s: %s returned %s, expected %s (%s)\n", r->id, r->fn, udm1_status_string(st),
                    udm1_status_string(r->expected), msg);
            failed = 1;
        } else if (strncmp(msg, r->fn, len) != 0 || msg[len] != ':' || strchr(msg, '\n')) {
            fprintf(stderr, "row %s: the message \"%s\" does not name %s on one line\n", r->id, msg, r->fn);
            failed = 1;
        }
    } else if (strcmp(msg, marker) == 0) {
        fprintf(stderr, "row %s: a refused draw left no message\n", r->id);
        failed = 1;
    }
    size_t from0 = 0;
    if (r->kind == CREATOR) { /* the handle set to NULL */
        void *handle;
        memcpy(&handle, f->out[0], sizeof handle);
        if (handle != NULL) {
            fprintf(stderr, "row %s: a failed creation left *out not NULL\n", r->id);
            failed = 1;
        }
        from0 = sizeof handle;
    } else if (r->kind != STATUS) { /* the n refused values */
        size_t size = r->kind == DRAW_F32 ? sizeof(float) : 8;
        for (uint32_t j = 0; j < r->n; ++j)
            if (!refused_value(f, r->kind, j)) {
                fprintf(stderr, "row %s: output %u of the refused draw is not its NaN (0 raw)\n", r->id, j);
                failed = 1;
                break;
            }
        from0 = r->n * size;
    }
    for (int k = 0; k < 3; ++k) {
        size_t at = first_changed(f, k, k == 0 ? from0 : 0);
        if (at < BUF_BYTES) {
            size_t last = at;
            for (size_t i = at; i < BUF_BYTES; ++i)
                if (O8(k)[i] != pattern[k][i]) last = i;
            fprintf(stderr, "row %s: %s wrote buffer %d on error: bytes %zu .. %zu changed\n", r->id, r->fn, k, at,
                    last);
            failed = 1;
        }
    }
    return failed;
}

/* A failed udm1_lattice_bound_add changes nothing: the points, the bound and every coefficient and class. */
static void test_lattice_bound_add_unchanged(fixture *f)
{
    double before[2 * 128], after[2 * 128], e0 = 0, e1 = 0;
    uint64_t order0[128], order1[128];
    CHECK_STATUS(udm1_lattice_bound_coefficients(f->lb, 0, 128, before), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_order(f->lb, 0, 128, order0), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_error(f->lb, &e0), UDM1_OK);
    double bad[2 * 65];
    memcpy(bad, f->transform, sizeof bad);
    bad[2 * 64] = NAN; /* the last coefficient of the next 128 values */
    CHECK_STATUS(udm1_lattice_bound_add(f->lb, bad, 128), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_add(f->lb, f->transform, 64), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_add(f->lb, NULL, 128), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_lattice_bound_add(f->lb_empty, f->transform, 16), UDM1_ERROR_INVALID_ARGUMENT); /* not > 2^lag */
    CHECK_STATUS(udm1_lattice_bound_add(f->lb_empty, f->transform, 96), UDM1_ERROR_INVALID_ARGUMENT); /* not 2^m */
    CHECK(udm1_lattice_bound_points(f->lb) == 128 && udm1_lattice_bound_points(f->lb_empty) == 0);
    CHECK_STATUS(udm1_lattice_bound_coefficients(f->lb, 0, 128, after), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_order(f->lb, 0, 128, order1), UDM1_OK);
    CHECK_STATUS(udm1_lattice_bound_error(f->lb, &e1), UDM1_OK);
    CHECK(memcmp(before, after, sizeof before) == 0 && memcmp(order0, order1, sizeof order0) == 0 && e0 == e1);
}

int main(int argc, char **argv)
{
    if (check_built_isa_missing()) return 77;
    static fixture fx;
    fixture *f = &fx;
    fixture_init(f);
    size_t rows = sizeof ROW_TABLE / sizeof ROW_TABLE[0], failed = 0;
    for (size_t i = 0; i < rows; ++i) {
        if (argc > 1 && strstr(ROW_TABLE[i].id, argv[1]) == NULL) continue; /* a filter: part of a row id */
        if (run_row(f, &ROW_TABLE[i])) {
            ++failed;
            ++check_failures;
        }
    }
    test_lattice_bound_add_unchanged(f);
    fprintf(stderr, "%zu rows, %zu failed\n", rows, failed);
    fixture_free(f);
    CHECK_DONE();
}
