// integrator.cpp - see integrator.h.
#include "integrator.h"

#include "udm1app/sampler.h"

#include "wavefront.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>

namespace udm1pt {

using udm1scene::cross;
using udm1scene::dot;
using udm1scene::Hit;
using udm1scene::normalize;
using udm1scene::SceneError;

namespace {

const int DIMS_PER_VERTEX = 6;

inline double max_component(Vec3 v) { return std::max({v.x, v.y, v.z}); }
inline bool nonzero(Vec3 v) { return v.x != 0 || v.y != 0 || v.z != 0; }
inline double power_heuristic(double f, double g) { return f * f + g * g > 0 ? f * f / (f * f + g * g) : 0; }

using udm1scene::Frame;

// The shading normal: interpolated vertex normals where the mesh has them, else the geometric one.
Vec3 shading_normal(const udm1scene::Shape &s, const Hit &h)
{
    if (s.kind != udm1scene::Shape::Triangles || s.N.empty()) return h.ng;
    const uint32_t *i = &s.indices[3 * (size_t)h.prim];
    auto N = [&](uint32_t k) { return Vec3(s.N[3 * k], s.N[3 * k + 1], s.N[3 * k + 2]); };
    Vec3 n = N(i[0]) * (1 - h.u - h.v) + N(i[1]) * h.u + N(i[2]) * h.v;
    double len = udm1scene::length(n);
    return len > 0 ? n * (1 / len) : h.ng;
}

// The origin of a ray leaving hit h towards w: offset to the side of the surface w goes to.
inline Vec3 spawn(const Hit &h, Vec3 w)
{
    double off = udm1scene::ray_offset(h.p, h.t);
    return h.p + (dot(h.ng, w) > 0 ? h.ng : -h.ng) * off;
}

struct Tracer {
    const udm1scene::Scene &scene;
    const udm1scene::EmbreeScene &rt;
    const Lights &lights;
    const Materials &materials;
    Bsdf default_bsdf;  // of a shape without a material
    int max_depth;
    Strategy strategy;
    bool roulette;
    int rr_depth;

    Vec3 trace(Vec3 o, Vec3 d, udm1_domain sample, uint64_t *rays) const
    {
        Vec3 L, beta(1, 1, 1);
        bool specular_bounce = false;
        double eta_scale = 1;  // the product of eta^2 over transmissions: roulette sees beta without it (pbrt)
        Bsdf scratch;          // a textured material's BSDF at the current vertex
        double p_b = 0;
        Vec3 prev_p;
        for (int depth = 0;; ++depth) {
            Hit h;
            ++*rays;
            if (!rt.intersect(o, d, 0.0, 1e300, &h)) {  // the ray leaves the scene: the environment, if any
                if (lights.has_environment()) {
                    Vec3 Le = lights.environment(d);
                    if (depth == 0 || specular_bounce || strategy == Strategy::Bsdf)
                        L = L + mul(beta, Le);
                    else if (strategy == Strategy::Mis)
                        L = L + mul(beta, Le) * power_heuristic(p_b, lights.environment_pdf(d));
                }
                break;
            }
            Vec3 wo = -d;
            Vec3 Le = lights.emitted(h, wo);
            if (nonzero(Le)) {
                if (depth == 0 || specular_bounce || strategy == Strategy::Bsdf) {
                    L = L + mul(beta, Le);
                } else if (strategy == Strategy::Mis) {
                    double p_l = lights.pdf(prev_p, h);
                    L = L + mul(beta, Le) * power_heuristic(p_b, p_l);
                }
            }
            if (depth == max_depth) break;
            // this vertex's values (integrator.h): always drawn, so that nothing depends on what happens
            double u[DIMS_PER_VERTEX];
            vertex_values(sample.stream, sample.index, depth, u);
            const double u_lp[2] = {u[0], u[1]}, u_lobe = u[2], u_rr = u[3], u_dir[2] = {u[4], u[5]};

            const udm1scene::Shape &shape = scene.shapes[h.shape];
            Vec3 ns = shading_normal(shape, h);
            const Bsdf &bsdf =
                shape.material >= 0 ? materials.at(shape.material, shape, h, wo, &ns, &scratch) : default_bsdf;
            Frame frame(ns);
            Vec3 wo_l = frame.to_local(wo);
            if (wo_l.z == 0) break;
            if (strategy != Strategy::Bsdf && bsdf.has_non_specular()) {  // next-event estimation
                LightSample ls;
                if (lights.sample(h.p, u_lp[0], u_lp[1], &ls)) {
                    Vec3 wi_l = frame.to_local(ls.wi);
                    Vec3 f = bsdf.f(wo_l, wi_l) * std::fabs(wi_l.z);
                    if (nonzero(f)) {
                        udm1scene::Segment sg = ls.infinite ? udm1scene::segment_to_infinity(h.p, h.ng, h.t, ls.wi)
                                                            : udm1scene::shadow_segment(h.p, h.ng, h.t, ls.q, ls.n);
                        ++*rays;
                        bool visible;
                        if (ls.sphere) {
                            // a ray that grazes a sphere meets Embree's float sphere up to ~1e-4 of the radius
                            // before the exact point: a hit on the light's own sphere is the light itself
                            Hit sh;
                            visible = sg.len > 0 && (!rt.intersect(sg.o, sg.d, 0.0, sg.len, &sh) || (int)sh.shape == ls.shape);
                        } else {
                            visible = sg.len > 0 && !rt.occluded(sg.o, sg.d, 0.0, sg.len);
                        }
                        if (visible) {
                            double w = strategy == Strategy::Mis && !ls.delta ? power_heuristic(ls.pdf, bsdf.pdf(wo_l, wi_l)) : 1;
                            L = L + mul(mul(beta, f), ls.L) * (w / ls.pdf);
                        }
                    }
                }
            }
            Sample bs;
            if (!bsdf.sample(wo_l, u_lobe, u_dir[0], u_dir[1], &bs) || bs.pdf <= 0 || !nonzero(bs.f)) break;
            Vec3 wi = normalize(frame.from_local(bs.wi));
            beta = mul(beta, bs.f) * (std::fabs(bs.wi.z) / bs.pdf);
            p_b = bs.pdf_is_proportional ? bsdf.pdf(wo_l, bs.wi) : bs.pdf;
            specular_bounce = bs.specular;
            if (!bs.reflection) eta_scale *= bs.eta * bs.eta;
            prev_p = h.p;
            if (!(max_component(beta) > 0) || !std::isfinite(max_component(beta))) break;
            if (roulette && depth >= rr_depth) {  // when the throughput is below 1
                double rr = max_component(beta) * eta_scale;
                if (rr < 1) {
                    double q = std::max(0.0, 1 - rr);
                    if (u_rr < q) break;
                    beta = beta * (1 / (1 - q));
                }
            }
            o = spawn(h, wi);
            d = wi;
        }
        return L;
    }
};

}  // namespace

Sequence make_sequence(const Options &opt, uint32_t dims)
{
    // at least 2 dimensions, at most the preset's own (the domains pad the rest)
    return Sequence(udm1app::create_render_sampler(opt.sampler, dims, true, opt.spp, opt.seed,
                                                   opt.randomize, "udm1-pt"),
                    udm1_seq_destroy);
}

Accumulator render(const udm1scene::Scene &scene, const udm1scene::EmbreeScene &rt, const Options &opt, Stats *stats)
{
    Materials materials(scene);
    return render(scene, rt, materials, opt, stats);
}

Accumulator render(const udm1scene::Scene &scene, const udm1scene::EmbreeScene &rt, const Materials &materials,
                   const Options &opt, Stats *stats)
{
    if (opt.spp == 0) throw std::runtime_error("spp must be at least 1");
    uint64_t count = opt.count ? opt.count : (opt.first < opt.spp ? opt.spp - opt.first : 0);
    if (opt.first >= opt.spp || count > opt.spp - opt.first)
        throw std::runtime_error("sample range [" + std::to_string(opt.first) + ", " + std::to_string(opt.first + count) +
                                 ") is not inside [0, " + std::to_string(opt.spp) + ")");
    int max_depth = opt.max_depth >= 0 ? opt.max_depth : scene.max_depth;
    if (max_depth < 0 || max_depth > 1000) throw std::runtime_error("maxdepth must be in 0..1000");
    Lights lights(scene, opt.near_light);

    udm1scene::Scene view = scene;
    if (opt.width > 0) view.width = opt.width, view.height = opt.height;
    int bounds[4] = {opt.bounds[0], opt.bounds[1], opt.bounds[2], opt.bounds[3]};
    udm1app::check_pixel_bounds(bounds, view.width, view.height);  // before anything is allocated
    Sequence seq_owner = make_sequence(opt, path_dims(max_depth));  // freed on every path
    udm1_seq *seq = seq_owner.get();
    Accumulator acc;
    acc.reset(view.width, view.height, bounds[0], bounds[1], bounds[2] - bounds[0], bounds[3] - bounds[1], {"R", "G", "B"},
              SAMPLE_SCALE);
    acc.spp = opt.spp, acc.first = opt.first, acc.count = count;
    const udm1scene::CameraRays camera(view);
    Tracer tracer{scene, rt, lights, materials, default_material(), max_depth, opt.strategy, opt.roulette, opt.rr_depth};
    std::string why = opt.loop == Loop::Scalar ? "scalar loop asked for" : wavefront_unsupported(scene, opt);
    if (opt.loop == Loop::Wavefront && !why.empty()) throw std::runtime_error("no wavefront loop: " + why);
    std::unique_ptr<Wavefront> wavefront;
    if (why.empty()) wavefront = std::make_unique<Wavefront>(scene, rt, materials, lights, max_depth, opt.roulette, opt.rr_depth);
    std::atomic<uint64_t> rays{0}, nonfinite{0}, clamped{0};
    auto t0 = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range2d<int>(bounds[1], bounds[3], 8, bounds[0], bounds[2], 8), [&](const tbb::blocked_range2d<int> &r) {
        if (wavefront) {
            Wavefront::Counts n;
            wavefront->render(seq, camera, r.cols().begin(), r.cols().end(), r.rows().begin(), r.rows().end(), opt.first,
                              count, scene.film_scale, &acc, &n);
            rays += n.rays, nonfinite += n.nonfinite, clamped += n.clamped;
            return;
        }
        uint64_t local_rays = 0, local_nonfinite = 0, local_clamped = 0;
        for (int y = r.rows().begin(); y < r.rows().end(); ++y)
            for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                uint64_t stream = ((uint64_t)y << 32) | (uint32_t)x;
                int64_t *px = &acc.sum[3 * ((size_t)(y - acc.y0) * acc.width + (x - acc.x0))];
                udm1_stream pixel;  // the pixel's randomization, once: its samples' domains draw inline
                udm1_stream_init(&pixel, seq, stream, 0, stream_dims(max_depth));
                for (uint64_t i = opt.first; i < opt.first + count; ++i) {
                    udm1_domain sample = udm1_domain_root(&pixel, i);
                    double uv[4];
                    udm1_domain_draw_f64(sample, camera.has_lens() ? 4 : 2, uv);
                    Vec3 o, d;
                    camera.ray(x + uv[0], y + uv[1], uv[2], uv[3], &o, &d);
                    Vec3 L = tracer.trace(o, d, sample, &local_rays) * scene.film_scale;
                    for (int k = 0; k < 3; ++k) {
                        double v = L[k];
                        if (!std::isfinite(v)) {
                            ++local_nonfinite;
                            continue;
                        }
                        if (v > MAX_SAMPLE) v = MAX_SAMPLE, ++local_clamped;
                        px[k] += (int64_t)std::llround(v * SAMPLE_SCALE);
                    }
                }
            }
        rays += local_rays, nonfinite += local_nonfinite, clamped += local_clamped;
    });
    acc.nonfinite = nonfinite, acc.clamped = clamped;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats->paths = (uint64_t)acc.width * acc.height * count;
    stats->rays = rays;
    stats->dimensions = udm1_seq_dimensions(seq);
    stats->path_dimensions = path_dims(max_depth);
    stats->wavefront = wavefront != nullptr;
    return acc;
}

}  // namespace udm1pt
