/* test_edges.c - the edges of the C API where a result could be silently wrong or a call could not
 * be stopped, one section per class of defect:
 *  - index arithmetic: dimension indices stop below 2^32 - 1 everywhere (fills, many points, the
 *    cursor), never wrap to dimension 0; counts of zero are checked like any other count;
 *  - a status of OK with a value that is not a number: discrepancies whose terms overflow a double
 *    give the true value (against an independent long-double reference) or +inf, never NaN; NaN
 *    inputs to status-returning functions are refused;
 *  - work without a bound: the metrics whose cost grows with their parameters (not their input) refuse
 *    more than their documented limit, at once (an alarm fails the test if a call runs on);
 *  - status-less functions and NULL: one rule for all (a neutral value, never a crash).
 */
#include <udm1/udm1.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(_WIN32)
#include <windows.h>
#else
#include <signal.h>
#include <unistd.h>
#endif

#include "check.h"

static const char too_slow_msg[] = "test_edges: a call with a huge work parameter ran for 20 s instead of being refused\n";

/* The alarm: the process ends with status 2 unless alarm_stop() comes within `seconds` (POSIX: alarm(),
 * Windows: a thread waiting on an event). */
#if defined(_WIN32)
static HANDLE alarm_event;

static DWORD WINAPI alarm_thread(LPVOID seconds)
{
    if (WaitForSingleObject(alarm_event, (DWORD)(uintptr_t)seconds * 1000u) == WAIT_TIMEOUT) {
        fputs(too_slow_msg, stderr);
        fflush(stderr);
        ExitProcess(2);
    }
    return 0;
}

static void alarm_start(unsigned seconds)
{
    alarm_event = CreateEventA(NULL, TRUE, FALSE, NULL);
    HANDLE t = alarm_event ? CreateThread(NULL, 0, alarm_thread, (LPVOID)(uintptr_t)seconds, 0, NULL) : NULL;
    CHECK(t != NULL);
    if (t) CloseHandle(t);
}

static void alarm_stop(void)
{
    if (alarm_event) SetEvent(alarm_event);
}
#else
static void too_slow(int sig)
{
    (void)sig;
    if (write(2, too_slow_msg, sizeof too_slow_msg - 1) < 0) _exit(3);
    _exit(2);
}

static void alarm_start(unsigned seconds)
{
    signal(SIGALRM, too_slow);
    alarm(seconds);
}

static void alarm_stop(void) { alarm(0); }
#endif

/* ---- index arithmetic ------------------------------------------------------------------------ */

static void dimension_indices(void)
{
    udm1_seq *seq = NULL;
    CHECK_STATUS(udm1_seq_create("wr", 4, 0, 7, &seq), UDM1_OK);
    const uint64_t stream = 3, index = 11;
    const uint32_t last = UDM1_DIMENSION_INDEX_LIMIT - 1; /* the largest dimension index */
    double v[4], w[4];

    /* many points: the dimension range must end at the limit */
    CHECK_STATUS(udm1_seq_fill_points_f64(seq, 1, &stream, &index, last, 1, v), UDM1_OK);
    CHECK(v[0] >= 0 && v[0] < 1);
    v[0] = 7;
    CHECK_STATUS(udm1_seq_fill_points_f64(seq, 1, &stream, &index, last, 2, v), UDM1_ERROR_DIMENSION);
    CHECK(v[0] == 7); /* nothing written */
    CHECK(strstr(udm1_last_error(), "first_dimension") != NULL);
    CHECK_STATUS(udm1_seq_fill_points_f64(seq, 1, &stream, &index, 0xFFFFFFFFu, 2, v), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_fill_points_f64(seq, 1, &stream, &index, 0xFFFFFFF0u, 0x20, v), UDM1_ERROR_DIMENSION);
    /* counts of zero: the same checks, nothing written */
    CHECK_STATUS(udm1_seq_fill_points_f64(seq, 0, NULL, NULL, 0, 2, NULL), UDM1_OK);
    CHECK_STATUS(udm1_seq_fill_points_f64(seq, 0, NULL, NULL, 0xFFFFFFFFu, 2, NULL), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_fill_points_f64(seq, 1, &stream, &index, 0, 0, v), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_fill_points_f64(seq, 0, NULL, NULL, 0, 0, NULL), UDM1_ERROR_DIMENSION);
    /* the row fills: ndims 0 and a range past D refused, also with count 0 */
    CHECK_STATUS(udm1_seq_fill_f64(seq, 0, 0, 0, 0, 0, NULL, 1), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_fill_f64(seq, 0, 0, 0, 3, 2, NULL, 2), UDM1_ERROR_DIMENSION);
    CHECK_STATUS(udm1_seq_fill_f64(seq, 0, 0, 0, 0xFFFFFFFFu, 2, NULL, 2), UDM1_ERROR_DIMENSION);

    /* the cursor: started at the last dimension it may hand out, one draw, then it is exhausted */
    udm1_cursor c;
    CHECK_STATUS(udm1_cursor_start(&c, seq, stream, index, last), UDM1_OK);
    w[0] = udm1_cursor_1d_f64(&c);
    CHECK_STATUS(udm1_seq_fill_points_f64(seq, 1, &stream, &index, last, 1, v), UDM1_OK);
    CHECK(w[0] == v[0]);
    double zero;
    CHECK_STATUS(udm1_seq_fill_points_f64(seq, 1, &stream, &index, 0, 1, &zero), UDM1_OK);
    double past = udm1_cursor_1d_f64(&c); /* was dimension 0's value: the counter wrapped */
    CHECKF(isnan(past), "a draw past the last dimension gave %.17g (dimension 0: %.17g)", past, zero);
    CHECK(strstr(udm1_last_error(), "udm1_cursor") != NULL);
    CHECK(isnan(udm1_cursor_1d(&c)));
    float f2[2];
    udm1_cursor_2d(&c, f2);
    CHECK(isnan(f2[0]) && isnan(f2[1]));
    /* a fill across the limit: the values up to it, NaN past it */
    CHECK_STATUS(udm1_cursor_start(&c, seq, stream, index, last - 1), UDM1_OK);
    udm1_cursor_fill_f64(&c, 4, w);
    CHECK_STATUS(udm1_seq_fill_points_f64(seq, 1, &stream, &index, last - 1, 2, v), UDM1_OK);
    CHECK(w[0] == v[0] && w[1] == v[1] && isnan(w[2]) && isnan(w[3]));
    CHECK(udm1_cursor_padded(&c) == 2);
    /* a cursor cannot start past the last dimension */
    CHECK_STATUS(udm1_cursor_start(&c, seq, stream, index, 0xFFFFFFFFu), UDM1_ERROR_DIMENSION);
    udm1_seq_destroy(seq);
}

/* ---- OK with a number: overflowing discrepancies, NaN inputs ----------------------------------- */

/* scipy's definitions in long double (exponent range to about 1e4932): the reference for d where a
 * double's terms overflow but the true value does not */
static long double discrepancy_ld(const double *x, size_t n, uint32_t d, uint32_t kind)
{
    long double a = 1, s1 = 0, s2 = 0;
    switch (kind) {
    case UDM1_DISCREPANCY_WRAP_AROUND: a = powl(4.0L / 3.0L, d); break;
    case UDM1_DISCREPANCY_CENTERED: a = powl(13.0L / 12.0L, d); break;
    case UDM1_DISCREPANCY_MIXTURE: a = powl(19.0L / 12.0L, d); break;
    default: a = powl(3.0L, -(long double)d); break;
    }
    for (size_t i = 0; i < n; ++i) {
        long double p = 1;
        for (uint32_t k = 0; k < d; ++k) {
            long double xi = x[i * d + k], t = fabsl(xi - 0.5L);
            if (kind == UDM1_DISCREPANCY_CENTERED) p *= 1 + t / 2 - t * t / 2;
            else if (kind == UDM1_DISCREPANCY_MIXTURE) p *= 5.0L / 3 - t / 4 - t * t / 4;
            else if (kind == UDM1_DISCREPANCY_L2_STAR) p *= (1 - xi * xi) / 2;
        }
        s1 += p;
        for (size_t j = 0; j < n; ++j) {
            long double q = 1;
            for (uint32_t k = 0; k < d; ++k) {
                long double xi = x[i * d + k], xj = x[j * d + k], ti = fabsl(xi - 0.5L), tj = fabsl(xj - 0.5L);
                long double u = fabsl(xi - xj);
                if (kind == UDM1_DISCREPANCY_WRAP_AROUND) q *= 1.5L - u * (1 - u);
                else if (kind == UDM1_DISCREPANCY_CENTERED) q *= 1 + ti / 2 + tj / 2 - u / 2;
                else if (kind == UDM1_DISCREPANCY_MIXTURE)
                    q *= 15.0L / 8 - ti / 4 - tj / 4 - 3 * u / 4 + u * u / 2;
                else q *= 1 - (xi > xj ? xi : xj);
            }
            s2 += q;
        }
    }
    long double v = kind == UDM1_DISCREPANCY_WRAP_AROUND ? -a + s2 / ((long double)n * n)
                                                         : a - 2 * s1 / n + s2 / ((long double)n * n);
    return kind == UDM1_DISCREPANCY_L2_STAR ? sqrtl(v > 0 ? v : 0) : v;
}

static void discrepancies_never_nan(void)
{
    enum { N = 6 };
    static const uint32_t dims[] = {513, 1500, 1760, 3000, 20000};
    static const uint32_t kinds[] = {UDM1_DISCREPANCY_L2_STAR, UDM1_DISCREPANCY_CENTERED, UDM1_DISCREPANCY_WRAP_AROUND,
                                     UDM1_DISCREPANCY_MIXTURE};
    double *x = malloc(sizeof(double) * N * 20000);
    uint64_t s = 0x9E3779B97F4A7C15ull;
    for (size_t i = 0; i < (size_t)N * 20000; ++i) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        x[i] = (double)(s >> 11) * 0x1p-53;
    }
    for (size_t a = 0; a < sizeof dims / sizeof dims[0]; ++a)
        for (size_t b = 0; b < 4; ++b) {
            uint32_t d = dims[a], kind = kinds[b];
            double got = -1;
            CHECK_STATUS(udm1_discrepancy(x, N, d, d, kind, &got), UDM1_OK);
            long double ref = discrepancy_ld(x, N, d, kind);
            double want = (double)ref; /* +inf where the true value exceeds a double */
            int ok = isinf(want) ? isinf(got) && got > 0
                                 : fabs(got - want) <= 1e-9 * fabs(want) + 1e-300;
            CHECKF(ok, "discrepancy kind %u, d = %u: %.17g, true value %.17Lg", kind, d, got, ref);
            /* the random-points expectation: finite or +inf, never NaN */
            double r = -1;
            CHECK_STATUS(udm1_discrepancy_random(N, d, kind, &r), UDM1_OK);
            CHECKF(!isnan(r) && r >= 0, "discrepancy_random kind %u, d = %u: %.17g", kind, d, r);
        }
    free(x);
}

static void nan_inputs_refused(void)
{
    static const udm1_color_entry map[] = {{0.0, {0, 0, 0}}, {1.0, {1, 1, 1}}};
    float rgb[3] = {7, 7, 7};
    CHECK_STATUS(udm1_color_map_eval(map, 2, NAN, rgb), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(rgb[0] == 7);
    CHECK(strstr(udm1_last_error(), "value") != NULL);
    CHECK_STATUS(udm1_color_map_eval(map, 2, INFINITY, rgb), UDM1_OK); /* +inf: past the last entry */
    CHECK(rgb[0] == 1);

    double pts[4] = {0.25, 0.5, NAN, 0.5}, out[2] = {7, 7};
    CHECK_STATUS(udm1_integrand_eval(UDM1_INTEGRAND_GAUSSIAN, 2, pts, 2, 2, out), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "point 1") != NULL);

    /* a pattern whose sum overflows: +inf or a refusal, never NaN with OK */
    udm1_noise *noise = NULL;
    CHECK_STATUS(udm1_noise_create(NULL, &noise), UDM1_ERROR_NULL_ARGUMENT);
    udm1_noise_desc nd;
    udm1_noise_desc_init(&nd);
    CHECK_STATUS(udm1_noise_create(&nd, &noise), UDM1_OK);
    udm1_pattern_params p;
    udm1_pattern_params_init(&p, UDM1_PATTERN_FBM);
    p.octaves = 10;
    p.omega = 1e300;
    double xyz[3 * 64], val[64];
    for (int i = 0; i < 3 * 64; ++i) xyz[i] = 0.37 * i;
    udm1_status st = udm1_pattern_points(noise, &p, xyz, 64, 3, val);
    if (st == UDM1_OK)
        for (int i = 0; i < 64; ++i) CHECKF(!isnan(val[i]), "fbm with omega 1e300 at point %d: NaN with UDM1_OK", i);
    else
        CHECK(st == UDM1_ERROR_INVALID_ARGUMENT);
    udm1_noise_destroy(noise);
}

/* ---- work without a bound ---------------------------------------------------------------------- */

static void work_limits(void)
{
    udm1_seq *seq = NULL;
    CHECK_STATUS(udm1_seq_create("wr", 2, 0, 1, &seq), UDM1_OK);
    double rmse = 0, spec[4];
    float img[4];
    alarm_start(20);
    CHECK_STATUS(udm1_integration_error(seq, UDM1_INTEGRAND_DISK, 2, 1ull << 62, 1, &rmse, NULL),
                 UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "limit") != NULL);
    CHECK_STATUS(udm1_integration_error(seq, UDM1_INTEGRAND_DISK, 2, 1ull << 20, 0xFFFFFFFFu, &rmse, NULL),
                 UDM1_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(udm1_spectrum_2d(seq, 0, 1ull << 62, 1, 2, spec), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "limit") != NULL);
    CHECK_STATUS(udm1_zoneplate(seq, 0, 2, 1, 0xFFFFFFFFu, img), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "limit") != NULL);
    alarm_stop();
    /* inside the limits: still computed */
    CHECK_STATUS(udm1_integration_error(seq, UDM1_INTEGRAND_DISK, 2, 1024, 4, &rmse, NULL), UDM1_OK);
    CHECK(rmse > 0 && rmse < 0.05);
    udm1_seq_destroy(seq);
}

/* ---- status-less functions and NULL ------------------------------------------------------------ */

static void null_handles(void)
{
    /* the rule (core.h): a neutral value - 0, NULL or NaN - and a message, never a crash */
    CHECK(isnan(udm1_noise_1d(NULL, 0.5)));
    CHECK(isnan(udm1_noise_2d(NULL, 0.5, 0.5)));
    CHECK(isnan(udm1_noise_3d(NULL, 0.5, 0.5, 0.5)));
    CHECK(strstr(udm1_last_error(), "udm1_noise_3d") != NULL);
    udm1_pattern_params p;
    udm1_pattern_params_init(&p, UDM1_PATTERN_MARBLE);
    CHECK(isnan(udm1_pattern_eval(NULL, &p, 0.1, 0.2, 0.3)));
    udm1_noise_desc nd;
    udm1_noise_desc_init(&nd);
    udm1_noise *noise = NULL;
    CHECK_STATUS(udm1_noise_create(&nd, &noise), UDM1_OK);
    CHECK(isnan(udm1_pattern_eval(noise, NULL, 0.1, 0.2, 0.3)));
    udm1_noise_destroy(noise);
    CHECK(udm1_pattern_from_name(NULL) == 0);
    CHECK(udm1_pattern_name(0) == NULL);
    CHECK(udm1_integrand_name(0) == NULL);
    CHECK(udm1_seq_dimensions(NULL) == 0 && udm1_seq_name(NULL) == NULL && udm1_seq_flags(NULL) == 0);
    CHECK(isnan(udm1_cursor_1d(NULL)));
    CHECK(isnan(udm1_cursor_1d_f64(NULL)));
    udm1_cursor_2d(NULL, NULL);
    udm1_cursor_2d_f64(NULL, NULL);
    udm1_cursor_fill(NULL, 4, NULL);
    udm1_cursor_fill_f64(NULL, 4, NULL);
    float f2[2] = {7, 7};
    udm1_cursor_2d(NULL, f2);
    CHECK(isnan(f2[0]) && isnan(f2[1]));
    double d4[4] = {7, 7, 7, 7};
    udm1_cursor_fill_f64(NULL, 4, d4);
    CHECK(isnan(d4[0]) && isnan(d4[3]));
    CHECK(udm1_cursor_padded(NULL) == 0);
    /* a cursor that was never started (zeroed) */
    udm1_cursor c;
    memset(&c, 0, sizeof c);
    CHECK(isnan(udm1_cursor_1d(&c)));
    udm1_seq *seq = NULL;
    CHECK_STATUS(udm1_seq_create("wr", 2, 0, 1, &seq), UDM1_OK);
    CHECK_STATUS(udm1_cursor_start(&c, seq, 0, 0, 0), UDM1_OK);
    udm1_cursor_2d(&c, NULL); /* no output array: nothing written, no crash */
    udm1_cursor_fill(&c, 2, NULL);
    udm1_seq_destroy(seq);
    udm1_noise_destroy(NULL);
    udm1_seq_destroy(NULL);
    udm1_seq_desc_init(NULL);
    udm1_noise_desc_init(NULL);
    udm1_pattern_params_init(NULL, UDM1_PATTERN_MARBLE);
}

int main(int argc, char **argv)
{
    /* test_edges [SECTION]: one section (by its function's name), or all */
    static const struct { const char *name; void (*run)(void); } sections[] = {
        {"dimension_indices", dimension_indices}, {"discrepancies_never_nan", discrepancies_never_nan},
        {"nan_inputs_refused", nan_inputs_refused}, {"work_limits", work_limits}, {"null_handles", null_handles}};
    for (size_t i = 0; i < sizeof sections / sizeof sections[0]; ++i)
        if (argc < 2 || strcmp(argv[1], sections[i].name) == 0) sections[i].run();
    CHECK_DONE();
}
