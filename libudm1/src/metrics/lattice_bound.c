/* lattice_bound.c - an embedded lattice rule's spectrum, its wavenumber order and its Fourier error
 * bound, kept across doublings (see udm1/lattice_bound.h).
 *
 * Doubling n -> 2n adds the odd points of the 2n-lattice; with O their transform and w = e^(-i pi / n),
 * S_2n[l] = S_n[l] + w^l O[l] and S_2n[2n - l] = conj(S_n[l] - w^l O[l]) for l = 0 .. n/2: class l of n
 * splits into l and l + n. The twiddles w^l are the products of two short tables (l = hi B + lo), so a
 * doubling costs sqrt(n) sines rather than n. Every operation is a correctly rounded add, multiply or
 * square root in one fixed order (the library is built without contraction into fused multiply-adds),
 * so the same transforms give the same spectrum, order and bound bit for bit. */
#include "core/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#define PI 3.14159265358979323846
#define MAX_POINTS ((uint64_t)1 << 32)

struct udm1_lattice_bound {
    uint32_t lag;
    double fudge;
    uint32_t m;        /* n = 2^m points held, when n > 0 */
    uint64_t n;
    uint64_t capacity; /* points the buffers hold */
    double *s;         /* S[l] = n Y[l] as (re, im), l = 0 .. n/2 */
    uint32_t *order;   /* position -> wavenumber class, n of them */
    double *ordered;   /* |S|^2 of the class at each position */
    uint64_t *flip;    /* a level's swaps: all ones or 0, one a position of its first block */
    double *twiddle;   /* the two tables of a doubling: fine (B entries), then coarse */
};

static void release(udm1_lattice_bound *b)
{
    free(b->s);
    free(b->order);
    free(b->ordered);
    free(b->flip);
    free(b->twiddle);
}

/* Buffers for `points` points; the spectrum and the order keep their first n entries. */
static udm1_status reserve(udm1_lattice_bound *b, uint64_t points, const char *fn)
{
    if (points <= b->capacity) return UDM1_OK;
    uint64_t c = b->capacity ? b->capacity : 64;
    while (c < points) c *= 2;
    uint32_t bits = 0;
    while (((uint64_t)1 << (2 * bits)) < c) ++bits;
    double *s = malloc(2 * (size_t)(c / 2 + 1) * sizeof *s);
    /* a doubling of n <= c / 2 points: B = 2^ceil(m / 2) fine twiddles, n / 2B + 1 <= B / 2 + 1 coarse ones */
    double *twiddle = malloc(2 * (3 * ((size_t)1 << bits) + 2) * sizeof *twiddle);
    double *ordered = malloc((size_t)c * sizeof *ordered);
    uint32_t *order = malloc((size_t)c * sizeof *order);
    uint64_t *flip = malloc((size_t)(c / 2) * sizeof *flip);
    if (!s || !twiddle || !ordered || !order || !flip) {
        free(s);
        free(twiddle);
        free(ordered);
        free(order);
        free(flip);
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory for %llu points", fn, (unsigned long long)c);
    }
    if (b->n) {
        memcpy(s, b->s, 2 * (size_t)(b->n / 2 + 1) * sizeof *s);
        memcpy(order, b->order, (size_t)b->n * sizeof *order);
    }
    release(b);
    b->s = s;
    b->twiddle = twiddle;
    b->order = order;
    b->ordered = ordered;
    b->flip = flip;
    b->capacity = c;
    return UDM1_OK;
}

udm1_status udm1_lattice_bound_create(uint32_t lag, double fudge, uint64_t capacity, udm1_lattice_bound **out)
{
    static const char fn[] = "udm1_lattice_bound_create";
    if (!out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: out is NULL", fn);
    *out = NULL;
    if (lag < 1 || lag > 30)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: lag must be 1 .. 30, not %u", fn, lag);
    if (!(isfinite(fudge) && fudge > 0))
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: fudge must be finite and positive, not %g", fn, fudge);
    if (capacity > MAX_POINTS)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: capacity %llu is above 2^32 points", fn,
                         (unsigned long long)capacity);
    udm1_lattice_bound *b = calloc(1, sizeof *b);
    if (!b) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory", fn);
    b->lag = lag;
    b->fudge = fudge;
    udm1_status st = reserve(b, capacity, fn);
    if (st != UDM1_OK) {
        free(b);
        return st;
    }
    *out = b;
    return UDM1_OK;
}

void udm1_lattice_bound_destroy(udm1_lattice_bound *b)
{
    if (!b) return;
    release(b);
    free(b);
}

void udm1_lattice_bound_reset(udm1_lattice_bound *b)
{
    if (!b) {
        udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_lattice_bound_reset: bound is NULL");
        return;
    }
    b->n = 0;
    b->m = 0;
}

uint64_t udm1_lattice_bound_points(const udm1_lattice_bound *b)
{
    if (!b) {
        udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_lattice_bound_points: bound is NULL");
        return 0;
    }
    return b->n;
}

static uint64_t fold(uint64_t k, uint64_t n) { return k < n - k ? k : n - k; }

/* flip[q] = all ones where hi[q] > lo[q], else 0, and the larger of the two into lo[q], the smaller into
 * hi[q] (selected by bit masks: no branch to mispredict on coefficients that compare at random; the same
 * values with SSE2 or without); whether any flips. */
static uint64_t compare(double *restrict lo, double *restrict hi, uint64_t *restrict flip, uint64_t count)
{
    uint64_t q = 0, any = 0;
#ifdef __SSE2__
    __m128i any2 = _mm_setzero_si128();
    for (; q + 2 <= count; q += 2) {
        __m128d a = _mm_loadu_pd(lo + q), c = _mm_loadu_pd(hi + q), swap = _mm_cmpgt_pd(c, a);
        __m128d diff = _mm_and_pd(_mm_xor_pd(a, c), swap);
        _mm_storeu_pd(lo + q, _mm_xor_pd(a, diff));
        _mm_storeu_pd(hi + q, _mm_xor_pd(c, diff));
        _mm_storeu_si128((__m128i *)(flip + q), _mm_castpd_si128(swap));
        any2 = _mm_or_si128(any2, _mm_castpd_si128(swap));
    }
    any = (uint64_t)_mm_movemask_pd(_mm_castsi128_pd(any2));
#endif
    for (; q < count; ++q) {
        uint64_t a, c;
        memcpy(&a, lo + q, sizeof a);
        memcpy(&c, hi + q, sizeof c);
        uint64_t swap = 0 - (uint64_t)(hi[q] > lo[q]);
        uint64_t diff = (a ^ c) & swap;
        a ^= diff;
        c ^= diff;
        memcpy(lo + q, &a, sizeof a);
        memcpy(hi + q, &c, sizeof c);
        flip[q] = swap;
        any |= swap;
    }
    return any;
}

/* The levels top .. bottom + 1 of the order: in every block of 2 half positions, p in [1, half) and
 * p + half swap when the class at p + half in the first block has the larger coefficient (the same swap
 * in every block: the split below each pair follows it). Only the first block's magnitudes are read,
 * so only they are swapped. */
static void reorder(udm1_lattice_bound *b, uint32_t top, uint32_t bottom)
{
    const uint64_t n = b->n;
    const double *s = b->s;
    double *ordered = b->ordered;
    uint32_t *order = b->order;
    uint64_t *flip = b->flip;
    const uint64_t first_block = (uint64_t)2 << top;
    for (uint64_t p = 0; p < first_block; ++p) {
        uint64_t l = fold(order[p], n);
        ordered[p] = s[2 * l] * s[2 * l] + s[2 * l + 1] * s[2 * l + 1];
    }
    for (uint32_t level = top; level > bottom; --level) {
        const uint64_t half = (uint64_t)1 << level;
        if (!compare(ordered + 1, ordered + half + 1, flip + 1, half - 1)) continue;
        for (uint64_t block = 0; block < n; block += 2 * half) {
            uint32_t *lo = order + block, *hi = order + block + half;
            for (uint64_t q = 1; q < half; ++q) {
                uint32_t diff = (lo[q] ^ hi[q]) & (uint32_t)flip[q];
                lo[q] ^= diff;
                hi[q] ^= diff;
            }
        }
    }
}

udm1_status udm1_lattice_bound_add(udm1_lattice_bound *b, const double *t, uint64_t n)
{
    static const char fn[] = "udm1_lattice_bound_add";
    if (!b || !t) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, b ? "transform" : "bound");
    if (b->n == 0) {
        if (n & (n - 1) || n <= ((uint64_t)1 << b->lag) || n > MAX_POINTS)
            return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT,
                             "%s: the first points must be a power of two in (2^%u, 2^32] (the lag %u), not %llu", fn,
                             b->lag, b->lag, (unsigned long long)n);
    } else if (n != b->n || 2 * n > MAX_POINTS) {
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: %llu points held: add %llu (up to 2^32 points), not %llu",
                         fn, (unsigned long long)b->n, (unsigned long long)b->n, (unsigned long long)n);
    }
    for (uint64_t l = 0; l <= n / 2; ++l)
        if (!isfinite(t[2 * l]) || !isfinite(t[2 * l + 1]))
            return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: transform coefficient %llu is not finite (%g, %g)", fn,
                             (unsigned long long)l, t[2 * l], t[2 * l + 1]);
    udm1_status st = reserve(b, b->n ? 2 * n : n, fn);
    if (st != UDM1_OK) return st;
    double *s = b->s;
    if (b->n == 0) {
        memcpy(s, t, 2 * (size_t)(n / 2 + 1) * sizeof *s);
        for (uint64_t k = 0; k < n; ++k) b->order[k] = (uint32_t)k;
        b->n = n;
        b->m = 0;
        while (((uint64_t)1 << b->m) < n) ++b->m;
        reorder(b, b->m - 1, 0);
        return UDM1_OK;
    }
    /* w^l = e^(-i pi l / n) = fine[l mod B] coarse[l / B], l = 0 .. n/2 */
    const uint64_t h = n / 2;
    uint32_t bits = 0;
    while (((uint64_t)1 << (2 * bits)) < n) ++bits;
    const uint64_t B = (uint64_t)1 << bits, coarse_count = h / B + 1;
    double *fine = b->twiddle, *coarse = b->twiddle + 2 * B;
    for (uint64_t j = 0; j < B; ++j) {
        double a = -PI * (double)j / (double)n;
        fine[2 * j] = cos(a);
        fine[2 * j + 1] = sin(a);
    }
    for (uint64_t j = 0; j < coarse_count; ++j) {
        double a = -PI * (double)(j * B) / (double)n;
        coarse[2 * j] = cos(a);
        coarse[2 * j + 1] = sin(a);
    }
    for (uint64_t l = 0; l <= h; ++l) {
        const double *f = fine + 2 * (l & (B - 1)), *c = coarse + 2 * (l >> bits);
        double wr = f[0] * c[0] - f[1] * c[1], wi = f[0] * c[1] + f[1] * c[0];
        double tr = wr * t[2 * l] - wi * t[2 * l + 1], ti = wr * t[2 * l + 1] + wi * t[2 * l];
        double sr = s[2 * l], si = s[2 * l + 1];
        if (l < h) { /* S_2n[2n - l] for l = 0 lands at n: the top of the new half spectrum */
            s[2 * (n - l)] = sr - tr;
            s[2 * (n - l) + 1] = -(si - ti);
        }
        s[2 * l] = sr + tr;
        s[2 * l + 1] = si + ti;
    }
    for (uint64_t k = 0; k < n; ++k) b->order[n + k] = b->order[k] + (uint32_t)n;
    b->n = 2 * n;
    b->m += 1;
    reorder(b, b->m - 1, b->m - b->lag - 1);
    return UDM1_OK;
}

udm1_status udm1_lattice_bound_error(const udm1_lattice_bound *b, double *error)
{
    static const char fn[] = "udm1_lattice_bound_error";
    if (!b || !error) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, b ? "error" : "bound");
    if (!b->n) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: no points added yet", fn);
    const uint64_t n = b->n, lo = n >> (b->lag + 1);
    double sum = 0;
    for (int careful = 0; careful < 2 && (careful == 0 || isinf(sum)); ++careful) {
        sum = 0; /* the second pass, when a square or the sum overflowed: hypot, without squares */
        for (uint64_t p = lo; p < 2 * lo; ++p) {
            const double *c = b->s + 2 * fold(b->order[p], n);
            sum += careful ? hypot(c[0], c[1]) : sqrt(c[0] * c[0] + c[1] * c[1]);
        }
    }
    *error = b->fudge * ldexp(sum, -2 * (int)b->m); /* fudge 2^-m sum |S| / n */
    return UDM1_OK;
}

/* The arguments of a read of [first, first + count) of the n held: a status naming the first bad one. */
static udm1_status check_range(const udm1_lattice_bound *b, uint64_t first, uint64_t count, const void *out,
                               const char *fn, const char *what)
{
    if (!b || (!out && count)) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: %s is NULL", fn, b ? "out" : "bound");
    if (first > b->n || count > b->n - first)
        return udm1_fail(UDM1_ERROR_INDEX_RANGE, "%s: %s [%llu, %llu + %llu) of %llu", fn, what,
                         (unsigned long long)first, (unsigned long long)first, (unsigned long long)count,
                         (unsigned long long)b->n);
    return UDM1_OK;
}

udm1_status udm1_lattice_bound_coefficients(const udm1_lattice_bound *b, uint64_t first, uint64_t count, double *out)
{
    udm1_status st = check_range(b, first, count, out, "udm1_lattice_bound_coefficients", "coefficients");
    if (st != UDM1_OK) return st;
    const uint64_t n = b->n;
    const double scale = count ? 1.0 / (double)n : 0; /* exact: n is a power of two */
    for (uint64_t j = 0; j < count; ++j) {
        uint64_t l = first + j, k = fold(l, n);
        out[2 * j] = b->s[2 * k] * scale;
        out[2 * j + 1] = (k == l ? 1 : -1) * b->s[2 * k + 1] * scale;
    }
    return UDM1_OK;
}

udm1_status udm1_lattice_bound_order(const udm1_lattice_bound *b, uint64_t first, uint64_t count, uint64_t *out)
{
    udm1_status st = check_range(b, first, count, out, "udm1_lattice_bound_order", "positions");
    if (st != UDM1_OK) return st;
    for (uint64_t j = 0; j < count; ++j) out[j] = b->order[first + j];
    return UDM1_OK;
}
