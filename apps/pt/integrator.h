// integrator.h - unidirectional path tracing with next-event estimation and
// multiple importance sampling (power heuristic), Russian roulette and a maximum
// depth, as pbrt-v4's "path" integrator, in RGB. Loops of two kinds trace it, with the same estimator and
// sampler points (Options::loop chooses): the scalar loop (one path and one Embree query at a time, in
// double, estimator.h) and the wavefront loop (many paths at a time, one Embree stream per bounce). The
// wavefront loop shades in float SIMD where the scene is in the diffuse subset (wavefront_diffuse.h) and
// otherwise through the scalar loop's own estimator, path by path (wavefront_general.h).
//
// The sampler's values: one udm1 domain tree per path (udm1/domain.h), so that no dimension is counted by
// hand. Sample i of pixel p is the root domain udm1_domain_root(stream of p, i):
//   root                 2 values: the position on the film, placed by the pixel filter (FilmResponse::sampler,
//                        pbrt-v4's filter importance sampling); 4 with a thin lens (2, 3: lens)
//   next(root, 1 + d)    the vertex of depth d (0, 1, ..., maxdepth - 1) that scatters, 4 values: 0, 1
//                        next-event estimation (0 picks the light by power and, rescaled, gives with 1 the
//                        point on it), 2, 3 the BSDF direction
//   child(that, 0)       2 values: the BSDF lobe or layer, Russian roulette
// and, where a path meets participating media (estimator.h, the volumetric estimator):
//   child(root, 0)       1 value: the path's hero channel (media sample distances by its coefficients)
//   child(next(root, 1 + d), 1 + k)   2 values: the distance to an interaction and its kind (absorption or
//                        scattering) along the k-th piece (k = 0, 1, ... : the interface surfaces passed
//                        before it) of the ray that finds vertex d; a vertex in a medium takes the vertex's
//                        four values as a surface does (light, then the phase function's direction). In a grid
//                        medium the first is the first tentative collision's distance and the second seeds the
//                        delta tracking's further values (grid_medium.h, TrackingRandom), as pbrt-v4 seeds its
//                        RNG; a shadow ray's ratio tracking is seeded by its light sample's two values
// The chain of next() is one jointly low-discrepancy pattern: the sequence's dimensions 0 .. 4 + 4 d + 3
// at the sample's index, as a cursor would hand them out (a Kronecker sequence's point of the whole
// path); the lobe and roulette values are decorrelated children, which draw the sequence's first two
// dimensions again (its best projection: a chain of 8 dimensions per vertex measured 8-19 % more error
// with Sobol and up to twice with R_d at 256-1024 spp, bench/bench_pt.py). Past the sequence's dimensions
// the values are padded (WMMR and HWMMR have 22): random, not low-discrepancy.
#pragma once

#include "bsdf.h"
#include "embree_scene.h"
#include "lights.h"
#include "material.h"
#include "scene.h"

#include "udm1app/partial_image.h"

#include <udm1/udm1.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace udm1pt {

// Changes whenever the estimator or the dimension layout above changes (cached references are
// reused only when it matches).
constexpr int LAYOUT_VERSION = 9;

// The dimensions a path of a maximum depth draws: the chain of next() (the lobe and roulette are children).
inline uint32_t path_dims(int max_depth) { return 4 + 4 * (uint32_t)max_depth; }

// The dimensions a pixel's stream holds: the path's, at most UDM1_STREAM_DIMS (farther ones draw through
// the library).
inline uint32_t stream_dims(int max_depth)
{
    uint32_t d = path_dims(max_depth);
    return d < UDM1_STREAM_DIMS ? d : UDM1_STREAM_DIMS;
}

// The six values of the vertex of depth `depth` of sample `index` of a pixel's stream (layout above):
// u[0], u[1] light, u[2] lobe, u[3] roulette, u[4], u[5] BSDF direction.
// Both loops call it once per vertex, the wavefront loop for every path of a batch: it takes the pixel's
// stream and the sample index, not a root domain, so that no 32-byte domain crosses a call (a domain
// passed through the stack costs a store-forwarding stall per call).
inline void vertex_values(const udm1_stream *pixel, uint64_t index, int depth, double u[6])
{
    udm1_domain vertex = udm1_domain_next(udm1_domain_root(pixel, index), 1 + (uint32_t)depth);
    double a[4], b[2];
    udm1_domain_draw_f64(vertex, 4, a);                        // light (a[0], a[1]), BSDF direction (a[2], a[3])
    udm1_domain_draw_f64(udm1_domain_child(vertex, 0), 2, b);  // lobe, roulette
    u[0] = a[0], u[1] = a[1], u[2] = b[0], u[3] = b[1], u[4] = a[2], u[5] = a[3];
}

// The two values of the k-th piece of the ray that finds vertex `depth` in a medium (layout above): the
// distance, the kind of interaction.
inline void segment_values(const udm1_stream *pixel, uint64_t index, int depth, int piece, double u[2])
{
    udm1_domain vertex = udm1_domain_next(udm1_domain_root(pixel, index), 1 + (uint32_t)depth);
    udm1_domain_draw_f64(udm1_domain_child(vertex, 1 + (uint32_t)piece), 2, u);
}

// How light is found: both (MIS), light sampling only, BSDF sampling only (which cannot find point, spot
// and distant lights: with Bsdf they are left out).
enum class Strategy { Mis, Nee, Bsdf };
// Which path loop traces: the wavefront loop (Auto, Wavefront) or the scalar loop, its reference (Scalar).
enum class Loop { Auto, Scalar, Wavefront };

// What a loop counts while it renders.
struct LoopCounts {
    uint64_t rays = 0, nonfinite = 0, clamped = 0;
};

struct Options {
    std::string sampler = "sobol-owen";
    uint32_t spp = 16;        // the whole render's samples per pixel (point sets use K = spp)
    uint64_t first = 0;       // this run's range of sample indices: [first, first + count)
    uint64_t count = 0;       // 0: all of [first, spp)
    int bounds[4] = {0, 0, 0, 0};  // the pixels rendered: [x0, x1) x [y0, y1); all zero: every pixel
    uint64_t seed = 1;
    uint32_t randomize = UDM1_RANDOMIZE_DEFAULT;
    int width = 0, height = 0;  // the image (0: the scene's film)
    // A crop of a film: the film's size and the image's place in it (0: the image is the whole film)
    int film_width = 0, film_height = 0, film_x0 = 0, film_y0 = 0;
    int max_depth = -1;         // -1: the scene's Integrator maxdepth (pbrt's default 5)
    Strategy strategy = Strategy::Mis;
    bool roulette = true;
    int rr_depth = 3;           // roulette from this vertex on (0 = the first hit; pbrt-v4 starts at 1)
    double near_light = Lights::NEAR_DEFAULT;  // see Lights; `bench/bench_pt.py --estimators` measures both
    Loop loop = Loop::Auto;
};

// What the film makes of a path's radiance L before it is summed, as pbrt-v4's RGB film adds a sample: the
// imaging ratio (Scene::film_scale), then Film "maxcomponentvalue" m: the sample scaled so that the largest
// of its sensor values - CIE X, Y and Z for the default cie1931 sensor - is at most m, then the sensor's white
// balance (Film "whitebalance", pbrt-v4's outputRGBFromSensorRGB). And where a sample
// lies on the film: the pixel filter (udm1scene::FilmSampler) places it and gives its weight's sign; with
// negative lobes (weighted) the pixel's sums hold a fourth channel W, the sum of the signs, and the pixel is
// the weighted mean (sum of sign L) / W, as pbrt-v4's film divides by its sum of weights.
struct FilmResponse {
    explicit FilmResponse(const udm1scene::Scene &scene);
    Vec3 operator()(Vec3 L) const
    {
        L = L * scale;
        if (clamp) {
            double m = std::max({udm1scene::dot(xyz[0], L), udm1scene::dot(xyz[1], L), udm1scene::dot(xyz[2], L)});
            if (m > max_component) L = L * (max_component / m);
        }
        if (balance) L = Vec3(udm1scene::dot(wb[0], L), udm1scene::dot(wb[1], L), udm1scene::dot(wb[2], L));
        return L;
    }
    double scale, max_component;
    bool clamp;
    Vec3 xyz[3];  // the rows of XYZ from linear sRGB
    bool balance;  // Film "whitebalance": wb, the adaptation on linear sRGB (udm1scene::white_balance_rgb), after the clamp
    Vec3 wb[3];
    udm1scene::FilmSampler sampler;
    bool weighted;  // sampler.signed_weights(): the sums hold W
    size_t stride;  // channels per pixel of the sums: 3 (R, G, B) or 4 (and W)
};

// The pixel's 2D sample of sample `index` (the root domain's first two values) drawn again and placed by the
// filter: the sign of its weight (for the loops that keep no sign per path).
inline int sample_sign(const FilmResponse &film, const udm1_stream *pixel, uint64_t index)
{
    double u[2];
    udm1_domain_draw_f64(udm1_domain_root(pixel, index), 2, u);
    return film.sampler.place(u);
}

// Per-pixel sums of the samples in fixed point (2^-24 units, int64, channels R, G, B), so that sums
// of disjoint sample ranges and tiles add up exactly: split and whole runs give the same image bit
// for bit (udm1app/partial_image.h).
using Accumulator = udm1app::PartialImage;
constexpr double SAMPLE_SCALE = 16777216.0;  // 2^24
constexpr double MAX_SAMPLE = 1e9;           // larger sample values are clamped (and counted)

// A sample's film value L (FilmResponse) into its pixel's sums px: each finite channel, clamped to MAX_SAMPLE, in
// fixed point times the sign of the filter's weight, and that sign into W where the film is weighted; a non-finite
// channel counts as 0 (pbrt-v4 zeroes such a sample's radiance) and is counted.
inline void add_sample(int64_t *px, Vec3 L, int sign, bool weighted, uint64_t *nonfinite, uint64_t *clamped)
{
    for (int k = 0; k < 3; ++k) {
        double v = L[k];
        if (!std::isfinite(v)) {
            ++*nonfinite;
            continue;
        }
        if (v > MAX_SAMPLE) v = MAX_SAMPLE, ++*clamped;
        int64_t q = (int64_t)std::llround(v * SAMPLE_SCALE);
        px[k] += sign < 0 ? -q : q;
    }
    if (weighted) px[3] += sign < 0 ? -(int64_t)SAMPLE_SCALE : (int64_t)SAMPLE_SCALE;
}

struct Stats {
    double seconds = 0;
    uint64_t paths = 0, rays = 0;  // camera paths; all rays (camera, continuation, shadow)
    uint32_t dimensions = 0;       // the sampler's own dimensions (the rest padded)
    uint32_t path_dimensions = 0;  // what a path of maximum depth uses
    const char *loop = "scalar";   // which loop traced: scalar, wavefront (diffuse, float SIMD), wavefront-general
};

// The sampler of a render: opt's preset, seed and randomization, min(dims, the preset's maximum)
// dimensions (at least 2), K = spp for point sets. Throws std::runtime_error (unknown sampler, bad
// parameters).
using Sequence = std::shared_ptr<const udm1_seq>;
Sequence make_sequence(const Options &opt, uint32_t dims);

// Throws std::runtime_error with a one-line message (unknown sampler, bad range, material, a forced
// wavefront loop on a scene outside its subset).
Accumulator render(const udm1scene::Scene &scene, const udm1scene::EmbreeScene &rt, const Options &opt, Stats *stats);
// The same with the scene's materials (and their textures) made once by the caller.
Accumulator render(const udm1scene::Scene &scene, const udm1scene::EmbreeScene &rt, const Materials &materials,
                   const Options &opt, Stats *stats);


}  // namespace udm1pt
