// estimator.h - the path estimator of integrator.h one vertex at a time, so that any loop can drive it:
// the scalar loop (integrator.cpp: one path, one Embree query at a time) and the batched loop
// (wavefront_general.h: many paths, one Embree stream per bounce) call the same code in the same order
// on the same double values, and so render the same image.
//
// A path is a PathState. For each ray it traces, its loop calls miss() (the ray left the scene) or
// scatter() (it hit h): emission found (MIS against the BSDF sample that found it), then, unless the
// path is at its maximum depth, this vertex's sampler values, the material, a light sample whose shadow
// ray scatter() hands back as a ShadowTest, and the BSDF sample that sets the next ray (roulette
// included). The loop answers the ShadowTest (is its segment free?) and calls arrive() for a free one
// before it traces the next ray: the light sample's MIS weight is computed only for a sample that
// arrives, as the scalar loop always did.
#pragma once

#include "integrator.h"

namespace udm1pt {

// A path between two vertices.
struct PathState {
    const udm1_stream *pixel = nullptr;  // the pixel's sampler stream (integrator.h)
    uint64_t index = 0;                  // the sample index
    Vec3 o, d;                           // the next ray
    Vec3 L, beta{1, 1, 1};               // radiance so far, throughput
    Vec3 prev_p, prev_n;                 // the last vertex and its geometric normal (MIS at a light the next ray hits)
    double importance_sum = NAN;         // the lights' importances at the last vertex, if its light sample made them
    double p_b = 0;                      // the BSDF sample's density there
    double eta_scale = 1;                // the product of eta^2 over transmissions: roulette sees beta without it (pbrt)
    bool specular_bounce = false;
    int depth = 0;                       // the vertex the next ray finds
};

// A light sample's shadow ray and what it adds to L if the segment is free.
struct ShadowTest {
    bool active = false;
    bool sphere = false;    // a sphere light: the segment is free if the first hit on it is the light's shape
    int shape = -1;         // (that shape)
    Vec3 o, d;              // origin, unit direction
    double len = 0;         // the segment's length
    // the contribution beta f L / pdf and its MIS weight's inputs (the weight is made by arrive())
    Vec3 beta_f, Li;
    double pdf = 0;
    bool weighted = false;  // MIS against the BSDF's density (else weight 1)
    Bsdf bsdf;              // the vertex's BSDF and directions, for that density
    Vec3 wo_l, wi_l;
};

class Estimator {
public:
    Estimator(const udm1scene::Scene &scene, const Lights &lights, const Materials &materials, int max_depth,
              Strategy strategy, bool roulette, int rr_depth)
        : scene_(scene), lights_(lights), materials_(materials), default_bsdf_(default_material()),
          max_depth_(max_depth), strategy_(strategy), roulette_(roulette), rr_depth_(rr_depth)
    {
    }
    // The ray p.o + t p.d left the scene: the environment's light, if any. The path ends.
    void miss(PathState &p) const;
    // The ray hit h. Fills *shadow (inactive if there is no light sample to test). Returns whether the path
    // goes on (p.o, p.d the next ray, p.depth one more).
    bool scatter(PathState &p, const udm1scene::Hit &h, ShadowTest *shadow) const;
    // The shadow test's segment is free: its light sample's contribution into p.L.
    void arrive(PathState &p, const ShadowTest &s) const;

private:
    const udm1scene::Scene &scene_;
    const Lights &lights_;
    const Materials &materials_;
    Bsdf default_bsdf_;  // of a shape without a material
    int max_depth_;
    Strategy strategy_;
    bool roulette_;
    int rr_depth_;
};

}  // namespace udm1pt
