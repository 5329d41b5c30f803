// wavefront_general.h - udm1-pt's wavefront loop for every scene it renders (every shape, material,
// texture, light and camera; every strategy): many paths at a time, one Embree SOA stream per bounce for
// their closest hits and one per bounce for their shadow rays, and each path's vertex through the
// estimator of estimator.h, in double, path by path. The scalar loop calls the same estimator in the same
// order on the same values, and Embree's streams return the hits of its single queries, so the two loops
// render the same image, bit for bit (tests/cpp/test_pt.cpp); what differs is how Embree is asked.
//
// The scenes of the diffuse subset (wavefront_diffuse.h) have a faster wavefront loop of their own, shading in float
// SIMD; this one is the rest's.
#pragma once

#include "estimator.h"
#include "udm1app/pixel_order.h"

namespace udm1pt {

class GeneralWavefront {
public:
    GeneralWavefront(const udm1scene::EmbreeScene &rt, const Estimator &estimator) : rt_(rt), estimator_(estimator) {}
    // Traces the samples [first, first + count) of the pixels [x0, x1) x [y0, y1) and adds them, as the
    // film makes them (FilmResponse), to acc's fixed-point sums (as the scalar loop does). Safe from many
    // threads at once for disjoint pixels. seq: the render's sequence, of stream_dims(max_depth) dimensions or fewer.
    // order: how the pixels' samples are named to the library (udm1app/pixel_order.h).
    void render(const udm1_seq *seq, const udm1app::PixelOrder &order, int max_depth,
                const udm1scene::CameraRays &camera, int x0, int x1, int y0, int y1, uint64_t first, uint64_t count,
                const FilmResponse &film, Accumulator *acc, LoopCounts *counts) const;

private:
    class Batch;  // a thread's batch of paths through the stages of a bounce (wavefront_general.cpp)
    const udm1scene::EmbreeScene &rt_;
    const Estimator &estimator_;
};

}  // namespace udm1pt
