/* test_api_errors.c - every bad input returns its status code, writes
 * nothing, leaves a one-line message naming the input, and never crashes. */
#include "check.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdint.h>
#include <string.h>

static int mentions(const char *needle)
{
    const char *msg = udm1_last_error();
    return strstr(msg, needle) != NULL && strchr(msg, '\n') == NULL;
}

static void test_versions_and_strings(void)
{
    CHECK(udm1_version() == UDM1_VERSION);
    CHECK(udm1_version() / 10000 == UDM1_VERSION_MAJOR);
    char expect[32];
    snprintf(expect, sizeof expect, "%d.%d.%d", UDM1_VERSION_MAJOR, UDM1_VERSION_MINOR, UDM1_VERSION_PATCH);
    CHECK(strcmp(udm1_version_string(), expect) == 0);
    for (int s = 0; s <= 8; ++s) CHECK(strlen(udm1_status_string((udm1_status)s)) > 0);
    CHECK(strcmp(udm1_status_string((udm1_status)999), "unknown status") == 0);
    CHECK(strcmp(udm1_status_string((udm1_status)-1), "unknown status") == 0);
}

static void test_presets(void)
{
    udm1_preset_info info;
    CHECK(udm1_preset_count() >= 10);
    CHECK_STATUS(udm1_preset_get(0, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_preset_get(udm1_preset_count(), &info), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_preset_get(SIZE_MAX, &info), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_preset_find(NULL, &info), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_preset_find("wr", NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_preset_find("WR", &info), UDM1_ERROR_UNKNOWN_PRESET);
    CHECK(mentions("'WR'"));
    CHECK_STATUS(udm1_preset_find("episwr", &info), UDM1_OK);
    CHECK(info.flags & UDM1_PRESET_POINT_SET);
    CHECK(info.max_dimensions == 2);
    for (size_t i = 0; i < udm1_preset_count(); ++i) {
        CHECK_STATUS(udm1_preset_get(i, &info), UDM1_OK);
        udm1_preset_info again;
        CHECK_STATUS(udm1_preset_find(info.name, &again), UDM1_OK);
        CHECK(again.max_dimensions == info.max_dimensions);
    }
}

static void test_create_errors(void)
{
    udm1_seq *s = (udm1_seq *)&s; /* must be reset to NULL on failure */
    CHECK_STATUS(udm1_seq_create(NULL, 2, 0, 0, &s), UDM1_ERROR_NULL_ARGUMENT);
    CHECK(s == NULL);
    CHECK_STATUS(udm1_seq_create("wr", 2, 0, 0, NULL), UDM1_ERROR_NULL_ARGUMENT);
    s = (udm1_seq *)&s;
    CHECK_STATUS(udm1_seq_create("nope", 2, 0, 0, &s), UDM1_ERROR_UNKNOWN_PRESET);
    CHECK(s == NULL);
    CHECK(mentions("'nope'"));
    CHECK_STATUS(udm1_seq_create("wr", 0, 0, 0, &s), UDM1_ERROR_DIMENSION);
    CHECK(mentions("dimensions is 0"));
    CHECK_STATUS(udm1_seq_create("wr", UDM1_MAX_DIMENSIONS + 1, 0, 0, &s), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_create("wr", UINT32_MAX, 0, 0, &s), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_create("we", 3, 0, 0, &s), UDM1_ERROR_DIMENSION);
    CHECK(mentions("'we'"));
    CHECK_STATUS(udm1_seq_create("wmmr", 23, 0, 0, &s), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_create("golden", 2, 0, 0, &s), UDM1_ERROR_DIMENSION);
    /* point counts */
    CHECK_STATUS(udm1_seq_create("epis", 1, 0, 0, &s), UDM1_ERROR_POINT_COUNT);
    CHECK(mentions("'epis'"));
    CHECK_STATUS(udm1_seq_create("episwr", 2, 0, 0, &s), UDM1_ERROR_POINT_COUNT);
    CHECK_STATUS(udm1_seq_create("episwr", 2, (uint64_t)UDM1_MAX_POINT_COUNT + 1, 0, &s), UDM1_ERROR_POINT_COUNT);
    CHECK_STATUS(udm1_seq_create("episwr", 3, 64, 0, &s), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_create("wr", 2, 64, 0, &s), UDM1_ERROR_POINT_COUNT);
    CHECK(s == NULL);
    CHECK_STATUS(udm1_seq_create("episwr", 2, UDM1_MAX_POINT_COUNT, 0, &s), UDM1_OK);
    udm1_seq_destroy(s);

    /* descriptors */
    udm1_seq_desc d;
    udm1_seq_desc_init(NULL); /* accepted */
    CHECK_STATUS(udm1_seq_create_desc(NULL, &s), UDM1_ERROR_NULL_ARGUMENT);
    udm1_seq_desc_init(&d);
    CHECK(d.struct_size == sizeof d && d.randomize == UDM1_RANDOMIZE_DEFAULT && d.preset == NULL);
    d.dimensions = 2;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_NULL_ARGUMENT); /* no preset, no alphas */
    d.preset = "wr";
    CHECK_STATUS(udm1_seq_create_desc(&d, NULL), UDM1_ERROR_NULL_ARGUMENT);
    d.struct_size = 0;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(mentions("struct_size"));
    udm1_seq_desc_init(&d);
    d.dimensions = 2;
    d.preset = "wr";
    d.randomize = UDM1_RANDOMIZE_SCREEN + 1;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(mentions("randomize"));
    d.randomize = UDM1_RANDOMIZE_NONE;
    d.screen_spp = 1; /* only with UDM1_RANDOMIZE_SCREEN */
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(mentions("screen_spp"));
    d.randomize = UDM1_RANDOMIZE_SCREEN; /* which needs a Weyl sequence, fixed N or progressive (0) */
    d.preset = "sobol";
    d.screen_spp = 16;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(mentions("Weyl"));
    d.screen_spp = 0;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(mentions("Weyl"));
    d.preset = "wr";
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_OK);
    CHECK(udm1_seq_randomization(s) == UDM1_RANDOMIZE_SCREEN);
    udm1_seq_destroy(s);
    d.screen_spp = 16;
    d.preset = "wr";
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_OK);
    CHECK(udm1_seq_randomization(s) == UDM1_RANDOMIZE_SCREEN);
    udm1_seq_destroy(s);
    d.randomize = UDM1_RANDOMIZE_NONE;
    d.screen_spp = 0;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_OK);
    CHECK(udm1_seq_randomize(s) == UDM1_RANDOMIZE_NONE);
    udm1_seq_destroy(s);
}

static void test_alpha_errors(void)
{
    udm1_seq *s = NULL;
    udm1_seq_desc d;
    udm1_alpha a[2];
    memset(a, 0, sizeof a);
    udm1_seq_desc_init(&d);
    d.dimensions = 2;
    d.alphas = a;
    a[0].kind = UDM1_ALPHA_SQRT;
    a[0].k = 2;
    a[1].kind = UDM1_ALPHA_SQRT;
    a[1].k = 16; /* a perfect square */
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_RATIONAL_ALPHA);
    CHECK(mentions("alphas[1]") && mentions("sqrt(16)"));
    a[1].k = 1;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_RATIONAL_ALPHA);
    a[1].k = 0;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_RATIONAL_ALPHA);
    a[1].k = (uint64_t)4294967295u * 4294967295u; /* (2^32-1)^2 */
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_RATIONAL_ALPHA);
    a[1].k = UINT64_MAX; /* not a square: fine */
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_OK);
    udm1_seq_destroy(s);
    a[1].kind = 77;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(mentions("alphas[1].kind"));
    a[1].kind = UDM1_ALPHA_DOUBLE;
    a[1].value = NAN;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_INVALID_ARGUMENT);
    a[1].value = INFINITY;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_INVALID_ARGUMENT);
    a[1].value = 3.0; /* integer: zero fraction */
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_RATIONAL_ALPHA);
    a[1].value = 1e300;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_RATIONAL_ALPHA);
    a[1].value = -0.25; /* frac = 0.75 */
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_OK);
    uint64_t hi = 0, lo = 0;
    CHECK_STATUS(udm1_seq_alpha(s, 1, &hi, &lo), UDM1_OK);
    CHECK(hi == 0xC000000000000000ull && lo == 0);
    udm1_seq_destroy(s);
    a[1].value = -1e-300; /* frac = 1 - 1e-300: rounds to 2^128 - 1 in 0.128, not to 0 */
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_OK);
    CHECK_STATUS(udm1_seq_alpha(s, 1, &hi, &lo), UDM1_OK);
    CHECK(hi == UINT64_MAX && lo == UINT64_MAX);
    udm1_seq_destroy(s);
    a[1].kind = UDM1_ALPHA_FIXED;
    a[1].fixed_hi = a[1].fixed_lo = 0;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_RATIONAL_ALPHA);
    a[1].fixed_lo = 1;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_OK);
    udm1_seq_destroy(s);
    a[1].reserved = 5;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_INVALID_ARGUMENT);
    a[1].reserved = 0;
    d.point_count = 3;
    CHECK_STATUS(udm1_seq_create_desc(&d, &s), UDM1_ERROR_POINT_COUNT);
    CHECK(s == NULL);
}

static void test_query_and_sample_errors(void)
{
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("episwr", 2, 64, 9, &s), UDM1_OK);
    /* queries on NULL */
    CHECK(udm1_seq_dimensions(NULL) == 0);
    CHECK(udm1_seq_name(NULL) == NULL);
    CHECK(udm1_seq_point_count(NULL) == 0);
    CHECK(udm1_seq_seed(NULL) == 0);
    CHECK(udm1_seq_randomize(NULL) == 0);
    CHECK(strcmp(udm1_seq_name(s), "episwr") == 0);
    CHECK(udm1_seq_point_count(s) == 64 && udm1_seq_seed(s) == 9 && udm1_seq_dimensions(s) == 2);
    uint64_t hi = 7, lo = 7, u = 7;
    CHECK_STATUS(udm1_seq_alpha(NULL, 0, &hi, &lo), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_seq_alpha(s, 0, NULL, &lo), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_seq_alpha(s, 2, &hi, &lo), UDM1_ERROR_DIMENSION);
    CHECK(hi == 7 && lo == 7);
    CHECK_STATUS(udm1_seq_offset(s, 0, 2, &u), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_offset(s, 0, 0, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK(u == 7);
    double f64 = 7.0;
    float f32 = 7.0f;
    CHECK_STATUS(udm1_seq_sample_u64(NULL, 0, 0, 0, &u), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_seq_sample_u64(s, 0, 0, 0, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_seq_sample_f64(s, 0, 0, 2, &f64), UDM1_ERROR_DIMENSION);
    CHECK(mentions("dimension 2"));
    CHECK_STATUS(udm1_seq_sample_f32(s, 0, 64, 0, &f32), UDM1_ERROR_INDEX_RANGE);
    CHECK(mentions("index 64"));
    CHECK_STATUS(udm1_seq_sample_f32(s, 0, UINT64_MAX, 0, &f32), UDM1_ERROR_INDEX_RANGE);
    CHECK(u == 7 && f64 == 7.0 && f32 == 7.0f);
    CHECK_STATUS(udm1_seq_sample_f32(s, 0, 63, 1, &f32), UDM1_OK);

    /* fills */
    float buf[16];
    for (int i = 0; i < 16; ++i) buf[i] = -1.0f;
    CHECK_STATUS(udm1_seq_fill_f32(NULL, 0, 0, 4, 0, 2, buf, 2), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 0, 4, 0, 2, NULL, 2), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 0, 0, 0, 2, NULL, 2), UDM1_OK); /* count 0: nothing to write */
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 0, 4, 0, 0, buf, 2), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 0, 4, 1, 2, buf, 2), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 0, 4, 2, 1, buf, 2), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 0, 4, UINT32_MAX, 2, buf, 2), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 0, 4, 0, UINT32_MAX, buf, 2), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 0, 4, 0, 2, buf, 1), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(mentions("stride"));
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 60, 5, 0, 2, buf, 2), UDM1_ERROR_INDEX_RANGE);
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 64, 1, 0, 2, buf, 2), UDM1_ERROR_INDEX_RANGE);
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 0, 4, 0, 2, buf, SIZE_MAX / 2), UDM1_ERROR_INVALID_ARGUMENT);
    for (int i = 0; i < 16; ++i) CHECK(buf[i] == -1.0f);
    CHECK_STATUS(udm1_seq_fill_f32(s, 0, 60, 4, 0, 2, buf, 2), UDM1_OK);
    udm1_seq_destroy(s);

    CHECK_STATUS(udm1_seq_create("wr", 3, 0, 9, &s), UDM1_OK);
    double dbuf[8];
    CHECK_STATUS(udm1_seq_fill_f64(s, 0, UINT64_MAX, 2, 0, 1, dbuf, 1), UDM1_ERROR_INDEX_RANGE);
    CHECK(mentions("2^64"));
    CHECK_STATUS(udm1_seq_fill_f64(s, 0, UINT64_MAX, 1, 0, 3, dbuf, 3), UDM1_OK);
    CHECK_STATUS(udm1_seq_fill_f64(s, 0, UINT64_MAX - 1, 2, 0, 3, dbuf, 4), UDM1_OK);
    CHECK_STATUS(udm1_seq_fill_u64(s, 0, 0, SIZE_MAX, 0, 3, (uint64_t *)dbuf, 3), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_seq_fill_u64(s, 0, 2, SIZE_MAX, 0, 3, (uint64_t *)dbuf, 3), UDM1_ERROR_INDEX_RANGE);

    /* cursor */
    udm1_cursor c;
    memset(&c, 0, sizeof c);
    CHECK_STATUS(udm1_cursor_start(NULL, s, 0, 0, 0), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_cursor_start(&c, NULL, 0, 0, 0), UDM1_ERROR_NULL_ARGUMENT);
    CHECK(c.seq == NULL);
    CHECK(udm1_cursor_padded(NULL) == 0);
    udm1_seq_destroy(s);
    CHECK_STATUS(udm1_seq_create("epis", 1, 8, 9, &s), UDM1_OK);
    CHECK_STATUS(udm1_cursor_start(&c, s, 0, 8, 0), UDM1_ERROR_INDEX_RANGE);
    CHECK(c.seq == NULL);
    CHECK_STATUS(udm1_cursor_start(&c, s, 0, 7, 0), UDM1_OK);
    udm1_seq_destroy(s);
    udm1_seq_destroy(NULL);
}

static void test_metric_errors(void)
{
    double pts[4] = {0.1, 0.2, 0.3, 0.4}, out = 7.0;
    CHECK_STATUS(udm1_discrepancy(NULL, 2, 2, 2, UDM1_DISCREPANCY_CENTERED, &out), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_discrepancy(pts, 2, 2, 2, UDM1_DISCREPANCY_CENTERED, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_discrepancy(pts, 0, 2, 2, UDM1_DISCREPANCY_CENTERED, &out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_discrepancy(pts, 2, 0, 2, UDM1_DISCREPANCY_CENTERED, &out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_discrepancy(pts, 2, 2, 1, UDM1_DISCREPANCY_CENTERED, &out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_discrepancy(pts, 2, 2, 2, 0, &out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_discrepancy(pts, 2, 2, 2, 5, &out), UDM1_ERROR_INVALID_ARGUMENT);
    pts[3] = NAN;
    CHECK_STATUS(udm1_discrepancy(pts, 2, 2, 2, UDM1_DISCREPANCY_CENTERED, &out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(mentions("point 1 coordinate 1"));
    pts[3] = 1.5;
    CHECK_STATUS(udm1_discrepancy(pts, 2, 2, 2, UDM1_DISCREPANCY_CENTERED, &out), UDM1_ERROR_INVALID_ARGUMENT);
    pts[3] = -0.0;
    CHECK_STATUS(udm1_discrepancy(pts, 2, 2, 2, UDM1_DISCREPANCY_CENTERED, &out), UDM1_OK);
    CHECK_STATUS(udm1_discrepancy_random(0, 2, UDM1_DISCREPANCY_CENTERED, &out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_discrepancy_random(2, 2, 9, &out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_discrepancy_random(2, 2, UDM1_DISCREPANCY_CENTERED, NULL), UDM1_ERROR_NULL_ARGUMENT);

    udm1_alpha_report rep;
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("wr", 64, 0, 0, &s), UDM1_OK);
    CHECK_STATUS(udm1_seq_check(NULL, 256, &rep), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_seq_check(s, 256, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_seq_check(s, 1, &rep), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_seq_check(s, 65537, &rep), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_seq_check(s, 65536, &rep), UDM1_ERROR_INVALID_ARGUMENT); /* over the work limit */
    CHECK(mentions("work limit"));
    udm1_seq_destroy(s);
    udm1_alpha a = {UDM1_ALPHA_SQRT, 0, 2, 0, 0, 0.0};
    CHECK_STATUS(udm1_alpha_check(NULL, 1, 256, &rep), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_alpha_check(&a, 0, 256, &rep), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_alpha_check(&a, UDM1_MAX_DIMENSIONS + 1, 256, &rep), UDM1_ERROR_INVALID_ARGUMENT);
    a.kind = 9;
    CHECK_STATUS(udm1_alpha_check(&a, 1, 256, &rep), UDM1_ERROR_INVALID_ARGUMENT);
}

int main(void)
{
    test_versions_and_strings();
    test_presets();
    test_create_errors();
    test_alpha_errors();
    test_query_and_sample_errors();
    test_metric_errors();
    CHECK_DONE();
}
