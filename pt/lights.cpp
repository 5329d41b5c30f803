// lights.cpp - see lights.h.
#include "lights.h"

#include <algorithm>
#include <cmath>

namespace udm1pt {

using udm1scene::cross;
using udm1scene::dot;
using udm1scene::length;
using udm1scene::normalize;

namespace {
const double PI = 3.14159265358979323846;
inline double luminance(Vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// An orthonormal basis around unit n (Duff et al. 2017).
void basis(Vec3 n, Vec3 *t, Vec3 *b)
{
    double s = std::copysign(1.0, n.z), a = -1.0 / (s + n.z), c = n.x * n.y * a;
    *t = Vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    *b = Vec3(c, s + n.y * n.y * a, -n.y);
}
}  // namespace

Lights::Lights(const udm1scene::Scene &scene)
{
    first_of_shape_.assign(scene.shapes.size(), -1);
    for (size_t k = 0; k < scene.shapes.size(); ++k) {
        const udm1scene::Shape &s = scene.shapes[k];
        if (s.light < 0) continue;
        const udm1scene::AreaLight &al = scene.lights[s.light];
        Vec3 L = al.L * al.scale;
        first_of_shape_[k] = (int)lights_.size();
        if (s.kind == udm1scene::Shape::Sphere) {
            Light l;
            l.sphere = true, l.center = s.center, l.radius = s.radius, l.area = 4 * PI * s.radius * s.radius;
            l.L = L, l.twosided = al.twosided, l.shape = (int)k;
            lights_.push_back(l);
            continue;
        }
        double total = 0;
        for (unsigned t = 0; t < s.indices.size() / 3; ++t) {
            const uint32_t *i = &s.indices[3 * (size_t)t];
            Light l;
            l.p0 = Vec3(s.P[3 * i[0]], s.P[3 * i[0] + 1], s.P[3 * i[0] + 2]);
            l.p1 = Vec3(s.P[3 * i[1]], s.P[3 * i[1] + 1], s.P[3 * i[1] + 2]);
            l.p2 = Vec3(s.P[3 * i[2]], s.P[3 * i[2] + 1], s.P[3 * i[2] + 2]);
            l.area = 0.5 * length(cross(l.p1 - l.p0, l.p2 - l.p0));
            l.n = l.area > 0 ? udm1scene::triangle_normal(s, t) : Vec3(0, 0, 1);
            l.L = L, l.twosided = al.twosided, l.shape = (int)k;
            total += l.area;
            lights_.push_back(l);  // zero-area triangles stay (indices match) with zero power
        }
        if (!(total > 0)) throw udm1scene::SceneError(s.where + ": an area light of zero area");
    }
    double sum = 0;
    for (const Light &l : lights_) {
        double power = luminance(l.L) * l.area * PI * (l.twosided ? 2 : 1);
        sum += power > 0 ? power : 0;
        cdf_.push_back(sum);
    }
    prob_.assign(lights_.size(), 0.0);
    if (sum > 0)
        for (size_t i = 0; i < lights_.size(); ++i) prob_[i] = (cdf_[i] - (i ? cdf_[i - 1] : 0)) / sum;
    else
        lights_.clear(), cdf_.clear(), prob_.clear(), first_of_shape_.assign(scene.shapes.size(), -1);
}

int Lights::light_of(const udm1scene::Hit &h) const
{
    if (h.shape >= first_of_shape_.size() || first_of_shape_[h.shape] < 0) return -1;
    const Light &first = lights_[first_of_shape_[h.shape]];
    return first_of_shape_[h.shape] + (first.sphere ? 0 : (int)h.prim);
}

Vec3 Lights::radiance(const Light &l, Vec3 n, Vec3 w) const
{
    if (!l.twosided && dot(n, w) <= 0) return Vec3();
    return l.L;
}

Vec3 Lights::emitted(const udm1scene::Hit &h, Vec3 w) const
{
    int i = light_of(h);
    if (i < 0) return Vec3();
    return radiance(lights_[i], h.ng, w);
}

double Lights::pdf_light(const Light &l, Vec3 p, Vec3 q, Vec3 nq) const
{
    Vec3 d = q - p;
    double d2 = dot(d, d);
    if (l.sphere) {
        double dc2 = dot(l.center - p, l.center - p), r2 = l.radius * l.radius;
        if (dc2 > r2 * 1.0001) {  // outside: the cone of directions
            double sin2 = r2 / dc2, one_minus_cos = sin2 < 0.00068523 ? sin2 / 2 + sin2 * sin2 / 8 : 1 - std::sqrt(1 - sin2);
            return 1 / (2 * PI * one_minus_cos);
        }
    }
    double c = std::fabs(dot(nq, d)) / std::sqrt(d2);
    return c > 0 ? d2 / (c * l.area) : 0;
}

double Lights::pdf(Vec3 p, const udm1scene::Hit &h) const
{
    int i = light_of(h);
    if (i < 0) return 0;
    return prob_[i] * pdf_light(lights_[i], p, h.p, h.ng);
}

bool Lights::sample(Vec3 p, double u_select, double u1, double u2, LightSample *s) const
{
    if (lights_.empty()) return false;
    double target = u_select * cdf_.back();
    size_t i = std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin();
    if (i >= lights_.size()) i = lights_.size() - 1;
    while (prob_[i] == 0 && i > 0) --i;  // (only with a zero-power light at the very end)
    const Light &l = lights_[i];
    s->shape = l.shape, s->sphere = l.sphere;
    Vec3 q, nq;
    if (l.sphere) {
        Vec3 dc = l.center - p;
        double dc2 = dot(dc, dc), r2 = l.radius * l.radius;
        if (dc2 > r2 * 1.0001) {
            // a direction in the cone the sphere subtends, then the point it hits
            double dist = std::sqrt(dc2), sin2_max = r2 / dc2, cos_max = std::sqrt(std::max(0.0, 1 - sin2_max));
            double one_minus_cos_max = sin2_max < 0.00068523 ? sin2_max / 2 + sin2_max * sin2_max / 8 : 1 - cos_max;
            double sin2 = sin2_max < 0.00068523 ? sin2_max * u1 : 0;
            double cos_t = sin2_max < 0.00068523 ? std::sqrt(1 - sin2) : (cos_max - 1) * u1 + 1;
            if (sin2_max >= 0.00068523) sin2 = std::max(0.0, 1 - cos_t * cos_t);
            // the angle at the centre between -dc and the point (pbrt-v4, Sphere::Sample)
            double cos_alpha = sin2 / std::sqrt(sin2_max) + cos_t * std::sqrt(std::max(0.0, 1 - sin2 / sin2_max));
            double sin_alpha = std::sqrt(std::max(0.0, 1 - cos_alpha * cos_alpha));
            double phi = 2 * PI * u2;
            Vec3 wc = dc * (1 / dist), t, b;
            basis(wc, &t, &b);
            nq = (t * (sin_alpha * std::cos(phi)) + b * (sin_alpha * std::sin(phi))) + (-wc) * cos_alpha;
            nq = normalize(nq);
            q = l.center + nq * l.radius;
            Vec3 d = q - p;
            s->dist = length(d);
            s->wi = d * (1 / s->dist);
            s->L = radiance(l, nq, -s->wi);
            s->pdf = prob_[i] / (2 * PI * one_minus_cos_max);
            return s->pdf > 0 && (s->L.x > 0 || s->L.y > 0 || s->L.z > 0);
        }
        // inside the sphere: by area
        double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * PI * u2;
        nq = Vec3(r * std::cos(phi), r * std::sin(phi), z);
        q = l.center + nq * l.radius;
    } else {
        double su = std::sqrt(u1), b0 = 1 - su, b1 = u2 * su;
        q = l.p0 * b0 + l.p1 * b1 + l.p2 * (1 - b0 - b1);
        nq = l.n;
    }
    Vec3 d = q - p;
    double d2 = dot(d, d);
    if (d2 <= 0) return false;
    s->dist = std::sqrt(d2);
    s->wi = d * (1 / s->dist);
    s->L = radiance(l, nq, -s->wi);
    s->pdf = prob_[i] * pdf_light(l, p, q, nq);
    return s->pdf > 0 && std::isfinite(s->pdf) && (s->L.x > 0 || s->L.y > 0 || s->L.z > 0);
}

}  // namespace udm1pt
