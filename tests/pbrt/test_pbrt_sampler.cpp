// test_pbrt_sampler.cpp - udm1's sampler for pbrt-v4 gives the library's values. Built twice: against
// the adapter alone (integrations/pbrt-v4/udm1_pbrt_sampler.h, every test run), and with
// UDM1_TEST_PATCHED_PBRT against pbrt-v4's own sampler class, pbrt::UDM1Sampler, from the snapshot in
// ../shared/anchors with integrations/pbrt-v4/udm1-sampler.patch applied (tests/pbrt/check_patch.sh, skipped
// where the snapshot is absent). Every value is compared with udm1's cursor (an independent path through
// the library: udm1_cursor_start at the pixel's stream, sample and dimension), bit for bit: pixel
// positions from dimensions 0 and 1, Get1D / Get2D from dimension 2 on or from a dimension the caller
// restarts at, past the 64 dimensions a stream holds and past the sequence's own, for Weyl, base-2 and
// PRNG presets, every randomization pbrt's scene file may name, pixels revisited out of order.
// And every combination, against the library's fills: each preset (and its "+tent") with each
// randomization, made from the scene's parameters (create_for_scene) and compared, at random pixels,
// sample indices and restart dimensions, with udm1_seq_fill_points_f64 and udm1_seq_sample_f32 of a
// sequence made here from the documented layout (udm1_seq_create_desc: D = min(the preset's, 64), K =
// the samples per pixel for a point set, screen's N = the samples per pixel); a combination the library
// refuses, or the adapter (fewer than 2 dimensions), is refused with one line, as are bad seeds and
// sample counts.
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
#undef CHECK  // (pbrt's own, with the patched sources)
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

// SplitMix64: the test's random pixels, indices and dimensions (reproducible).
struct Random {
    uint64_t s;
    uint64_t next()
    {
        uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    uint64_t below(uint64_t n) { return next() % n; }
    // a generator of its own per name (FNV-1a of the name)
    static Random of(const std::string &name)
    {
        uint64_t h = 0xCBF29CE484222325ull;
        for (unsigned char c : name) h = (h ^ c) * 0x100000001B3ull;
        return Random{h};
    }
};

const char *const RANDOMIZATIONS[] = {"default", "none", "shift", "permute", "owen", "screen"};

// The sequence a scene's parameters stand for, made here from the adapter's documented layout; null
// where the library refuses it.
udm1_seq *reference_sequence(const std::string &preset, uint32_t randomize, uint64_t seed, uint32_t spp)
{
    udm1_preset_info info;
    if (udm1_preset_find(preset.c_str(), &info) != UDM1_OK) return nullptr;
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    desc.preset = preset.c_str();
    desc.dimensions = info.max_dimensions < 64 ? info.max_dimensions : 64;
    desc.point_count = (info.flags & UDM1_PRESET_POINT_SET) ? spp : 0;
    desc.seed = seed;
    desc.randomize = randomize;
    desc.screen_spp = randomize == UDM1_RANDOMIZE_SCREEN ? spp : 0;
    udm1_seq *seq = nullptr;
    return udm1_seq_create_desc(&desc, &seq) == UDM1_OK ? seq : nullptr;
}

// The library's values of dimensions [dim, dim + n) of sample i of pixel (x, y): the many-points fill
// (doubles, converted to floats as udm1/seq.h documents: exactly the top 24 bits) and, inside the
// sequence's dimensions, the per-sample call.
void library_values(const udm1_seq *seq, int x, int y, uint64_t i, uint32_t dim, uint32_t n, double *f64, float *f32)
{
    uint64_t stream = ((uint64_t)(uint32_t)y << 32) | (uint32_t)x;
    CHECK(udm1_seq_fill_points_f64(seq, 1, &stream, &i, dim, n, f64) == UDM1_OK, "fill_points: %s", udm1_last_error());
    for (uint32_t k = 0; k < n; ++k) {
        f32[k] = (float)(std::floor(f64[k] * 16777216.0) / 16777216.0);
        float v;
        if (dim + k < udm1_seq_dimensions(seq) && udm1_seq_sample_f32(seq, stream, i, dim + k, &v) == UDM1_OK)
            CHECK(same(v, f32[k]), "sample_f32 and fill_points differ at dim %u", dim + k);
    }
}

bool one_line(const std::string &s) { return !s.empty() && s.find('\n') == std::string::npos; }

// Every preset (and its +tent) x every randomization, from a scene's parameters.
void check_every_combination()
{
    const int spp = 16;
    int combinations = 0, refused = 0;
    for (size_t p = 0; p < udm1_preset_count(); ++p) {
        udm1_preset_info info;
        udm1_preset_get(p, &info);
        for (int tent = 0; tent < 2; ++tent) {
            std::string preset = std::string(info.name) + (tent ? "+tent" : "");
            for (const char *randomization : RANDOMIZATIONS) {
                uint32_t randomize = 0;
                udm1pbrt::randomization_from_name(randomization, &randomize);
                Random rng = Random::of(preset + "/" + randomization);
                long long seed = (long long)rng.below(0x80000000ull);
                std::string error;
                udm1pbrt::SharedSeq seq = udm1pbrt::create_for_scene(preset, randomization, seed, spp, &error);
                udm1_seq *ref = reference_sequence(preset, randomize, (uint64_t)seed, spp);
                ++combinations;
                if (!ref || info.max_dimensions < 2) {  // refused by the library, or by the adapter
                    ++refused;
                    CHECK(!seq, "%s/%s: accepted, but the library (or the pixel's 2 dimensions) refuses it",
                          preset.c_str(), randomization);
                    bool named = error.find("udm1 sampler: ") == 0 && error.find(preset) != std::string::npos;
                    CHECK(one_line(error) && named, "%s/%s: the refusal is not one line naming the preset: '%s'",
                          preset.c_str(), randomization, error.c_str());
                    udm1_seq_destroy(ref);
                    continue;
                }
                CHECK(seq != nullptr, "%s/%s: refused: %s", preset.c_str(), randomization, error.c_str());
                if (!seq) {
                    udm1_seq_destroy(ref);
                    continue;
                }
                Sampler a(seq, spp);
                int mismatches = 0;
                for (int t = 0; t < 12; ++t) {
                    // pixels near the origin and anywhere in pbrt's int range; samples in [0, spp), and for a
                    // sequence any int; a pass from the pixel's dimensions, then a restart at a random one
                    int x = (int)(t % 3 ? rng.below(64) : rng.below(0x80000000ull));
                    int y = (int)(t % 4 ? rng.below(64) : rng.below(0x80000000ull));
                    bool point_set = info.flags & UDM1_PRESET_POINT_SET;
                    int i = (int)(t % 5 == 4 && !point_set ? rng.below(0x80000000ull) : rng.below(spp));
                    uint32_t restart = (uint32_t)rng.below(150);
                    double f64[80];
                    float f32[80];
                    a.start(x, y, i, 0);
                    Float u[2];
                    a.pixel(u);
                    library_values(ref, x, y, (uint64_t)i, 0, 80, f64, f32);
                    mismatches += !same(u[0], (Float)f32[0]) + !same(u[1], (Float)f32[1]);
                    for (uint32_t dim = 2; dim < 78;) {  // past the 64 a stream holds and past D
                        if (rng.below(2)) {
                            mismatches += !same(a.one(), (Float)f32[dim]);
                            dim += 1;
                        } else {
                            a.two(u);
                            mismatches += !same(u[0], (Float)f32[dim]) + !same(u[1], (Float)f32[dim + 1]);
                            dim += 2;
                        }
                    }
                    a.start(x, y, i, (int)restart);
                    uint32_t first = restart > 2 ? restart : 2;
                    library_values(ref, x, y, (uint64_t)i, first, 3, f64, f32);
                    mismatches += !same(a.one(), (Float)f32[0]);
                    a.two(u);
                    mismatches += !same(u[0], (Float)f32[1]) + !same(u[1], (Float)f32[2]);
#if !defined(UDM1_TEST_PATCHED_PBRT)
                    // the double draws (pbrt built with PBRT_FLOAT_AS_DOUBLE)
                    udm1pbrt::PixelSampler d(seq);
                    d.start(x, y, i, (int)restart);
                    double w[2];
                    mismatches += d.get1d<double>() != f64[0];
                    d.get2d(w);
                    mismatches += w[0] != f64[1] || w[1] != f64[2];
                    d.pixel2d(w);
                    library_values(ref, x, y, (uint64_t)i, 0, 2, f64, f32);
                    mismatches += w[0] != f64[0] || w[1] != f64[1];
#endif
                }
                CHECK(mismatches == 0, "%s/%s: %d values differ from the library's", preset.c_str(), randomization,
                      mismatches);
                udm1_seq_destroy(ref);
            }
        }
    }
    CHECK(combinations == (int)udm1_preset_count() * 2 * 6 && refused > 0 && refused < combinations,
          "%d combinations, %d refused", combinations, refused);
}

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
    // a scene's parameters: each bad one refused with one line naming it (pbrt's ints are 32-bit: a negative
    // seed is not wrapped to a large one, a count of 0 or less is not a sample count)
    const struct {
        const char *preset, *randomization;
        long long seed, spp;
        const char *named;
    } bad[] = {{"wr", "owen-ish", 0, 16, "randomization 'owen-ish'"},
               {"wr", "", 0, 16, "randomization ''"},
               {"wr", "default", -1, 16, "seed -1"},
               {"wr", "default", -2147483648LL, 16, "seed -2147483648"},
               {"wr", "default", 1LL << 31, 16, "seed 2147483648"},
               {"wr", "default", 0, 0, "pixelsamples 0"},
               {"wr", "default", 0, -16, "pixelsamples -16"},
               {"wr", "default", 0, 1LL << 31, "pixelsamples 2147483648"},
               {"nope", "default", 0, 16, "nope"},
               {"golden", "default", 0, 16, "golden"},
               {"epis+tent", "shift", 0, 16, "epis+tent"},
               {"pmj02", "default", 0, 1 << 20, "pixelsamples 1048576"},
               {"lattice", "default", 0, (1 << 24) + 1, "pixelsamples 16777217"},
               {"sobol", "screen", 0, 16, "randomization 'screen'"}};
    for (const auto &b : bad) {
        error.clear();
        udm1pbrt::SharedSeq seq = udm1pbrt::create_for_scene(b.preset, b.randomization, b.seed, b.spp, &error);
        CHECK(!seq && one_line(error) && error.find(b.named) != std::string::npos,
              "%s/%s seed %lld spp %lld: %s, error '%s'", b.preset, b.randomization, b.seed, b.spp,
              seq ? "accepted" : "refused", error.c_str());
    }
    // the largest accepted: seed and samples 2^31 - 1 (a sequence)
    CHECK(udm1pbrt::create_for_scene("wr", "owen", 2147483647LL, 2147483647LL, &error) != nullptr, "%s", error.c_str());
    // a sample index past a point set's K draws NaN (the library refuses it), never another point
    udm1pbrt::SharedSeq set = udm1pbrt::create_for_scene("hammersley", "default", 3, 8, &error);
    if (set) {
        Sampler s(set, 8);
        s.start(1, 2, 8, 0);
        Float u[2];
        s.pixel(u);
        CHECK(std::isnan(u[0]) && std::isnan(u[1]) && std::isnan(s.one()), "index 8 of an 8-point set drew values");
    }
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
    check_every_combination();
    if (failures) {
        std::fprintf(stderr, "test_pbrt_sampler: %d failure(s)\n", failures);
        return 1;
    }
#if defined(UDM1_TEST_PATCHED_PBRT)
    std::printf("pbrt-v4's UDM1Sampler (patched snapshot) equals udm1's cursor and fills: ok\n");
#else
    std::printf("udm1_pbrt_sampler.h equals udm1's cursor and fills: ok\n");
#endif
    return 0;
}
