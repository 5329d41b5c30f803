// lights.cpp - see lights.h.
#include "lights.h"

#include "bilinear_patch.h"
#include "quadrics.h"
#include "udm1app/image_read.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace udm1pt {

using udm1scene::cross;
using udm1scene::dot;
using udm1scene::length;
using udm1scene::normalize;

namespace {
const double PI = 3.14159265358979323846;
inline double luminance(Vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }
inline double max_component(Vec3 c) { return std::max({c.x, c.y, c.z}); }
inline Vec3 min3(Vec3 a, Vec3 b) { return Vec3(std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)); }
inline Vec3 max3(Vec3 a, Vec3 b) { return Vec3(std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)); }

// pbrt-v4's bounds for sampling a triangle by solid angle: below, the spherical triangle is too
// thin for the arithmetic; above, nearly a hemisphere
const double MIN_SPHERICAL_AREA = 3e-4, MAX_SPHERICAL_AREA = 6.22;


inline double safe_asin(double x) { return std::asin(std::clamp(x, -1.0, 1.0)); }
inline double safe_sqrt(double x) { return std::sqrt(std::max(0.0, x)); }
inline double angle_between(Vec3 a, Vec3 b)  // accurate for nearly equal and nearly opposite unit vectors
{
    return dot(a, b) < 0 ? PI - 2 * safe_asin(length(a + b) / 2) : 2 * safe_asin(length(b - a) / 2);
}
inline Vec3 gram_schmidt(Vec3 v, Vec3 w) { return v - w * dot(v, w); }

// The solid angle of triangle (p0, p1, p2) seen from p (Van Oosterom and Strackee 1983).
double solid_angle(Vec3 p, Vec3 p0, Vec3 p1, Vec3 p2)
{
    Vec3 a = normalize(p0 - p), b = normalize(p1 - p), c = normalize(p2 - p);
    return std::fabs(2 * std::atan2(dot(a, cross(b, c)), 1 + dot(a, b) + dot(a, c) + dot(b, c)));
}

// Arvo's (1995) uniform sampling of the spherical triangle that (p0, p1, p2) subtends from p, in
// pbrt-v4's formulation: returns the point of the triangle the sampled direction meets.
bool sample_spherical_triangle(Vec3 p, Vec3 p0, Vec3 p1, Vec3 p2, double u0, double u1, Vec3 *q)
{
    Vec3 a = normalize(p0 - p), b = normalize(p1 - p), c = normalize(p2 - p);
    Vec3 n_ab = cross(a, b), n_bc = cross(b, c), n_ca = cross(c, a);
    if (dot(n_ab, n_ab) == 0 || dot(n_bc, n_bc) == 0 || dot(n_ca, n_ca) == 0) return false;
    n_ab = normalize(n_ab), n_bc = normalize(n_bc), n_ca = normalize(n_ca);
    double alpha = angle_between(n_ab, -n_ca), beta = angle_between(n_bc, -n_ab), gamma = angle_between(n_ca, -n_bc);
    double A_pi = alpha + beta + gamma, Ap_pi = PI + u0 * (A_pi - PI);  // the sub-triangle's area, plus pi
    double sin_a = std::sin(alpha), cos_a = std::cos(alpha), sin_ap = std::sin(Ap_pi), cos_ap = std::cos(Ap_pi);
    double sin_phi = sin_ap * cos_a - cos_ap * sin_a, cos_phi = cos_ap * cos_a + sin_ap * sin_a;
    double k1 = cos_phi + cos_a, k2 = sin_phi - sin_a * dot(a, b);
    double den = (k2 * sin_phi + k1 * cos_phi) * sin_a;
    double cos_bp = den != 0 ? std::clamp((k2 + (k2 * cos_phi - k1 * sin_phi) * cos_a) / den, -1.0, 1.0) : 1.0;
    double sin_bp = safe_sqrt(1 - cos_bp * cos_bp);
    Vec3 cp = a * cos_bp + normalize(gram_schmidt(c, a)) * sin_bp;
    double cos_t = 1 - u1 * (1 - dot(cp, b)), sin_t = safe_sqrt(1 - cos_t * cos_t);
    Vec3 w = b * cos_t + normalize(gram_schmidt(cp, b)) * sin_t;
    // where w meets the triangle (Moller-Trumbore), barycentrics clamped into it
    Vec3 e1 = p1 - p0, e2 = p2 - p0, s1 = cross(w, e2);
    double div = dot(s1, e1);
    if (div == 0 || !std::isfinite(div)) return false;
    Vec3 sp = p - p0;
    double b1 = std::clamp(dot(sp, s1) / div, 0.0, 1.0), b2 = std::clamp(dot(w, cross(sp, e1)) / div, 0.0, 1.0);
    if (b1 + b2 > 1) {
        double sum = b1 + b2;
        b1 /= sum, b2 /= sum;
    }
    *q = p0 * (1 - b1 - b2) + p1 * b1 + p2 * b2;
    return std::isfinite(q->x) && std::isfinite(q->y) && std::isfinite(q->z);
}

// The spherical rectangle that the rectangle s + [0, 1] eu + [0, 1] ev (eu, ev perpendicular) subtends from p,
// in the frame of Urena, Fajardo and King (2013): x along eu, y along ev, z towards the rectangle's plane
// from p; its corners' coordinates and its solid angle (the sum of its interior angles less 2 pi).
struct SphericalRectangle {
    Vec3 x, y, z;
    double x0, y0, x1, y1, z0;
    double b0, b1, k, solid_angle;
    SphericalRectangle(Vec3 p, Vec3 s, Vec3 eu, Vec3 ev)
    {
        double lu = length(eu), lv = length(ev);
        x = eu * (1 / lu), y = ev * (1 / lv), z = cross(x, y);
        Vec3 d = s - p;
        z0 = dot(d, z);
        if (z0 > 0) z = -z, z0 = -z0;
        x0 = dot(d, x), y0 = dot(d, y), x1 = x0 + lu, y1 = y0 + lv;
        Vec3 v00(x0, y0, z0), v01(x0, y1, z0), v10(x1, y0, z0), v11(x1, y1, z0);
        auto unit = [](Vec3 v) {
            double l = length(v);
            return l > 0 ? v * (1 / l) : Vec3();
        };
        Vec3 n0 = unit(cross(v00, v10)), n1 = unit(cross(v10, v11)), n2 = unit(cross(v11, v01)), n3 = unit(cross(v01, v00));
        double g0 = angle_between(-n0, n1), g1 = angle_between(-n1, n2), g2 = angle_between(-n2, n3), g3 = angle_between(-n3, n0);
        b0 = n0.z, b1 = n2.z, k = 2 * PI - g2 - g3;
        solid_angle = g0 + g1 + g2 + g3 - 2 * PI;
        if (!(solid_angle > 0) || !std::isfinite(solid_angle)) solid_angle = 0;
    }
};

// pbrt-v4 samples a rectangular patch by solid angle where it subtends more than 1e-4 sr; udm1-pt also by area
// where it subtends nearly a hemisphere (as pbrt-v4 limits triangles): there the shading point lies on or
// next to the rectangle's plane, and directions uniform over the hemisphere would put every sample at the
// point's foot, lighting a rectangle by itself.
bool rectangle_by_solid_angle(double omega) { return omega > 1e-4 && omega <= MAX_SPHERICAL_AREA; }

double rectangle_solid_angle(Vec3 p, Vec3 s, Vec3 eu, Vec3 ev) { return SphericalRectangle(p, s, eu, ev).solid_angle; }

// A point of the rectangle whose direction from p is uniform over the solid angle it subtends (Urena et al.).
bool sample_spherical_rectangle(Vec3 p, Vec3 s, Vec3 eu, Vec3 ev, double u0, double u1, Vec3 *q)
{
    SphericalRectangle r(p, s, eu, ev);
    if (!(r.solid_angle > 0)) return false;
    double au = u0 * r.solid_angle + r.k;  // the azimuth of the sampled sub-rectangle's edge
    double fu = (std::cos(au) * r.b0 - r.b1) / std::sin(au);
    double cu = std::clamp(std::copysign(1 / std::sqrt(fu * fu + r.b0 * r.b0), fu), -0x1.fffffffffffffp-1, 0x1.fffffffffffffp-1);
    double xu = std::clamp(-(cu * r.z0) / safe_sqrt(1 - cu * cu), r.x0, r.x1);
    double dd = std::sqrt(xu * xu + r.z0 * r.z0);
    double h0 = r.y0 / std::sqrt(dd * dd + r.y0 * r.y0), h1 = r.y1 / std::sqrt(dd * dd + r.y1 * r.y1);
    double hv = h0 + u1 * (h1 - h0), hv2 = hv * hv;
    double yv = hv2 < 1 - 1e-12 ? hv * dd / std::sqrt(1 - hv2) : r.y1;
    *q = p + r.x * xu + r.y * yv + r.z * r.z0;
    return std::isfinite(q->x) && std::isfinite(q->y) && std::isfinite(q->z);
}
}  // namespace

// The equal-area mapping's forward direction, from pbrt-v4's definition: the square's diagonal distance
// gives the polar angle's sine-like radius, the position along the diagonal the azimuth.
Vec3 equal_area_square_to_sphere(double u, double v)
{
    double a = 2 * u - 1, b = 2 * v - 1, ap = std::fabs(a), bp = std::fabs(b);
    double signed_distance = 1 - (ap + bp), r = 1 - std::fabs(signed_distance);
    double phi = (r == 0 ? 1 : (bp - ap) / r + 1) * PI / 4;
    double z = std::copysign(1 - r * r, signed_distance), s = r * std::sqrt(std::max(0.0, 2 - r * r));
    return Vec3(std::copysign(std::cos(phi), a) * s, std::copysign(std::sin(phi), b) * s, z);
}

// Its inverse, with an exact arctangent.
void equal_area_sphere_to_square(Vec3 d, double *u, double *v)
{
    double x = std::fabs(d.x), y = std::fabs(d.y), z = std::fabs(d.z);
    double r = std::sqrt(std::max(0.0, 1 - z));
    double a = std::max(x, y), b = a == 0 ? 0 : std::min(x, y) / a;
    double phi = std::atan(b) * 2 / PI;
    if (x < y) phi = 1 - phi;
    double vv = phi * r, uu = r - vv;
    if (d.z < 0) {  // the southern hemisphere: mirrored into the square's corners
        std::swap(uu, vv);
        uu = 1 - uu, vv = 1 - vv;
    }
    *u = 0.5 * (std::copysign(uu, d.x) + 1);
    *v = 0.5 * (std::copysign(vv, d.y) + 1);
}

namespace {
// An environment image: square, RGB, finite; 8-bit files decoded from sRGB (pbrt-v4 reads them so).
EnvironmentMap read_environment(const udm1scene::LightSource &src)
{
    udm1app::LoadedImage im;
    try {
        im = udm1app::read_image(src.filename);
    } catch (const std::exception &e) {
        throw udm1scene::SceneError(src.where + ": LightSource \"infinite\": " + e.what());
    }
    auto fail = [&](const std::string &why) {
        throw udm1scene::SceneError(src.where + ": LightSource \"infinite\": " + src.filename + ": " + why);
    };
    if (im.width != im.height)
        fail("the image is " + std::to_string(im.width) + "x" + std::to_string(im.height) +
             ", not square (pbrt-v4's equal-area environment maps are)");
    if (im.channels < 3) fail("the image needs R, G and B channels");
    EnvironmentMap m;
    m.res = im.width;
    m.rgb.resize(3 * (size_t)m.res * m.res);
    for (size_t p = 0; p < (size_t)m.res * m.res; ++p)
        for (int c = 0; c < 3; ++c) {
            float x = im.pixels[p * im.channels + c];
            if (!std::isfinite(x)) fail("a pixel is not finite (" + udm1scene::number_text(x) + ")");
            if (im.bits == 8) x = udm1app::srgb_to_linear(x);
            m.rgb[3 * p + c] = std::max(0.0f, x);
        }
    m.row_cdf.assign(m.res + 1, 0.0);
    m.pixel_cdf.assign((size_t)m.res * (m.res + 1), 0.0);
    for (int y = 0; y < m.res; ++y) {
        double *row = &m.pixel_cdf[(size_t)y * (m.res + 1)];
        for (int x = 0; x < m.res; ++x) {
            const float *c = &m.rgb[3 * ((size_t)y * m.res + x)];
            row[x + 1] = row[x] + luminance(Vec3(c[0], c[1], c[2]));
        }
        m.row_cdf[y + 1] = m.row_cdf[y] + row[m.res];
    }
    m.total = m.row_cdf[m.res];
    return m;
}

// The index i with cdf[i] <= target < cdf[i + 1] among cdf[0..n], skipping empty intervals, and target
// rescaled to [0, 1) within it.
int pick(const double *cdf, int n, double target, double *rescaled)
{
    int i = (int)(std::upper_bound(cdf, cdf + n + 1, target) - cdf) - 1;
    i = std::clamp(i, 0, n - 1);
    while (cdf[i + 1] <= cdf[i] && i > 0) --i;
    double w = cdf[i + 1] - cdf[i];
    *rescaled = w > 0 ? std::clamp((target - cdf[i]) / w, 0.0, 0x1.fffffffffffffp-1) : 0;
    return i;
}

// pbrt-v4's SmoothStep: 0 below a, 1 above b, a cubic between.
double smooth_step(double x, double a, double b)
{
    if (a == b) return x < a ? 0 : 1;
    double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}
}  // namespace

// Solid-angle sampling only near the light (area / distance^2 to its centroid above near_): farther
// away 1/r^2 varies little over the light and area sampling gives the same error for less work
// (`python bench/bench_pt.py --estimators` measures the choice).
Lights::Lights(const udm1scene::Scene &scene, double near) : near_(near)
{
    first_of_shape_.assign(scene.shapes.size(), -1);
    for (size_t k = 0; k < scene.shapes.size(); ++k) {
        const udm1scene::Shape &s = scene.shapes[k];
        if (s.light < 0) continue;
        const udm1scene::AreaLight &al = scene.lights[s.light];
        Vec3 L = al.L * al.scale;
        // pbrt-v4: an emitter of alpha 0 is a delta light that rays never meet; one of alpha below 0 (its
        // emission masked everywhere) sends no light (the parser refused alpha textures and alphas in (0, 1))
        const bool invisible = s.alpha_tex < 0 && s.alpha == 0;
        if (s.alpha_tex < 0 && s.alpha < 0) L = Vec3();
        first_of_shape_[k] = (int)lights_.size();
        if (s.kind == udm1scene::Shape::Sphere) {
            Light l;
            l.kind = Light::Sphere, l.center = s.center, l.radius = s.radius, l.area = 4 * PI * s.radius * s.radius;
            l.L = L, l.twosided = al.twosided, l.shape = (int)k, l.invisible = invisible;
            l.reversed = s.reverse_orientation;  // (the parser refused sphere lights that are not rigidly placed)
            lights_.push_back(l);
            continue;
        }
        if (s.kind == udm1scene::Shape::Disk || s.kind == udm1scene::Shape::Cylinder) {
            Light l;  // (the parser refused those pbrt-v4 renders inconsistently: rigidly placed, whole disks)
            l.kind = s.kind == udm1scene::Shape::Disk ? Light::Disk : Light::Cylinder;
            l.src = &s, l.area = udm1scene::quadric_area(s), l.center = s.center;
            l.L = L, l.twosided = al.twosided, l.shape = (int)k, l.invisible = invisible;
            l.reversed = s.reverse_orientation;
            if (l.kind == Light::Disk) {
                l.n = udm1scene::quadric_normal(s, s.world_from_object.point(Vec3(0, 0, s.height)));
                if (l.reversed) l.n = -l.n;
            }
            lights_.push_back(l);
            continue;
        }
        if (s.kind == udm1scene::Shape::Bilinear) {
            double total = 0;
            for (unsigned t = 0; t < s.indices.size() / 4; ++t) {
                udm1scene::Patch q = udm1scene::patch_of(s, t);
                Light l;
                l.kind = Light::Patch, l.src = &s, l.prim = t;
                l.p0 = q.p00, l.p1 = q.p10, l.p2 = q.p01, l.p3 = q.p11;
                l.rectangle = q.rectangle(), l.area = q.area();
                if (!std::isfinite(l.area)) l.area = 0;
                q.corner_weights(l.w);
                l.centroid = (q.p00 + q.p10 + q.p01 + q.p11) * 0.25;
                l.n = udm1scene::patch_normal(s, t, 0.5, 0.5);
                l.L = L, l.twosided = al.twosided, l.shape = (int)k, l.invisible = invisible;
                total += l.area;
                lights_.push_back(l);  // (zero-area patches stay, with zero power)
            }
            if (!(total > 0)) throw udm1scene::SceneError(s.where + ": an area light of zero area");
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
            l.centroid = (l.p0 + l.p1 + l.p2) * (1.0 / 3);
            l.n = l.area > 0 ? udm1scene::triangle_normal(s, t) : Vec3(0, 0, 1);
            l.L = L, l.twosided = al.twosided, l.shape = (int)k, l.invisible = invisible;
            // pbrt-v4 faces the normal to the interpolated vertex normal point by point: one side emits
            // throughout only where the vertex normals all lie on that side (triangle_normal's)
            if (!s.N.empty() && !l.twosided && l.area > 0)
                for (int v = 0; v < 3; ++v)
                    if (dot(l.n, Vec3(s.N[3 * i[v]], s.N[3 * i[v] + 1], s.N[3 * i[v] + 2])) < 0)
                        throw udm1scene::SceneError(s.where + ": a one-sided emitting triangle whose vertex normals point "
                                                              "to both sides of it (its emitting side changes across "
                                                              "it) is not modelled");
            total += l.area;
            lights_.push_back(l);  // zero-area triangles stay (indices match) with zero power
        }
        if (!(total > 0)) throw udm1scene::SceneError(s.where + ": an area light of zero area");
    }
    // the scene's bounding sphere: the power of lights at infinity, as pbrt-v4 measures it
    Vec3 lo, hi;
    scene.bounds(&lo, &hi);
    double r = std::max(0.5 * length(hi - lo), 1e-9);
    std::vector<double> extra_power;  // of the light sources, in order
    for (const udm1scene::LightSource &src : scene.light_sources) {
        only_area_ = false;
        Light l;
        l.L = src.L;
        double power = 0;
        switch (src.kind) {
        case udm1scene::LightSource::Point:
            l.kind = Light::Point, l.center = src.position;
            power = 4 * PI * luminance(l.L);
            break;
        case udm1scene::LightSource::Spot:
            l.kind = Light::Spot, l.center = src.position, l.axis = src.direction;
            l.cos_start = src.cos_start, l.cos_end = src.cos_end;
            power = 2 * PI * luminance(l.L) * ((1 - l.cos_start) + (l.cos_start - l.cos_end) / 2);
            break;
        case udm1scene::LightSource::Distant:
            l.kind = Light::Distant, l.axis = src.direction, l.at_infinity = true;
            power = PI * r * r * luminance(l.L);
            break;
        case udm1scene::LightSource::Infinite: {
            l.kind = Light::Infinite, l.at_infinity = true;
            l.world_from_light = src.world_from_light;
            src.world_from_light.inverse(&l.light_from_world);  // (the parser refused a singular one)
            double mean = luminance(l.L);
            if (!src.filename.empty()) {
                maps_.push_back(read_environment(src));
                const EnvironmentMap &m = maps_.back();
                l.map = (int)maps_.size() - 1;
                if (src.illuminance > 0) {  // pbrt-v4: the upper hemisphere's illuminance of the map
                    double e = 0;
                    for (int y = 0; y < m.res; ++y)
                        for (int x = 0; x < m.res; ++x) {
                            Vec3 w = equal_area_square_to_sphere((x + 0.5) / m.res, (y + 0.5) / m.res);
                            const float *c = &m.rgb[3 * ((size_t)y * m.res + x)];
                            if (w.z > 0) e += luminance(Vec3(c[0], c[1], c[2])) * w.z;
                        }
                    e *= 2 * PI / ((double)m.res * m.res);
                    if (e > 0) l.L = l.L * (src.illuminance / e);
                }
                mean = l.L.x * m.total / ((double)m.res * m.res);
            }
            power = 4 * PI * PI * r * r * mean;
            environments_.push_back((int)lights_.size());
            break;
        }
        }
        lights_.push_back(l);
        extra_power.push_back(power);
    }
    double sum = 0;
    size_t next_extra = 0;
    for (const Light &l : lights_) {
        bool surface = l.kind == Light::Triangle || l.kind == Light::Sphere || l.kind == Light::Disk ||
                       l.kind == Light::Cylinder || l.kind == Light::Patch;
        double power = surface ? luminance(l.L) * l.area * PI * (l.twosided ? 2 : 1) : extra_power[next_extra++];
        power_.push_back(power > 0 ? power : 0);
        sum += power_.back();
        cdf_.push_back(sum);
    }
    prob_.assign(lights_.size(), 0.0);
    if (sum > 0) {
        for (size_t i = 0; i < lights_.size(); ++i) prob_[i] = (cdf_[i] - (i ? cdf_[i - 1] : 0)) / sum;
    } else {
        lights_.clear(), cdf_.clear(), prob_.clear(), power_.clear(), environments_.clear();
        first_of_shape_.assign(scene.shapes.size(), -1);
    }
    make_groups();
}

// The groups of the lights not at infinity (lights.h) and their bounds, pbrt-v4's for each kind of light
// (DiffuseAreaLight, PointLight, SpotLight::Bounds), a shape's over its triangles.
void Lights::make_groups()
{
    for (size_t i = 0; i < lights_.size();) {
        Light &l = lights_[i];
        if (l.at_infinity) {
            if (power_[i] > 0) infinite_.push_back((int)i);
            ++i;
            continue;
        }
        Group g;
        g.first = i, g.count = 1;
        if (l.kind == Light::Triangle || l.kind == Light::Patch)  // the shape's triangles or patches
            while (i + g.count < lights_.size() && lights_[i + g.count].kind == l.kind &&
                   lights_[i + g.count].shape == l.shape)
                ++g.count;
        double sum = 0;
        for (size_t k = i; k < i + g.count; ++k) g.cdf.push_back(sum += power_[k]), lights_[k].group = (int)groups_.size();
        if (l.kind == Light::Triangle) {
            g.lo = g.hi = l.p0;
            Vec3 axis;
            for (size_t k = i; k < i + g.count; ++k) {
                const Light &t = lights_[k];
                for (Vec3 v : {t.p0, t.p1, t.p2}) g.lo = min3(g.lo, v), g.hi = max3(g.hi, v);
                axis = axis + t.n * t.area;
                g.phi += max_component(t.L) * t.area * PI;
            }
            double len = length(axis);
            g.w = len > 0 ? axis * (1 / len) : Vec3(0, 0, 1), g.cos_o = len > 0 ? 1 : -1;
            for (size_t k = i; k < i + g.count && len > 0; ++k)
                if (lights_[k].area > 0) g.cos_o = std::min(g.cos_o, dot(g.w, lights_[k].n));
            g.twosided = l.twosided;
        } else if (l.kind == Light::Patch) {  // (pbrt-v4's NormalBounds: each patch's corner normals)
            g.lo = g.hi = l.p0;
            Vec3 axis;
            for (size_t k = i; k < i + g.count; ++k) {
                const Light &t = lights_[k];
                for (Vec3 v : {t.p0, t.p1, t.p2, t.p3}) g.lo = min3(g.lo, v), g.hi = max3(g.hi, v);
                axis = axis + t.n * t.area;
                g.phi += max_component(t.L) * t.area * PI;
            }
            double len = length(axis);
            g.w = len > 0 ? axis * (1 / len) : Vec3(0, 0, 1), g.cos_o = len > 0 ? 1 : -1;
            for (size_t k = i; k < i + g.count && len > 0; ++k)
                if (lights_[k].area > 0)
                    for (double u : {0.0, 1.0})
                        for (double v : {0.0, 1.0})
                            g.cos_o = std::min(g.cos_o, dot(g.w, udm1scene::patch_normal(*lights_[k].src, lights_[k].prim, u, v)));
            g.twosided = l.twosided;
        } else if (l.kind == Light::Disk || l.kind == Light::Cylinder) {  // a disk's one normal; a cylinder's all
            udm1scene::shape_bounds(*l.src, &g.lo, &g.hi);
            g.w = l.kind == Light::Disk ? l.n : Vec3(0, 0, 1), g.cos_o = l.kind == Light::Disk ? 1 : -1;
            g.phi = max_component(l.L) * l.area * PI, g.twosided = l.twosided;
        } else if (l.kind == Light::Sphere) {  // its normals: every direction
            Vec3 r(l.radius, l.radius, l.radius);
            g.lo = l.center - r, g.hi = l.center + r, g.w = Vec3(0, 0, 1), g.cos_o = -1;
            g.phi = max_component(l.L) * l.area * PI, g.twosided = l.twosided;
        } else if (l.kind == Light::Point) {
            g.lo = g.hi = l.center, g.w = Vec3(0, 0, 1), g.cos_o = -1, g.phi = 4 * PI * max_component(l.L);
        } else {  // a spot
            g.lo = g.hi = l.center, g.w = l.axis, g.cos_o = l.cos_start, g.phi = 4 * PI * max_component(l.L);
            g.cos_e = std::cos(std::acos(std::clamp(l.cos_end, -1.0, 1.0)) - std::acos(std::clamp(l.cos_start, -1.0, 1.0)));
            if (g.cos_e == 1 && l.cos_end != l.cos_start) g.cos_e = 0.999;  // (pbrt-v4's slop for round-off)
        }
        g.center = (g.lo + g.hi) * 0.5, g.half_diagonal = length(g.hi - g.lo) / 2;
        g.radius2 = dot(g.hi - g.center, g.hi - g.center), g.sin_o = safe_sqrt(1 - g.cos_o * g.cos_o);
        if (sum > 0) groups_.push_back(std::move(g));
        else
            for (size_t k = i; k < i + g.count; ++k) lights_[k].group = -1;
        i += g.count;
    }
    by_importance_ = groups_.size() <= MAX_BY_IMPORTANCE;
}

// pbrt-v4's LightBounds::Importance of group g at the point p with unit normal n (zero: none).
double Lights::importance(const Group &g, Vec3 p, Vec3 n) const
{
    auto cos_sub = [](double sin_a, double cos_a, double sin_b, double cos_b) {  // cos(max(0, a - b))
        return cos_a > cos_b ? 1.0 : cos_a * cos_b + sin_a * sin_b;
    };
    auto sin_sub = [](double sin_a, double cos_a, double sin_b, double cos_b) {  // sin(max(0, a - b))
        return cos_a > cos_b ? 0.0 : sin_a * cos_b - cos_a * sin_b;
    };
    Vec3 v = p - g.center;
    double dc2 = dot(v, v);
    double d2 = std::max(dc2, g.half_diagonal);  // (pbrt-v4 clamps the squared distance so)
    Vec3 wi = dc2 > 0 ? v * (1 / std::sqrt(dc2)) : Vec3(0, 0, 1);
    double cos_w = dot(g.w, wi);
    if (g.twosided) cos_w = std::fabs(cos_w);
    double sin_w = safe_sqrt(1 - cos_w * cos_w);
    // the cone of directions from p that the box subtends (its bounding sphere's)
    double cos_b = -1, sin_b = 0;
    if (dc2 >= g.radius2 && dc2 > 0) {
        double sin2 = g.radius2 / dc2;
        cos_b = safe_sqrt(1 - sin2), sin_b = std::sqrt(sin2);
    }
    const double sin_o = g.sin_o;
    double cos_x = cos_sub(sin_w, cos_w, sin_o, g.cos_o), sin_x = sin_sub(sin_w, cos_w, sin_o, g.cos_o);
    double cos_p = cos_sub(sin_x, cos_x, sin_b, cos_b);
    if (cos_p <= g.cos_e) return 0;
    double imp = g.phi * cos_p / d2;
    if (n.x != 0 || n.y != 0 || n.z != 0) {
        double cos_i = std::fabs(dot(wi, n)), sin_i = safe_sqrt(1 - cos_i * cos_i);
        imp *= cos_sub(sin_i, cos_i, sin_b, cos_b);
    }
    return imp > 0 ? imp : 0;
}

double Lights::importances(Vec3 p, Vec3 n, double *imp) const
{
    double sum = 0;
    for (size_t k = 0; k < groups_.size(); ++k) sum += imp[k] = importance(groups_[k], p, n);
    return sum;
}

double Lights::infinite_probability() const
{
    return infinite_.empty() ? 0 : 1.0 / (double)(infinite_.size() + (groups_.empty() ? 0 : 1));
}

double Lights::group_probability(size_t g, Vec3 p, Vec3 n, double sum) const
{
    double rest = 1 - infinite_.size() * infinite_probability();
    if (groups_.size() == 1) return rest;
    if (std::isnan(sum)) {
        double imp[MAX_BY_IMPORTANCE];
        sum = importances(p, n, imp);
    }
    return sum > 0 ? rest * (importance(groups_[g], p, n) / sum) : 0;
}

bool Lights::choose(double u1, Vec3 p, Vec3 n, size_t *light, double *rescaled, double *probability,
                    double *importance_sum) const
{
    const double ONE_MINUS_EPS = 0x1.fffffffffffffp-1;
    // the interval of [0, cdf.back()) that target falls in, skipping empty ones, and target rescaled to it
    auto pick = [&](const double *cdf, size_t count, double target, double *u) {
        size_t k = 0;
        while (k + 1 < count && cdf[k] <= target) ++k;
        while (k > 0 && cdf[k] == cdf[k - 1]) --k;  // (rounding past the last non-empty interval)
        double lo = k ? cdf[k - 1] : 0.0;
        *u = std::clamp((target - lo) / (cdf[k] - lo), 0.0, ONE_MINUS_EPS);
        return k;
    };
    if (!by_importance_) {  // by power: cdf_, the same at every point
        size_t i = std::upper_bound(cdf_.begin(), cdf_.end(), u1 * cdf_.back()) - cdf_.begin();
        if (i >= lights_.size()) i = lights_.size() - 1;
        while (prob_[i] == 0 && i > 0) --i;  // (only with a zero-power light at the very end)
        double lo = i ? cdf_[i - 1] : 0.0, u = std::min((u1 * cdf_.back() - lo) / (cdf_[i] - lo), ONE_MINUS_EPS);
        *light = i, *rescaled = u >= 0 ? u : 0, *probability = prob_[i];
        return prob_[i] > 0;
    }
    double p_inf = infinite_.size() * infinite_probability();
    if (u1 < p_inf) {  // a light at infinity, each as likely
        double t = u1 / p_inf * (double)infinite_.size();
        size_t k = std::min((size_t)t, infinite_.size() - 1);
        *light = (size_t)infinite_[k], *rescaled = std::clamp(t - (double)k, 0.0, ONE_MINUS_EPS);
        *probability = infinite_probability();
        return true;
    }
    double u = std::min((u1 - p_inf) / (1 - p_inf), ONE_MINUS_EPS), pg = 1 - p_inf;
    size_t g = 0;
    if (groups_.size() > 1) {  // a group by importance
        double imp[MAX_BY_IMPORTANCE], sum = importances(p, n, imp);
        if (importance_sum) *importance_sum = sum;
        if (!(sum > 0)) return false;
        double acc[MAX_BY_IMPORTANCE], a = 0;
        for (size_t k = 0; k < groups_.size(); ++k) acc[k] = a += imp[k];
        g = pick(acc, groups_.size(), u * sum, &u);
        pg *= imp[g] / sum;
    }
    const Group &G = groups_[g];  // then a light of it by power
    size_t k = pick(G.cdf.data(), G.count, u * G.cdf.back(), &u);
    *light = G.first + k, *rescaled = u;
    *probability = pg * ((G.cdf[k] - (k ? G.cdf[k - 1] : 0.0)) / G.cdf.back());
    return true;
}

double Lights::probability(size_t i, Vec3 p, Vec3 n, double importance_sum) const
{
    if (!by_importance_) return prob_[i];
    if (lights_[i].at_infinity) return infinite_probability();
    if (power_[i] == 0 || lights_[i].group < 0) return 0;
    const Group &G = groups_[lights_[i].group];
    size_t k = i - G.first;
    return group_probability((size_t)lights_[i].group, p, n, importance_sum) *
           ((G.cdf[k] - (k ? G.cdf[k - 1] : 0.0)) / G.cdf.back());
}

int Lights::light_of(const udm1scene::Hit &h) const
{
    if (h.shape >= first_of_shape_.size() || first_of_shape_[h.shape] < 0) return -1;
    const Light &first = lights_[first_of_shape_[h.shape]];
    bool single = first.kind == Light::Sphere || first.kind == Light::Disk || first.kind == Light::Cylinder;
    return first_of_shape_[h.shape] + (single ? 0 : (int)h.prim);
}

Vec3 Lights::radiance(const Light &l, Vec3 n, Vec3 w) const
{
    if (!l.twosided && dot(n, w) <= 0) return Vec3();
    return l.L;
}

Vec3 Lights::environment_of(const Light &l, Vec3 d) const
{
    if (l.map < 0) return l.L;
    const EnvironmentMap &m = maps_[l.map];
    double u, v;
    equal_area_sphere_to_square(normalize(l.light_from_world.vector(d)), &u, &v);
    int x = std::clamp((int)(u * m.res), 0, m.res - 1), y = std::clamp((int)(v * m.res), 0, m.res - 1);
    const float *c = &m.rgb[3 * ((size_t)y * m.res + x)];
    return Vec3(c[0] * l.L.x, c[1] * l.L.y, c[2] * l.L.z);
}

double Lights::environment_pdf_of(const Light &l, Vec3 d) const
{
    if (l.map < 0) return 1 / (4 * PI);
    const EnvironmentMap &m = maps_[l.map];
    double u, v;
    equal_area_sphere_to_square(normalize(l.light_from_world.vector(d)), &u, &v);
    int x = std::clamp((int)(u * m.res), 0, m.res - 1), y = std::clamp((int)(v * m.res), 0, m.res - 1);
    const double *row = &m.pixel_cdf[(size_t)y * (m.res + 1)];
    return (row[x + 1] - row[x]) / m.total * ((double)m.res * m.res) / (4 * PI);  // the square's area is 4 pi sr
}

Vec3 Lights::environment(Vec3 d) const
{
    Vec3 L;
    for (int i : environments_) L = L + environment_of(lights_[i], d);
    return L;
}

double Lights::environment_pdf(Vec3 d) const
{
    double pdf = 0;
    for (int i : environments_)
        pdf += (by_importance_ ? infinite_probability() : prob_[i]) * environment_pdf_of(lights_[i], d);
    return pdf;
}

Vec3 Lights::environment_maps(Vec3 d) const
{
    Vec3 L;
    for (int i : environments_)
        if (lights_[i].map >= 0) L = L + environment_of(lights_[i], d);
    return L;
}

double Lights::environment_map_pdf(Vec3 d) const
{
    double pdf = 0;
    for (int i : environments_)
        if (lights_[i].map >= 0) pdf += (by_importance_ ? infinite_probability() : prob_[i]) * environment_pdf_of(lights_[i], d);
    return pdf;
}

// The lights that are not shapes: point and spot lights (a delta in position), distant lights (a delta
// in direction), environments (uniform: by uniform directions; a map: by its pixels' luminance).
bool Lights::sample_source(const Light &l, double prob, Vec3 p, double u1, double u2, LightSample *s) const
{
    s->n = Vec3();
    if (l.kind == Light::Point || l.kind == Light::Spot) {
        Vec3 d = l.center - p;
        double d2 = dot(d, d);
        if (!(d2 > 0)) return false;
        s->dist = std::sqrt(d2), s->wi = d * (1 / s->dist), s->q = l.center;
        double falloff = l.kind == Light::Spot ? smooth_step(-dot(s->wi, l.axis), l.cos_end, l.cos_start) : 1;
        s->L = l.L * (falloff / d2), s->pdf = prob, s->delta = true;
        return falloff > 0;
    }
    s->infinite = true;
    if (l.kind == Light::Distant) {
        s->wi = l.axis, s->L = l.L, s->pdf = prob, s->delta = true;
        return true;
    }
    if (l.map < 0) {  // a uniform environment: uniform directions
        double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z)), sn, cs;
        udm1scene::sincos_2pi(u2, &sn, &cs);
        s->wi = Vec3(r * cs, r * sn, z), s->L = l.L, s->pdf = prob / (4 * PI), s->uniform = true;
        return true;
    }
    const EnvironmentMap &m = maps_[l.map];  // a row by u1, a pixel of it by u2, the point in it by both rescaled
    double fy, fx;
    int y = pick(m.row_cdf.data(), m.res, u1 * m.total, &fy);
    const double *row = &m.pixel_cdf[(size_t)y * (m.res + 1)];
    int x = pick(row, m.res, u2 * row[m.res], &fx);
    Vec3 w = equal_area_square_to_sphere((x + fx) / m.res, (y + fy) / m.res);
    s->wi = normalize(l.world_from_light.vector(w));
    const float *c = &m.rgb[3 * ((size_t)y * m.res + x)];
    s->L = Vec3(c[0] * l.L.x, c[1] * l.L.y, c[2] * l.L.z);
    s->pdf = prob * (row[x + 1] - row[x]) / m.total * ((double)m.res * m.res) / (4 * PI);
    return s->pdf > 0;
}

Vec3 Lights::emitted(const udm1scene::Hit &h, Vec3 w) const
{
    int i = light_of(h);
    if (i < 0) return Vec3();
    return radiance(lights_[i], h.ng, w);
}

bool Lights::by_solid_angle(const Light &l, Vec3 p, double *omega) const
{
    // far, or behind a one-sided light (no light reaches p however it is sampled): by area, the cheaper
    if (far(l, p) || (!l.twosided && dot(l.n, p - l.p0) <= 0)) return false;
    *omega = solid_angle(p, l.p0, l.p1, l.p2);
    return *omega >= MIN_SPHERICAL_AREA && *omega <= MAX_SPHERICAL_AREA;
}

double Lights::pdf_light(const Light &l, Vec3 p, const udm1scene::Hit &h) const
{
    const Vec3 q = h.p, nq = h.ng;
    Vec3 d = q - p;
    double d2 = dot(d, d);
    if (l.kind == Light::Sphere) {
        double dc2 = dot(l.center - p, l.center - p), r2 = l.radius * l.radius;
        if (dc2 > r2 * 1.0001) {  // outside: the cone of directions
            double sin2 = r2 / dc2, one_minus_cos = sin2 < 0.00068523 ? sin2 / 2 + sin2 * sin2 / 8 : 1 - std::sqrt(1 - sin2);
            return 1 / (2 * PI * one_minus_cos);
        }
    }
    double omega;
    if (l.kind == Light::Triangle && by_solid_angle(l, p, &omega)) return 1 / omega;
    double c = std::fabs(dot(nq, d)) / std::sqrt(d2);
    if (!(c > 0)) return 0;
    if (l.kind == Light::Patch) {
        if (l.rectangle) {
            omega = rectangle_solid_angle(p, l.p0, l.p1 - l.p0, l.p2 - l.p0);
            if (rectangle_by_solid_angle(omega)) return 1 / omega;
            return d2 / (c * l.area);
        }
        udm1scene::Patch pq{l.p0, l.p1, l.p2, l.p3};
        Vec3 dpdu, dpdv;
        pq.derivatives(h.u, h.v, &dpdu, &dpdv);
        double jac = length(cross(dpdu, dpdv));
        return jac > 0 ? udm1scene::bilinear_pdf(h.u, h.v, l.w) / jac * d2 / c : 0;
    }
    return d2 / (c * l.area);
}

double Lights::pdf(Vec3 p, Vec3 n, const udm1scene::Hit &h, double importance_sum) const
{
    int i = light_of(h);
    if (i < 0 || lights_[i].invisible) return 0;
    double prob = probability((size_t)i, p, n, importance_sum);
    return prob > 0 ? prob * pdf_light(lights_[i], p, h) : 0;
}

// A point on a disk, cylinder or patch light for the shading point p, its normal (the emitting side's)
// and the solid-angle density of choosing it (without the choice of the light): pdf_light()'s.
bool Lights::sample_surface(const Light &l, Vec3 p, double u1, double u2, Vec3 *q, Vec3 *nq, double *pdf) const
{
    if (l.kind == Light::Disk || l.kind == Light::Cylinder) {
        udm1scene::quadric_sample_area(*l.src, u1, u2, q, nq);
        if (l.reversed) *nq = -*nq;
        Vec3 d = *q - p;
        double d2 = dot(d, d), c = d2 > 0 ? std::fabs(dot(*nq, d)) / std::sqrt(d2) : 0;
        *pdf = c > 0 ? d2 / (c * l.area) : 0;
        return *pdf > 0 && std::isfinite(*pdf);
    }
    udm1scene::Patch pq{l.p0, l.p1, l.p2, l.p3};
    double u, v, pdf_uv = 1;
    if (l.rectangle) {
        Vec3 eu = l.p1 - l.p0, ev = l.p2 - l.p0;
        double omega = rectangle_solid_angle(p, l.p0, eu, ev);
        if (rectangle_by_solid_angle(omega)) {  // by solid angle
            if (!sample_spherical_rectangle(p, l.p0, eu, ev, u1, u2, q)) return false;
            u = std::clamp(dot(*q - l.p0, eu) / dot(eu, eu), 0.0, 1.0), v = std::clamp(dot(*q - l.p0, ev) / dot(ev, ev), 0.0, 1.0);
            *nq = udm1scene::patch_normal(*l.src, l.prim, u, v);
            *pdf = 1 / omega;
            return std::isfinite(*pdf);
        }
        u = u1, v = u2;
    } else {
        udm1scene::sample_bilinear(u1, u2, l.w, &u, &v);
        pdf_uv = udm1scene::bilinear_pdf(u, v, l.w);
    }
    Vec3 dpdu, dpdv;
    pq.derivatives(u, v, &dpdu, &dpdv);
    double jac = length(cross(dpdu, dpdv));
    if (!(jac > 0)) return false;
    *q = pq.at(u, v);
    *nq = udm1scene::patch_normal(*l.src, l.prim, u, v);
    Vec3 d = *q - p;
    double d2 = dot(d, d), c = d2 > 0 ? std::fabs(dot(*nq, d)) / std::sqrt(d2) : 0;
    *pdf = c > 0 ? (l.rectangle ? 1 / l.area : pdf_uv / jac) * d2 / c : 0;
    return *pdf > 0 && std::isfinite(*pdf);
}

bool Lights::sample(Vec3 p, Vec3 n, double u1, double u2, LightSample *s) const
{
    size_t i;
    double prob;
    if (lights_.empty() || !choose(u1, p, n, &i, &u1, &prob, &s->importance_sum)) return false;
    const Light &l = lights_[i];
    s->shape = l.shape, s->sphere = l.kind == Light::Sphere;
    s->delta = s->infinite = s->uniform = false;
    if (l.kind == Light::Disk || l.kind == Light::Cylinder || l.kind == Light::Patch) {
        Vec3 q, nq;
        double pdf;
        if (!sample_surface(l, p, u1, u2, &q, &nq, &pdf)) return false;
        Vec3 d = q - p;
        double d2 = dot(d, d);
        if (d2 <= 0) return false;
        s->dist = std::sqrt(d2), s->wi = d * (1 / s->dist), s->q = q, s->n = nq;
        s->L = radiance(l, nq, -s->wi);
        s->pdf = prob * pdf;
        s->delta = l.invisible;  // (pbrt-v4: a delta light, without MIS)
        return s->pdf > 0 && std::isfinite(s->pdf) && (s->L.x > 0 || s->L.y > 0 || s->L.z > 0);
    }
    if (l.kind != Light::Triangle && l.kind != Light::Sphere) return sample_source(l, prob, p, u1, u2, s);
    s->delta = l.invisible;
    Vec3 q, nq;
    double omega = 0;
    bool spherical = false;  // a triangle sampled by solid angle
    if (l.kind == Light::Sphere) {
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
            double sin_phi, cos_phi;
            udm1scene::sincos_2pi(u2, &sin_phi, &cos_phi);
            Vec3 wc = dc * (1 / dist);
            udm1scene::Frame f(wc);
            nq = (f.t * (sin_alpha * cos_phi) + f.b * (sin_alpha * sin_phi)) + (-wc) * cos_alpha;
            nq = normalize(nq);
            q = l.center + nq * l.radius;
            if (l.reversed) nq = -nq;  // the side it emits from, as where rays hit it
            Vec3 d = q - p;
            s->dist = length(d);
            s->wi = d * (1 / s->dist);
            s->L = radiance(l, nq, -s->wi);
            s->q = q, s->n = nq;
            s->pdf = prob / (2 * PI * one_minus_cos_max);
            return s->pdf > 0 && (s->L.x > 0 || s->L.y > 0 || s->L.z > 0);
        }
        // inside the sphere: by area
        double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z)), sin_phi, cos_phi;
        udm1scene::sincos_2pi(u2, &sin_phi, &cos_phi);
        nq = Vec3(r * cos_phi, r * sin_phi, z);
        q = l.center + nq * l.radius;
        if (l.reversed) nq = -nq;
    } else {
        // by solid angle where the spherical triangle is well formed (pbrt-v4), else by area
        spherical = by_solid_angle(l, p, &omega);
        if (!spherical || !sample_spherical_triangle(p, l.p0, l.p1, l.p2, u1, u2, &q)) {
            if (spherical) return false;
            double su = std::sqrt(u1), b0 = 1 - su, b1 = u2 * su;
            q = l.p0 * b0 + l.p1 * b1 + l.p2 * (1 - b0 - b1);
        }
        nq = l.n;
    }
    Vec3 d = q - p;
    double d2 = dot(d, d);
    if (d2 <= 0) return false;
    s->dist = std::sqrt(d2);
    s->wi = d * (1 / s->dist);
    s->q = q, s->n = nq;
    s->L = radiance(l, nq, -s->wi);
    // the density pdf_light() gives, without deciding the sampling method again
    double c = std::fabs(dot(nq, d)) / s->dist;
    s->pdf = prob * (spherical ? 1 / omega : c > 0 ? d2 / (c * l.area) : 0);
    return s->pdf > 0 && std::isfinite(s->pdf) && (s->L.x > 0 || s->L.y > 0 || s->L.z > 0);
}

}  // namespace udm1pt
