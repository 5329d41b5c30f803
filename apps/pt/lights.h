// lights.h - the scene's lights for the path tracer, chosen in proportion to their power: every
// emitting triangle and sphere (pbrt-v4's diffuse area light: radiance L * scale on the side the surface
// normal faces, or on both sides if twosided) and pbrt-v4's LightSources: point and spot lights,
// distant lights, and environments ("infinite": uniform, or an equal-area octahedral image,
// importance-sampled by its pixels). Triangles near the shading point (area > 0.25 distance^2) are
// sampled as pbrt-v4 samples them, by the solid angle they subtend (Arvo's spherical triangle sampling,
// for solid angles in 3e-4..6.22 sr), which keeps the estimate bounded where area sampling's 1/r^2
// gives fireflies; farther away by area, which is as good there and cheaper. Spheres seen from outside
// are sampled by their cone of directions.
#pragma once

#include "embree_scene.h"
#include "scene.h"

#include <algorithm>
#include <map>
#include <vector>

namespace udm1pt {

using udm1scene::Vec3;

struct LightSample {
    Vec3 wi;          // unit direction from the shading point to the light
    Vec3 L;           // radiance arriving along -wi (a point or spot light: intensity / distance^2)
    double pdf = 0;   // solid-angle density, including the choice of the light (a delta light: the choice)
    double dist = 0;  // distance to the sampled point (infinite: unused)
    Vec3 q, n;        // the sampled point and the light's unit normal there (a point or spot light: n = 0)
    int shape = -1;   // the light's shape (Scene::shapes index), or -1
    bool sphere = false;
    bool delta = false;     // point, spot, distant: only light sampling finds it (no MIS)
    bool infinite = false;  // distant or environment: the shadow ray goes to infinity
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

    // Sample a light for point p from one 2D point (u1, u2): u1 picks the light by power and,
    // rescaled to [0, 1) within the light's interval, gives with u2 the point on it (sample reuse,
    // so that a stratified 2D point stays stratified over all the lights together).
    bool sample(Vec3 p, double u1, double u2, LightSample *s) const;

    // The light that sample() picks with u1 (by power), and u1 rescaled to [0, 1) within its interval.
    size_t choose(double u1, double *rescaled) const
    {
        double target = u1 * cdf_.back();
        size_t i = 0;
        if (cdf_.size() <= 16) {  // upper_bound without its unpredictable branches: the count of cdf <= target
            for (double c : cdf_) i += c <= target;
        } else {
            i = std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin();
        }
        if (i >= lights_.size()) i = lights_.size() - 1;
        while (prob_[i] == 0 && i > 0) --i;  // (only with a zero-power light at the very end)
        double lo = i ? cdf_[i - 1] : 0.0;
        double u = std::min((target - lo) / (cdf_[i] - lo), 0x1.fffffffffffffp-1);  // reuse: uniform in [0, 1) again
        *rescaled = u >= 0 ? u : 0;
        return i;
    }
    // Whether sample() takes triangle light i at p by area (not by solid angle; false for other kinds).
    bool by_area(size_t i, Vec3 p) const
    {
        double omega;
        return lights_[i].kind == Light::Triangle && !by_solid_angle(lights_[i], p, &omega);  // (false when far, first)
    }

    struct Light {
        enum Kind { Triangle, Sphere, Point, Spot, Distant, Infinite } kind = Triangle;
        Vec3 p0, p1, p2, n;  // triangle: vertices, unit normal (emitting side for one-sided lights)
        Vec3 centroid;       // triangle
        Vec3 center;         // sphere; point and spot: the position
        Vec3 axis;           // spot: its axis; distant: towards the light
        double radius = 0, area = 0;
        double cos_start = 1, cos_end = 0;  // spot
        Vec3 L;              // radiance (area, distant, uniform environment) or intensity (point, spot)
        bool twosided = false;
        int shape = -1;
        int map = -1;                      // environment: its image (maps_), or -1 for a uniform one
        udm1scene::Mat4 light_from_world;  // environment: the map's frame
        udm1scene::Mat4 world_from_light;
    };
    const Light &light(size_t i) const { return lights_[i]; }
    double probability(size_t i) const { return prob_[i]; }  // of choosing light i
    const std::vector<double> &cdf() const { return cdf_; }  // choose()'s power CDF, one entry per light
    double near() const { return near_; }                    // the constructor's near
    bool has_environment() const { return !environments_.empty(); }
    bool only_area_lights() const { return only_area_; }

    // Radiance leaving hit h towards w (unit, pointing away from the surface); zero if h is not on a light.
    Vec3 emitted(const udm1scene::Hit &h, Vec3 w) const;
    // Radiance from the environments along a ray that leaves the scene in direction d, and the density
    // (solid angle, including the choice) with which sample() would have chosen that direction.
    Vec3 environment(Vec3 d) const;
    double environment_pdf(Vec3 d) const;

    // The density (solid angle, including the choice) with which sample() would give the direction
    // from p to the light point h.
    double pdf(Vec3 p, const udm1scene::Hit &h) const;

    // The light of a hit, or -1.
    int light_of(const udm1scene::Hit &h) const;

private:
    Vec3 radiance(const Light &l, Vec3 n, Vec3 w) const;
    bool sample_source(const Light &l, double prob, Vec3 p, double u1, double u2, LightSample *s) const;
    Vec3 environment_of(const Light &l, Vec3 d) const;  // radiance along direction d (world)
    double environment_pdf_of(const Light &l, Vec3 d) const;  // without the choice
    double pdf_light(const Light &l, Vec3 p, Vec3 q, Vec3 nq) const;  // solid angle, without the choice
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
    std::vector<double> cdf_;                // power CDF
    std::vector<double> prob_;               // choice probability of each light
    std::vector<int> first_of_shape_;        // light index of a shape's first triangle, or -1
    std::vector<int> environments_;          // the lights that are environments
    std::vector<EnvironmentMap> maps_;
};

}  // namespace udm1pt
