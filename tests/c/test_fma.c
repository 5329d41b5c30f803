/* test_fma.c - the library's emulated fused multiply-add (libudm1/src/core/fma.h, what a Windows build
 * without FMA computes cellular noise with) against the processor's FMA instruction (x86-64 with FMA,
 * AArch64), or the C library's fma where the processor has none (glibc's rounds once), bit for bit, in
 * double and float: random bit patterns (every exponent, subnormals, overflow), products whose rounding is
 * a tie broken by a tiny addend or not, cancellations (c = -RN(a b): the product's rounding error),
 * results in and near the subnormals, signed zeros, infinities and NaN. Skips (77) on Windows without FMA:
 * its C library's fma is not rounded once, no reference. */
#include "check.h"

#define UDM1_FMA_EMULATED 1
#include "core/fma.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("fma"))) static double hw_fma(double a, double b, double c) { return __builtin_fma(a, b, c); }
__attribute__((target("fma"))) static float hw_fmaf(float a, float b, float c) { return __builtin_fmaf(a, b, c); }
static int have_reference(void) { return __builtin_cpu_supports("fma"); }
#elif !defined(_WIN32)
static double hw_fma(double a, double b, double c) { return fma(a, b, c); }
static float hw_fmaf(float a, float b, float c) { return fmaf(a, b, c); }
static int have_reference(void) { return 1; }
#else
static double hw_fma(double a, double b, double c) { return fma(a, b, c); }
static float hw_fmaf(float a, float b, float c) { return fmaf(a, b, c); }
static int have_reference(void) { return 0; }
#endif

static uint64_t rng = 12345;
static uint64_t next64(void) /* splitmix64 */
{
    uint64_t z = (rng += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double from_bits(uint64_t b)
{
    double x;
    memcpy(&x, &b, sizeof x);
    return x;
}

static float from_bits32(uint32_t b)
{
    float x;
    memcpy(&x, &b, sizeof x);
    return x;
}

/* a double of random significand, sign and exponent in [lo, hi] (unbiased) */
static double random_double(int lo, int hi)
{
    uint64_t e = (uint64_t)(lo + (int)(next64() % (uint64_t)(hi - lo + 1)) + 1023);
    return from_bits((next64() & 0x800FFFFFFFFFFFFFull) | e << 52);
}

static int bad, badf, cases;

static void check(double a, double b, double c)
{
    double got = udm1_fma(a, b, c), want = hw_fma(a, b, c);
    ++cases;
    if (memcmp(&got, &want, sizeof got) != 0 && !(isnan(got) && isnan(want)) && bad++ < 5)
        fprintf(stderr, "fma(%a, %a, %a) = %a, the instruction %a\n", a, b, c, got, want);
}

static void checkf(float a, float b, float c)
{
    float got = udm1_fmaf(a, b, c), want = hw_fmaf(a, b, c);
    ++cases;
    if (memcmp(&got, &want, sizeof got) != 0 && !(isnan(got) && isnan(want)) && badf++ < 5)
        fprintf(stderr, "fmaf(%a, %a, %a) = %a, the instruction %a\n", (double)a, (double)b, (double)c, (double)got,
                (double)want);
}

int main(void)
{
    if (!have_reference()) {
        printf("SKIP: no FMA instruction and a C library whose fma is not rounded once: no reference\n");
        return 77;
    }
    /* random bit patterns: every exponent, subnormals, overflow, infinities and NaN now and then */
    for (int i = 0; i < 300000; ++i) {
        check(from_bits(next64()), from_bits(next64()), from_bits(next64()));
        checkf(from_bits32((uint32_t)next64()), from_bits32((uint32_t)next64()), from_bits32((uint32_t)next64()));
    }
    /* operands of moderate size, the addend near the product or far from it */
    for (int i = 0; i < 300000; ++i) {
        double a = random_double(-30, 30), b = random_double(-30, 30);
        int k = (int)(next64() % 200) - 100;
        double c = random_double(-60 + k, 60 + k);
        check(a, b, c);
        check(a, b, -a * b);            /* cancellation: the product's rounding error */
        check(a, b, -a * b + c * 0x1p-60);
        checkf((float)a, (float)b, (float)c);
        checkf((float)a, (float)b, -(float)a * (float)b);
    }
    /* ties: a b with exactly one bit past the significand (odd a and b of 27 bits: the product's 54th bit
     * set, the rest 0), alone, and with addends of every size that break the tie either way */
    for (int i = 0; i < 100000; ++i) {
        double a = ldexp((double)((next64() >> 37) | 1 | (1ull << 26)), -26), b = ldexp((double)((next64() >> 37) | 1 | (1ull << 26)), -26);
        int k = (int)(next64() % 180);
        check(a, b, 0x1p-200 * ((next64() & 1) ? 1 : -1));
        check(a, b, ldexp(1.0, -k) * ((next64() & 1) ? 1 : -1));
        check(a, b, -ldexp(1.0, -k));
        float af = (float)ldexp((double)((next64() >> 52) | 1 | (1u << 11)), -11);
        float bf = (float)ldexp((double)((next64() >> 52) | 1 | (1u << 11)), -11);
        checkf(af, bf, (float)ldexp(1.0, -(int)(next64() % 60)));
        checkf(af, bf, -(float)ldexp(1.0, -(int)(next64() % 60)));
    }
    /* results in and near the subnormals, and near overflow */
    for (int i = 0; i < 100000; ++i) {
        double a = random_double(-600, -450), b = random_double(-600, -450);
        check(a, b, random_double(-1080, -1000));
        check(a, b, -a * b);
        check(random_double(500, 520), random_double(500, 520), random_double(1000, 1023));
        checkf((float)random_double(-80, -60), (float)random_double(-80, -60), (float)random_double(-150, -120));
        checkf((float)random_double(60, 64), (float)random_double(60, 64), -(float)random_double(120, 127));
    }
    /* signed zeros, infinities and NaN */
    static const double special[] = {0.0, -0.0, 1.0, -1.0, 0x1p-1074, -0x1p-1074, 0x1.fffffffffffffp1023, INFINITY,
                                     -INFINITY, NAN, 0x1p-537, 3.0};
    enum { S = sizeof special / sizeof *special };
    for (int i = 0; i < S; ++i)
        for (int j = 0; j < S; ++j)
            for (int k = 0; k < S; ++k) {
                check(special[i], special[j], special[k]);
                checkf((float)special[i], (float)special[j], (float)special[k]);
            }
    CHECKF(bad == 0, "%d of the double cases differ", bad);
    CHECKF(badf == 0, "%d of the float cases differ", badf);
    printf("%d cases, the emulated fma and fmaf equal the reference\n", cases);
    CHECK_DONE();
}
