/* test_threads.c - one const handle used by many threads at once gives the
 * same values as one thread: fills, samples and cursors on a shared sequence. */
#define _POSIX_C_SOURCE 200809L
#include "check.h"

#include <udm1/udm1.h>

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

enum { THREADS = 8, D = 12, N = 20000 };

typedef struct work {
    const udm1_seq *seq;
    int id;
    double *out; /* N x D */
    uint64_t stream;
} work;

static void *run(void *arg)
{
    work *w = arg;
    /* each thread computes the whole table, in its own order of pieces */
    size_t piece = 997 + 13 * (size_t)w->id;
    for (size_t first = 0; first < N; first += piece) {
        size_t count = N - first < piece ? N - first : piece;
        if (udm1_seq_fill_f64(w->seq, w->stream, first, count, 0, D, w->out + first * D, D) != UDM1_OK) return w;
    }
    /* and re-checks a few values through the cursor */
    for (size_t i = (size_t)w->id; i < N; i += 101) {
        udm1_cursor c;
        udm1_cursor_start(&c, w->seq, w->stream, i, 0);
        for (int j = 0; j < D; ++j)
            if (udm1_cursor_1d_f64(&c) != w->out[i * D + j]) return w;
    }
    return NULL;
}

int main(void)
{
    udm1_seq *s = NULL;
    CHECK_STATUS(udm1_seq_create("hwmmr", D, 0, 77, &s), UDM1_OK);
    double *ref = malloc(sizeof(double) * N * D);
    CHECK_STATUS(udm1_seq_fill_f64(s, 9, 0, N, 0, D, ref, D), UDM1_OK);
    pthread_t th[THREADS];
    work w[THREADS];
    for (int t = 0; t < THREADS; ++t) {
        w[t].seq = s;
        w[t].id = t;
        w[t].stream = 9;
        w[t].out = malloc(sizeof(double) * N * D);
        CHECK(pthread_create(&th[t], NULL, run, &w[t]) == 0);
    }
    for (int t = 0; t < THREADS; ++t) {
        void *ret = &w[t];
        pthread_join(th[t], &ret);
        CHECKF(ret == NULL, "thread %d failed", t);
        CHECKF(memcmp(ref, w[t].out, sizeof(double) * N * D) == 0, "thread %d differs", t);
        free(w[t].out);
    }
    free(ref);
    udm1_seq_destroy(s);
    CHECK_DONE();
}
