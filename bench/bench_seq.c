/* bench_seq.c - throughput of libudm1's sequences: values per second on one
 * thread, bulk fill and per-sample calls, f32 and f64, at d = 2 and d = 32.
 *
 * Anchors measured in the same run, so every figure is also a ratio:
 *  - "memset": writing the same buffer with memset (the store-bandwidth ceiling);
 *  - "fmod-double": the naive x = fmod(n * alpha, 1) loop in double precision
 *    (inexact past n ~ 2^20, shown for speed only).
 *
 * Usage: udm1_bench_seq [--seconds S] [--csv]
 * Each figure is the best of 5 repetitions of at least S/5 seconds (default S = 1).
 */
#define _POSIX_C_SOURCE 199309L
#include <udm1/udm1.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define POINTS 8192 /* per fill call: the buffer stays in L1/L2 */

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static volatile double sink;

typedef struct job {
    const udm1_seq *seq;
    uint32_t dims;
    int f32;
    void *buf;
} job;

typedef double (*run_fn)(const job *, uint64_t rep); /* returns number of values produced */

static double run_fill(const job *j, uint64_t rep)
{
    uint64_t first = rep * POINTS;
    udm1_status st = j->f32 ? udm1_seq_fill_f32(j->seq, 7, first, POINTS, 0, j->dims, j->buf, j->dims)
                            : udm1_seq_fill_f64(j->seq, 7, first, POINTS, 0, j->dims, j->buf, j->dims);
    if (st != UDM1_OK) {
        fprintf(stderr, "bench_seq: %s\n", udm1_last_error());
        exit(1);
    }
    sink += j->f32 ? ((float *)j->buf)[rep % POINTS] : ((double *)j->buf)[rep % POINTS];
    return (double)POINTS * j->dims;
}

static double run_sample(const job *j, uint64_t rep)
{
    uint64_t first = rep * POINTS;
    if (j->f32) {
        float *out = j->buf;
        for (uint64_t i = 0; i < POINTS; ++i)
            for (uint32_t d = 0; d < j->dims; ++d) udm1_seq_sample_f32(j->seq, 7, first + i, d, &out[i * j->dims + d]);
    } else {
        double *out = j->buf;
        for (uint64_t i = 0; i < POINTS; ++i)
            for (uint32_t d = 0; d < j->dims; ++d) udm1_seq_sample_f64(j->seq, 7, first + i, d, &out[i * j->dims + d]);
    }
    sink += j->f32 ? ((float *)j->buf)[rep % POINTS] : ((double *)j->buf)[rep % POINTS];
    return (double)POINTS * j->dims;
}

static double run_cursor(const job *j, uint64_t rep)
{
    uint64_t first = rep * POINTS;
    float *out = j->buf;
    for (uint64_t i = 0; i < POINTS; ++i) {
        udm1_cursor c;
        udm1_cursor_start(&c, j->seq, 7, first + i, 0);
        for (uint32_t d = 0; d < j->dims; ++d) out[i * j->dims + d] = udm1_cursor_1d(&c);
    }
    sink += out[rep % POINTS];
    return (double)POINTS * j->dims;
}

static double run_memset(const job *j, uint64_t rep)
{
    size_t bytes = (size_t)POINTS * j->dims * (j->f32 ? 4 : 8);
    memset(j->buf, (int)(rep & 0x3f), bytes);
    sink += ((unsigned char *)j->buf)[rep % bytes];
    return (double)POINTS * j->dims;
}

static double run_fmod(const job *j, uint64_t rep)
{
    static const double alpha[2] = {1.4142135623730951, 1.7320508075688772};
    uint64_t first = rep * POINTS;
    if (j->f32) {
        float *out = j->buf;
        for (uint64_t i = 0; i < POINTS; ++i)
            for (uint32_t d = 0; d < j->dims; ++d)
                out[i * j->dims + d] = (float)fmod((double)(first + i) * alpha[d & 1] * (1.0 + d), 1.0);
    } else {
        double *out = j->buf;
        for (uint64_t i = 0; i < POINTS; ++i)
            for (uint32_t d = 0; d < j->dims; ++d)
                out[i * j->dims + d] = fmod((double)(first + i) * alpha[d & 1] * (1.0 + d), 1.0);
    }
    sink += j->f32 ? ((float *)j->buf)[rep % POINTS] : ((double *)j->buf)[rep % POINTS];
    return (double)POINTS * j->dims;
}

static double measure(run_fn fn, const job *j, double seconds)
{
    double best = 0.0;
    uint64_t rep = 0;
    for (int trial = 0; trial < 5; ++trial) {
        double values = 0.0, t0 = now(), t;
        do {
            values += fn(j, rep++);
            t = now();
        } while (t - t0 < seconds / 5.0);
        double rate = values / (t - t0);
        if (rate > best) best = rate;
    }
    return best;
}

int main(int argc, char **argv)
{
    double seconds = 1.0;
    int csv = 0;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) {
            char *end;
            seconds = strtod(argv[++i], &end);
            if (*end || !(seconds > 0.0) || seconds > 3600.0) {
                fprintf(stderr, "bench_seq: --seconds '%s' is not a number in (0, 3600]\n", argv[i]);
                return 2;
            }
        } else if (strcmp(argv[i], "--csv") == 0) {
            csv = 1;
        } else {
            fprintf(stderr, "bench_seq: unknown argument '%s' (usage: udm1_bench_seq [--seconds S] [--csv])\n",
                    argv[i]);
            return 2;
        }
    }
    static const uint32_t dims_list[] = {2, 32};
    static const char *presets[] = {"wr", "rd"};
    void *buf = malloc((size_t)POINTS * 32 * sizeof(double));
    if (!buf) return 1;
    if (csv)
        printf("preset,dims,type,method,values_per_second,ratio_to_memset\n");
    else
        printf("%-7s %4s %4s %-12s %16s %10s\n", "preset", "d", "type", "method", "values/s", "x memset");
    for (size_t p = 0; p < sizeof presets / sizeof *presets; ++p)
        for (size_t di = 0; di < 2; ++di)
            for (int f32 = 1; f32 >= 0; --f32) {
                uint32_t dims = dims_list[di];
                udm1_seq *seq;
                if (udm1_seq_create(presets[p], dims, 0, 1, &seq) != UDM1_OK) {
                    fprintf(stderr, "bench_seq: %s\n", udm1_last_error());
                    return 1;
                }
                job j = {seq, dims, f32, buf};
                struct { const char *name; run_fn fn; } methods[] = {
                    {"memset", run_memset}, {"fmod-double", run_fmod}, {"bulk", run_fill},
                    {"per-sample", run_sample}, {"cursor", run_cursor}};
                double anchor = 0.0;
                for (size_t m = 0; m < sizeof methods / sizeof *methods; ++m) {
                    if (methods[m].fn == run_cursor && !f32) continue; /* the cursor's float draw */
                    double rate = measure(methods[m].fn, &j, seconds);
                    if (m == 0) anchor = rate;
                    if (csv)
                        printf("%s,%u,%s,%s,%.4g,%.4f\n", presets[p], dims, f32 ? "f32" : "f64", methods[m].name, rate,
                               rate / anchor);
                    else
                        printf("%-7s %4u %4s %-12s %16.4g %10.3f\n", presets[p], dims, f32 ? "f32" : "f64",
                               methods[m].name, rate, rate / anchor);
                    fflush(stdout);
                }
                udm1_seq_destroy(seq);
            }
    free(buf);
    return 0;
}
