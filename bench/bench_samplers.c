/* bench_samplers.c - every sampler measured the same way, in one run.
 *
 *   udm1_bench_samplers throughput [--seconds S]
 *       values per second of every preset, one thread: bulk fill and
 *       per-sample random access (float), at d = 2 and d = 32 where the preset
 *       allows; each with its ratio to the "wr" Weyl sequence and to memset,
 *       measured in the same run. Point sets use K = 4096.
 *   udm1_bench_samplers error [--reps R] [--ns N1,N2,...] [--samplers a,b,...] [--time-repeats K] [--quick]
 *       CSV: sampler,integrand,d,n,reps,rmse,relative_rmse,seconds_per_estimate,create_seconds
 *       for the 2D integrands (d = 2) and the Genz families (d = 8): the RMSE
 *       over R randomizations (streams) and the time of one estimate (filling
 *       n points and evaluating the integrand, the sampler's creation apart);
 *       with K > 1 the R estimates are timed K times and the fastest counts
 *       (a short measurement that another process interrupted is not the one kept).
 *
 * Progress goes to stderr; results to stdout.
 */
#define _POSIX_C_SOURCE 199309L
#include <udm1/udm1.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void die(const char *msg)
{
    fprintf(stderr, "udm1_bench_samplers: %s\n", msg);
    exit(2);
}

static udm1_seq *create(const char *name, uint32_t dims, uint64_t k, double *seconds)
{
    udm1_preset_info info;
    if (udm1_preset_find(name, &info) != UDM1_OK) {
        char msg[128];
        snprintf(msg, sizeof msg, "unknown sampler '%.64s'", name);
        die(msg);
    }
    udm1_seq *s = NULL;
    double t0 = now();
    udm1_status st = udm1_seq_create(name, dims, (info.flags & UDM1_PRESET_POINT_SET) ? k : 0, 1, &s);
    if (seconds) *seconds = now() - t0;
    return st == UDM1_OK ? s : NULL;
}

static volatile float sink;

static double rate_bulk(udm1_seq *s, uint32_t dims, float *buf, size_t points, double seconds)
{
    double best = 0.0;
    for (int trial = 0; trial < 3; ++trial) {
        double t0 = now(), t;
        size_t values = 0;
        uint64_t stream = 0;
        do {
            udm1_seq_fill_f32(s, stream++, 0, points, 0, dims, buf, dims);
            sink += buf[stream % points];
            values += points * dims;
            t = now();
        } while (t - t0 < seconds / 3);
        if (values / (t - t0) > best) best = values / (t - t0);
    }
    return best;
}

static double rate_sample(udm1_seq *s, uint32_t dims, size_t points, double seconds)
{
    double best = 0.0;
    for (int trial = 0; trial < 3; ++trial) {
        double t0 = now(), t;
        size_t values = 0;
        uint64_t stream = 0;
        do {
            float acc = 0.0f, v;
            for (size_t i = 0; i < points; i += 7)
                for (uint32_t j = 0; j < dims; ++j) {
                    udm1_seq_sample_f32(s, stream, i, j, &v);
                    acc += v;
                    ++values;
                }
            ++stream;
            sink += acc;
            t = now();
        } while (t - t0 < seconds / 3);
        if (values / (t - t0) > best) best = values / (t - t0);
    }
    return best;
}

static int throughput(double seconds)
{
    enum { POINTS = 4096 };
    float *buf = malloc(sizeof(float) * POINTS * 32);
    static const uint32_t dims_list[2] = {2, 32};
    printf("%-12s %4s %14s %8s %8s %14s %8s\n", "sampler", "d", "bulk values/s", "x wr", "x memset", "per-sample/s",
           "x wr");
    for (int di = 0; di < 2; ++di) {
        uint32_t d = dims_list[di];
        /* anchors of this d, in this run */
        double t0 = now(), ms;
        size_t bytes = 0;
        do {
            memset(buf, (int)(bytes & 0x3f), sizeof(float) * POINTS * d);
            sink += buf[bytes % POINTS];
            bytes += sizeof(float) * POINTS * d;
        } while (now() - t0 < seconds / 3);
        ms = bytes / sizeof(float) / (now() - t0);
        udm1_seq *wr = create("wr", d, 0, NULL);
        double wr_bulk = rate_bulk(wr, d, buf, POINTS, seconds), wr_one = rate_sample(wr, d, POINTS, seconds);
        udm1_seq_destroy(wr);
        for (size_t p = 0; p < udm1_preset_count(); ++p) {
            udm1_preset_info info;
            udm1_preset_get(p, &info);
            if (info.max_dimensions < d) continue;
            udm1_seq *s = create(info.name, d, POINTS, NULL);
            if (!s) continue;
            double bulk = rate_bulk(s, d, buf, POINTS, seconds), one = rate_sample(s, d, POINTS, seconds);
            printf("%-12s %4u %14.4g %8.2f %8.3f %14.4g %8.2f\n", info.name, d, bulk, bulk / wr_bulk, bulk / ms, one,
                   one / wr_one);
            fflush(stdout);
            udm1_seq_destroy(s);
        }
        printf("%-12s %4u %14.4g %8.2f %8.3f\n", "(memset)", d, ms, ms / wr_bulk, 1.0);
    }
    free(buf);
    return 0;
}

static int parse_list(const char *text, char items[][32], int max)
{
    int n = 0;
    const char *p = text;
    while (*p && n < max) {
        const char *c = strchr(p, ',');
        size_t len = c ? (size_t)(c - p) : strlen(p);
        if (len == 0 || len >= 32) die("bad list item");
        memcpy(items[n], p, len);
        items[n][len] = 0;
        ++n;
        p = c ? c + 1 : p + len;
    }
    return n;
}

static int error_table(uint32_t reps, const char *ns_text, const char *samplers_text, int quick, uint32_t repeats)
{
    char ns_items[32][32], names[64][32];
    int nn = parse_list(ns_text ? ns_text : (quick ? "64,256,1000" : "64,256,1000,1024,4096,10000,16384"), ns_items, 32);
    uint64_t ns[32];
    for (int i = 0; i < nn; ++i) {
        char *end;
        ns[i] = strtoull(ns_items[i], &end, 10);
        if (*end || ns[i] == 0 || ns[i] > (1u << 22)) die("--ns takes whole numbers in 1..2^22");
    }
    int ns_count = 0;
    if (samplers_text) {
        ns_count = parse_list(samplers_text, names, 64);
    } else {
        for (size_t p = 0; p < udm1_preset_count() && ns_count < 64; ++p) {
            udm1_preset_info info;
            udm1_preset_get(p, &info);
            if (info.max_dimensions >= 2) snprintf(names[ns_count++], 32, "%s", info.name);
        }
    }
    printf("sampler,integrand,d,n,reps,rmse,relative_rmse,seconds_per_estimate,create_seconds\n");
    for (int si = 0; si < ns_count; ++si) {
        fprintf(stderr, "[bench] %s (%d/%d)\n", names[si], si + 1, ns_count);
        for (uint32_t k = 1; udm1_integrand_name(k); ++k) {
            uint32_t d = k <= UDM1_INTEGRAND_STEP ? 2 : 8;
            udm1_preset_info info;
            if (udm1_preset_find(names[si], &info) != UDM1_OK) die("unknown sampler in --samplers");
            if (info.max_dimensions < d) continue;
            double exact;
            udm1_integrand_exact(k, d, &exact);
            for (int i = 0; i < nn; ++i) {
                double create_s;
                udm1_seq *s = create(names[si], d, ns[i], &create_s);
                if (!s) continue; /* e.g. a point count the sampler does not take */
                double rmse = 0.0, t = INFINITY;
                udm1_status st = UDM1_OK;
                for (uint32_t r = 0; r < repeats && st == UDM1_OK; ++r) { /* the same estimates each time */
                    double t0 = now();
                    st = udm1_integration_error(s, k, d, ns[i], reps, &rmse, NULL);
                    t = fmin(t, (now() - t0) / reps);
                }
                udm1_seq_destroy(s);
                if (st != UDM1_OK) continue;
                printf("%s,%s,%u,%llu,%u,%.6g,%.6g,%.6g,%.6g\n", names[si], udm1_integrand_name(k), d,
                       (unsigned long long)ns[i], reps, rmse, rmse / fabs(exact), t, create_s);
            }
            fflush(stdout);
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) die("usage: udm1_bench_samplers throughput|error [options]");
    double seconds = 0.6;
    uint32_t reps = 32, repeats = 1;
    const char *ns = NULL, *samplers = NULL;
    int quick = 0;
    for (int i = 2; i < argc; ++i) {
        char *end;
        if (strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) {
            seconds = strtod(argv[++i], &end);
            if (*end || !(seconds > 0 && seconds <= 3600)) die("--seconds takes a number in (0, 3600]");
        } else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) {
            unsigned long v = strtoul(argv[++i], &end, 10);
            if (*end || v == 0 || v > 100000) die("--reps takes a whole number in 1..100000");
            reps = (uint32_t)v;
        } else if (strcmp(argv[i], "--time-repeats") == 0 && i + 1 < argc) {
            unsigned long v = strtoul(argv[++i], &end, 10);
            if (*end || v == 0 || v > 100) die("--time-repeats takes a whole number in 1..100");
            repeats = (uint32_t)v;
        } else if (strcmp(argv[i], "--ns") == 0 && i + 1 < argc) {
            ns = argv[++i];
        } else if (strcmp(argv[i], "--samplers") == 0 && i + 1 < argc) {
            samplers = argv[++i];
        } else if (strcmp(argv[i], "--quick") == 0) {
            quick = 1;
        } else {
            fprintf(stderr, "udm1_bench_samplers: unknown argument '%s'\n", argv[i]);
            return 2;
        }
    }
    if (strcmp(argv[1], "throughput") == 0) return throughput(seconds);
    if (strcmp(argv[1], "error") == 0) return error_table(reps, ns, samplers, quick, repeats);
    fprintf(stderr, "udm1_bench_samplers: unknown mode '%s' (throughput or error)\n", argv[1]);
    return 2;
}
