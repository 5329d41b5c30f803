/* patterns.c - fractal sums and POV-Ray 3.7's procedural patterns over udm1's
 * noise, POV-Ray's wave shaping and colour maps. Definitions in udm1.h. */
#include "core/finite.h"
#include "noise/noise_tables.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define NUM_WAVES UDM1_NOISE_WAVES

static const char *const NAMES[] = {NULL,    "noise",  "fbm",   "turbulence", "ridged",  "bozo",
                                    "bumps", "granite", "agate", "marble",     "wood",    "wrinkles",
                                    "leopard", "onion", "ripples", "waves", "crackle"};
#define LAST_PATTERN UDM1_PATTERN_CRACKLE

const char *udm1_pattern_name(uint32_t pattern)
{
    return pattern >= 1 && pattern <= LAST_PATTERN ? NAMES[pattern] : NULL;
}

uint32_t udm1_pattern_from_name(const char *name)
{
    if (!name) return 0;
    for (uint32_t p = 1; p <= LAST_PATTERN; ++p)
        if (strcmp(NAMES[p], name) == 0) return p;
    return 0;
}

void udm1_pattern_params_init(udm1_pattern_params *params, uint32_t pattern)
{
    if (!params) return;
    memset(params, 0, sizeof *params);
    params->struct_size = (uint32_t)sizeof *params;
    params->pattern = pattern;
    params->octaves = 6;
    params->wave = UDM1_WAVE_DEFAULT;
    params->omega = 0.5;
    params->lambda = 2.0;
    params->frequency = 1.0;
    params->phase = 0.0;
    params->exponent = 1.0;
    params->agate_turb = 1.0;
    params->crackle_form[0] = -1.0;
    params->crackle_form[1] = 1.0;
    params->crackle_metric = 2.0;
}

static double clamp01(double v) { return v < 0 ? 0 : (v > 1 ? 1 : v); }
static double frac(double v) { return v - floor(v); }
static double cyc(double v) { return sin(2.0 * PI * frac(v)); }

/* POV's Noise, over udm1's: in [0, 1] */
static double N(const udm1_noise *n, double x, double y, double z) { return clamp01(0.5 + 0.5 * udm1_noise_3d(n, x, y, z)); }

static void dnoise(const udm1_noise *n, double x, double y, double z, double out[3])
{
    out[0] = udm1_noise_3d(n, x, y, z);
    out[1] = udm1_noise_3d(n, x + 31.416, y - 47.853, z + 12.793);
    out[2] = udm1_noise_3d(n, x - 101.234, y + 67.125, z - 23.478);
}

static double turbulence(const udm1_noise *n, const udm1_pattern_params *p, double x, double y, double z)
{
    double v = clamp01(2.0 * N(n, x, y, z) - 0.5), amp = 1.0, s = 1.0;
    for (uint32_t i = 1; i < p->octaves; ++i) {
        amp *= p->omega;
        s *= p->lambda;
        v += amp * (2.0 * N(n, x * s, y * s, z * s) - 0.5);
    }
    return v;
}

static void dturbulence(const udm1_noise *n, const udm1_pattern_params *p, double x, double y, double z,
                        double out[3])
{
    dnoise(n, x, y, z, out);
    double amp = 1.0, s = 1.0, d[3];
    for (uint32_t i = 1; i < p->octaves; ++i) {
        amp *= p->omega;
        s *= p->lambda;
        dnoise(n, x * s, y * s, z * s, d);
        for (int c = 0; c < 3; ++c) out[c] += amp * d[c];
    }
}

/* the frequencies of the waves pattern (the sources are in the noise) */
static double wave_frequency(int i)
{
    uint32_t r = (uint32_t)-560851967;
    for (int k = 0; k <= i; ++k) r = r * 1812433253u + 12345u;
    return ((r >> 16) & 0x7FFFu) * (1.0 / 32767.0) + 0.01;
}

/* POV-Ray's crackle over udm1's exact cellular search */
static double crackle(const udm1_noise *n, const udm1_pattern_params *p, double x, double y, double z)
{
    const double m = p->crackle_metric, c[3] = {x, y, z};
    double F[3], q[3];
    udm1_cellular_nearest3(n, m, c, F, p->crackle_solid ? q : NULL);
    if (p->crackle_solid) return N(n, q[0], q[1], q[2]);
    double off = p->crackle_offset, v = 0.0;
    if (off != 0.0) off = m == 2.0 ? off * off : m == 1.0 ? off : pow(off, m);
    for (int k = 0; k < 3; ++k) {
        double s = F[k] + off;
        double d = m == 2.0 ? sqrt(s) : m == 1.0 ? s : pow(s, 1.0 / m);
        v += p->crackle_form[k] * d;
    }
    return clamp01(v);
}

static double raw(const udm1_noise *n, const udm1_pattern_params *p, double x, double y, double z)
{
    switch (p->pattern) {
    case UDM1_PATTERN_CRACKLE: return crackle(n, p, x, y, z);
    case UDM1_PATTERN_NOISE: return udm1_noise_3d(n, x, y, z);
    case UDM1_PATTERN_FBM:
    case UDM1_PATTERN_RIDGED: {
        double v = 0.0, amp = 1.0, s = 1.0;
        for (uint32_t i = 0; i < p->octaves; ++i) {
            double t = udm1_noise_3d(n, x * s, y * s, z * s);
            if (p->pattern == UDM1_PATTERN_RIDGED) t = (1.0 - fabs(t)) * (1.0 - fabs(t));
            v += amp * t;
            amp *= p->omega;
            s *= p->lambda;
        }
        return v;
    }
    case UDM1_PATTERN_TURBULENCE: return turbulence(n, p, x, y, z);
    case UDM1_PATTERN_BOZO:
    case UDM1_PATTERN_BUMPS: return N(n, x, y, z);
    case UDM1_PATTERN_GRANITE: {
        double v = 0.0, s = 4.0, w = 1.0;
        for (int i = 0; i < 6; ++i, s *= 2.0, w *= 0.5) v += fmin(fabs(1.0 - 2.0 * N(n, x * s, y * s, z * s)), 0.5) * w;
        return v;
    }
    case UDM1_PATTERN_AGATE: {
        double t = p->agate_turb * turbulence(n, p, x, y, z);
        double v = 0.5 * (cyc(1.3 * t + 1.1 * z) + 1.0);
        return v < 0 ? 0.0 : pow(fmin(v, 1.0), 0.77);
    }
    case UDM1_PATTERN_MARBLE: return x + p->turbulence[0] * turbulence(n, p, x, y, z);
    case UDM1_PATTERN_WOOD: {
        if (p->turbulence[0] == 0 && p->turbulence[1] == 0 && p->turbulence[2] == 0) return sqrt(x * x + y * y);
        double d[3];
        dturbulence(n, p, x, y, z, d);
        double px = x + cyc((x + d[0]) * p->turbulence[0]), py = y + cyc((y + d[1]) * p->turbulence[1]);
        return sqrt(px * px + py * py);
    }
    case UDM1_PATTERN_WRINKLES: {
        double v = 0.0, s = 1.0, w = 1.0;
        for (int i = 0; i < 10; ++i, s *= 2.0, w *= 0.5) v += w * clamp01(2.0 * N(n, x * s, y * s, z * s) - 0.5);
        return v / 2.0;
    }
    case UDM1_PATTERN_LEOPARD: {
        double v = (sin(x) + sin(y) + sin(z)) / 3.0;
        return v * v;
    }
    case UDM1_PATTERN_ONION: return fmod(sqrt(x * x + y * y + z * z), 1.0);
    case UDM1_PATTERN_RIPPLES:
    case UDM1_PATTERN_WAVES: {
        double sum = 0.0;
        for (int i = 0; i < NUM_WAVES; ++i) {
            const double *s = n->wave_source[i];
            double dx = x - s[0], dy = y - s[1], dz = z - s[2], d = sqrt(dx * dx + dy * dy + dz * dz);
            if (d == 0.0) d = 1.0;
            if (p->pattern == UDM1_PATTERN_RIPPLES) {
                sum += cyc(d * p->frequency + p->phase);
            } else {
                double f = wave_frequency(i);
                sum += cyc(d * p->frequency * f + p->phase) / f;
            }
        }
        return p->pattern == UDM1_PATTERN_RIPPLES ? 0.5 * (1.0 + sum / NUM_WAVES) : 0.2 * (2.5 + sum / NUM_WAVES);
    }
    default: return NAN;
    }
}

static int is_pov(uint32_t pattern) { return pattern >= UDM1_PATTERN_BOZO; }

static double shape(const udm1_pattern_params *p, double v)
{
    if (p->frequency != 0.0) v = fmod(v * p->frequency + p->phase, 1.00001);
    if (v < 0) v -= floor(v);
    uint32_t wave = p->wave;
    if (wave == UDM1_WAVE_DEFAULT)
        wave = (p->pattern == UDM1_PATTERN_MARBLE || p->pattern == UDM1_PATTERN_WOOD) ? UDM1_WAVE_TRIANGLE
                                                                                      : UDM1_WAVE_RAMP;
    switch (wave) {
    case UDM1_WAVE_TRIANGLE: {
        double t = frac(v);
        return t >= 0.5 ? 2.0 * (1.0 - t) : 2.0 * t;
    }
    case UDM1_WAVE_SINE: return (1.0 + cyc(v)) / 2.0;
    case UDM1_WAVE_SCALLOP: return fabs(cyc(v / 2.0));
    case UDM1_WAVE_CUBIC: return v * v * (3.0 - 2.0 * v);
    case UDM1_WAVE_POLY: return pow(v, p->exponent);
    default: return v;
    }
}

/* Size of the first (1.2) layout of udm1_pattern_params: later layouts only append. */
#define PATTERN_PARAMS_V1_SIZE (offsetof(udm1_pattern_params, agate_turb) + sizeof(double))

/* The caller's params (an older layout's missing fields: the defaults), checked, into p. */
static udm1_status load_params(const char *fn, const udm1_noise *n, const udm1_pattern_params *caller, const void *out,
                               udm1_pattern_params *p)
{
    if (!n || !caller || !out) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: a pointer argument is NULL", fn);
    udm1_status st = udm1_read_struct(fn, "params", "udm1_pattern_params_init", caller, PATTERN_PARAMS_V1_SIZE, p,
                                      sizeof *p);
    if (st != UDM1_OK) return st;
    if (p->pattern < 1 || p->pattern > LAST_PATTERN)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: unknown pattern %u", fn, p->pattern);
    if (p->octaves < 1 || p->octaves > 10)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: octaves %u is outside 1..10", fn, p->octaves);
    if (p->wave > UDM1_WAVE_POLY) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: unknown wave %u", fn, p->wave);
    const double nums[] = {p->omega,         p->lambda,          p->turbulence[0],   p->turbulence[1],
                           p->turbulence[2], p->frequency,       p->phase,           p->exponent,
                           p->agate_turb,    p->crackle_form[0], p->crackle_form[1], p->crackle_form[2],
                           p->crackle_metric, p->crackle_offset};
    for (size_t i = 0; i < sizeof nums / sizeof *nums; ++i)
        if (!isfinite(nums[i]))
            return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: a pattern parameter is not finite", fn);
    if (p->crackle_form[0] == 0 && p->crackle_form[1] == 0 && p->crackle_form[2] == 0)
        p->crackle_form[0] = -1.0, p->crackle_form[1] = 1.0;
    if (p->crackle_metric == 0) p->crackle_metric = 2.0;
    if (!(p->crackle_metric >= 1.0 && p->crackle_metric <= 64.0))
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: params.crackle_metric %g is outside [1, 64]", fn,
                         p->crackle_metric);
    if (p->crackle_offset < 0)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: params.crackle_offset %g is negative", fn, p->crackle_offset);
    if (p->crackle_solid > 1 || p->reserved)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: params.crackle_solid %u is not 0 or 1 (or reserved is not 0)",
                         fn, p->crackle_solid);
    return UDM1_OK;
}

/* A checked pattern at a finite point */
static double eval(const udm1_noise *n, const udm1_pattern_params *p, double x, double y, double z)
{
    int has_turb = p->turbulence[0] != 0 || p->turbulence[1] != 0 || p->turbulence[2] != 0;
    if (is_pov(p->pattern) && has_turb && p->pattern != UDM1_PATTERN_MARBLE && p->pattern != UDM1_PATTERN_WOOD) {
        double d[3];
        dturbulence(n, p, x, y, z, d);
        x += d[0] * p->turbulence[0];
        y += d[1] * p->turbulence[1];
        z += d[2] * p->turbulence[2];
        if (!isfinite(x) || !isfinite(y) || !isfinite(z)) return NAN;
    }
    double v = raw(n, p, x, y, z);
    if (!is_pov(p->pattern)) return v;
    return shape(p, v);
}

double udm1_pattern_eval(const udm1_noise *n, const udm1_pattern_params *caller, double x, double y, double z)
{
    udm1_pattern_params p;
    if (UDM1_UNLIKELY(load_params("udm1_pattern_eval", n, caller, &x, &p) != UDM1_OK)) return NAN;
    if (!isfinite(x) || !isfinite(y) || !isfinite(z)) return NAN;
    return eval(n, &p, x, y, z);
}

/* Whether the raw pattern p (NOISE, FBM, RIDGED, TURBULENCE) is a number, and with `gradient` its
 * gradient finite, at every point whose coordinates are at most `reach` in magnitude: each octave's scaled
 * coordinates (lambda^i P) and the sums of the octaves' weights (omega^i; with the gradient times
 * lambda^i) stay well inside the double range, the noise and its derivatives being bounded (|n| < 1.1, each
 * derivative below 16; the bounds here have room for 16 times more). Where this does not hold (or for
 * the other patterns, not bounded here) a value may be NaN somewhere, and the batch calls compute into a
 * scratch buffer that they copy to the caller's only when every value is a number. */
static int raw_sums_finite(const udm1_pattern_params *p, double reach, int gradient)
{
    const double limit = DBL_MAX / 256;
    uint32_t octaves = p->pattern == UDM1_PATTERN_NOISE ? 1 : p->octaves;
    double amp = 1.0, s = 1.0, weights = 0.0, slopes = 0.0;
    for (uint32_t i = 0; i < octaves; ++i) {
        if (i > 0 && !(reach * fabs(s) <= limit)) return 0; /* (octave 0: the finite coordinates themselves) */
        weights += fabs(amp);
        slopes += fabs(amp) * fabs(s);
        amp *= p->omega;
        s *= p->lambda;
    }
    return p->pattern <= UDM1_PATTERN_RIDGED && weights <= limit && (!gradient || slopes <= limit);
}

/* The largest coordinate magnitude of n finite 3D points (point i at xyz[i * stride]), where p's octaves
 * beyond the first need it (raw_sums_finite); else 0. */
static double reach_of(const udm1_pattern_params *p, const double *xyz, size_t count, size_t stride)
{
    if (p->pattern > UDM1_PATTERN_RIDGED || p->pattern == UDM1_PATTERN_NOISE || p->octaves < 2) return 0.0;
    double r = 0.0;
    for (size_t i = 0; i < count; ++i)
        for (int c = 0; c < 3; ++c) {
            double a = fabs(xyz[i * stride + c]);
            r = a > r ? a : r;
        }
    return r;
}

/* A pattern that is not a number at a finite point: an octave's scale (lambda^i P) or its sum
 * (omega^i) left the range of a double. Refused rather than written as NaN. */
static udm1_status not_a_number(const char *fn, const char *what, size_t a, size_t b)
{
    if (what[1] == 'i') /* "pixel": (column, row) */
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT,
                         "%s: the pattern is not a number at pixel (%zu, %zu): an octave's scale or sum overflows a "
                         "double (omega, lambda, octaves, coordinates)", fn, b, a);
    return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT,
                     "%s: the pattern is not a number at point %zu: an octave's scale or sum overflows a double "
                     "(omega, lambda, octaves, coordinates)", fn, a);
}

udm1_status udm1_pattern_grid(const udm1_noise *n, const udm1_pattern_params *caller, uint32_t width,
                              uint32_t height, uint32_t row0, uint32_t rows, const double origin[3],
                              const double step_x[3], const double step_y[3], float *out)
{
    static const char fn[] = "udm1_pattern_grid";
    udm1_pattern_params params;
    const udm1_pattern_params *p = &params;
    udm1_status st = load_params(fn, n, caller, out, &params);
    if (st != UDM1_OK) return st;
    if (!origin || !step_x || !step_y) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: origin or a step is NULL", fn);
    if (width == 0 || height == 0 || width > 65536 || height > 65536)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: width %u x height %u: each must be in 1..65536", fn, width,
                         height);
    if (row0 >= height || rows > height - row0)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: rows [%u, %u + %u) past the height %u", fn, row0, row0,
                         rows, height);
    for (int c = 0; c < 3; ++c)
        if (!isfinite(origin[c]) || !isfinite(step_x[c]) || !isfinite(step_y[c]))
            return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: origin and steps must be finite", fn);
    /* noise and fBm rows go through the batch call (vectorized), octave by octave; the sums are
     * the same as udm1_pattern_eval's, term by term */
    int batch = p->pattern == UDM1_PATTERN_NOISE || p->pattern == UDM1_PATTERN_FBM;
    double *xyz = batch ? malloc(sizeof(double) * 4 * width) : NULL;
    double *val = xyz ? xyz + 3 * (size_t)width : NULL;
    double *acc = batch ? malloc(sizeof(double) * width) : NULL;
    if (batch && (!xyz || !acc)) batch = 0;
    /* the rows go straight to out where no pixel can be NaN (raw_sums_finite over the grid's reach: each
     * coordinate is at most |origin| + width |step_x| + (row0 + rows) |step_y|, with room for rounding),
     * else to a scratch image copied to out once every pixel is a number: a refused grid writes nothing */
    double reach = 0.0;
    for (int c = 0; c < 3; ++c)
        reach = fmax(reach, fabs(origin[c]) + width * fabs(step_x[c]) + (row0 + (double)rows) * fabs(step_y[c]));
    reach *= 1.0 + 0x1p-40;
    int direct = reach <= DBL_MAX / 256 && raw_sums_finite(p, reach, 0); /* (the coordinates are computed) */
    size_t pixels = (size_t)rows * width;
    float *image = direct ? out : malloc(sizeof(float) * (pixels ? pixels : 1));
    if (!image) {
        free(xyz);
        free(acc);
        return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory for %zu pixels", fn, pixels);
    }
    for (uint32_t j = 0; j < rows; ++j) {
        double b = row0 + j + 0.5;
        if (batch) {
            uint32_t octaves = p->pattern == UDM1_PATTERN_NOISE ? 1 : p->octaves;
            double amp = 1.0, s = 1.0;
            for (uint32_t o = 0; o < octaves; ++o) {
                for (uint32_t i = 0; i < width; ++i) {
                    double a = i + 0.5;
                    for (int c = 0; c < 3; ++c) xyz[3 * (size_t)i + c] = (origin[c] + a * step_x[c] + b * step_y[c]) * s;
                }
                if (udm1_noise_points(n, 3, xyz, width, 3, val) != UDM1_OK) { /* a scaled coordinate overflowed */
                    free(xyz);
                    free(acc);
                    if (image != out) free(image);
                    return not_a_number(fn, "pixel", row0 + j, 0);
                }
                /* as the per-point sum: v = 0, v += amp t (the raw noise pattern is t itself) */
                for (uint32_t i = 0; i < width; ++i)
                    acc[i] = p->pattern == UDM1_PATTERN_NOISE ? val[i] : (o == 0 ? 0.0 : acc[i]) + amp * val[i];
                amp *= p->omega;
                s *= p->lambda;
            }
            for (uint32_t i = 0; i < width; ++i) image[(size_t)j * width + i] = (float)acc[i];
        } else {
            for (uint32_t i = 0; i < width; ++i) {
                double a = i + 0.5, q[3];
                for (int c = 0; c < 3; ++c) q[c] = origin[c] + a * step_x[c] + b * step_y[c];
                image[(size_t)j * width + i] = (float)eval(n, p, q[0], q[1], q[2]);
            }
        }
        for (uint32_t i = 0; i < width; ++i)
            if (isnan(image[(size_t)j * width + i])) {
                free(xyz);
                free(acc);
                if (image != out) free(image);
                return not_a_number(fn, "pixel", row0 + j, i);
            }
    }
    if (image != out) {
        memcpy(out, image, sizeof(float) * pixels);
        free(image);
    }
    free(xyz);
    free(acc);
    return UDM1_OK;
}

udm1_status udm1_pattern_points(const udm1_noise *n, const udm1_pattern_params *caller, const double *xyz,
                                size_t count, size_t stride, double *out)
{
    static const char fn[] = "udm1_pattern_points";
    udm1_pattern_params params;
    const udm1_pattern_params *p = &params;
    udm1_status st = load_params(fn, n, caller, out, &params);
    if (st != UDM1_OK) return st;
    if (!xyz) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: xyz is NULL", fn);
    if (stride < 3) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: stride %zu < 3", fn, stride);
    const double *axes[3] = {xyz, xyz + 1, xyz + 2};
    size_t bad = udm1_first_nonfinite_f64(3, axes, stride, count, NULL);
    if (bad < count) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: point %zu is not finite", fn, bad);
    /* straight to out where no value can be NaN, else through a scratch buffer (raw_sums_finite) */
    int direct = raw_sums_finite(p, reach_of(p, xyz, count, stride), 0);
    double *values = direct ? out : malloc(sizeof(double) * (count ? count : 1));
    if (!values) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory for %zu points", fn, count);
    for (size_t i = 0; i < count; ++i) {
        const double *q = xyz + i * stride;
        values[i] = eval(n, p, q[0], q[1], q[2]);
        if (isnan(values[i])) {
            if (values != out) free(values);
            return not_a_number(fn, "point", i, 0);
        }
    }
    if (values != out) {
        memcpy(out, values, sizeof(double) * count);
        free(values);
    }
    return UDM1_OK;
}

/* The raw pattern p->pattern (NOISE, FBM, TURBULENCE, RIDGED) at c and its gradient: the operations of
 * raw() and turbulence() for the value, the chain rule for the gradient. */
static double raw_gradient(const udm1_noise *n, const udm1_pattern_params *p, const double c[3], double grad[3])
{
    double g[3], q[3];
    grad[0] = grad[1] = grad[2] = 0.0;
    if (p->pattern == UDM1_PATTERN_NOISE) {
        double v = udm1_lattice_f64(n, 3, c, g);
        for (int k = 0; k < 3; ++k) grad[k] = g[k];
        return v;
    }
    if (p->pattern == UDM1_PATTERN_TURBULENCE) {
        /* clamp01(2 N - 1/2) + sum amp (2 N(s P) - 1/2), N = clamp01(0.5 + 0.5 n) */
        double t = udm1_lattice_f64(n, 3, c, g);
        double Nv = 0.5 + 0.5 * t, dN = Nv > 0 && Nv < 1 ? 0.5 : 0.0;
        double Nc = clamp01(Nv), u = 2.0 * Nc - 0.5, du = u > 0 && u < 1 ? 2.0 * dN : 0.0;
        double v = clamp01(u), amp = 1.0, s = 1.0;
        for (int k = 0; k < 3; ++k) grad[k] = du * g[k];
        for (uint32_t i = 1; i < p->octaves; ++i) {
            amp *= p->omega;
            s *= p->lambda;
            for (int k = 0; k < 3; ++k) q[k] = c[k] * s;
            t = udm1_lattice_f64(n, 3, q, g);
            Nv = 0.5 + 0.5 * t;
            dN = Nv > 0 && Nv < 1 ? 0.5 : 0.0;
            v += amp * (2.0 * clamp01(Nv) - 0.5);
            for (int k = 0; k < 3; ++k) grad[k] += amp * 2.0 * dN * s * g[k];
        }
        return v;
    }
    /* FBM and RIDGED: sum amp t_i, t_i = n(s P) or (1 - |n(s P)|)^2 */
    double v = 0.0, amp = 1.0, s = 1.0;
    for (uint32_t i = 0; i < p->octaves; ++i) {
        for (int k = 0; k < 3; ++k) q[k] = c[k] * s;
        double t = udm1_lattice_f64(n, 3, q, g), dt = 1.0;
        if (p->pattern == UDM1_PATTERN_RIDGED) {
            dt = -2.0 * (1.0 - fabs(t)) * (t > 0 ? 1.0 : t < 0 ? -1.0 : 0.0);
            t = (1.0 - fabs(t)) * (1.0 - fabs(t));
        }
        v += amp * t;
        for (int k = 0; k < 3; ++k) grad[k] += amp * dt * s * g[k];
        amp *= p->omega;
        s *= p->lambda;
    }
    return v;
}

udm1_status udm1_pattern_gradient(const udm1_noise *n, const udm1_pattern_params *caller, const double *xyz,
                                  size_t count, size_t stride, double *value, double *gradient)
{
    static const char fn[] = "udm1_pattern_gradient";
    udm1_pattern_params params;
    const udm1_pattern_params *p = &params;
    udm1_status st = load_params(fn, n, caller, gradient ? (const void *)gradient : (const void *)value, &params);
    if (st != UDM1_OK) return st;
    if (!xyz) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "%s: xyz is NULL", fn);
    if (p->pattern > UDM1_PATTERN_RIDGED)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: pattern %s has no gradient here (noise, fbm, turbulence, "
                         "ridged have)", fn, NAMES[p->pattern]);
    if (stride < 3) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: stride %zu < 3", fn, stride);
    const double *axes[3] = {xyz, xyz + 1, xyz + 2};
    size_t bad = udm1_first_nonfinite_f64(3, axes, stride, count, NULL);
    if (bad < count) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: point %zu is not finite", fn, bad);
    /* straight to the outputs where every value and gradient is finite, else through a scratch buffer of
     * both (raw_sums_finite), copied to the outputs once every point is */
    double *scratch = NULL, *v_out = value, *g_out = gradient;
    if (!raw_sums_finite(p, reach_of(p, xyz, count, stride), 1)) {
        scratch = malloc(sizeof(double) * 4 * (count ? count : 1));
        if (!scratch) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "%s: out of memory for %zu points", fn, count);
        v_out = value ? scratch : NULL;
        g_out = gradient ? scratch + count : NULL;
    }
    for (size_t i = 0; i < count; ++i) {
        double g[3], v = raw_gradient(n, p, xyz + i * stride, g);
        if (!isfinite(v) || !isfinite(g[0]) || !isfinite(g[1]) || !isfinite(g[2])) {
            free(scratch);
            return not_a_number(fn, "point", i, 0);
        }
        if (v_out) v_out[i] = v;
        if (g_out)
            for (int k = 0; k < 3; ++k) g_out[3 * i + k] = g[k];
    }
    if (scratch) {
        if (value) memcpy(value, v_out, sizeof(double) * count);
        if (gradient) memcpy(gradient, g_out, sizeof(double) * 3 * count);
        free(scratch);
    }
    return UDM1_OK;
}

/* ---- colour maps ---- */

udm1_status udm1_color_map_eval(const udm1_color_entry *e, size_t count, double value, float rgb[3])
{
    if (!e || !rgb) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_color_map_eval: a pointer argument is NULL");
    if (count == 0) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "udm1_color_map_eval: no entries");
    for (size_t k = 1; k < count; ++k)
        if (!(e[k].value >= e[k - 1].value))
            return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "udm1_color_map_eval: entry %zu is not sorted by value", k);
    if (isnan(value)) return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "udm1_color_map_eval: the value is not a number");
    if (!(value < e[count - 1].value)) {
        memcpy(rgb, e[count - 1].rgb, sizeof(float) * 3);
        return UDM1_OK;
    }
    size_t k = 0;
    while (e[k].value < value) ++k;
    if (k == 0 || e[k].value == value) {
        memcpy(rgb, e[k].rgb, sizeof(float) * 3);
        return UDM1_OK;
    }
    double w = (e[k].value - value) / (e[k].value - e[k - 1].value);
    for (int c = 0; c < 3; ++c) rgb[c] = (float)(w * e[k - 1].rgb[c] + (1.0 - w) * e[k].rgb[c]);
    return UDM1_OK;
}

static const udm1_color_entry GREY[] = {{0.0, {0, 0, 0}}, {1.0, {1, 1, 1}}};
static const udm1_color_entry BOZO[] = {{0.4, {1, 1, 1}}, {0.4, {0, 1, 0}}, {0.6, {0, 1, 0}},
                                        {0.6, {0, 0, 1}}, {0.8, {0, 0, 1}}, {0.8, {1, 0, 0}}};
static const udm1_color_entry MARBLE[] = {{0.0, {0.9f, 0.8f, 0.8f}}, {0.9, {0.9f, 0.08f, 0.08f}}, {0.9, {0, 0, 0}}};
static const udm1_color_entry WOOD[] = {{0.6, {0.666f, 0.312f, 0.2f}}, {0.6, {0.4f, 0.1333f, 0.066f}}};
static const udm1_color_entry AGATE[] = {{0.0, {1, 1, 1}},          {0.5, {0.95f, 0.75f, 0.5f}}, {0.5, {0.9f, 0.7f, 0.5f}},
                                         {0.6, {0.9f, 0.7f, 0.4f}}, {0.6, {1, 0.7f, 0.4f}},      {1.0, {0.6f, 0.3f, 0}}};

udm1_status udm1_pattern_default_colors(uint32_t pattern, const udm1_color_entry **entries, size_t *count)
{
    if (!entries || !count) return udm1_fail(UDM1_ERROR_NULL_ARGUMENT, "udm1_pattern_default_colors: a pointer is NULL");
    if (pattern < 1 || pattern > LAST_PATTERN)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "udm1_pattern_default_colors: unknown pattern %u", pattern);
#define SET(T) (*entries = T, *count = sizeof T / sizeof *T)
    switch (pattern) {
    case UDM1_PATTERN_BOZO: SET(BOZO); break;
    case UDM1_PATTERN_MARBLE: SET(MARBLE); break;
    case UDM1_PATTERN_WOOD: SET(WOOD); break;
    case UDM1_PATTERN_AGATE: SET(AGATE); break;
    default: SET(GREY); break;
    }
#undef SET
    return UDM1_OK;
}
