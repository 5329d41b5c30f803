/* fuzz_api.c - fuzzer bytes turned into udm1 C API calls with any arguments.
 *
 * Invariants checked (a failure aborts, which the fuzzer and the replay test report):
 *  - no crash, no hang, no sanitizer report;
 *  - every status is a udm1_status with a message string, and a failing call writes nothing;
 *  - every value is in [0, 1) (f64 and f32) and the raw values agree with the f64 conversion;
 *  - a bulk fill equals per-sample access and the cursor, value for value;
 *  - many points at once equal the cursor, with a first dimension anywhere below 2^32; a dimension range
 *    reaching the index limit is refused, and a cursor that passes it draws NaN;
 *  - a discrepancy is never NaN, at any dimension;
 *  - an exact sum does not depend on split or order, cancels with the negated values, refuses non-finite ones. */
#include "fuzz_bytes.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void check_status(udm1_status st)
{
    REQUIRE((int)st >= 0 && (int)st < 64);
    REQUIRE(udm1_status_string(st) != NULL);
    if (st != UDM1_OK) REQUIRE(udm1_last_error() != NULL && udm1_last_error()[0] != '\0');
}

static const char *preset_name(uint64_t pick, char *buf, size_t len)
{
    size_t count = udm1_preset_count();
    udm1_preset_info info;
    if (pick % 8 == 7) return "no-such-preset";
    if (udm1_preset_get((size_t)(pick / 8) % count, &info) != UDM1_OK) return "wr";
    snprintf(buf, len, "%s%s", info.name, (pick & 16) ? "+tent" : "");
    return buf;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bytes b = {data, size};
    char name[64];
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    desc.preset = preset_name(take(&b, 1), name, sizeof name);
    desc.dimensions = (uint32_t)take(&b, 1) % 70;          /* includes 0 and above every 64-dim preset */
    uint64_t pc = take(&b, 2);
    desc.point_count = (pc & 0x8000) ? pc * 65537u : pc % 300; /* small, zero, or huge */
    desc.seed = take(&b, 8);
    desc.randomize = (uint32_t)take(&b, 1) % 8;            /* includes invalid values */
    desc.screen_spp = (uint32_t)take(&b, 1) % 5;
    int debug = getenv("UDM1_FUZZ_DEBUG") != NULL; /* prints the calls, to reproduce a finding by hand */
    if (debug)
        fprintf(stderr, "create %s d=%u K=%llu seed=%llu randomize=%u screen_spp=%u\n", desc.preset, desc.dimensions,
                (unsigned long long)desc.point_count, (unsigned long long)desc.seed, desc.randomize, desc.screen_spp);
    udm1_seq *seq = (udm1_seq *)(uintptr_t)1;              /* must be set to NULL on failure */
    udm1_status st = udm1_seq_create_desc(&desc, &seq);
    check_status(st);
    if (st != UDM1_OK) {
        REQUIRE(seq == NULL);
        return 0;
    }
    uint32_t d = udm1_seq_dimensions(seq);
    uint64_t k = udm1_seq_point_count(seq);
    for (int round = 0; round < 4 && b.n; ++round) {
        uint64_t stream = take(&b, 8);
        uint64_t first = take(&b, 1) & 1 ? take(&b, 8) : take(&b, 2);
        size_t count = (size_t)take(&b, 1) % 40;
        uint32_t dim0 = (uint32_t)take(&b, 1) % (d + 2);
        uint32_t nd = (uint32_t)take(&b, 1) % (d + 2);
        size_t stride = nd + (size_t)take(&b, 1) % 3;
        if (debug)
            fprintf(stderr, "fill stream=%llu first=%llu count=%zu dim0=%u nd=%u stride=%zu\n",
                    (unsigned long long)stream, (unsigned long long)first, count, dim0, nd, stride);
        double *f64 = calloc(count * (stride ? stride : 1) + 1, sizeof(double));
        float *f32 = calloc(count * (stride ? stride : 1) + 1, sizeof(float));
        uint64_t *u64 = calloc(count * (stride ? stride : 1) + 1, sizeof(uint64_t));
        REQUIRE(f64 && f32 && u64);
        udm1_status s1 = udm1_seq_fill_f64(seq, stream, first, count, dim0, nd, f64, stride);
        udm1_status s2 = udm1_seq_fill_f32(seq, stream, first, count, dim0, nd, f32, stride);
        udm1_status s3 = udm1_seq_fill_u64(seq, stream, first, count, dim0, nd, u64, stride);
        check_status(s1), check_status(s2), check_status(s3);
        REQUIRE(s1 == s2 && s2 == s3);
        if (s1 == UDM1_OK) {
            for (size_t i = 0; i < count; ++i) {
                for (uint32_t j = 0; j < nd; ++j) {
                    double v = f64[i * stride + j];
                    float w = f32[i * stride + j];
                    uint64_t raw = u64[i * stride + j];
                    REQUIRE(v >= 0.0 && v < 1.0 && w >= 0.0f && w < 1.0f);
                    REQUIRE(v == (double)(raw >> 11) * 0x1p-53);
                    uint64_t one = 0;
                    REQUIRE(udm1_seq_sample_u64(seq, stream, first + i, dim0 + j, &one) == UDM1_OK);
                    REQUIRE(one == raw); /* bulk equals per-sample */
                }
            }
            if (count > 0 && nd > 0) { /* and the cursor, along the first row */
                udm1_cursor c;
                REQUIRE(udm1_cursor_start(&c, seq, stream, first, dim0) == UDM1_OK);
                for (uint32_t j = 0; j < nd; ++j) REQUIRE(udm1_cursor_1d_f64(&c) == f64[j]);
            }
        } else {
            for (size_t i = 0; i < count * stride; ++i) REQUIRE(f64[i] == 0.0 && u64[i] == 0); /* nothing written */
        }
        free(f64), free(f32), free(u64);
        /* random access anywhere, including past the point count and the dimensions */
        uint64_t raw = 0;
        udm1_status s4 = udm1_seq_sample_u64(seq, stream, k ? take(&b, 2) % (k + 2) : take(&b, 8), (uint32_t)take(&b, 1),
                                            &raw);
        check_status(s4);
        /* a cursor past every dimension (padding) */
        udm1_cursor c;
        if (udm1_cursor_start(&c, seq, stream, k ? first % k : first, (uint32_t)take(&b, 1)) == UDM1_OK) {
            double pad[40];
            udm1_cursor_fill_f64(&c, (uint32_t)(take(&b, 1) % 40), pad);
        }
    }
    /* many points at once, the first dimension anywhere (the index limit included), against the cursor */
    {
        uint32_t fd = (take(&b, 1) & 1) ? (uint32_t)take(&b, 4) : (uint32_t)take(&b, 1) % (d + 4);
        uint32_t nd = (uint32_t)take(&b, 1) % 6;
        size_t np = (size_t)take(&b, 1) % 5;
        uint64_t streams[4], idx[4];
        for (size_t i = 0; i < np; ++i) {
            streams[i] = take(&b, 1) & 1 ? take(&b, 8) : take(&b, 1);
            idx[i] = k ? take(&b, 2) % (k + 1) : take(&b, 8);
        }
        double out[4 * 5];
        udm1_status s5 = udm1_seq_fill_points_f64(seq, np, streams, idx, fd, nd, out);
        check_status(s5);
        int bad_dims = nd == 0 || fd >= UDM1_DIMENSION_INDEX_LIMIT || nd > UDM1_DIMENSION_INDEX_LIMIT - fd;
        if (bad_dims) REQUIRE(s5 == UDM1_ERROR_DIMENSION);
        if (s5 == UDM1_OK)
            for (size_t i = 0; i < np; ++i) {
                udm1_cursor c;
                REQUIRE(udm1_cursor_start(&c, seq, streams[i], idx[i], fd) == UDM1_OK);
                for (uint32_t j = 0; j < nd; ++j) REQUIRE(udm1_cursor_1d_f64(&c) == out[i * nd + j]);
            }
        /* a cursor near the limit: values up to it, NaN past it */
        udm1_cursor c;
        uint32_t near = UDM1_DIMENSION_INDEX_LIMIT - 1 - (uint32_t)take(&b, 1) % 4;
        if (udm1_cursor_start(&c, seq, 0, 0, near) == UDM1_OK) {
            double v[6];
            udm1_cursor_fill_f64(&c, 6, v);
            for (uint32_t j = 0; j < 6; ++j)
                REQUIRE((uint64_t)near + j < UDM1_DIMENSION_INDEX_LIMIT ? (v[j] >= 0.0 && v[j] < 1.0) : isnan(v[j]));
        }
    }
    /* a discrepancy of a few points at any dimension: a number or +inf, never NaN */
    {
        uint32_t dd = 1 + (uint32_t)take(&b, 2) % 3000;
        size_t np = 1 + (size_t)take(&b, 1) % 3;
        double *x = malloc(sizeof(double) * np * dd), disc = -1;
        REQUIRE(x);
        for (size_t i = 0; i < np * dd; ++i) x[i] = (double)(take(&b, 1) % 65) / 64.0;
        udm1_status s6 = udm1_discrepancy(x, np, dd, dd, 1 + (uint32_t)take(&b, 1) % 4, &disc);
        check_status(s6);
        if (s6 == UDM1_OK) REQUIRE(!isnan(disc) && disc >= 0);
        free(x);
    }
    /* the exact sum of any doubles: refused (nothing written) iff one is not finite; else the same words
     * for any split and order, and the negated values cancel it to zero */
    {
        double x[64], neg[64];
        size_t nx = (size_t)take(&b, 1) % 65, cut = nx ? (size_t)take(&b, 1) % (nx + 1) : 0;
        int finite = 1;
        for (size_t i = 0; i < nx; ++i) {
            uint64_t bits = take(&b, 8);
            memcpy(&x[i], &bits, sizeof bits);
            finite &= isfinite(x[i]) != 0;
            neg[nx - 1 - i] = -x[i];
        }
        uint64_t whole[UDM1_EXACT_SUM_WORDS] = {0}, parts[UDM1_EXACT_SUM_WORDS] = {0}, zero[UDM1_EXACT_SUM_WORDS] = {0};
        udm1_status s7 = udm1_exact_sum_add(x, nx, whole);
        check_status(s7);
        REQUIRE((s7 == UDM1_OK) == finite);
        if (s7 == UDM1_OK) {
            REQUIRE(udm1_exact_sum_add(x + cut, nx - cut, parts) == UDM1_OK);
            REQUIRE(udm1_exact_sum_add(x, cut, parts) == UDM1_OK);
            REQUIRE(memcmp(whole, parts, sizeof whole) == 0);
            REQUIRE(udm1_exact_sum_add(neg, nx, whole) == UDM1_OK);
            REQUIRE(memcmp(whole, zero, sizeof whole) == 0);
        } else {
            REQUIRE(memcmp(whole, zero, sizeof whole) == 0);
        }
    }
    udm1_alpha_report rep;
    uint64_t n = take(&b, 2) % 300;
    if (d <= 8 && n <= 128 && udm1_seq_check(seq, n, &rep) == UDM1_OK) REQUIRE(rep.message[0] != 0);
    udm1_seq_destroy(seq);
    return 0;
}
