// lights.h - the scene's area lights for the path tracer: every emitting triangle
// and sphere, chosen in proportion to its power. Triangles near the shading point
// (area > 0.25 distance^2) are sampled as pbrt-v4 samples them, by the solid angle
// they subtend (Arvo's spherical triangle sampling, for solid angles in 3e-4..6.22 sr),
// which keeps the estimate bounded where area sampling's 1/r^2 gives fireflies;
// farther away by area, which is as good there and cheaper. Spheres seen from
// outside are sampled by their cone of directions. Emission is pbrt-v4's diffuse
// area light: radiance L * scale on the side the surface normal faces, or on both
// sides if twosided.
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
    Vec3 L;           // emitted radiance arriving along -wi
    double pdf = 0;   // solid-angle density, including the choice of the light
    double dist = 0;  // distance to the sampled point
    Vec3 q, n;        // the sampled point and the light's unit normal there (shadow rays end short of it)
    int shape = -1;   // the light's shape (Scene::shapes index)
    bool sphere = false;
};

class Lights {
public:
    // Throws udm1scene::SceneError (file:line of the Shape) for a light of zero area.
    // near: triangles are sampled by solid angle where area > near * distance^2 (0: wherever the
    // solid angle allows; infinity: never, always by area). The default is the measured choice.
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
    // Whether sample() takes triangle light i at p by area (not by solid angle; false for spheres).
    bool by_area(size_t i, Vec3 p) const
    {
        double omega;
        return !lights_[i].sphere && !by_solid_angle(lights_[i], p, &omega);  // (false when far, first)
    }

    struct Light {
        bool sphere = false;
        Vec3 p0, p1, p2, n;  // triangle: vertices, unit normal (emitting side for one-sided lights)
        Vec3 centroid;  // triangle
        Vec3 center;    // sphere
        double radius = 0, area = 0;
        Vec3 L;
        bool twosided = false;
        int shape = -1;
    };
    const Light &light(size_t i) const { return lights_[i]; }
    double probability(size_t i) const { return prob_[i]; }  // of choosing light i
    const std::vector<double> &cdf() const { return cdf_; }  // choose()'s power CDF, one entry per light
    double near() const { return near_; }                    // the constructor's near

    // Radiance leaving hit h towards w (unit, pointing away from the surface); zero if h is not on a light.
    Vec3 emitted(const udm1scene::Hit &h, Vec3 w) const;

    // The density (solid angle, including the choice) with which sample() would give the direction
    // from p to the light point h.
    double pdf(Vec3 p, const udm1scene::Hit &h) const;

    // The light of a hit, or -1.
    int light_of(const udm1scene::Hit &h) const;

private:
    Vec3 radiance(const Light &l, Vec3 n, Vec3 w) const;
    double pdf_light(const Light &l, Vec3 p, Vec3 q, Vec3 nq) const;  // solid angle, without the choice
    bool by_solid_angle(const Light &l, Vec3 p, double *omega) const;  // triangle l sampled by solid angle from p?
    // triangle l far from p: area / distance^2 to its centroid below near_ (then sampled by area: as good, cheaper)
    bool far(const Light &l, Vec3 p) const
    {
        Vec3 d = l.centroid - p;
        return l.area < near_ * udm1scene::dot(d, d);
    }
    double near_;
    std::vector<Light> lights_;
    std::vector<double> cdf_;                // power CDF
    std::vector<double> prob_;               // choice probability of each light
    std::vector<int> first_of_shape_;        // light index of a shape's first triangle, or -1
};

}  // namespace udm1pt
