/* test_exact_sum.c - udm1_exact_sum_add: against integer arithmetic where the sum is known, the ends of
 * the double range, independence of order and split, and its bad inputs. */
#include "check.h"

#include <udm1/udm1.h>

#include <float.h>
#include <math.h>
#include <string.h>

#define W UDM1_EXACT_SUM_WORDS

static uint64_t rng = 7;
static uint64_t next(void)
{
    uint64_t z = (rng += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* words = k 2^shift, k a signed 64-bit integer, in W words of two's complement */
static void words_of(int64_t k, int shift, uint64_t *out)
{
    uint64_t fill = k < 0 ? ~0ull : 0, u = (uint64_t)k;
    int w = shift / 64, o = shift % 64;
    for (int i = 0; i < W; ++i) out[i] = i < w ? 0 : fill;
    out[w] = u << o;
    if (w + 1 < W) out[w + 1] = o ? (u >> (64 - o)) | (fill << o) : fill;
}

static int equal(const uint64_t *a, const uint64_t *b) { return memcmp(a, b, W * sizeof *a) == 0; }

static void test_known_sums(void)
{
    /* k 2^-20 for integers |k| < 2^40: their sum is (sum k) 2^-20, that is (sum k) << 1054 in the words */
    double x[1000];
    for (int trial = 0; trial < 20; ++trial) {
        int64_t total = 0;
        for (int i = 0; i < 1000; ++i) {
            int64_t k = (int64_t)(next() >> 24) - ((int64_t)1 << 39);
            total += k;
            x[i] = ldexp((double)k, -20);
        }
        uint64_t got[W] = {0}, want[W];
        CHECK_STATUS(udm1_exact_sum_add(x, 1000, got), UDM1_OK);
        words_of(total, 1074 - 20, want);
        CHECKF(equal(got, want), "trial %d", trial);
    }
    /* the smallest subnormal is 1, its negative -1 (all ones) */
    uint64_t got[W] = {0}, want[W];
    double tiny = 5e-324;
    CHECK_STATUS(udm1_exact_sum_add(&tiny, 1, got), UDM1_OK);
    words_of(1, 0, want);
    CHECK(equal(got, want));
    double two[2] = {-5e-324, -5e-324};
    memset(got, 0, sizeof got);
    CHECK_STATUS(udm1_exact_sum_add(two, 2, got), UDM1_OK);
    words_of(-2, 0, want);
    CHECK(equal(got, want));
    /* DBL_MAX = (2^53 - 1) 2^971: 4 of them are (2^53 - 1) 2^2047, at the top of the words' range */
    double big[4] = {DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX};
    memset(got, 0, sizeof got);
    CHECK_STATUS(udm1_exact_sum_add(big, 4, got), UDM1_OK);
    words_of(((int64_t)1 << 53) - 1, 971 + 1074 + 2, want);
    CHECK(equal(got, want));
    double back[4] = {-DBL_MAX, -DBL_MAX, -DBL_MAX, -DBL_MAX};
    CHECK_STATUS(udm1_exact_sum_add(back, 4, got), UDM1_OK);
    memset(want, 0, sizeof want);
    CHECK(equal(got, want)); /* and back to 0 */
    /* 1e16 + 1 - 1e16 is 1 here (in doubles it is 0) */
    double cancel[3] = {1e16, 1.0, -1e16};
    CHECK_STATUS(udm1_exact_sum_add(cancel, 3, got), UDM1_OK);
    words_of(1, 1074, want);
    CHECK(equal(got, want));
}

static void test_order_and_split(void)
{
    enum { N = 4096 };
    static double x[N], y[N];
    for (int i = 0; i < N; ++i) { /* every exponent, both signs, subnormals, zeros */
        uint64_t bits = next();
        if ((bits >> 52 & 0x7ff) == 0x7ff) bits &= ~(1ull << 62);
        memcpy(&x[i], &bits, sizeof bits);
    }
    x[0] = 0.0, x[1] = -0.0, x[2] = DBL_MAX, x[3] = -DBL_MAX, x[4] = 5e-324;
    uint64_t whole[W] = {0};
    CHECK_STATUS(udm1_exact_sum_add(x, N, whole), UDM1_OK);
    for (int trial = 0; trial < 10; ++trial) {
        memcpy(y, x, sizeof x);
        for (int i = N - 1; i > 0; --i) { /* shuffle */
            int j = (int)(next() % (uint64_t)(i + 1));
            double t = y[i]; y[i] = y[j]; y[j] = t;
        }
        uint64_t parts[W] = {0};
        for (size_t at = 0; at < N;) { /* pieces of random length into one sum */
            size_t len = 1 + next() % 300;
            if (len > N - at) len = N - at;
            CHECK_STATUS(udm1_exact_sum_add(y + at, len, parts), UDM1_OK);
            at += len;
        }
        CHECKF(equal(parts, whole), "trial %d", trial);
    }
    /* the sum and its negation cancel to 0 */
    for (int i = 0; i < N; ++i) y[i] = -x[i];
    CHECK_STATUS(udm1_exact_sum_add(y, N, whole), UDM1_OK);
    uint64_t zero[W] = {0};
    CHECK(equal(whole, zero));
}

static void test_bad_input(void)
{
    uint64_t words[W] = {0}, before[W];
    double ok = 1.5;
    CHECK_STATUS(udm1_exact_sum_add(&ok, 1, words), UDM1_OK);
    memcpy(before, words, sizeof words);
    double bad[3] = {1.0, 2.0, NAN};
    CHECK_STATUS(udm1_exact_sum_add(bad, 3, words), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "x[2] is NaN") != NULL);
    CHECK(equal(words, before)); /* nothing added */
    bad[2] = -INFINITY;
    CHECK_STATUS(udm1_exact_sum_add(bad, 3, words), UDM1_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(udm1_last_error(), "x[2] is infinite") != NULL);
    CHECK(equal(words, before));
    CHECK_STATUS(udm1_exact_sum_add(NULL, 3, words), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_exact_sum_add(&ok, 1, NULL), UDM1_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(udm1_exact_sum_add(NULL, 0, words), UDM1_OK);
    CHECK(equal(words, before));
}

int main(void)
{
    test_known_sums();
    test_order_and_split();
    test_bad_input();
    CHECK_DONE();
}
