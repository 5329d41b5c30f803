// estimator.cpp - see estimator.h.
#include "estimator.h"

#include "media.h"
#include "surface.h"

#include <algorithm>
#include <cmath>

namespace udm1pt {

using udm1scene::dot;
using udm1scene::Frame;
using udm1scene::Hit;
using udm1scene::normalize;

namespace {

inline double max_component(Vec3 v) { return std::max({v.x, v.y, v.z}); }
inline bool nonzero(Vec3 v) { return v.x != 0 || v.y != 0 || v.z != 0; }
inline double power_heuristic(double f, double g) { return f * f + g * g > 0 ? f * f / (f * f + g * g) : 0; }

// The origin of a ray leaving hit h towards w: offset to the side of the surface w goes to.
inline Vec3 spawn(const Hit &h, Vec3 w)
{
    double off = udm1scene::ray_offset(h.p, h.t);
    return h.p + (dot(h.ng, w) > 0 ? h.ng : -h.ng) * off;
}

}  // namespace

Estimator::Estimator(const udm1scene::Scene &scene, const Lights &lights, const Materials &materials, int max_depth,
                     Strategy strategy, bool roulette, int rr_depth)
    : scene_(scene), lights_(lights), materials_(materials), default_bsdf_(default_material()), max_depth_(max_depth),
      strategy_(strategy), roulette_(roulette), rr_depth_(rr_depth)
{
    interface_ = interface_shapes(scene);
    media_ = uses_media(scene);
    volumetric_ = media_ || std::find(interface_.begin(), interface_.end(), 1) != interface_.end();
    grids_.resize(scene.media.size());
    if (media_)
        for (size_t i = 0; i < scene.media.size(); ++i)
            if (scene.media[i].kind != udm1scene::Medium::Homogeneous) grids_[i] = std::make_unique<GridMedium>(scene.media[i]);
    Vec3 lo, hi;
    scene.bounds(&lo, &hi);
    scene_radius_ = udm1scene::length(hi - lo) / 2;
}

void Estimator::miss(PathState &p) const
{
    if (!lights_.has_environment()) return;
    Vec3 Le = lights_.environment(p.d);
    if (p.depth == 0 || p.specular_bounce || strategy_ == Strategy::Bsdf)
        p.L = p.L + mul(p.beta, Le);
    else if (strategy_ == Strategy::Mis)
        p.L = p.L + mul(p.beta, Le) * power_heuristic(p.p_b, lights_.environment_pdf(p.d));
}

bool Estimator::scatter(PathState &p, const Hit &h, ShadowTest *shadow) const
{
    shadow->active = false;
    Vec3 wo = -p.d;
    Vec3 Le = lights_.emitted(h, wo);
    if (nonzero(Le)) {
        if (p.depth == 0 || p.specular_bounce || strategy_ == Strategy::Bsdf) {
            p.L = p.L + mul(p.beta, Le);
        } else if (strategy_ == Strategy::Mis) {
            double p_l = lights_.pdf(p.prev_p, p.prev_n, h, p.importance_sum);
            p.L = p.L + mul(p.beta, Le) * power_heuristic(p.p_b, p_l);
        }
    }
    if (p.depth == max_depth_) return false;
    // this vertex's values (integrator.h): always drawn, so that nothing depends on what happens
    double u[6];
    vertex_values(p.pixel, p.index, p.depth, u);
    const double u_lp[2] = {u[0], u[1]}, u_lobe = u[2], u_rr = u[3], u_dir[2] = {u[4], u[5]};

    const udm1scene::Shape &shape = scene_.shapes[h.shape];
    Vec3 ns = udm1scene::shading_normal(shape, h);  // (surface.h)
    Bsdf scratch;  // a textured material's BSDF at this vertex
    const Bsdf &bsdf = shape.material >= 0 ? materials_.at(shape.material, shape, h, wo, &ns, &scratch) : default_bsdf_;
    Frame frame = shading_frame(bsdf, shape, h, ns);  // (material.h)
    Vec3 wo_l = frame.to_local(wo);
    if (wo_l.z == 0) return false;
    double importance_sum = NAN;  // (for MIS at a light the next ray may hit)
    if (strategy_ != Strategy::Bsdf && bsdf.has_non_specular()) {  // next-event estimation
        LightSample ls;
        bool sampled = lights_.sample(h.p, h.ng, u_lp[0], u_lp[1], &ls);
        importance_sum = ls.importance_sum;
        if (sampled) {
            Vec3 wi_l = frame.to_local(ls.wi);
            Vec3 f = bsdf.f(wo_l, wi_l) * std::fabs(wi_l.z);
            if (nonzero(f)) {
                udm1scene::Segment sg = ls.infinite ? udm1scene::segment_to_infinity(h.p, h.ng, h.t, ls.wi)
                                                    : udm1scene::shadow_segment(h.p, h.ng, h.t, ls.q, ls.n);
                if (sg.len > 0) {
                    ShadowTest &s = *shadow;
                    s.active = true, s.walk = false;
                    // a ray that grazes a sphere meets Embree's float sphere up to ~1e-4 of the radius before
                    // the exact point: a hit on the light's own sphere is the light itself
                    s.sphere = ls.sphere, s.shape = ls.shape;
                    s.o = sg.o, s.d = sg.d, s.len = sg.len;
                    s.beta_f = mul(p.beta, f), s.Li = ls.L, s.pdf = ls.pdf;
                    s.weighted = strategy_ == Strategy::Mis && !ls.delta;
                    if (s.weighted) s.bsdf = bsdf, s.wo_l = wo_l, s.wi_l = wi_l;
                }
            }
        }
    }
    Sample bs;
    if (!bsdf.sample(wo_l, u_lobe, u_dir[0], u_dir[1], &bs) || bs.pdf <= 0 || !nonzero(bs.f)) return false;
    Vec3 wi = normalize(frame.from_local(bs.wi));
    p.beta = mul(p.beta, bs.f) * (std::fabs(bs.wi.z) / bs.pdf);
    p.p_b = bs.pdf_is_proportional ? bsdf.pdf(wo_l, bs.wi) : bs.pdf;
    p.specular_bounce = bs.specular;
    if (!bs.reflection) p.eta_scale *= bs.eta * bs.eta;
    p.prev_p = h.p, p.prev_n = h.ng, p.importance_sum = importance_sum;
    if (!(max_component(p.beta) > 0) || !std::isfinite(max_component(p.beta))) return false;
    if (roulette_ && p.depth >= rr_depth_) {  // when the throughput is below 1
        double rr = max_component(p.beta) * p.eta_scale;
        if (rr < 1) {
            double q = std::max(0.0, 1 - rr);
            if (u_rr < q) return false;
            p.beta = p.beta * (1 / (1 - q));
        }
    }
    p.o = spawn(h, wi);
    p.d = wi;
    ++p.depth;
    return true;
}

void Estimator::arrive(PathState &p, const ShadowTest &s) const
{
    if (s.walk) {  // the volumetric estimator's (ShadowTest::T_u)
        double pdf_s = s.weighted ? (s.scatter_pdf >= 0 ? s.scatter_pdf : s.bsdf.pdf(s.wo_l, s.wi_l)) : 0;
        double avg;
        if (s.tracked) {  // the strategies' densities with their own factors from the grid media
            Vec3 r = mul(mul(s.r_p, s.T_u), s.F_l * s.pdf + s.F_u * pdf_s);
            avg = (r.x + r.y + r.z) / 3;
        } else {
            avg = (s.r_p.x * s.T_u.x + s.r_p.y * s.T_u.y + s.r_p.z * s.T_u.z) * (s.pdf + pdf_s) / 3;
        }
        if (avg > 0) p.L = p.L + mul(mul(s.beta_f, s.Li), s.T) * (s.T_u[p.hero] / avg);
        return;
    }
    double w = s.weighted ? power_heuristic(s.pdf, s.bsdf.pdf(s.wo_l, s.wi_l)) : 1;
    p.L = p.L + mul(s.beta_f, s.Li) * (w / s.pdf);
}


// ---- the volumetric estimator (estimator.h): pbrt-v4's VolPathIntegrator in RGB -------------------------

namespace {

const int MAX_CROSSINGS = 256;  // interface surfaces one ray may pass (a safety net: the path ends there)

inline double average(Vec3 v) { return (v.x + v.y + v.z) / 3; }

}  // namespace

void Estimator::start(PathState &p) const
{
    p.medium = media_ ? scene_.camera.medium : -1;
    if (media_) {
        double u;
        udm1_domain_draw_f64(udm1_domain_child(udm1_domain_root(p.pixel, p.index), 0), 1, &u);
        p.hero = std::min(2, (int)(u * 3));
    }
}

int Estimator::medium_after(int medium, const Hit &h, Vec3 w) const
{
    const udm1scene::Shape &s = scene_.shapes[h.shape];
    if (!media_ || s.inside == s.outside) return medium;  // not a transition: the ray's medium (pbrt-v4)
    return dot(w, h.ng) > 0 ? s.outside : s.inside;
}

bool Estimator::step(PathState &p, const Hit *h, ShadowTest *shadow) const
{
    shadow->active = false;
    if (p.medium >= 0) {
        bool scattered = false;
        if (!medium_step(p, h ? h->t : INFINITY, shadow, &scattered)) return false;
        if (scattered) return true;
    }
    if (!h) {
        volumetric_miss(p);
        return false;
    }
    return surface_step(p, *h, shadow);
}

// The environment: a uniform one found only here (pbrt-v4's volumetric path tracer does not light-sample it:
// a uniform sky is all the BSDF's, and a sky seen through a medium that extends to infinity is black, as in
// pbrt-v4), an image by MIS with light sampling.
void Estimator::volumetric_miss(PathState &p) const
{
    if (!lights_.has_environment()) return;
    Vec3 all = mul(p.beta, lights_.environment(p.d)), maps = mul(p.beta, lights_.environment_maps(p.d));
    if (p.depth == 0 || p.specular_bounce || strategy_ == Strategy::Bsdf)
        p.L = p.L + all * (1 / average(p.r_u));
    else if (strategy_ == Strategy::Mis)
        p.L = p.L + (all - maps) * (1 / average(p.r_u)) +
              maps * (1 / average(p.r_u + p.r_l * lights_.environment_map_pdf(p.d)));
    else  // (light sampling only: the uniform skies, which it does not sample)
        p.L = p.L + (all - maps) * (1 / average(p.r_u));
}

// The ray's piece in medium p.medium up to t_end (the surface it hits, or infinity): the medium's emission
// along it, exactly (sigma_a Le (1 - T) / sigma_t per channel). A medium that only absorbs then takes the
// transmittance exactly. In one that scatters, the distance to an interaction is drawn by the hero channel's
// sigma_t (for a homogeneous medium the majorant: no null collisions); before t_end the interaction absorbs
// (the path ends) or scatters (*scattered: a vertex in the medium, with light sampling and the phase
// function's direction); past it the ray goes on to t_end, its throughput and rescaled probabilities taking
// the transmittance relative to the hero's.
bool Estimator::medium_step(PathState &p, double t_end, ShadowTest *shadow, bool *scattered) const
{
    if (grids_[p.medium]) return grid_step(p, *grids_[p.medium], t_end, shadow, scattered);
    const udm1scene::Medium &m = scene_.media[p.medium];
    const Vec3 st = m.sigma_a + m.sigma_s;
    if (p.depth < max_depth_ && nonzero(m.Le)) {  // (pbrt-v4 adds a medium's emission below the maximum depth)
        Vec3 e;
        for (int k = 0; k < 3; ++k) e[k] = st[k] > 0 ? m.sigma_a[k] * m.Le[k] * -std::expm1(-st[k] * t_end) / st[k] : 0;
        p.L = p.L + mul(p.beta, e) * (1 / average(p.r_u));
    }
    if (!nonzero(m.sigma_s)) {  // absorption only: the transmittance exactly (nothing to sample)
        p.beta = mul(p.beta, transmittance(m, t_end));
        return max_component(p.beta) > 0;
    }
    double u[2];
    segment_values(p.pixel, p.index, p.depth, p.crossings, u);
    const int c = p.hero;
    const double t = st[c] > 0 ? -std::log1p(-u[0]) / st[c] : INFINITY;
    if (!(t < t_end)) {  // no interaction before the surface
        Vec3 T = transmittance(m, t_end);
        double inv = 1 / T[c];  // (T[c] > 0: the hero passed)
        p.beta = mul(p.beta, T) * inv, p.r_u = mul(p.r_u, T) * inv, p.r_l = mul(p.r_l, T) * inv;
        return max_component(p.beta) > 0;
    }
    if (u[1] * st[c] < m.sigma_a[c]) return false;  // absorbed
    if (p.depth == max_depth_) return false;
    const Vec3 T = transmittance(m, t);
    const Vec3 ratio = mul(T, m.sigma_s) * (1 / (T[c] * m.sigma_s[c]));  // each channel's density over the hero's
    p.beta = mul(p.beta, ratio), p.r_u = mul(p.r_u, ratio);
    if (!(max_component(p.beta) > 0) || !(max_component(p.r_u) > 0)) return false;
    return medium_vertex(p, p.o + p.d * t, m.g, shadow, scattered);
}

// A vertex in a medium at x (p.beta and p.r_u already hold the sampled interaction): its values as a surface
// vertex's (integrator.h), light sampling through the phase function, the phase function's direction.
bool Estimator::medium_vertex(PathState &p, Vec3 x, double g, ShadowTest *shadow, bool *scattered) const
{
    double v[6];
    vertex_values(p.pixel, p.index, p.depth, v);
    const Vec3 wo = -p.d;
    double importance_sum = NAN;
    if (strategy_ != Strategy::Bsdf) {
        LightSample ls;
        bool sampled = lights_.sample(x, Vec3(), v[0], v[1], &ls);
        importance_sum = ls.importance_sum;
        if (sampled && !ls.uniform) {
            double ph = hg_phase(dot(wo, ls.wi), g);
            udm1scene::Segment sg = ls.infinite ? udm1scene::segment_to_infinity(x, Vec3(), 0, ls.wi)
                                                : udm1scene::shadow_segment(x, Vec3(), 0, ls.q, ls.n);
            if (sg.len > 0 && ph > 0) {
                walking_shadow(p, ls, sg, p.medium, Vec3(ph, ph, ph), v, shadow);
                shadow->scatter_pdf = ph;
            }
        }
    }
    double pdf;
    Vec3 wi = sample_hg(wo, g, v[4], v[5], &pdf);
    if (!(pdf > 0)) return false;
    p.r_l = p.r_u * (1 / pdf);  // (the phase function is sampled exactly: beta unchanged)
    p.prev_p = x, p.prev_n = Vec3(), p.importance_sum = importance_sum;
    p.specular_bounce = false;
    p.o = x, p.d = wi;
    ++p.depth, p.crossings = 0;
    *scattered = true;
    return true;
}

// The ray's piece in a grid medium up to t_end, by delta tracking as pbrt-v4's VolPathIntegrator samples it
// (SampleT_maj): tentative collisions drawn by the hero channel's majorant, segment by segment (the first
// distance from the piece's first sampler value, the rest and each collision's kind from a TrackingRandom
// seeded by its second); at each, the medium's emission (estimated: sigma_a Le over the majorant's density),
// then absorption (the path ends), scattering (a vertex in the medium) or a null collision (the walk goes
// on), chosen by the hero channel's coefficients over its majorant; every channel weighted by its own
// majorant and coefficients over the hero's, as pbrt-v4 weights its wavelengths.
bool Estimator::grid_step(PathState &p, const GridMedium &g, double t_end, ShadowTest *shadow, bool *scattered) const
{
    double u[2];
    segment_values(p.pixel, p.index, p.depth, p.crossings, u);
    TrackingRandom rng(tracking_seed(&u[1], 1));
    const int c = p.hero;
    const bool emits = g.emissive() && p.depth < max_depth_;
    MajorantIterator it = g.majorants(p.o, p.d, t_end);
    MajorantSegment seg;
    Vec3 T_maj(1, 1, 1);
    double uu = u[0];
    while (it.next(&seg)) {
        const Vec3 sm = seg.sigma_maj;
        if (sm[c] == 0) {  // (the hero sees nothing here: the other channels' majorants still attenuate)
            for (int k = 0; k < 3; ++k) T_maj[k] *= std::exp(-sm[k] * (seg.t1 - seg.t0));
            continue;
        }
        double t0 = seg.t0;
        for (;;) {
            double t = t0 - std::log1p(-uu) / sm[c];
            uu = rng.uniform();
            if (!(t < seg.t1)) {
                for (int k = 0; k < 3; ++k) T_maj[k] *= std::exp(-sm[k] * (seg.t1 - t0));
                break;
            }
            for (int k = 0; k < 3; ++k) T_maj[k] *= std::exp(-sm[k] * (t - t0));
            const Vec3 x = p.o + p.d * t;
            const GridMedium::Point mp = g.at(x);
            if (emits && nonzero(mp.Le)) {
                double pdf = sm[c] * T_maj[c];
                Vec3 r_e = mul(p.r_u, mul(sm, T_maj)) * (1 / pdf);
                if (nonzero(r_e))
                    p.L = p.L + mul(mul(p.beta, T_maj), mul(mp.sigma_a, mp.Le)) * (1 / (pdf * average(r_e)));
            }
            const double p_absorb = mp.sigma_a[c] / sm[c], p_scatter = mp.sigma_s[c] / sm[c];
            const double p_null = std::max(0.0, 1 - p_absorb - p_scatter);
            const double um = rng.uniform() * (p_absorb + p_scatter + p_null);
            if (um < p_absorb) return false;  // absorbed
            if (um < p_absorb + p_scatter) {
                if (p.depth == max_depth_) return false;
                double pdf = T_maj[c] * mp.sigma_s[c];
                Vec3 ratio = mul(T_maj, mp.sigma_s) * (1 / pdf);
                p.beta = mul(p.beta, ratio), p.r_u = mul(p.r_u, ratio);
                if (!(max_component(p.beta) > 0) || !(max_component(p.r_u) > 0)) return false;
                return medium_vertex(p, x, scene_.media[p.medium].g, shadow, scattered);
            }
            // a null collision
            Vec3 sigma_n;
            for (int k = 0; k < 3; ++k) sigma_n[k] = std::max(0.0, sm[k] - mp.sigma_a[k] - mp.sigma_s[k]);
            double pdf = T_maj[c] * sigma_n[c];
            if (!(pdf > 0)) return false;
            p.beta = mul(p.beta, mul(T_maj, sigma_n)) * (1 / pdf);
            p.r_u = mul(p.r_u, mul(T_maj, sigma_n)) * (1 / pdf);
            p.r_l = mul(p.r_l, mul(T_maj, sm)) * (1 / pdf);
            if (!(max_component(p.beta) > 0) || !(max_component(p.r_u) > 0)) return false;
            T_maj = Vec3(1, 1, 1);
            t0 = t;
        }
    }
    if (!(T_maj[c] > 0)) return false;
    const double inv = 1 / T_maj[c];
    p.beta = mul(p.beta, T_maj) * inv, p.r_u = mul(p.r_u, T_maj) * inv, p.r_l = mul(p.r_l, T_maj) * inv;
    return max_component(p.beta) > 0;
}

// A shadow ray's piece of length len in a grid medium, by ratio tracking (pbrt-v4's TraceTransmittance): at
// each tentative collision (the hero channel's majorant) the estimate takes the null coefficient over the
// majorant's density, the strategies' factors theirs; Russian roulette where the estimate falls below 0.05.
// Its random values from a TrackingRandom seeded by the light sample's sampler values and the piece (pbrt-v4
// seeds it by the piece's ray: a seed that rounding in the ray's origin would change between the loops).
bool Estimator::track_shadow(ShadowTest &s, const GridMedium &g, double len) const
{
    TrackingRandom rng(s.seed + (uint64_t)s.crossings * UDM1_GOLDEN_GAMMA);
    const int c = s.hero;
    s.tracked = true;
    MajorantIterator it = g.majorants(s.o, s.d, len);
    MajorantSegment seg;
    Vec3 T_maj(1, 1, 1), T = s.T;
    while (it.next(&seg)) {
        const Vec3 sm = seg.sigma_maj;
        if (sm[c] == 0) {
            for (int k = 0; k < 3; ++k) T_maj[k] *= std::exp(-sm[k] * (seg.t1 - seg.t0));
            continue;
        }
        double t0 = seg.t0;
        for (;;) {
            double t = t0 - std::log1p(-rng.uniform()) / sm[c];
            if (!(t < seg.t1)) {
                for (int k = 0; k < 3; ++k) T_maj[k] *= std::exp(-sm[k] * (seg.t1 - t0));
                break;
            }
            for (int k = 0; k < 3; ++k) T_maj[k] *= std::exp(-sm[k] * (t - t0));
            const GridMedium::Point mp = g.at(s.o + s.d * t);
            Vec3 sigma_n;
            for (int k = 0; k < 3; ++k) sigma_n[k] = std::max(0.0, sm[k] - mp.sigma_a[k] - mp.sigma_s[k]);
            const double pdf = T_maj[c] * sm[c];
            T = mul(T, mul(T_maj, sigma_n)) * (1 / pdf);
            s.F_l = mul(s.F_l, mul(T_maj, sm)) * (1 / pdf);
            s.F_u = mul(s.F_u, mul(T_maj, sigma_n)) * (1 / pdf);
            const Vec3 Tr = T * (1 / average(mul(s.r_p, s.F_l)));
            if (max_component(Tr) < 0.05) {  // Russian roulette
                if (rng.uniform() < 0.75) T = Vec3();
                else T = T * (1 / 0.25);
            }
            if (!nonzero(T)) {
                s.T = T;
                return false;
            }
            T_maj = Vec3(1, 1, 1);
            t0 = t;
        }
    }
    const double inv = 1 / T_maj[c];
    if (!std::isfinite(inv)) {
        s.T = Vec3();
        return false;
    }
    s.T = mul(T, T_maj) * inv, s.F_l = mul(s.F_l, T_maj) * inv, s.F_u = mul(s.F_u, T_maj) * inv;
    return nonzero(s.T);
}

void Estimator::walking_shadow(const PathState &p, const LightSample &ls, const udm1scene::Segment &sg, int medium,
                               Vec3 f, const double u_light[2], ShadowTest *s) const
{
    s->active = s->walk = true;
    s->sphere = ls.sphere, s->shape = ls.shape;
    // (a light at infinity: pbrt-v4 ends the shadow ray at twice the scene's bounding radius, which media on
    // the way attenuate)
    s->o = sg.o, s->d = sg.d, s->len = std::isfinite(sg.len) ? sg.len : 2 * scene_radius_;
    s->end = sg.o + sg.d * s->len;
    s->medium = medium, s->crossings = 0, s->T = s->T_u = Vec3(1, 1, 1);
    s->beta_f = mul(p.beta, f), s->Li = ls.L, s->pdf = ls.pdf, s->r_p = p.r_u;
    s->weighted = strategy_ == Strategy::Mis && !ls.delta;
    s->scatter_pdf = -1;
    s->tracked = false, s->F_l = s->F_u = Vec3(1, 1, 1), s->hero = p.hero;
    s->seed = tracking_seed(u_light, 2);
}

Crossing Estimator::cross(ShadowTest &s, const Hit *h) const
{
    if (s.medium >= 0 && grids_[s.medium]) {
        if (!track_shadow(s, *grids_[s.medium], h ? h->t : s.len)) return Crossing::Blocked;
    } else if (s.medium >= 0) {
        const udm1scene::Medium &m = scene_.media[s.medium];
        Vec3 T = transmittance(m, h ? h->t : s.len);
        s.T = mul(s.T, T);
        if (nonzero(m.sigma_s)) s.T_u = mul(s.T_u, T);
    }
    if (!nonzero(s.T)) return Crossing::Blocked;
    if (!h) return Crossing::Arrived;
    if (!interface_[h->shape] || ++s.crossings > MAX_CROSSINGS) return Crossing::Blocked;
    s.medium = medium_after(s.medium, *h, s.d);
    s.o = spawn(*h, s.d);
    s.len = dot(s.end - s.o, s.d);
    return s.len > 0 ? Crossing::Onward : Crossing::Arrived;
}

// A surface the ray hit: an interface surface is passed (the ray goes on in the medium on its far side, the
// same vertex still to find); else pbrt-v4's surface vertex with the rescaled probabilities.
bool Estimator::surface_step(PathState &p, const Hit &h, ShadowTest *shadow) const
{
    if (interface_[h.shape]) {
        if (++p.crossings > MAX_CROSSINGS) return false;
        p.medium = medium_after(p.medium, h, p.d);
        p.o = spawn(h, p.d);
        return true;
    }
    Vec3 wo = -p.d;
    Vec3 Le = lights_.emitted(h, wo);
    if (nonzero(Le)) {
        if (p.depth == 0 || p.specular_bounce || strategy_ == Strategy::Bsdf) {
            p.L = p.L + mul(p.beta, Le) * (1 / average(p.r_u));
        } else if (strategy_ == Strategy::Mis) {
            double p_l = lights_.pdf(p.prev_p, p.prev_n, h, p.importance_sum);
            p.L = p.L + mul(p.beta, Le) * (1 / average(p.r_u + p.r_l * p_l));
        }
    }
    if (p.depth == max_depth_) return false;
    double u[6];
    vertex_values(p.pixel, p.index, p.depth, u);
    const double u_lp[2] = {u[0], u[1]}, u_lobe = u[2], u_rr = u[3], u_dir[2] = {u[4], u[5]};
    const udm1scene::Shape &shape = scene_.shapes[h.shape];
    Vec3 ns = shading_normal(shape, h);
    Bsdf scratch;
    const Bsdf &bsdf = shape.material >= 0 ? materials_.at(shape.material, shape, h, wo, &ns, &scratch) : default_bsdf_;
    Frame frame = shading_frame(bsdf, shape, h, ns);  // (material.h)
    Vec3 wo_l = frame.to_local(wo);
    if (wo_l.z == 0) return false;
    double importance_sum = NAN;
    if (strategy_ != Strategy::Bsdf && bsdf.has_non_specular()) {
        LightSample ls;
        bool sampled = lights_.sample(h.p, h.ng, u_lp[0], u_lp[1], &ls);
        importance_sum = ls.importance_sum;
        if (sampled && !ls.uniform) {
            Vec3 wi_l = frame.to_local(ls.wi);
            Vec3 f = bsdf.f(wo_l, wi_l) * std::fabs(wi_l.z);
            if (nonzero(f)) {
                udm1scene::Segment sg = ls.infinite ? udm1scene::segment_to_infinity(h.p, h.ng, h.t, ls.wi)
                                                    : udm1scene::shadow_segment(h.p, h.ng, h.t, ls.q, ls.n);
                if (sg.len > 0) {
                    walking_shadow(p, ls, sg, medium_after(p.medium, h, sg.d), f, u_lp, shadow);
                    if (shadow->weighted) shadow->bsdf = bsdf, shadow->wo_l = wo_l, shadow->wi_l = wi_l;
                }
            }
        }
    }
    Sample bs;
    if (!bsdf.sample(wo_l, u_lobe, u_dir[0], u_dir[1], &bs) || bs.pdf <= 0 || !nonzero(bs.f)) return false;
    Vec3 wi = normalize(frame.from_local(bs.wi));
    p.beta = mul(p.beta, bs.f) * (std::fabs(bs.wi.z) / bs.pdf);
    p.r_l = p.r_u * (1 / (bs.pdf_is_proportional ? bsdf.pdf(wo_l, bs.wi) : bs.pdf));
    p.specular_bounce = bs.specular;
    if (!bs.reflection) p.eta_scale *= bs.eta * bs.eta;
    p.prev_p = h.p, p.prev_n = h.ng, p.importance_sum = importance_sum;
    if (!(max_component(p.beta) > 0) || !std::isfinite(max_component(p.beta))) return false;
    if (roulette_ && p.depth >= rr_depth_) {  // pbrt-v4's: on the throughput over the rescaled probability
        double rr = max_component(p.beta) * p.eta_scale / average(p.r_u);
        if (rr < 1) {
            double q = std::max(0.0, 1 - rr);
            if (u_rr < q) return false;
            p.beta = p.beta * (1 / (1 - q));
        }
    }
    p.medium = medium_after(p.medium, h, wi);
    p.o = spawn(h, wi);
    p.d = wi;
    ++p.depth, p.crossings = 0;
    return true;
}

}  // namespace udm1pt
