// lights.h - the scene's lights for the path tracer: every emitting triangle, sphere, disk, cylinder and
// bilinear patch (pbrt-v4's diffuse area light: radiance L * scale on the side the surface normal faces,
// or on both sides if twosided; an emitter of alpha 0 is invisible to rays and found by light sampling
// alone, as pbrt-v4 makes it a delta light) and pbrt-v4's LightSources: point and spot lights, distant lights, and environments
// ("infinite": uniform, or an equal-area octahedral image, importance-sampled by its pixels).
// A light is chosen for a shading point (p, n) in two steps. First a group: each light at infinity
// (distant, environment) is one with probability 1 / (lights at infinity + 1); the others are grouped, an
// emitting shape (all its triangles) or a point or spot light a group, and chosen in proportion to their
// importance at (p, n) (pbrt-v4's LightBounds::Importance: power over squared distance, bounded by the
// angles between the group's emission cone, the direction to it and the surface normal), all groups at
// once as pbrt-v4's exhaustive light sampler does; a single group is always chosen (where its importance
// is 0 it sends no light: the same estimate, without the importance). Then a light of the group in
// proportion to its power. pbrt-v4 weighs each triangle by its own importance; a shape's triangles share
// it here, so that a mesh light costs one importance, not one per triangle. Above MAX_BY_IMPORTANCE groups
// every light is chosen by power alone, the same at every point. Triangles near the shading point (area > 0.25 distance^2) are
// sampled as pbrt-v4 samples them, by the solid angle they subtend (Arvo's spherical triangle sampling,
// for solid angles in 3e-4..6.22 sr), which keeps the estimate bounded where area sampling's 1/r^2
// gives fireflies; farther away by area, which is as good there and cheaper. Spheres seen from outside
// are sampled by their cone of directions. Disks and cylinders by area (pbrt-v4's); bilinear patches as
// pbrt-v4 samples them: a rectangle by the solid angle it subtends (Urena et al.'s spherical rectangle,
// where that exceeds 1e-4 sr), else by area, nearly uniformly through the corners' differential areas.
#pragma once

#include "embree_scene.h"
#include "scene.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace udm1pt {

using udm1scene::Vec3;

struct LightSample {
    double importance_sum = NAN;  // the groups' importances at the point, summed (NaN: not computed), for pdf()
    Vec3 wi;          // unit direction from the shading point to the light
    Vec3 L;           // radiance arriving along -wi (a point or spot light: intensity / distance^2)
    double pdf = 0;   // solid-angle density, including the choice of the light (a delta light: the choice)
    double dist = 0;  // distance to the sampled point (infinite: unused)
    Vec3 q, n;        // the sampled point and the light's unit normal there (a point or spot light: n = 0)
    int shape = -1;   // the light's shape (Scene::shapes index), or -1
    bool sphere = false;
    bool delta = false;     // point, spot, distant: only light sampling finds it (no MIS)
    bool infinite = false;  // distant or environment: the shadow ray goes to infinity
    bool uniform = false;   // a uniform environment
};

// An environment map as pbrt-v4's ImageInfiniteLight reads it: a square image in pbrt-v4's equal-area
// octahedral mapping (Clarberg's), looked up at the nearest pixel, sampled in proportion to its pixels'
// luminance (so a pixel's radiance over its density is the same everywhere).
struct EnvironmentMap {
    int res = 0;
    std::vector<float> rgb;         // res x res, top row first
    std::vector<double> row_cdf;    // res + 1 entries: the rows' luminance, cumulated
    std::vector<double> pixel_cdf;  // res x (res + 1): within each row
    double total = 0;               // the sum of the pixels' luminance
};

// pbrt-v4's equal-area mapping between the unit square and the unit sphere (Clarberg 2008).
Vec3 equal_area_square_to_sphere(double u, double v);
void equal_area_sphere_to_square(Vec3 d, double *u, double *v);

class Lights {
public:
    // Throws udm1scene::SceneError (file:line of the Shape or LightSource) for an area light of zero area
    // or an environment map that cannot be used. near: triangles are sampled by solid angle where area >
    // near * distance^2 (0: wherever the solid angle allows; infinity: never, always by area).
    explicit Lights(const udm1scene::Scene &scene, double near = NEAR_DEFAULT);
    static constexpr double NEAR_DEFAULT = 0.25;

    bool empty() const { return lights_.empty(); }
    size_t count() const { return lights_.size(); }

    static constexpr size_t MAX_BY_IMPORTANCE = 64;  // groups

    // Sample a light for the shading point p with unit geometric normal n (zero: none) from one 2D point
    // (u1, u2): u1 picks the light (choose()) and, rescaled to [0, 1) within the light's interval, gives
    // with u2 the point on it (sample reuse, so that a stratified 2D point stays stratified over all the
    // lights together). False if no light reaches p (every importance 0) or the sample carries nothing.
    bool sample(Vec3 p, Vec3 n, double u1, double u2, LightSample *s) const;

    // The light that sample() picks at (p, n) with u1, u1 rescaled to [0, 1) within its interval, and the
    // probability of that choice; false if no light has importance there.
    bool choose(double u1, Vec3 p, Vec3 n, size_t *light, double *rescaled, double *probability,
                double *importance_sum = nullptr) const;
    // Whether sample() takes triangle light i at p by area (not by solid angle; false for other kinds).
    bool by_area(size_t i, Vec3 p) const
    {
        double omega;
        return lights_[i].kind == Light::Triangle && !by_solid_angle(lights_[i], p, &omega);  // (false when far, first)
    }

    struct Light {
        enum Kind { Triangle, Sphere, Point, Spot, Distant, Infinite, Disk, Cylinder, Patch } kind = Triangle;
        Vec3 p0, p1, p2, n;  // triangle: vertices, unit normal (emitting side for one-sided lights)
        Vec3 p3;             // patch: p00 p10 p01 p11 in p0 p1 p2 p3
        bool rectangle = false;  // patch: pbrt-v4's IsRectangle
        double w[4] = {0, 0, 0, 0};  // patch, not a rectangle: the corners' differential areas
        const udm1scene::Shape *src = nullptr;  // disk, cylinder, patch: its shape
        bool invisible = false;  // an emitter of alpha 0: light sampling alone finds it (a delta light)
        Vec3 centroid;       // triangle
        Vec3 center;         // sphere; point and spot: the position
        Vec3 axis;           // spot: its axis; distant: towards the light
        double radius = 0, area = 0;
        double cos_start = 1, cos_end = 0;  // spot
        Vec3 L;              // radiance (area, distant, uniform environment) or intensity (point, spot)
        bool twosided = false;
        bool reversed = false;  // sphere: emits inwards (ReverseOrientation)
        int shape = -1;
        unsigned prim = 0;                 // patch: its index in its shape
        int map = -1;                      // environment: its image (maps_), or -1 for a uniform one
        udm1scene::Mat4 light_from_world;  // environment: the map's frame
        udm1scene::Mat4 world_from_light;
        bool at_infinity = false;  // distant and environment lights
        int group = -1;            // its group (the others), or -1
    };
    // A group of lights chosen together (above): lights_[first, first + count), their powers cumulated
    // (the choice within the group), and pbrt-v4's LightBounds of the group: its box, the axis and cones
    // of its emission (cos_o: normals around the axis; cos_e: emission around a normal), a bound of its power.
    struct Group {
        size_t first = 0, count = 0;
        std::vector<double> cdf;
        Vec3 lo, hi, w;
        double phi = 0, cos_o = 1, cos_e = 0;
        bool twosided = false;
        Vec3 center;                              // of the box (made once, for importance())
        double half_diagonal = 0, radius2 = 0, sin_o = 0;
    };
    const Light &light(size_t i) const { return lights_[i]; }
    double power(size_t i) const { return power_[i]; }       // light i's power (0 for a triangle of no area)
    // The probability that choose() picks light i at (p, n).
    double probability(size_t i, Vec3 p, Vec3 n, double importance_sum = NAN) const;
    bool by_importance() const { return by_importance_; }
    // Whether choose() does not depend on the point (one group and no light at infinity, or by power), and
    // then the lights it chooses from, lights [*first, *first + cdf.size()), with the power CDF it uses.
    bool fixed_choice(size_t *first, const std::vector<double> **cdf) const
    {
        if (!by_importance_) return *first = 0, *cdf = &cdf_, true;
        if (groups_.size() != 1 || !infinite_.empty()) return false;
        return *first = groups_[0].first, *cdf = &groups_[0].cdf, true;
    }
    double near() const { return near_; }                    // the constructor's near
    bool has_environment() const { return !environments_.empty(); }
    bool only_area_lights() const { return only_area_; }

    // Radiance leaving hit h towards w (unit, pointing away from the surface); zero if h is not on a light.
    Vec3 emitted(const udm1scene::Hit &h, Vec3 w) const;
    // Radiance from the environments along a ray that leaves the scene in direction d, and the density
    // (solid angle, including the choice) with which sample() would have chosen that direction.
    Vec3 environment(Vec3 d) const;
    double environment_pdf(Vec3 d) const;
    // The same radiance and density without the uniform environments (which pbrt-v4's volumetric path tracer
    // does not light-sample: estimator.h).
    Vec3 environment_maps(Vec3 d) const;
    double environment_map_pdf(Vec3 d) const;

    // The density (solid angle, including the choice) with which sample() at (p, n) would give the
    // direction from p to the light point h. importance_sum: a sample's at (p, n) if there was one (the
    // same density, without the other groups' importances again).
    double pdf(Vec3 p, Vec3 n, const udm1scene::Hit &h, double importance_sum = NAN) const;

    // The light of a hit, or -1.
    int light_of(const udm1scene::Hit &h) const;

private:
    Vec3 radiance(const Light &l, Vec3 n, Vec3 w) const;
    double importance(const Group &g, Vec3 p, Vec3 n) const;      // pbrt-v4's LightBounds::Importance
    double importances(Vec3 p, Vec3 n, double *imp) const;        // of every group; their sum
    double infinite_probability() const;                          // of each light at infinity (by importance)
    double group_probability(size_t g, Vec3 p, Vec3 n, double sum) const;  // of group g at (p, n) (sum: NaN or
                                                                            // the importances' there)
    void make_groups();
    bool sample_source(const Light &l, double prob, Vec3 p, double u1, double u2, LightSample *s) const;
    Vec3 environment_of(const Light &l, Vec3 d) const;  // radiance along direction d (world)
    double environment_pdf_of(const Light &l, Vec3 d) const;  // without the choice
    double pdf_light(const Light &l, Vec3 p, const udm1scene::Hit &h) const;  // solid angle, without the choice
    bool sample_surface(const Light &l, Vec3 p, double u1, double u2, Vec3 *q, Vec3 *nq, double *pdf) const;  // disk,
                                                                                    // cylinder, patch
    bool by_solid_angle(const Light &l, Vec3 p, double *omega) const;  // triangle l sampled by solid angle from p?
    // triangle l far from p: area / distance^2 to its centroid below near_ (then sampled by area: as good, cheaper)
    bool far(const Light &l, Vec3 p) const
    {
        Vec3 d = l.centroid - p;
        return l.area < near_ * udm1scene::dot(d, d);
    }
    double near_;
    bool only_area_ = true;                  // no LightSource
    std::vector<Light> lights_;
    std::vector<double> cdf_;                // power CDF (choice by power)
    std::vector<double> prob_;               // choice probability of each light (by power)
    std::vector<double> power_;
    bool by_importance_ = false;             // the choice by importance (else by power)
    std::vector<Group> groups_;              // the lights not at infinity, by group
    std::vector<int> infinite_;              // the lights at infinity
    std::vector<int> first_of_shape_;        // light index of a shape's first triangle, or -1
    std::vector<int> environments_;          // the lights that are environments
    std::vector<EnvironmentMap> maps_;
};

}  // namespace udm1pt
