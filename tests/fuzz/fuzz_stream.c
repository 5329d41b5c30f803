/* fuzz_stream.c - fuzzer bytes turned into streams (udm1/stream.h) and domains (udm1/domain.h): any preset,
 * randomization, point count, first dimension and count, and any derivations, indices and draw sizes.
 *
 * Invariants checked (a failure aborts, which the fuzzer and the replay test report):
 *  - no crash, no hang, no sanitizer report; udm1_stream_init refuses (a status with a message, the struct
 *    left as it was) or succeeds;
 *  - a stream's draws, inline or through the library, raw, float and double, equal the cursor of the same
 *    (stream, index, first + dim) bit for bit, or are refused: NaN (0 raw) with a message;
 *  - a domain's draws, whatever derivation made it, equal udm1_domain_fill_raw (the library's own
 *    computation) bit for bit, its floats and doubles are those raw values converted, or it is refused
 *    alike by both;
 *  - a fill of many dimensions (more than a chunk of 64) writes all of them or, refused, none; the double
 *    draw of as many writes them or n NaN, and nothing past them. */
#include "fuzz_bytes.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *preset_name(uint64_t pick, char *buf, size_t len)
{
    size_t count = udm1_preset_count();
    udm1_preset_info info;
    if (udm1_preset_get((size_t)(pick / 2) % count, &info) != UDM1_OK) return "wr";
    snprintf(buf, len, "%s%s", info.name, (pick & 1) ? "+tent" : "");
    return buf;
}

/* one draw of n (1..4) dimensions from the stream, compared with the cursor */
static void stream_draw(const udm1_seq *seq, const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n)
{
    uint64_t raw[4] = {1, 1, 1, 1};
    float f32[4] = {2, 2, 2, 2};
    double f64[4] = {2, 2, 2, 2};
    udm1_stream_draw_raw(st, index, dim, n, raw);
    udm1_stream_draw_f32(st, index, dim, n, f32);
    udm1_stream_draw_f64(st, index, dim, n, f64);
    uint64_t d0 = (uint64_t)st->first + dim, K = udm1_seq_point_count(seq);
    if ((K && index >= K) || d0 + n > UDM1_DIMENSION_INDEX_LIMIT) { /* refused, and only then */
        for (uint32_t j = 0; j < n; ++j) REQUIRE(isnan(f64[j]) && isnan(f32[j]) && raw[j] == 0);
        REQUIRE(udm1_last_error()[0] != '\0');
        return;
    }
    udm1_cursor c;
    REQUIRE(udm1_cursor_start(&c, seq, st->stream, index, (uint32_t)d0) == UDM1_OK);
    for (uint32_t j = 0; j < n; ++j) {
        double want = udm1_cursor_1d_f64(&c);
        REQUIRE(want == f64[j]);
        REQUIRE(f64[j] == udm1_raw_to_f64(raw[j]) && f32[j] == udm1_raw_to_f32(raw[j]));
        REQUIRE(f64[j] >= 0.0 && f64[j] < 1.0 && f32[j] >= 0.0f && f32[j] < 1.0f);
    }
}

#define SENTINEL 0xA5
static int untouched(const void *p, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (((const unsigned char *)p)[i] != SENTINEL) return 0;
    return 1;
}

/* a fill of n (up to 300) dimensions: all written, or none */
static void stream_fill_long(const udm1_stream *st, uint64_t index, uint32_t dim, uint32_t n)
{
    enum { MAX = 300 };
    uint64_t raw[MAX];
    float f32[MAX];
    double f64[MAX];
    memset(raw, SENTINEL, sizeof raw), memset(f32, SENTINEL, sizeof f32), memset(f64, SENTINEL, sizeof f64);
    udm1_status s1 = udm1_stream_fill_raw(st, index, dim, n, raw), s2 = udm1_stream_fill_f32(st, index, dim, n, f32);
    udm1_stream_draw_f64(st, index, dim, n, f64);
    REQUIRE(s1 == s2);
    if (s1 != UDM1_OK) {
        REQUIRE(untouched(raw, sizeof raw) && untouched(f32, sizeof f32));
        for (uint32_t j = 0; j < n; ++j) REQUIRE(isnan(f64[j]));
    } else {
        for (uint32_t j = 0; j < n; ++j) REQUIRE(f32[j] == udm1_raw_to_f32(raw[j]) && f64[j] == udm1_raw_to_f64(raw[j]));
        REQUIRE(untouched(raw + n, sizeof raw - n * sizeof *raw) && untouched(f32 + n, sizeof f32 - n * sizeof *f32));
    }
    REQUIRE(untouched(f64 + n, sizeof f64 - n * sizeof *f64));
}

/* one draw of n (1..4) dimensions from the domain, compared with the library's own computation */
static void domain_draw(udm1_domain d, uint32_t n)
{
    uint64_t raw[4] = {1, 1, 1, 1}, lib[4] = {3, 3, 3, 3};
    float f32[4] = {2, 2, 2, 2};
    double f64[4] = {2, 2, 2, 2};
    udm1_domain_draw_raw(d, n, raw);
    udm1_domain_draw_f32(d, n, f32);
    udm1_domain_draw_f64(d, n, f64);
    udm1_status s = udm1_domain_fill_raw(&d, n, lib);
    for (uint32_t j = 0; j < n; ++j) {
        if (s != UDM1_OK) {
            REQUIRE(udm1_last_error()[0] != '\0');
            REQUIRE(isnan(f64[j]) && isnan(f32[j]) && raw[j] == 0);
            continue;
        }
        REQUIRE(raw[j] == lib[j]);
        REQUIRE(f64[j] == udm1_raw_to_f64(lib[j]) && f32[j] == udm1_raw_to_f32(lib[j]));
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bytes b = {data, size};
    char name[64];
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    desc.preset = preset_name(take(&b, 1), name, sizeof name);
    desc.dimensions = 1 + (uint32_t)take(&b, 1) % 80;
    uint64_t pc = take(&b, 2);
    desc.point_count = pc % 600;
    desc.seed = take(&b, 8);
    desc.randomize = (uint32_t)take(&b, 1) % 7;
    desc.screen_spp = (uint32_t)take(&b, 1) % 5;
    udm1_seq *seq = NULL;
    if (udm1_seq_create_desc(&desc, &seq) != UDM1_OK) return 0; /* fuzz_api covers the creation's errors */
    uint64_t K = udm1_seq_point_count(seq);
    for (int round = 0; round < 3 && b.n; ++round) {
        udm1_stream st;
        memset(&st, 0xA5, sizeof st);
        uint64_t stream = take(&b, 1) & 1 ? take(&b, 8) : take(&b, 1);
        uint32_t first = (take(&b, 1) & 3) == 3 ? (uint32_t)take(&b, 4) : (uint32_t)take(&b, 1) % 90;
        uint32_t count = (uint32_t)take(&b, 1) % (UDM1_STREAM_DIMS + 3);
        udm1_status s = udm1_stream_init(&st, seq, stream, first, count);
        REQUIRE((int)s >= 0 && udm1_status_string(s) != NULL);
        if (s != UDM1_OK) {
            REQUIRE(udm1_last_error()[0] != '\0');
            REQUIRE(st.struct_size == 0xA5A5A5A5u); /* left as it was */
            continue;
        }
        for (int k = 0; k < 6 && b.n; ++k) {
            uint64_t pick = take(&b, 1), index;
            if (K) index = pick & 1 ? take(&b, 2) % (K + 2) : take(&b, 1) % K; /* past K too */
            else index = pick & 1 ? take(&b, 8) : take(&b, 2);
            uint32_t dim = (pick & 6) == 6 ? (uint32_t)take(&b, 4) : (uint32_t)take(&b, 1) % (count + 3);
            uint32_t n = 1 + (uint32_t)(pick >> 3) % 4;
            stream_draw(seq, &st, index, dim, n);
            stream_fill_long(&st, index, dim, 60 + (uint32_t)((index + dim + k) % 241)); /* (no new bytes read) */
            /* a domain from that sample: a chain of derivations from its root */
            udm1_domain d = udm1_domain_root(&st, index);
            int steps = (int)(take(&b, 1) % 5);
            for (int i = 0; i < steps; ++i) {
                uint64_t op = take(&b, 1), key = op & 8 ? take(&b, 8) : take(&b, 1);
                switch (op % 4) {
                case 0: d = udm1_domain_next(d, (uint32_t)(op & 16 ? take(&b, 4) : take(&b, 1) % 4)); break;
                case 1: d = udm1_domain_child(d, key); break;
                case 2: {
                    uint32_t m = 1 + (uint32_t)take(&b, 1) % 16;
                    d = udm1_domain_split(d, key, m, (uint32_t)take(&b, 1) % m);
                    break;
                }
                default: d = udm1_domain_chain(d, key, take(&b, 2)); break;
                }
            }
            domain_draw(d, 1 + (uint32_t)take(&b, 1) % 4);
        }
    }
    udm1_seq_destroy(seq);
    return 0;
}
