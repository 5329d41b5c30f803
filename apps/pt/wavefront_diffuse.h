// wavefront_diffuse.h - udm1-pt's path loop for the scenes of the common subset, many paths at a time: the
// same estimator, dimension layout and sampler points as the scalar loop (integrator.h), traced in
// batches of up to 4096 paths with one Embree SOA stream per bounce for the closest hits (over the
// paths' own origin and direction arrays; camera rays flagged coherent) and one for the shadow rays,
// the sampler's values from each path's domains (one stream per pixel of the tile), the light choice
// (Lights::choose, path by path) and the shading (light sample, MIS, BSDF sample,
// roulette, next ray) in loops over the live paths that the compiler vectorizes.
//
// The subset: triangle meshes without vertex normals, untextured diffuse materials without bump maps,
// triangle area lights (no LightSource), a pinhole camera, MIS (--strategy mis). Everything else - spheres, coated,
// metal, glass, mixes, textures, vertex normals, a thin lens, the single-strategy estimators - goes
// through the scalar loop. Light sampling by solid angle near a light is done in double by Lights, path
// by path, as in the scalar loop (a vectorized test with a margin picks the paths Lights decides for);
// everything else in float.
//
// Each path's result depends only on its own pixel, sample index and the scene: not on which other
// paths share its batch (Embree's stream and single queries return the same hits, and the vectorized
// loop does the same float operations in every lane), so images stay bit-identical across thread
// counts and split sample ranges. They are not bit-identical to the scalar loop's (float against
// double arithmetic): the two agree in the mean and per pixel within rounding (tests/cpp/test_pt.cpp).
#pragma once

#include "integrator.h"
#include "udm1app/pixel_order.h"

#include <string>
#include <vector>

namespace udm1pt {

// Why the wavefront loop cannot render (scene, opt), in a few words naming the first shape, material
// or option outside its subset; empty if it can.
std::string diffuse_wavefront_unsupported(const udm1scene::Scene &scene, const Options &opt);

class DiffuseWavefront {
public:
    // The scene must be in the subset (diffuse_wavefront_unsupported() empty).
    DiffuseWavefront(const udm1scene::Scene &scene, const udm1scene::EmbreeScene &rt, const Materials &materials,
              const Lights &lights, int max_depth, bool roulette, int rr_depth);

    // Traces the samples [first, first + count) of the pixels [x0, x1) x [y0, y1) and adds them, as the
    // film makes them (FilmResponse), to acc's fixed-point sums (as the scalar loop does). Safe from many
    // threads at once for disjoint pixels.
    // order: how the pixels' samples are named to the library (udm1app/pixel_order.h).
    void render(const udm1_seq *seq, const udm1app::PixelOrder &order, const udm1scene::CameraRays &camera, int x0,
                int x1, int y0, int y1, uint64_t first, uint64_t count, const FilmResponse &film, Accumulator *acc,
                LoopCounts *counts) const;

    // Per triangle (its geometry's first entry + the triangle's index) and per light: what the loop reads.
    struct Triangles {
        std::vector<size_t> first;                   // Embree geometry ID -> its shape's first triangle's entry
        std::vector<float> nx, ny, nz, rr, rg, rb;  // unit geometric normal; diffuse reflectance / pi
        std::vector<int> light;                      // the triangle's light (Lights' index), or -1
    };
    struct LightArrays {  // triangle lights, structure of arrays, in float
        std::vector<float> x0, y0, z0, x1, y1, z1, x2, y2, z2, nx, ny, nz, area, er, eg, eb;
        std::vector<int> twosided;
    };

    struct LightNear {  // per light: centroid and area, for the test of whether Lights may sample it by solid angle
        std::vector<double> cx, cy, cz, area;
        double near = 0;  // Lights::near()
    };
    // Lights::choose as tables where it does not depend on the point (Lights::fixed_choice): the lights
    // [first, first + cdf.size()), their power CDF, each one's interval [lo, hi) and probability, and the
    // light of each count of CDF entries <= target (past the lights of no power)
    struct LightChoice {
        bool fixed = false;
        size_t first = 0;
        std::vector<double> cdf, lo, hi;
        std::vector<float> prob;
        std::vector<int> pick;
    };

private:
    class Batch;  // a thread's batch of paths through the stages of a bounce (wavefront.cpp)
    const udm1scene::Scene &scene_;
    const udm1scene::EmbreeScene &rt_;
    const Lights &lights_;
    int max_depth_, rr_depth_;
    bool roulette_;
    Triangles tri_;
    LightArrays lights_f_;
    LightNear near_;
    LightChoice choice_;
};

}  // namespace udm1pt
