// ao_render.h - ambient occlusion as the paper defines it (section 4.2):
// A(p) = (1/pi) * integral over the hemisphere of V(p, w) cos(theta) dw,
// estimated per pixel with a udm1 sampler's 2D points mapped to
// cosine-weighted directions, so that A = E[V]: each pixel's integrand is 2D.
#pragma once

#include "embree_scene.h"

#include "udm1app/partial_image.h"

#include <udm1/udm1.h>

#include <string>
#include <vector>

namespace udm1ao {

enum class Method { Single, Packet, Stream };  // how occlusion rays go to Embree

struct Options {
    std::string sampler = "episwr";  // the paper's best AO set
    uint32_t spp = 64;               // the whole render's samples per pixel (point sets use K = spp)
    uint32_t first = 0, count = 0;   // this run's sample indices [first, first + count); count 0: up to spp
    int bounds[4] = {0, 0, 0, 0};    // the pixels rendered: [x0, x1) x [y0, y1); all zero: every pixel
    uint64_t seed = 1;
    uint32_t randomize = UDM1_RANDOMIZE_DEFAULT;
    int width = 0, height = 0;       // 0: 256 x 256 for built-in scenes, else the scene's film
    double max_distance = 1e300;     // occlusion ray length
    bool jitter = false;             // the 4D variant: dims 0,1 jitter the primary ray, 2,3 the direction
    uint32_t direction_dim = 0;      // without jitter: the direction from dims (D, D + 1), D even
    Method method = Method::Stream;  // the fastest here (bench/bench_ao.cpp, BENCHMARKS.md)
};

struct Stats {
    double seconds = 0;
    uint64_t rays = 0;  // primary and occlusion rays
};

struct Image {
    int width = 0, height = 0;  // the window rendered (the whole image unless opt.bounds says otherwise)
    std::vector<float> values;  // row-major, top row first: unoccluded rays / rays
    udm1app::PartialImage sums; // the same as exact counts of unoccluded rays (channel "A"): ranges and
                                // tiles of one render merge exactly (udm1app/partial_image.h)
};

// Render the AO image. The result depends only on the options (not on threads or tiles).
// Throws std::runtime_error with udm1's message for a bad sampler, spp, range or window.
Image render(const udm1scene::Scene &scene, const udm1scene::EmbreeScene &rt, const Options &opt, Stats *stats);

// The AO estimate at one point p with normal n (facing the side sampled), from points
// [0, spp) of stream `stream`, dimensions (dim0, dim0 + 1). For tests and embedding.
double ao_at(const udm1scene::EmbreeScene &rt, udm1scene::Vec3 p, udm1scene::Vec3 n, const udm1_seq *seq,
             uint64_t stream, uint32_t spp, uint32_t dim0, double max_distance, Method method);

// Cosine-weighted direction around n from (u1, u2) in [0, 1)^2.
udm1scene::Vec3 cosine_direction(udm1scene::Vec3 n, double u1, double u2);

// The sampler for AO: `opt.sampler` with the dimensions AO needs and K = spp for point sets.
udm1_seq *make_sampler(const Options &opt);

}  // namespace udm1ao
