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
//
// Scenes with participating media (Integrator "volpath") or interface surfaces take the volumetric
// estimator (volumetric() true), pbrt-v4's VolPathIntegrator in RGB: its loop
// calls start() once per path, then step() for each ray it traces (with the hit, or nullptr for a miss),
// and answers a ShadowTest whose `walk` is set segment by segment: it finds the first surface on the
// segment (closest hit) and calls cross(), until cross() says the sample arrived (then arrive()) or is
// blocked. In a homogeneous medium a path samples the distance to its next interaction by one channel, the
// path's hero channel, chosen once per path; every channel's estimate is weighted by the average of the
// channels' densities (one-sample MIS across channels, the RGB counterpart of pbrt-v4's hero wavelength).
// Light sampling and BSDF or phase sampling are combined by the balance heuristic through pbrt-v4's
// rescaled path probabilities r_u and r_l; shadow rays take the exact transmittance exp(-sigma_t d), so
// do paths through media that only absorb, and a medium's emission along a segment is integrated exactly.
#pragma once

#include "grid_medium.h"
#include "integrator.h"

#include <memory>

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
    // the volumetric estimator's own (pbrt-v4's VolPathIntegrator state, in RGB)
    Vec3 r_u{1, 1, 1}, r_l{1, 1, 1};     // rescaled path probabilities: of the path as sampled, of light sampling
    int medium = -1;                     // the medium the next ray starts in (Scene::media), or -1
    int hero = 0;                        // the channel that samples distances in media
    int crossings = 0;                   // interface surfaces the ray from the last vertex has passed
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
    // the volumetric estimator's: the segment is walked through interface surfaces (Estimator::cross)
    bool walk = false;
    int medium = -1;        // the medium of the piece from o
    int crossings = 0;
    Vec3 end;               // the segment's far end
    Vec3 T{1, 1, 1};        // the transmittance of the pieces walked
    // its part in scattering media, where paths sample distances (their density has it; a path through a
    // medium that only absorbs takes its transmittance exactly, as shadow rays take it everywhere). Both
    // strategies' densities in the balance heuristic over channels and strategies carry it, as pbrt-v4's
    // ratio-tracked shadow rays carry their transmittance: the light sample's weight is
    // T_u[hero] / average over channels j of r_p[j] T_u[j] (light pdf + BSDF or phase pdf).
    Vec3 T_u{1, 1, 1};
    Vec3 r_p;               // the path's r_u at the vertex
    double scatter_pdf = -1;  // the phase function's density of the direction (-1: the BSDF's, from bsdf)
    // its pieces in grid media, ratio tracked (pbrt-v4's): T holds the tracking's estimate, F_l and F_u the
    // factors of the light sample's and the path's rescaled densities (relative to the hero channel's)
    bool tracked = false;
    Vec3 F_l{1, 1, 1}, F_u{1, 1, 1};
    int hero = 0;
    uint64_t seed = 0;      // of the tracking's random values (from the light sample's sampler values)
};

// What a shadow ray's piece found (Estimator::cross).
enum class Crossing { Blocked, Arrived, Onward };

class Estimator {
public:
    Estimator(const udm1scene::Scene &scene, const Lights &lights, const Materials &materials, int max_depth,
              Strategy strategy, bool roulette, int rr_depth);
    // Whether paths take the volumetric estimator (media or interface surfaces; above).
    bool volumetric() const { return volumetric_; }
    // The ray p.o + t p.d left the scene: the environment's light, if any. The path ends.
    void miss(PathState &p) const;
    // The ray hit h. Fills *shadow (inactive if there is no light sample to test). Returns whether the path
    // goes on (p.o, p.d the next ray, p.depth one more).
    bool scatter(PathState &p, const udm1scene::Hit &h, ShadowTest *shadow) const;
    // The shadow test's segment is free: its light sample's contribution into p.L.
    void arrive(PathState &p, const ShadowTest &s) const;

    // The volumetric estimator. A path begins: its medium (the camera's) and hero
    // channel. Then each ray p.o + t p.d it traces, with h its first hit (nullptr: none): the medium up to
    // it (emission; absorption or scattering, a vertex in the medium), else h (an interface surface is
    // passed: the ray goes on from its far side) or the environment. Returns whether the path goes on.
    void start(PathState &p) const;
    bool step(PathState &p, const udm1scene::Hit *h, ShadowTest *shadow) const;
    // A walking shadow test's piece from s.o along s.d, h its first surface before s.len (nullptr: none; a
    // sphere light's own shape counts as none): its transmittance taken; blocked by a surface that is not
    // an interface; onward (s.o, s.len, s.medium the next piece's) past an interface.
    Crossing cross(ShadowTest &s, const udm1scene::Hit *h) const;

private:
    // the volumetric estimator's parts
    bool medium_step(PathState &p, double t_end, ShadowTest *shadow, bool *scattered) const;
    bool grid_step(PathState &p, const GridMedium &g, double t_end, ShadowTest *shadow, bool *scattered) const;
    bool medium_vertex(PathState &p, Vec3 x, double g, ShadowTest *shadow, bool *scattered) const;
    bool track_shadow(ShadowTest &s, const GridMedium &g, double len) const;  // false: blocked
    bool surface_step(PathState &p, const udm1scene::Hit &h, ShadowTest *shadow) const;
    void volumetric_miss(PathState &p) const;
    int medium_after(int medium, const udm1scene::Hit &h, Vec3 w) const;  // of a ray leaving h along w
    // light sampling's shadow test from x towards ls (the rest of it the caller's)
    void walking_shadow(const PathState &p, const LightSample &ls, const udm1scene::Segment &sg, int medium,
                        Vec3 f, const double u_light[2], ShadowTest *s) const;

    const udm1scene::Scene &scene_;
    const Lights &lights_;
    const Materials &materials_;
    Bsdf default_bsdf_;  // of a shape without a material
    int max_depth_;
    Strategy strategy_;
    bool roulette_;
    int rr_depth_;
    bool volumetric_ = false, media_ = false;  // the volumetric estimator; media rendered (Integrator "volpath")
    std::vector<char> interface_;              // per shape: the interface material
    std::vector<std::unique_ptr<GridMedium>> grids_;  // per medium: its grid (uniformgrid, cloud) or null
    double scene_radius_ = 0;                  // of the scene's bounding sphere
};

}  // namespace udm1pt
