// bsdf.cpp - see bsdf.h. Formulas follow pbrt-v4 (Pharr, Jakob, Humphreys, 4th ed., chapters 9
// and 14): Trowbridge-Reitz with visible-normal sampling, the rough dielectric, and the layered
// random walk without a medium.
#include "bsdf.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace udm1pt {

namespace {

const double PI = 3.14159265358979323846;
const double ONE_MINUS_EPS = 0x1.fffffffffffffp-1;

inline double sqr(double x) { return x * x; }
inline double cos2(Vec3 w) { return w.z * w.z; }
inline double sin2(Vec3 w) { return std::max(0.0, 1 - cos2(w)); }
inline double tan2(Vec3 w) { return sin2(w) / cos2(w); }
inline double cos_phi(Vec3 w)
{
    double s = std::sqrt(sin2(w));
    return s == 0 ? 1 : std::clamp(w.x / s, -1.0, 1.0);
}
inline double sin_phi(Vec3 w)
{
    double s = std::sqrt(sin2(w));
    return s == 0 ? 0 : std::clamp(w.y / s, -1.0, 1.0);
}
inline bool same_hemisphere(Vec3 a, Vec3 b) { return a.z * b.z > 0; }
inline Vec3 face_forward(Vec3 n, Vec3 v) { return udm1scene::dot(n, v) < 0 ? -n : n; }
inline Vec3 reflect(Vec3 wo, Vec3 n) { return -wo + n * (2 * udm1scene::dot(wo, n)); }
inline Vec3 scale(Vec3 v, double s) { return v * s; }

// Refraction of wi through a surface with normal n and relative eta; false on total internal reflection.
bool refract(Vec3 wi, Vec3 n, double eta, double *etap, Vec3 *wt)
{
    double cos_i = udm1scene::dot(n, wi);
    if (cos_i < 0) eta = 1 / eta, cos_i = -cos_i, n = -n;
    double sin2_i = std::max(0.0, 1 - cos_i * cos_i), sin2_t = sin2_i / (eta * eta);
    if (sin2_t >= 1) return false;
    double cos_t = std::sqrt(1 - sin2_t);
    *wt = -wi * (1 / eta) + n * (cos_i / eta - cos_t);
    if (etap) *etap = eta;
    return true;
}

// A small deterministic generator for the layered random walk, seeded from the directions.
struct Rng {
    uint64_t s;
    static uint64_t mix(uint64_t z)
    {
        z += 0x9e3779b97f4a7c15ull;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    static uint64_t hash(Vec3 v, uint64_t h)
    {
        for (double c : {v.x, v.y, v.z}) {
            uint64_t b;
            std::memcpy(&b, &c, 8);
            h = mix(h ^ b);
        }
        return h;
    }
    Rng(uint64_t a, uint64_t b) : s(mix(a ^ mix(b))) {}
    double operator()()
    {
        s += 0x9e3779b97f4a7c15ull;
        return std::min(ONE_MINUS_EPS, (mix(s) >> 11) * 0x1p-53);
    }
};

// Transmittance through the layer of thickness dz along w (no medium: pbrt's Tr with sigma_t = 1).
inline double Tr(double dz, Vec3 w)
{
    if (std::fabs(dz) <= 1e-300) return 1;
    return std::exp(-std::fabs(dz / w.z));
}

inline double power_heuristic(double f, double g) { return f * f + g * g > 0 ? f * f / (f * f + g * g) : 0; }

}  // namespace

// ---- Trowbridge-Reitz ----

double Microfacets::D(Vec3 wm) const
{
    double t2 = tan2(wm);
    if (std::isinf(t2) || std::isnan(t2)) return 0;
    double c4 = sqr(cos2(wm));
    if (c4 < 1e-16) return 0;
    // isotropic (ax == ay, every material of the scenes): cos^2 phi + sin^2 phi = 1, no azimuth needed
    double e = ax == ay ? t2 / (ax * ax) : t2 * (sqr(cos_phi(wm) / ax) + sqr(sin_phi(wm) / ay));
    return 1 / (PI * ax * ay * c4 * sqr(1 + e));
}

double Microfacets::lambda(Vec3 w) const
{
    double t2 = tan2(w);
    if (std::isinf(t2) || std::isnan(t2)) return 0;
    double a2 = ax == ay ? ax * ax : sqr(cos_phi(w) * ax) + sqr(sin_phi(w) * ay);
    return (std::sqrt(1 + a2 * t2) - 1) / 2;
}

double Microfacets::pdf(Vec3 w, Vec3 wm) const
{
    return G1(w) / std::fabs(w.z) * D(wm) * std::fabs(udm1scene::dot(w, wm));
}

Vec3 Microfacets::sample_wm(Vec3 w, double u1, double u2) const
{
    // visible normals by spherical caps (Dupuy and Benyoub 2023): w stretched to the hemisphere
    // configuration, a uniform point on the cap of the unit sphere below it (u1 its height, u2 its
    // azimuth), their sum the stretched visible normal. The same density as pbrt-v4's (Heitz 2018), with
    // fewer square roots and no frame.
    Vec3 wh = udm1scene::normalize(Vec3(ax * w.x, ay * w.y, w.z));
    if (wh.z < 0) wh = -wh;
    double z = (1 - u1) * (1 + wh.z) - wh.z, sin_t = std::sqrt(std::max(0.0, 1 - z * z)), sin_phi, cos_phi;
    udm1scene::sincos_2pi(u2, &sin_phi, &cos_phi);
    Vec3 h(sin_t * cos_phi + wh.x, sin_t * sin_phi + wh.y, z + wh.z);
    return udm1scene::normalize(Vec3(ax * h.x, ay * h.y, std::max(1e-6, h.z)));
}

double fresnel_dielectric(double cos_i, double eta)
{
    cos_i = std::clamp(cos_i, -1.0, 1.0);
    if (cos_i < 0) eta = 1 / eta, cos_i = -cos_i;
    double sin2_i = 1 - cos_i * cos_i, sin2_t = sin2_i / (eta * eta);
    if (sin2_t >= 1) return 1;
    double cos_t = std::sqrt(std::max(0.0, 1 - sin2_t));
    double r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    double r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return (r_parl * r_parl + r_perp * r_perp) / 2;
}

// ---- dielectric interface ----

Vec3 Dielectric::f(Vec3 wo, Vec3 wi, Mode mode) const
{
    if (specular()) return Vec3();
    double co = wo.z, ci = wi.z;
    bool refl = co * ci > 0;
    double etap = 1;
    if (!refl) etap = co > 0 ? eta : 1 / eta;
    Vec3 wm = wi * etap + wo;
    if (ci == 0 || co == 0 || udm1scene::dot(wm, wm) == 0) return Vec3();
    wm = face_forward(udm1scene::normalize(wm), Vec3(0, 0, 1));
    if (udm1scene::dot(wm, wi) * ci < 0 || udm1scene::dot(wm, wo) * co < 0) return Vec3();
    double F = fresnel_dielectric(udm1scene::dot(wo, wm), eta);
    double v;
    if (refl) {
        v = mf.D(wm) * mf.G(wo, wi) * F / std::fabs(4 * ci * co);
    } else {
        double denom = sqr(udm1scene::dot(wi, wm) + udm1scene::dot(wo, wm) / etap) * ci * co;
        v = mf.D(wm) * (1 - F) * mf.G(wo, wi) * std::fabs(udm1scene::dot(wi, wm) * udm1scene::dot(wo, wm) / denom);
        if (mode == Mode::Radiance) v /= etap * etap;
    }
    return Vec3(v, v, v);
}

double Dielectric::pdf(Vec3 wo, Vec3 wi, Mode, unsigned lobes) const
{
    if (specular()) return 0;
    double co = wo.z, ci = wi.z;
    bool refl = co * ci > 0;
    double etap = 1;
    if (!refl) etap = co > 0 ? eta : 1 / eta;
    Vec3 wm = wi * etap + wo;
    if (ci == 0 || co == 0 || udm1scene::dot(wm, wm) == 0) return 0;
    wm = face_forward(udm1scene::normalize(wm), Vec3(0, 0, 1));
    if (udm1scene::dot(wm, wi) * ci < 0 || udm1scene::dot(wm, wo) * co < 0) return 0;
    double R = fresnel_dielectric(udm1scene::dot(wo, wm), eta), T = 1 - R;
    if (!(lobes & Reflect)) R = 0;
    if (!(lobes & Transmit)) T = 0;
    if (R == 0 && T == 0) return 0;
    if (refl) return mf.pdf(wo, wm) / (4 * std::fabs(udm1scene::dot(wo, wm))) * R / (R + T);
    double denom = sqr(udm1scene::dot(wi, wm) + udm1scene::dot(wo, wm) / etap);
    return mf.pdf(wo, wm) * std::fabs(udm1scene::dot(wi, wm)) / denom * T / (R + T);
}

bool Dielectric::sample(Vec3 wo, double uc, double u1, double u2, Mode mode, unsigned lobes, Sample *s) const
{
    if (specular()) {
        double R = fresnel_dielectric(wo.z, eta), T = 1 - R;
        if (!(lobes & Reflect)) R = 0;
        if (!(lobes & Transmit)) T = 0;
        if (R == 0 && T == 0) return false;
        s->specular = true;
        if (uc < R / (R + T)) {
            s->wi = Vec3(-wo.x, -wo.y, wo.z);
            double v = R / std::fabs(s->wi.z);
            s->f = Vec3(v, v, v), s->pdf = R / (R + T), s->reflection = true;
            return true;
        }
        double etap;
        Vec3 wi;
        if (!refract(wo, Vec3(0, 0, 1), eta, &etap, &wi)) return false;
        double v = T / std::fabs(wi.z);
        if (mode == Mode::Radiance) v /= etap * etap;
        s->wi = wi, s->f = Vec3(v, v, v), s->pdf = T / (R + T), s->reflection = false, s->eta = etap;
        return true;
    }
    Vec3 wm = mf.sample_wm(wo, u1, u2);
    double R = fresnel_dielectric(udm1scene::dot(wo, wm), eta), T = 1 - R;
    if (!(lobes & Reflect)) R = 0;
    if (!(lobes & Transmit)) T = 0;
    if (R == 0 && T == 0) return false;
    s->specular = false;
    // the microfacet terms once: D(wm) and lambda(wo) serve both the density and the value
    const double D = mf.D(wm), lambda_o = mf.lambda(wo);
    const double pdf_wm = 1 / (1 + lambda_o) / std::fabs(wo.z) * D * std::fabs(udm1scene::dot(wo, wm));  // mf.pdf(wo, wm)
    if (uc < R / (R + T)) {
        Vec3 wi = reflect(wo, wm);
        if (!same_hemisphere(wo, wi)) return false;
        s->pdf = pdf_wm / (4 * std::fabs(udm1scene::dot(wo, wm))) * R / (R + T);
        double v = D * (1 / (1 + lambda_o + mf.lambda(wi))) * R / (4 * wi.z * wo.z);
        s->wi = wi, s->f = Vec3(v, v, v), s->reflection = true;
        return s->pdf > 0;
    }
    double etap;
    Vec3 wi;
    if (!refract(wo, wm, eta, &etap, &wi) || same_hemisphere(wo, wi) || wi.z == 0) return false;
    double denom = sqr(udm1scene::dot(wi, wm) + udm1scene::dot(wo, wm) / etap);
    double dwm_dwi = std::fabs(udm1scene::dot(wi, wm)) / denom;
    s->pdf = pdf_wm * dwm_dwi * T / (R + T);
    double v = T * D * (1 / (1 + lambda_o + mf.lambda(wi))) *
               std::fabs(udm1scene::dot(wi, wm) * udm1scene::dot(wo, wm) / (wi.z * wo.z * denom));
    if (mode == Mode::Radiance) v /= etap * etap;
    s->wi = wi, s->f = Vec3(v, v, v), s->reflection = false, s->eta = etap;
    return s->pdf > 0;
}

// ---- conductor ----

double fresnel_complex(double cos_i, double eta, double k)
{
    // |r_s|^2 and |r_p|^2 with complex arithmetic, as pbrt-v4's FrComplex
    cos_i = std::clamp(cos_i, 0.0, 1.0);
    double sin2_i = 1 - cos_i * cos_i;
    // eta_c = eta + i k; sin2_t = sin2_i / eta_c^2; cos_t = sqrt(1 - sin2_t)
    double e2r = eta * eta - k * k, e2i = 2 * eta * k, e2n = e2r * e2r + e2i * e2i;
    double s2r = sin2_i * e2r / e2n, s2i = -sin2_i * e2i / e2n;  // sin2_i / eta_c^2
    double ar = 1 - s2r, ai = -s2i;                               // 1 - sin2_t
    double mod = std::sqrt(ar * ar + ai * ai), ctr = std::sqrt((mod + ar) / 2);
    double cti = std::copysign(std::sqrt(std::max(0.0, (mod - ar) / 2)), ai);
    auto norm2 = [](double r, double i) { return r * r + i * i; };
    // r_parl = (eta_c cos_i - cos_t) / (eta_c cos_i + cos_t); r_perp = (cos_i - eta_c cos_t) / (cos_i + eta_c cos_t)
    double ecr = eta * cos_i, eci = k * cos_i;
    double rpl = norm2(ecr - ctr, eci - cti) / norm2(ecr + ctr, eci + cti);
    double ect_r = eta * ctr - k * cti, ect_i = eta * cti + k * ctr;
    double rpp = norm2(cos_i - ect_r, -ect_i) / norm2(cos_i + ect_r, ect_i);
    return (rpl + rpp) / 2;
}

Vec3 FresnelTable::at(double c) const
{
    double x = std::clamp(c, 0.0, 1.0) * (N - 1);
    int i = std::min((int)x, N - 2);
    double t = x - i;
    return Vec3(r[0][i] + t * (r[0][i + 1] - r[0][i]), r[1][i] + t * (r[1][i + 1] - r[1][i]),
                r[2][i] + t * (r[2][i + 1] - r[2][i]));
}

Vec3 Conductor::fresnel(double c) const
{
    if (table) return table->at(c);
    return Vec3(fresnel_complex(c, eta.x, k.x), fresnel_complex(c, eta.y, k.y), fresnel_complex(c, eta.z, k.z));
}

Vec3 Conductor::f(Vec3 wo, Vec3 wi) const
{
    if (!same_hemisphere(wo, wi) || specular()) return Vec3();
    double co = std::fabs(wo.z), ci = std::fabs(wi.z);
    if (co == 0 || ci == 0) return Vec3();
    Vec3 wm = wi + wo;
    if (udm1scene::dot(wm, wm) == 0) return Vec3();
    wm = udm1scene::normalize(wm);
    Vec3 F = fresnel(std::fabs(udm1scene::dot(wo, wm)));
    return F * (mf.D(wm) * mf.G(wo, wi) / (4 * ci * co));
}

double Conductor::pdf(Vec3 wo, Vec3 wi) const
{
    if (!same_hemisphere(wo, wi) || specular()) return 0;
    Vec3 wm = wo + wi;
    if (udm1scene::dot(wm, wm) == 0) return 0;
    wm = face_forward(udm1scene::normalize(wm), Vec3(0, 0, 1));
    return mf.pdf(wo, wm) / (4 * std::fabs(udm1scene::dot(wo, wm)));
}

bool Conductor::sample(Vec3 wo, double u1, double u2, Sample *s) const
{
    if (specular()) {
        Vec3 wi(-wo.x, -wo.y, wo.z);
        if (wi.z == 0) return false;
        s->wi = wi, s->f = fresnel(std::fabs(wi.z)) * (1 / std::fabs(wi.z)), s->pdf = 1;
        s->specular = true, s->reflection = true;
        return true;
    }
    if (wo.z == 0) return false;
    Vec3 wm = mf.sample_wm(wo, u1, u2);
    Vec3 wi = reflect(wo, wm);
    if (!same_hemisphere(wo, wi)) return false;
    const double D = mf.D(wm), lambda_o = mf.lambda(wo);  // once, for the density and the value
    s->pdf = 1 / (1 + lambda_o) / std::fabs(wo.z) * D * std::fabs(udm1scene::dot(wo, wm)) / (4 * std::fabs(udm1scene::dot(wo, wm)));
    double co = std::fabs(wo.z), ci = std::fabs(wi.z);
    if (ci == 0 || co == 0 || !(s->pdf > 0)) return false;
    s->f = fresnel(std::fabs(udm1scene::dot(wo, wm))) * (D * (1 / (1 + lambda_o + mf.lambda(wi))) / (4 * ci * co));
    s->wi = wi, s->specular = false, s->reflection = true;
    return true;
}

// ---- Lambertian ----

Vec3 Lambert::f(Vec3 wo, Vec3 wi) const { return same_hemisphere(wo, wi) ? R * (1 / PI) : Vec3(); }

double Lambert::pdf(Vec3 wo, Vec3 wi, unsigned lobes) const
{
    if (!(lobes & Reflect) || !same_hemisphere(wo, wi)) return 0;
    return std::fabs(wi.z) / PI;
}

bool Lambert::sample(Vec3 wo, double u1, double u2, unsigned lobes, Sample *s) const
{
    if (!(lobes & Reflect)) return false;
    double r = std::sqrt(u1), sin_phi, cos_phi;
    udm1scene::sincos_2pi(u2, &sin_phi, &cos_phi);
    Vec3 wi(r * cos_phi, r * sin_phi, std::sqrt(std::max(0.0, 1 - u1)));
    if (wo.z < 0) wi.z = -wi.z;
    s->wi = wi, s->f = R * (1 / PI), s->pdf = std::fabs(wi.z) / PI, s->specular = false, s->reflection = true;
    s->pdf_is_proportional = false;
    return s->pdf > 0;
}

// ---- diffuse transmission ----

Vec3 DiffuseTransmission::f(Vec3 wo, Vec3 wi) const { return (same_hemisphere(wo, wi) ? R : T) * (1 / PI); }

double DiffuseTransmission::pdf(Vec3 wo, Vec3 wi) const
{
    double pr = std::max({R.x, R.y, R.z}), pt = std::max({T.x, T.y, T.z});
    if (pr == 0 && pt == 0) return 0;
    return (same_hemisphere(wo, wi) ? pr : pt) / (pr + pt) * std::fabs(wi.z) / PI;
}

bool DiffuseTransmission::sample(Vec3 wo, double uc, double u1, double u2, Sample *s) const
{
    double pr = std::max({R.x, R.y, R.z}), pt = std::max({T.x, T.y, T.z});
    if (pr == 0 && pt == 0) return false;
    bool reflect = uc < pr / (pr + pt);
    double r = std::sqrt(u1), sin_phi, cos_phi;
    udm1scene::sincos_2pi(u2, &sin_phi, &cos_phi);
    Vec3 wi(r * cos_phi, r * sin_phi, std::sqrt(std::max(0.0, 1 - u1)));
    if ((wo.z < 0) == reflect) wi.z = -wi.z;  // reflection: wo's side; transmission: the other
    s->wi = wi, s->f = (reflect ? R : T) * (1 / PI);
    s->pdf = (reflect ? pr : pt) / (pr + pt) * std::fabs(wi.z) / PI;
    s->specular = false, s->reflection = reflect, s->eta = 1;
    return s->pdf > 0;
}

// ---- Henyey-Greenstein ----

double henyey_greenstein(double cos_theta, double g)
{
    g = std::clamp(g, -0.99, 0.99);
    double denom = 1 + g * g + 2 * g * cos_theta;
    return (1 - g * g) / (4 * PI * denom * std::sqrt(std::max(0.0, denom)));
}

Vec3 sample_henyey_greenstein(Vec3 wo, double g, double u1, double u2, double *pdf)
{
    g = std::clamp(g, -0.99, 0.99);
    double cos_t = std::fabs(g) < 1e-3 ? 1 - 2 * u1
                                       : -1 / (2 * g) * (1 + g * g - sqr((1 - g * g) / (1 + g - 2 * g * u1)));
    double sin_t = std::sqrt(std::max(0.0, 1 - cos_t * cos_t)), sin_phi, cos_phi;
    udm1scene::sincos_2pi(u2, &sin_phi, &cos_phi);
    udm1scene::Frame f(wo);
    *pdf = henyey_greenstein(cos_t, g);
    return f.from_local(Vec3(sin_t * cos_phi, sin_t * sin_phi, cos_t));
}

// ---- layered: dielectric coat over a diffuse or conductor base, two-sided, a medium between ----

namespace {

// The interface at the top (the coat) or the bottom (the base) of the layers.
struct Interface {
    const Coated *c;
    bool top;
    Vec3 f(Vec3 wo, Vec3 wi, Mode mode) const
    {
        return top ? c->top.f(wo, wi, mode) : c->metal_base ? c->metal.f(wo, wi) : c->bottom.f(wo, wi);
    }
    double pdf(Vec3 wo, Vec3 wi, Mode mode, unsigned lobes = Both) const
    {
        if (top) return c->top.pdf(wo, wi, mode, lobes);
        if (c->metal_base) return lobes & Reflect ? c->metal.pdf(wo, wi) : 0;
        return c->bottom.pdf(wo, wi, lobes);
    }
    bool sample(Vec3 wo, double uc, double u1, double u2, Mode mode, unsigned lobes, Sample *s) const
    {
        if (top) return c->top.sample(wo, uc, u1, u2, mode, lobes, s);
        if (c->metal_base) return (lobes & Reflect) && c->metal.sample(wo, u1, u2, s);
        return c->bottom.sample(wo, u1, u2, lobes, s);
    }
    bool specular() const { return top ? c->top.specular() : c->metal_base && c->metal.specular(); }
};

inline Mode flip(Mode m) { return m == Mode::Radiance ? Mode::Importance : Mode::Radiance; }
inline double max_component(Vec3 v) { return std::max({v.x, v.y, v.z}); }
inline bool nonzero(Vec3 v) { return v.x != 0 || v.y != 0 || v.z != 0; }
// pbrt-v4's SampleExponential: -log(1 - u) / a
inline double sample_exponential(double u, double a) { return -std::log(1 - u) / a; }

}  // namespace

Vec3 Coated::f(Vec3 wo, Vec3 wi, Mode mode) const
{
    if (wo.z < 0) wo = -wo, wi = -wi;  // two-sided
    Interface top_i{this, true}, bottom_i{this, false};
    // light enters through the top; it leaves through the top (reflection) or, for
    // transmission, the bottom (neither base transmits)
    bool refl = same_hemisphere(wo, wi);
    Interface enter = top_i, exit = refl ? top_i : bottom_i, non_exit = refl ? bottom_i : top_i;
    double exit_z = refl ? thickness : 0;
    const bool medium = nonzero(albedo);
    Vec3 f;
    if (refl) f = enter.f(wo, wi, mode) * samples;
    Rng rng(Rng::hash(wo, 1), Rng::hash(wi, 2));
    for (int sidx = 0; sidx < samples; ++sidx) {
        Sample wos, wis;
        double uc = rng(), a = rng(), b = rng();
        if (!enter.sample(wo, uc, a, b, mode, Transmit, &wos) || !nonzero(wos.f) || wos.pdf == 0 || wos.wi.z == 0)
            continue;
        uc = rng(), a = rng(), b = rng();
        if (!exit.sample(wi, uc, a, b, flip(mode), Transmit, &wis) || !nonzero(wis.f) || wis.pdf == 0 || wis.wi.z == 0)
            continue;
        Vec3 beta = wos.f * (std::fabs(wos.wi.z) / wos.pdf);
        double z = thickness;
        Vec3 w = wos.wi;
        for (int depth = 0; depth < max_depth; ++depth) {
            if (depth > 3 && max_component(beta) < 0.25) {
                double q = std::max(0.0, 1 - max_component(beta));
                if (rng() < q) break;
                beta = beta * (1 / (1 - q));
            }
            if (!medium) {
                z = z == thickness ? 0 : thickness;
                beta = beta * Tr(thickness, w);
            } else {  // the medium: a scattering event inside the layer, or the next interface
                double zp = w.z > 0 ? z + sample_exponential(rng(), 1 / std::fabs(w.z))
                                    : z - sample_exponential(rng(), 1 / std::fabs(w.z));
                if (zp == z) continue;
                if (0 < zp && zp < thickness) {
                    // next-event estimate through the exit interface along the presampled wis
                    double wt = 1;
                    if (!exit.specular()) wt = power_heuristic(wis.pdf, henyey_greenstein(dot(-w, -wis.wi), g));
                    f = f + mul(mul(beta, albedo), wis.f) *
                                (henyey_greenstein(dot(-w, -wis.wi), g) * wt * Tr(zp - exit_z, wis.wi) / wis.pdf);
                    double ps_pdf;
                    double u1 = rng(), u2 = rng();
                    Vec3 pw = sample_henyey_greenstein(-w, g, u1, u2, &ps_pdf);
                    if (ps_pdf == 0 || pw.z == 0) continue;
                    beta = mul(beta, albedo);  // (p / pdf = 1)
                    w = pw, z = zp;
                    if (((z < exit_z && w.z > 0) || (z > exit_z && w.z < 0)) && !exit.specular()) {
                        Vec3 fexit = exit.f(-w, wi, mode);
                        if (nonzero(fexit)) {  // (the density of the presampled strategy: see below)
                            double wexit = power_heuristic(ps_pdf, exit.pdf(wi, -w, flip(mode), Transmit));
                            f = f + mul(beta, fexit) * (Tr(zp - exit_z, pw) * wexit);
                        }
                    }
                    continue;
                }
                z = std::clamp(zp, 0.0, thickness);
            }
            if (z == exit_z) {
                Sample bs;
                uc = rng(), a = rng(), b = rng();
                if (!exit.sample(-w, uc, a, b, mode, Reflect, &bs) || !nonzero(bs.f) || bs.pdf == 0 || bs.wi.z == 0)
                    break;
                beta = mul(beta, bs.f) * (std::fabs(bs.wi.z) / bs.pdf);
                w = bs.wi;
            } else {
                if (!non_exit.specular()) {  // next-event estimate along the presampled exit direction
                    double wt = 1;
                    if (!exit.specular()) wt = power_heuristic(wis.pdf, non_exit.pdf(-w, -wis.wi, mode));
                    f = f + mul(mul(beta, non_exit.f(-w, -wis.wi, mode)), wis.f) *
                                (std::fabs(wis.wi.z) * wt * Tr(thickness, wis.wi) / wis.pdf);
                }
                Sample bs;
                uc = rng(), a = rng(), b = rng();
                if (!non_exit.sample(-w, uc, a, b, mode, Reflect, &bs) || !nonzero(bs.f) || bs.pdf == 0 ||
                    bs.wi.z == 0)
                    break;
                beta = mul(beta, bs.f) * (std::fabs(bs.wi.z) / bs.pdf);
                w = bs.wi;
                if (!exit.specular()) {
                    // The MIS weight against the presampled exit direction needs the density with which
                    // that strategy (sampling from wi, adjoint mode) yields -w. pbrt-v4 uses the reverse
                    // density exit.pdf(-w, wi): the two weights then do not sum to 1 and f() is biased
                    // against sample() (7 % at roughness 0.3, tests/cpp/test_pt.cpp).
                    Vec3 fexit = exit.f(-w, wi, mode);
                    if (nonzero(fexit)) {
                        double wt = 1;
                        if (!non_exit.specular()) wt = power_heuristic(bs.pdf, exit.pdf(wi, -w, flip(mode), Transmit));
                        f = f + mul(beta, fexit) * (Tr(thickness, bs.wi) * wt);
                    }
                }
            }
        }
    }
    return f * (1.0 / samples);
}

double Coated::pdf(Vec3 wo, Vec3 wi, Mode mode) const
{
    if (wo.z < 0) wo = -wo, wi = -wi;
    Interface top_i{this, true}, bottom_i{this, false};
    Rng rng(Rng::hash(wi, 3), Rng::hash(wo, 4));
    double sum = 0;
    if (same_hemisphere(wo, wi)) sum += samples * top_i.pdf(wo, wi, mode, Reflect);
    for (int sidx = 0; sidx < samples; ++sidx) {
        if (same_hemisphere(wo, wi)) {  // TRT: through the coat, off the base, back out
            Interface r_i = bottom_i, t_i = top_i;
            Sample wos, wis;
            double a = rng(), b = rng(), c = rng();
            bool ok_o = t_i.sample(wo, a, b, c, mode, Transmit, &wos);
            a = rng(), b = rng(), c = rng();
            bool ok_i = t_i.sample(wi, a, b, c, flip(mode), Transmit, &wis);
            if (ok_o && nonzero(wos.f) && wos.pdf > 0 && ok_i && nonzero(wis.f) && wis.pdf > 0) {
                if (t_i.specular()) {
                    sum += r_i.pdf(-wos.wi, -wis.wi, mode);
                } else {
                    Sample rs;
                    a = rng(), b = rng(), c = rng();
                    if (r_i.sample(-wos.wi, a, b, c, mode, Both, &rs) && nonzero(rs.f) && rs.pdf > 0) {
                        if (r_i.specular()) {
                            sum += t_i.pdf(-rs.wi, wi, mode);
                        } else {
                            double r_pdf = r_i.pdf(-wos.wi, -wis.wi, mode);
                            sum += power_heuristic(wis.pdf, r_pdf) * r_pdf;
                            double t_pdf = t_i.pdf(-rs.wi, wi, mode);
                            sum += power_heuristic(rs.pdf, t_pdf) * t_pdf;
                        }
                    }
                }
            }
        }
        // TT (transmission through both layers) is impossible: neither base transmits
    }
    return 0.1 * (1 / (4 * PI)) + 0.9 * (sum / samples);  // mixed with a uniform density, as pbrt
}

bool Coated::sample(Vec3 wo, double uc, double u1, double u2, Mode mode, Sample *out) const
{
    bool flip_wi = false;
    if (wo.z < 0) wo = -wo, flip_wi = true;
    Sample bs;
    if (!top.sample(wo, uc, u1, u2, mode, Both, &bs) || !nonzero(bs.f) || bs.pdf == 0 || bs.wi.z == 0) return false;
    if (bs.reflection) {
        if (flip_wi) bs.wi = -bs.wi;
        bs.pdf_is_proportional = true;
        *out = bs;
        return true;
    }
    Vec3 w = bs.wi;
    bool specular_path = bs.specular;
    Rng rng(Rng::hash(wo, 5), Rng::mix((uint64_t)(uc * 0x1p53) ^ Rng::mix((uint64_t)(u1 * 0x1p53)) ^
                                        Rng::mix(Rng::mix((uint64_t)(u2 * 0x1p53)))));
    Vec3 f = bs.f * std::fabs(bs.wi.z);
    double pdf = bs.pdf, z = thickness;
    const bool medium = nonzero(albedo);
    Interface top_i{this, true}, bottom_i{this, false};
    for (int depth = 0; depth < max_depth; ++depth) {
        double rr = max_component(f) / pdf;
        if (depth > 3 && rr < 0.25) {
            double q = std::max(0.0, 1 - rr);
            if (rng() < q) return false;
            pdf *= 1 - q;
        }
        if (w.z == 0) return false;
        if (medium) {  // a scattering event inside the layer, or the next interface
            double dz = sample_exponential(rng(), 1 / std::fabs(w.z)), zp = w.z > 0 ? z + dz : z - dz;
            if (zp == z) return false;
            if (0 < zp && zp < thickness) {
                double ps_pdf;
                double a = rng(), b = rng();
                Vec3 pw = sample_henyey_greenstein(-w, g, a, b, &ps_pdf);
                if (ps_pdf == 0 || pw.z == 0) return false;
                f = mul(f, albedo) * ps_pdf;  // (albedo p, p = pdf)
                pdf *= ps_pdf;
                specular_path = false;
                w = pw, z = zp;
                continue;
            }
            z = std::clamp(zp, 0.0, thickness);
        } else {
            z = z == thickness ? 0 : thickness;
            f = f * Tr(thickness, w);
        }
        Interface in = z == 0 ? bottom_i : top_i;
        Sample s;
        double c = rng(), a = rng(), b = rng();
        if (!in.sample(-w, c, a, b, mode, Both, &s) || !nonzero(s.f) || s.pdf == 0 || s.wi.z == 0) return false;
        f = mul(f, s.f);
        pdf *= s.pdf;
        specular_path = specular_path && s.specular;
        w = s.wi;
        if (!s.reflection) {  // left the layers
            out->reflection = same_hemisphere(wo, w);
            out->specular = specular_path;
            out->wi = flip_wi ? -w : w;
            out->f = f;
            out->pdf = pdf;
            out->pdf_is_proportional = true;
            return true;
        }
        f = f * std::fabs(s.wi.z);
    }
    return false;
}

// ---- measured: a tabulated BSDF file ----

MeasuredTables::MeasuredTables(const udm1scene::TabulatedBsdf &b) : isotropic(b.isotropic)
{
    ndf = BilinearWarp(b.ndf.data(), b.ndf_w, b.ndf_h, {}, false);
    sigma = BilinearWarp(b.sigma.data(), b.sigma_w, b.sigma_h, {}, false);
    vndf = BilinearWarp(b.vndf.data(), b.vndf_w, b.vndf_h, {b.phi_i, b.theta_i}, true);
    luminance = BilinearWarp(b.luminance.data(), b.w, b.h, {b.phi_i, b.theta_i}, true);
    for (int c = 0; c < 3; ++c) rgb[c] = BilinearWarp(b.rgb[c].data(), b.w, b.h, {b.phi_i, b.theta_i}, false);
}

namespace {

// The tables' coordinates of an elevation and an azimuth, and back.
inline double theta_to_u(double theta) { return std::sqrt(theta * (2 / PI)); }
inline double phi_to_u(double phi) { return phi * (1 / (2 * PI)) + 0.5; }
inline double u_to_theta(double u) { return u * u * (PI / 2); }
inline double u_to_phi(double u) { return (2 * u - 1) * PI; }
inline double theta_of(Vec3 w) { return std::acos(std::clamp(w.z, -1.0, 1.0)); }

// The solid angle of the normal per unit area of its (theta, phi) coordinates, times 4 (wo . wm), the
// half vector's: the density of wi per unit density of the normal's coordinates (pbrt-v4 bounds the first
// factor below by 1e-6).
inline double measured_jacobian(double ux, double sin_theta_m, double cos_om)
{
    return 4 * cos_om * std::max(2 * PI * PI * ux * sin_theta_m, 1e-6);
}

}  // namespace

// Where the pair (wo, wi) lies in the tables: wo's angles (param), the half vector's point (ux, uy) of the
// ndf's square, and the point (a, b) that vndf warps to it, with vndf's density there. False where pbrt-v4's
// MeasuredBxDF is 0: wi on the other side, or wi = -wo. Directions below the surface are mirrored above.
struct MeasuredLookup {
    Vec3 wo, wm;
    double theta_o = 0, phi_o = 0, param[2] = {0, 0};
    double ux = 0, uy = 0, a = 0, b = 0, vndf_pdf = 0;
};

static bool measured_lookup(const MeasuredTables &t, Vec3 wo, Vec3 wi, MeasuredLookup *l)
{
    if (!same_hemisphere(wo, wi)) return false;
    if (wo.z < 0) wo = -wo, wi = -wi;
    Vec3 wm = wi + wo;
    if (udm1scene::dot(wm, wm) == 0) return false;
    l->wo = wo, l->wm = wm = udm1scene::normalize(wm);
    l->theta_o = theta_of(wo), l->phi_o = std::atan2(wo.y, wo.x);
    l->param[0] = l->phi_o, l->param[1] = l->theta_o;
    l->ux = theta_to_u(theta_of(wm));
    l->uy = phi_to_u(t.isotropic ? std::atan2(wm.y, wm.x) - l->phi_o : std::atan2(wm.y, wm.x));
    l->uy -= std::floor(l->uy);
    t.vndf.invert(l->ux, l->uy, l->param, &l->a, &l->b, &l->vndf_pdf);
    return true;
}

Vec3 Measured::f(Vec3 wo, Vec3 wi) const
{
    MeasuredLookup l;
    if (!measured_lookup(*t, wo, wi, &l)) return Vec3();
    if (wo.z < 0) wi = -wi;
    Vec3 fr(std::max(0.0, t->rgb[0].eval(l.a, l.b, l.param)), std::max(0.0, t->rgb[1].eval(l.a, l.b, l.param)),
            std::max(0.0, t->rgb[2].eval(l.a, l.b, l.param)));
    return fr * (t->ndf.eval(l.ux, l.uy) / (4 * t->sigma.eval(theta_to_u(l.theta_o), phi_to_u(l.phi_o)) * wi.z));
}

double Measured::pdf(Vec3 wo, Vec3 wi) const
{
    MeasuredLookup l;
    if (!measured_lookup(*t, wo, wi, &l)) return 0;
    const double lum_pdf = t->luminance.eval(l.a, l.b, l.param);
    return l.vndf_pdf * lum_pdf /
           measured_jacobian(l.ux, std::sqrt(l.wm.x * l.wm.x + l.wm.y * l.wm.y), udm1scene::dot(l.wo, l.wm));
}

bool Measured::sample(Vec3 wo, double u1, double u2, Sample *s) const
{
    const bool flip_wi = wo.z <= 0;
    if (flip_wi) wo = -wo;
    const double theta_o = theta_of(wo), phi_o = std::atan2(wo.y, wo.x);
    const double param[2] = {phi_o, theta_o};
    double a, b, lum_pdf, ux, uy, vndf_pdf;
    t->luminance.sample(u1, u2, param, &a, &b, &lum_pdf);
    t->vndf.sample(a, b, param, &ux, &uy, &vndf_pdf);
    double phi_m = u_to_phi(uy) + (t->isotropic ? phi_o : 0), theta_m = u_to_theta(ux);
    double sin_m = std::sin(theta_m), cos_m = std::cos(theta_m);
    Vec3 wm(sin_m * std::cos(phi_m), sin_m * std::sin(phi_m), cos_m);
    Vec3 wi = reflect(wo, wm);
    if (wi.z <= 0) return false;
    Vec3 fr(std::max(0.0, t->rgb[0].eval(a, b, param)), std::max(0.0, t->rgb[1].eval(a, b, param)),
            std::max(0.0, t->rgb[2].eval(a, b, param)));
    s->f = fr * (t->ndf.eval(ux, uy) / (4 * t->sigma.eval(theta_to_u(theta_o), phi_to_u(phi_o)) * wi.z));
    s->pdf = vndf_pdf * lum_pdf / measured_jacobian(ux, sin_m, udm1scene::dot(wo, wm));
    s->wi = flip_wi ? -wi : wi;
    s->specular = false, s->reflection = true, s->eta = 1;
    return s->pdf > 0 && std::isfinite(s->pdf);
}

bool ThinDielectric::sample(Vec3 wo, double uc, Sample *s) const
{
    double R = fresnel_dielectric(std::fabs(wo.z), eta), T = 1 - R;
    if (R < 1) R += T * T * R / (1 - R * R), T = 1 - R;  // (the inner reflections, as pbrt-v4 sums them)
    if (wo.z == 0) return false;
    s->specular = true, s->eta = 1;
    if (uc < R / (R + T)) {
        s->wi = Vec3(-wo.x, -wo.y, wo.z);
        double v = R / std::fabs(s->wi.z);
        s->f = Vec3(v, v, v), s->pdf = R / (R + T), s->reflection = true;
    } else {
        s->wi = -wo;
        double v = T / std::fabs(s->wi.z);
        s->f = Vec3(v, v, v), s->pdf = T / (R + T), s->reflection = false;
    }
    return s->pdf > 0;
}

// ---- the material ----

Vec3 Bsdf::f(Vec3 wo, Vec3 wi, Mode mode) const
{
    switch (kind) {
    case Diffuse: return diffuse.f(wo, wi);
    case CoatedDiffuse: case CoatedConductor: return coated.f(wo, wi, mode);
    case DielectricKind: return dielectric.f(wo, wi, mode);
    case DiffuseTransmissionKind: return transmission.f(wo, wi);
    case MeasuredKind: return measured.f(wo, wi);
    case ThinDielectricKind: return Vec3();  // (specular only)
    default: return conductor.f(wo, wi);
    }
}

double Bsdf::pdf(Vec3 wo, Vec3 wi, Mode mode) const
{
    switch (kind) {
    case Diffuse: return diffuse.pdf(wo, wi, Both);
    case CoatedDiffuse: case CoatedConductor: return coated.pdf(wo, wi, mode);
    case DielectricKind: return dielectric.pdf(wo, wi, mode, Both);
    case DiffuseTransmissionKind: return transmission.pdf(wo, wi);
    case MeasuredKind: return measured.pdf(wo, wi);
    case ThinDielectricKind: return 0;
    default: return conductor.pdf(wo, wi);
    }
}

bool Bsdf::sample(Vec3 wo, double uc, double u1, double u2, Sample *s, Mode mode) const
{
    *s = Sample();
    switch (kind) {
    case Diffuse: return diffuse.sample(wo, u1, u2, Both, s);
    case CoatedDiffuse: case CoatedConductor: return coated.sample(wo, uc, u1, u2, mode, s);
    case DielectricKind: return dielectric.sample(wo, uc, u1, u2, mode, Both, s);
    case DiffuseTransmissionKind: return transmission.sample(wo, uc, u1, u2, s);
    case MeasuredKind: return measured.sample(wo, u1, u2, s);
    case ThinDielectricKind: return thin.sample(wo, uc, s);
    default: return conductor.sample(wo, u1, u2, s);
    }
}

}  // namespace udm1pt
