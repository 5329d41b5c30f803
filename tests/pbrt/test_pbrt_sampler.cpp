// test_pbrt_sampler.cpp - udm1's sampler for pbrt-v4 gives the library's values. Built twice: against
// the adapter alone (integrations/pbrt-v4/udm1_pbrt_sampler.h, every test run), and with
// UDM1_TEST_PATCHED_PBRT against pbrt-v4's own sampler class, pbrt::UDM1Sampler, from the snapshot in
// ../shared/anchors with integrations/pbrt-v4/udm1-sampler.patch applied (tests/pbrt/check_patch.sh, skipped
// where the snapshot is absent). Every value is compared with udm1's cursor (an independent path through
// the library: udm1_cursor_start at the pixel's stream, sample and dimension), bit for bit: pixel
// positions from dimensions 0 and 1, Get1D / Get2D from dimension 2 on or from a dimension the caller
// restarts at, past the 64 dimensions a stream holds and past the sequence's own, for Weyl, base-2 and
// PRNG presets, every randomization pbrt's scene file may name, pixels revisited out of order.
#if defined(UDM1_TEST_PATCHED_PBRT)
#include <pbrt/samplers.h>
#else
#include "udm1_pbrt_sampler.h"
#endif

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

static int failures = 0;
#define CHECK(cond, ...)                                                 \
    do {                                                                 \
        if (!(cond)) {                                                   \
            ++failures;                                                  \
            std::fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);    \
            std::fprintf(stderr, __VA_ARGS__);                           \
            std::fprintf(stderr, "\n");                                  \
        }                                                                \
    } while (0)

namespace {

#if defined(UDM1_TEST_PATCHED_PBRT)
using Float = pbrt::Float;
// pbrt-v4's class, made as its Create makes it (the parameter dictionary aside)
struct Sampler {
    pbrt::UDM1Sampler s;
    Sampler(udm1pbrt::SharedSeq seq, int spp) : s(std::move(seq), spp, "test", "test", 0) {}
    void start(int x, int y, int i, int dim) { s.StartPixelSample(pbrt::Point2i(x, y), i, dim); }
    void pixel(Float u[2]) { pbrt::Point2f p = s.GetPixel2D(); u[0] = p.x, u[1] = p.y; }
    Float one() { return s.Get1D(); }
    void two(Float u[2]) { pbrt::Point2f p = s.Get2D(); u[0] = p.x, u[1] = p.y; }
};
#else
using Float = float;
struct Sampler {
    udm1pbrt::PixelSampler s;
    Sampler(udm1pbrt::SharedSeq seq, int) : s(std::move(seq)) {}
    void start(int x, int y, int i, int dim) { s.start(x, y, i, dim); }
    void pixel(Float u[2]) { s.pixel2d(u); }
    Float one() { return s.get1d<Float>(); }
    void two(Float u[2]) { s.get2d(u); }
};
#endif

// The library's value of dimension `dim` of sample i of pixel (x, y), through the cursor.
Float reference(const udm1_seq *seq, int x, int y, int i, uint32_t dim)
{
    udm1_cursor c;
    udm1_status st = udm1_cursor_start(&c, seq, ((uint64_t)(uint32_t)y << 32) | (uint32_t)x, (uint64_t)i, dim);
    CHECK(st == UDM1_OK, "cursor_start: %s", udm1_last_error());
    if (sizeof(Float) == sizeof(float)) return (Float)udm1_cursor_1d(&c);
    return (Float)udm1_cursor_1d_f64(&c);
}

bool same(Float a, Float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void check_sequence(const char *preset, const char *randomization, int spp)
{
    uint32_t randomize = 0;
    CHECK(udm1pbrt::randomization_from_name(randomization, &randomize), "randomization %s", randomization);
    std::string error;
    udm1pbrt::SharedSeq seq = udm1pbrt::create_sequence(preset, randomize, 7, (uint32_t)spp, &error);
    CHECK(seq != nullptr, "%s/%s: %s", preset, randomization, error.c_str());
    if (!seq) return;
    Sampler a(seq, spp);
    Sampler b(seq, spp);  // a second clone interleaved with the first: no shared per-pixel state
    // pixels in an order that revisits them, samples out of order
    const int pixels[][2] = {{0, 0}, {1, 0}, {0, 1}, {37, 11}, {1, 0}, {511, 300}, {0, 0}, {2, 70000}};
    int mismatches = 0;
    for (const auto &p : pixels)
        for (int i : {0, 1, 5, spp - 1, 3}) {
            if (i >= spp) continue;
            Float u[2], v[2];
            a.start(p[0], p[1], i, 0);
            b.start(p[0] + 1, p[1], i, 0);
            a.pixel(u);
            b.pixel(v);
            mismatches += !same(u[0], reference(seq.get(), p[0], p[1], i, 0)) + !same(u[1], reference(seq.get(), p[0], p[1], i, 1));
            mismatches += !same(v[0], reference(seq.get(), p[0] + 1, p[1], i, 0));
            // a path's draws: 1D, 2D, 1D, 2D, ... from dimension 2, to dimension 80 (past the 64 a
            // stream holds and past WMMR's 22)
            uint32_t dim = 2;
            while (dim < 80) {
                if (dim % 3 == 0) {
                    Float x = a.one();
                    mismatches += !same(x, reference(seq.get(), p[0], p[1], i, dim));
                    dim += 1;
                } else {
                    a.two(u);
                    mismatches += !same(u[0], reference(seq.get(), p[0], p[1], i, dim)) +
                                  !same(u[1], reference(seq.get(), p[0], p[1], i, dim + 1));
                    dim += 2;
                }
                CHECK(u[0] >= 0 && u[0] < 1 && u[1] >= 0 && u[1] < 1, "%s: value outside [0, 1)", preset);
            }
            // a restart at a given dimension (pbrt-v4's wavefront integrator), and one below 2
            a.start(p[0], p[1], i, 9);
            mismatches += !same(a.one(), reference(seq.get(), p[0], p[1], i, 9));
            a.start(p[0], p[1], i, 1);
            mismatches += !same(a.one(), reference(seq.get(), p[0], p[1], i, 2));
        }
    CHECK(mismatches == 0, "%s/%s: %d values differ from the cursor's", preset, randomization, mismatches);
}

void check_refusals()
{
    uint32_t r = 12345;
    CHECK(!udm1pbrt::randomization_from_name("owen-ish", &r) && r == 12345, "an unknown randomization accepted");
    std::string error;
    CHECK(!udm1pbrt::create_sequence("no-such-preset", UDM1_RANDOMIZE_DEFAULT, 0, 16, &error), "unknown preset");
    CHECK(error.find("no-such-preset") != std::string::npos, "the error does not name the preset: %s", error.c_str());
    error.clear();
    // screen-space randomization is for the Weyl sequences: the library's own refusal, passed on
    CHECK(!udm1pbrt::create_sequence("halton", UDM1_RANDOMIZE_SCREEN, 0, 16, &error) && !error.empty(),
          "screen randomization of halton accepted");
}

}  // namespace

int main()
{
    check_sequence("wr", "default", 16);
    check_sequence("wr", "screen", 16);
    check_sequence("wr", "none", 16);
    check_sequence("rd", "shift", 8);
    check_sequence("wmmr", "default", 16);
    check_sequence("hwmmr", "screen", 64);
    check_sequence("sobol-owen", "default", 16);
    check_sequence("sobol", "permute", 16);
    check_sequence("halton", "owen", 16);
    check_sequence("pmj02", "default", 16);
    check_sequence("pcg32", "default", 16);
    check_refusals();
    if (failures) {
        std::fprintf(stderr, "test_pbrt_sampler: %d failure(s)\n", failures);
        return 1;
    }
#if defined(UDM1_TEST_PATCHED_PBRT)
    std::printf("pbrt-v4's UDM1Sampler (patched snapshot) equals udm1's cursor: ok\n");
#else
    std::printf("udm1_pbrt_sampler.h equals udm1's cursor: ok\n");
#endif
    return 0;
}
