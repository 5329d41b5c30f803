/* fuzz_noise.c - the noise and pattern API at any coordinates and parameters: NaN, infinities, 1e300,
 * subnormals, huge periods and octaves, every table source.
 *
 * Invariants: no crash, no hang, no sanitizer report; statuses are udm1_status values with a message;
 * finite coordinates give finite noise with |n| < 1.1; a non-finite coordinate gives NaN from the scalar
 * functions and an error from the batch ones; batch values equal the scalar ones; a batch that fails
 * (noise, noise with gradients, cellular noise, patterns, grids) leaves its outputs as they were. */
#include "fuzz_bytes.h"

#include <udm1/udm1.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SENTINEL 0xA5
/* Whether the n bytes at p are all SENTINEL (a failed batch's outputs, filled with it before the call). */
static int untouched(const void *p, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (((const unsigned char *)p)[i] != SENTINEL) return 0;
    return 1;
}

/* A coordinate: any bit pattern, or one of the hard cases. */
static double coord(bytes *b)
{
    static const double hard[] = {0.0, -0.0, 0.5, -4.2, 1e12, -1e12, 2147483648.5, 4503599627370496.0, 1e300,
                                  -1e300, 5e-324, 1e-310};
    uint64_t sel = take(b, 1);
    if (sel < 64) {
        uint64_t bits = take(b, 8);
        double v;
        memcpy(&v, &bits, sizeof v);
        return v;
    }
    if (sel < 80) return sel & 1 ? NAN : (sel & 2 ? INFINITY : -INFINITY);
    if (sel < 160) return hard[sel % (sizeof hard / sizeof hard[0])];
    return ((double)(int64_t)take(b, 4)) / 1024.0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bytes b = {data, size};
    static const char *tables[] = {NULL, "perlin", "drand48", "wr", "wopt", "rd", "sobol", "pcg32", "nope", "lattice"};
    udm1_noise_desc desc;
    udm1_noise_desc_init(&desc);
    desc.kind = (uint32_t)take(&b, 1) % 3;
    desc.table = tables[take(&b, 1) % (sizeof tables / sizeof tables[0])];
    desc.seed = take(&b, 8);
    for (int i = 0; i < 3; ++i) {
        uint64_t p = take(&b, 1);
        desc.period[i] = p < 128 ? 0 : (p < 250 ? (uint32_t)(p - 127) : (uint32_t)take(&b, 4));
    }
    udm1_noise *noise = (udm1_noise *)(uintptr_t)1;
    udm1_status st = udm1_noise_create(&desc, &noise);
    REQUIRE(udm1_status_string(st) != NULL);
    if (st != UDM1_OK) {
        REQUIRE(noise == NULL && udm1_last_error()[0] != '\0');
        return 0;
    }
    double pts[3 * 8];
    int finite = 1;
    for (int i = 0; i < 24; ++i) {
        pts[i] = coord(&b);
        finite &= isfinite(pts[i]) != 0;
    }
    for (int i = 0; i < 8; ++i) {
        double x = pts[3 * i], y = pts[3 * i + 1], z = pts[3 * i + 2];
        double v3 = udm1_noise_3d(noise, x, y, z), v2 = udm1_noise_2d(noise, x, y), v1 = udm1_noise_1d(noise, x);
        int finite3 = isfinite(x) && isfinite(y) && isfinite(z);
        if (finite3 && !(isfinite(v3) && fabs(v3) < 1.1)) {
            fprintf(stderr, "fuzz_noise: noise_3d(%.17g, %.17g, %.17g) = %.17g\n", x, y, z, v3);
            abort();
        }
        if (!finite3 && !isnan(v3)) {
            fprintf(stderr, "fuzz_noise: noise_3d(%.17g, %.17g, %.17g) = %.17g, not NaN\n", x, y, z, v3);
            abort();
        }
        if (isfinite(x) && isfinite(y)) REQUIRE(isfinite(v2) && fabs(v2) < 1.1);
        if (isfinite(x)) REQUIRE(isfinite(v1) && fabs(v1) < 1.1);
    }
    double out[8];
    memset(out, SENTINEL, sizeof out);
    st = udm1_noise_points(noise, 3, pts, 8, 3, out);
    REQUIRE(st == (finite ? UDM1_OK : UDM1_ERROR_INVALID_ARGUMENT));
    if (st == UDM1_OK)
        for (int i = 0; i < 8; ++i) REQUIRE(out[i] == udm1_noise_3d(noise, pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]));
    else
        REQUIRE(untouched(out, sizeof out));
    /* the same points with gradients, in double and float, and cellular noise: all or nothing */
    {
        const double *axes[3] = {pts, pts + 1, pts + 2};
        double value[8], grad[24];
        float ptsf[24], valuef[8], gradf[24];
        int finite_f = 1;
        for (int i = 0; i < 24; ++i) {
            ptsf[i] = (float)pts[i];
            finite_f &= isfinite(ptsf[i]) != 0;
        }
        const float *axesf[3] = {ptsf, ptsf + 1, ptsf + 2};
        memset(value, SENTINEL, sizeof value), memset(grad, SENTINEL, sizeof grad);
        st = udm1_noise_eval(noise, 3, axes, 3, 8, value, grad);
        REQUIRE(udm1_status_string(st) != NULL);
        if (st != UDM1_OK) REQUIRE(untouched(value, sizeof value) && untouched(grad, sizeof grad));
        if (finite) REQUIRE(st == UDM1_OK);
        memset(valuef, SENTINEL, sizeof valuef), memset(gradf, SENTINEL, sizeof gradf);
        st = udm1_noise_eval_f32(noise, 3, axesf, 3, 8, valuef, gradf);
        if (st != UDM1_OK) REQUIRE(untouched(valuef, sizeof valuef) && untouched(gradf, sizeof gradf));
        if (finite_f) REQUIRE(st == UDM1_OK);
        udm1_cellular_params cp; /* from bytes already read: the corpus keeps feeding what follows as before */
        udm1_cellular_params_init(&cp);
        cp.metric = (uint32_t)(desc.seed % 5), cp.output = (uint32_t)(desc.seed >> 8) % 6;
        cp.jitter = (desc.seed >> 16) & 1 ? pts[9] : 0.5;
        memset(value, SENTINEL, sizeof value);
        st = udm1_cellular_eval(noise, &cp, 2 + (uint32_t)(desc.seed >> 24) % 2, axes, 3, 8, value);
        REQUIRE(udm1_status_string(st) != NULL);
        if (st != UDM1_OK) REQUIRE(untouched(value, sizeof value));
        memset(valuef, SENTINEL, sizeof valuef);
        st = udm1_cellular_eval_f32(noise, &cp, 3, axesf, 3, 8, valuef);
        if (st != UDM1_OK) REQUIRE(untouched(valuef, sizeof valuef));
    }

    udm1_pattern_params par;
    uint32_t pattern = (uint32_t)take(&b, 1) % 17; /* includes 0 and 16: unknown */
    udm1_pattern_params_init(&par, pattern);
    if (take(&b, 1) & 1) { /* any parameters */
        par.octaves = (uint32_t)take(&b, 1) % 14;
        par.wave = (uint32_t)take(&b, 1) % 9;
        par.omega = coord(&b), par.lambda = coord(&b), par.frequency = coord(&b), par.phase = coord(&b);
        par.exponent = coord(&b), par.agate_turb = coord(&b);
        for (int i = 0; i < 3; ++i) par.turbulence[i] = coord(&b);
    }
    double pv[8];
    memset(pv, SENTINEL, sizeof pv);
    udm1_status st_points = st = udm1_pattern_points(noise, &par, pts, 8, 3, pv);
    REQUIRE(udm1_status_string(st) != NULL);
    if (st != UDM1_OK) REQUIRE(untouched(pv, sizeof pv));
    if (st == UDM1_OK)
        for (int i = 0; i < 8; ++i) REQUIRE(pv[i] == udm1_pattern_eval(noise, &par, pts[3 * i], pts[3 * i + 1],
                                                                        pts[3 * i + 2]) ||
                                            (isnan(pv[i]) && isnan(udm1_pattern_eval(noise, &par, pts[3 * i],
                                                                                     pts[3 * i + 1], pts[3 * i + 2]))));
    if (par.pattern >= UDM1_PATTERN_NOISE && par.pattern <= UDM1_PATTERN_RIDGED) {
        double pg[8], gg[24];
        memset(pg, SENTINEL, sizeof pg), memset(gg, SENTINEL, sizeof gg);
        st = udm1_pattern_gradient(noise, &par, pts, 8, 3, pg, gg);
        REQUIRE(udm1_status_string(st) != NULL);
        if (st != UDM1_OK) REQUIRE(untouched(pg, sizeof pg) && untouched(gg, sizeof gg));
        if (st == UDM1_OK && st_points == UDM1_OK) /* its values are the pattern's */
            for (int i = 0; i < 8; ++i) REQUIRE(pg[i] == pv[i]);
    }
    float grid[4 * 3];
    double origin[3] = {pts[0], pts[1], pts[2]}, sx[3] = {pts[3], pts[4], pts[5]}, sy[3] = {pts[6], pts[7], pts[8]};
    memset(grid, SENTINEL, sizeof grid);
    st = udm1_pattern_grid(noise, &par, 4, 3, 0, 3, origin, sx, sy, grid);
    REQUIRE(udm1_status_string(st) != NULL);
    if (st != UDM1_OK) REQUIRE(untouched(grid, sizeof grid));
    udm1_noise_destroy(noise);
    return 0;
}
