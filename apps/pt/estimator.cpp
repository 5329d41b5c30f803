// estimator.cpp - see estimator.h.
#include "estimator.h"

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

// The shading normal: interpolated vertex normals where the mesh has them, else the geometric one.
Vec3 shading_normal(const udm1scene::Shape &s, const Hit &h)
{
    if (s.kind != udm1scene::Shape::Triangles || s.N.empty()) return h.ng;
    const uint32_t *i = &s.indices[3 * (size_t)h.prim];
    auto N = [&](uint32_t k) { return Vec3(s.N[3 * k], s.N[3 * k + 1], s.N[3 * k + 2]); };
    Vec3 n = udm1scene::world_normal(h, N(i[0]) * (1 - h.u - h.v) + N(i[1]) * h.u + N(i[2]) * h.v);
    double len = udm1scene::length(n);
    return len > 0 ? n * (1 / len) : h.ng;
}

// The origin of a ray leaving hit h towards w: offset to the side of the surface w goes to.
inline Vec3 spawn(const Hit &h, Vec3 w)
{
    double off = udm1scene::ray_offset(h.p, h.t);
    return h.p + (dot(h.ng, w) > 0 ? h.ng : -h.ng) * off;
}

}  // namespace

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
    Vec3 ns = shading_normal(shape, h);
    Bsdf scratch;  // a textured material's BSDF at this vertex
    const Bsdf &bsdf = shape.material >= 0 ? materials_.at(shape.material, shape, h, wo, &ns, &scratch) : default_bsdf_;
    Frame frame(ns);
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
                    s.active = true;
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
    double w = s.weighted ? power_heuristic(s.pdf, s.bsdf.pdf(s.wo_l, s.wi_l)) : 1;
    p.L = p.L + mul(s.beta_f, s.Li) * (w / s.pdf);
}

}  // namespace udm1pt
