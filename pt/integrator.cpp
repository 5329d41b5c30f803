// integrator.cpp - see integrator.h.
#include "integrator.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
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

Vec3 rgb_param(const udm1scene::ParamSet &ps, const std::string &name, Vec3 fallback)
{
    const udm1scene::Param *p = ps.find(name);
    if (!p) return fallback;
    Vec3 v;
    if (!ps.get_rgb(name, &v)) throw SceneError(p->where + ": '" + name + "' must be \"rgb " + name + "\" [r g b]");
    if (v.x < 0 || v.y < 0 || v.z < 0) throw SceneError(p->where + ": '" + name + "' must not be negative");
    return v;
}

void only(const udm1scene::ParamSet &ps, std::initializer_list<const char *> allowed, const std::string &what)
{
    for (const udm1scene::Param &p : ps.params) {
        bool ok = p.name == "type";  // MakeNamedMaterial's own parameter
        for (const char *a : allowed) ok |= p.name == a;
        if (!ok) throw SceneError(p.where + ": " + what + ": unsupported parameter '" + p.name + "'");
    }
}

// RGB stand-ins for pbrt-v4's named spectra (pbrt works spectrally; udm1-pt in RGB): the refractive
// index n + i k of metals at about 650, 550 and 450 nm (the RGB table of Hindefjord, from the same
// measured data pbrt-v4 ships), and the index of glasses at 550 nm.
struct NamedSpectrum {
    const char *name;
    Vec3 value;
};
const NamedSpectrum NAMED_SPECTRA[] = {
    {"metal-Au-eta", Vec3(0.18299, 0.42108, 1.3734)}, {"metal-Au-k", Vec3(3.4242, 2.3459, 1.7704)},
    {"metal-Ag-eta", Vec3(0.15943, 0.14512, 0.13547)}, {"metal-Ag-k", Vec3(3.9291, 3.19, 2.3808)},
    {"metal-Cu-eta", Vec3(0.27105, 0.67693, 1.3164)}, {"metal-Cu-k", Vec3(3.6092, 2.6248, 2.2921)},
    {"metal-Al-eta", Vec3(1.3456, 0.96521, 0.61722)}, {"metal-Al-k", Vec3(7.4746, 6.3995, 5.3031)},
    {"glass-BK7", Vec3(1.5185, 1.5185, 1.5185)}, {"glass-BAF10", Vec3(1.6700, 1.6700, 1.6700)},
    {"glass-F11", Vec3(1.6200, 1.6200, 1.6200)},
};

// A "spectrum" or "rgb" or "float" parameter as RGB: a named spectrum, (lambda, value) pairs
// (piecewise linear, taken at 650/550/450 nm), an rgb triple or one number.
Vec3 spectrum_param(const udm1scene::ParamSet &ps, const std::string &name, Vec3 fallback)
{
    const udm1scene::Param *p = ps.find(name);
    if (!p) return fallback;
    if (p->type == "float" && p->numbers.size() == 1) return Vec3(p->numbers[0], p->numbers[0], p->numbers[0]);
    if (p->type == "rgb" && p->numbers.size() == 3) return Vec3(p->numbers[0], p->numbers[1], p->numbers[2]);
    if (p->type == "spectrum" && p->strings.size() == 1) {
        for (const NamedSpectrum &n : NAMED_SPECTRA)
            if (p->strings[0] == n.name) return n.value;
        throw SceneError(p->where + ": '" + name + "': the named spectrum \"" + p->strings[0] + "\" is not known");
    }
    if (p->type == "spectrum" && p->numbers.size() >= 2 && p->numbers.size() % 2 == 0) {
        auto at = [&](double lambda) {
            const std::vector<double> &v = p->numbers;
            if (lambda <= v[0]) return v[1];
            for (size_t i = 2; i < v.size(); i += 2)
                if (lambda <= v[i]) return v[i - 1] + (v[i + 1] - v[i - 1]) * (lambda - v[i - 2]) / (v[i] - v[i - 2]);
            return v[v.size() - 1];
        };
        for (size_t i = 2; i < p->numbers.size(); i += 2)
            if (!(p->numbers[i] > p->numbers[i - 2]))
                throw SceneError(p->where + ": '" + name + "': wavelengths must increase");
        return Vec3(at(650), at(550), at(450));
    }
    throw SceneError(p->where + ": '" + name + "' must be a float, an rgb triple, a named spectrum or (lambda, value) pairs");
}

// pbrt-v4's roughness parameters: roughness or uroughness/vroughness, remapped unless remaproughness false.
udm1pt::Microfacets roughness_param(const udm1scene::ParamSet &ps, const std::string &what)
{
    double r = ps.get_float("roughness", 0.0);
    double ur = ps.get_float("uroughness", r), vr = ps.get_float("vroughness", r);
    if (!(ur >= 0 && vr >= 0)) throw SceneError(ps.where + ": " + what + ": roughness must not be negative");
    if (ps.get_bool("remaproughness", true)) ur = std::sqrt(ur), vr = std::sqrt(vr);  // pbrt's RoughnessToAlpha
    udm1pt::Microfacets mf;
    mf.ax = ur, mf.ay = vr;
    return mf;
}

struct Tracer {
    const udm1scene::Scene &scene;
    const udm1scene::EmbreeScene &rt;
    const Lights &lights;
    const std::vector<Bsdf> &bsdfs;
    Bsdf default_bsdf;
    int max_depth;
    Strategy strategy;
    bool roulette;
    int rr_depth;

    Vec3 trace(Vec3 o, Vec3 d, udm1_cursor *c, uint64_t *rays) const
    {
        Vec3 L, beta(1, 1, 1);
        bool specular_bounce = false;
        double eta_scale = 1;  // the product of eta^2 over transmissions: roulette sees beta without it (pbrt)
        double p_b = 0;
        Vec3 prev_p;
        for (int depth = 0;; ++depth) {
            Hit h;
            ++*rays;
            if (!rt.intersect(o, d, 0.0, 1e300, &h)) break;
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
            // this vertex's 6 dimensions, always drawn, so that the layout does not depend on what happens
            double u[DIMS_PER_VERTEX];
            udm1_cursor_fill_f64(c, DIMS_PER_VERTEX, u);
            const double u_lp[2] = {u[0], u[1]}, u_lobe = u[2], u_rr = u[3], u_dir[2] = {u[4], u[5]};

            const udm1scene::Shape &shape = scene.shapes[h.shape];
            const Bsdf &bsdf = shape.material >= 0 ? bsdfs[shape.material] : default_bsdf;
            Frame frame(shading_normal(shape, h));
            Vec3 wo_l = frame.to_local(wo);
            if (wo_l.z == 0) break;
            if (strategy != Strategy::Bsdf && bsdf.has_non_specular()) {  // next-event estimation
                LightSample ls;
                if (lights.sample(h.p, u_lp[0], u_lp[1], &ls)) {
                    Vec3 wi_l = frame.to_local(ls.wi);
                    Vec3 f = bsdf.f(wo_l, wi_l) * std::fabs(wi_l.z);
                    if (nonzero(f)) {
                        Vec3 so = spawn(h, ls.wi);
                        Vec3 q = h.p + ls.wi * ls.dist;
                        double len = udm1scene::length(q - so) - 2 * udm1scene::ray_offset(q);
                        ++*rays;
                        bool visible;
                        if (ls.sphere) {
                            // a ray that grazes a sphere meets Embree's float sphere up to ~1e-4 of the radius
                            // before the exact point: a hit on the light's own sphere is the light itself
                            Hit sh;
                            visible = len > 0 && (!rt.intersect(so, ls.wi, 0.0, len, &sh) || (int)sh.shape == ls.shape);
                        } else {
                            visible = len > 0 && !rt.occluded(so, ls.wi, 0.0, len);
                        }
                        if (visible) {
                            double w = strategy == Strategy::Mis ? power_heuristic(ls.pdf, bsdf.pdf(wo_l, wi_l)) : 1;
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

std::vector<float> Accumulator::mean() const
{
    std::vector<float> out(sum.size());
    double k = count ? 1.0 / (SCALE * (double)count) : 0.0;
    for (size_t i = 0; i < sum.size(); ++i) out[i] = (float)((double)sum[i] * k);
    return out;
}

std::vector<Bsdf> materials(const udm1scene::Scene &scene)
{
    std::vector<Bsdf> out;
    for (const udm1scene::Material &m : scene.materials) {
        Bsdf b;
        const udm1scene::ParamSet &ps = m.params;
        if (m.type == "diffuse") {
            only(ps, {"reflectance"}, "diffuse");
            b.kind = Bsdf::Diffuse;
            b.diffuse.R = rgb_param(ps, "reflectance", Vec3(0.5, 0.5, 0.5));
        } else if (m.type == "coateddiffuse") {
            only(ps, {"reflectance", "roughness", "uroughness", "vroughness", "remaproughness", "thickness", "eta",
                      "maxdepth", "nsamples", "albedo", "g"},
                 "coateddiffuse");
            b.kind = Bsdf::CoatedDiffuse;
            Coated &c = b.coated;
            c.bottom.R = rgb_param(ps, "reflectance", Vec3(0.5, 0.5, 0.5));
            c.top.mf = roughness_param(ps, "coateddiffuse");
            c.top.eta = ps.get_float("eta", 1.5);
            c.thickness = std::max(ps.get_float("thickness", 0.01), 1e-300);
            c.max_depth = ps.get_int("maxdepth", 10);
            c.samples = ps.get_int("nsamples", 1);
            if (!(c.top.eta > 0)) throw SceneError(ps.where + ": coateddiffuse: eta must be positive");
            if (c.max_depth < 1 || c.max_depth > 100 || c.samples < 1 || c.samples > 100)
                throw SceneError(ps.where + ": coateddiffuse: maxdepth and nsamples must be in 1..100");
            Vec3 albedo = rgb_param(ps, "albedo", Vec3());
            if (nonzero(albedo))
                throw SceneError(ps.where + ": coateddiffuse: a scattering medium between the layers (albedo > 0) "
                                            "is not supported");
        } else if (m.type == "conductor") {
            only(ps, {"eta", "k", "roughness", "uroughness", "vroughness", "remaproughness"}, "conductor");
            b.kind = Bsdf::ConductorKind;
            b.conductor.eta = spectrum_param(ps, "eta", Vec3(0.27105, 0.67693, 1.3164));  // pbrt's default: copper
            b.conductor.k = spectrum_param(ps, "k", Vec3(3.6092, 2.6248, 2.2921));
            b.conductor.mf = roughness_param(ps, "conductor");
            if (!(b.conductor.eta.x > 0 && b.conductor.eta.y > 0 && b.conductor.eta.z > 0) ||
                !(b.conductor.k.x >= 0 && b.conductor.k.y >= 0 && b.conductor.k.z >= 0))
                throw SceneError(ps.where + ": conductor: eta must be positive and k not negative");
        } else if (m.type == "dielectric") {
            only(ps, {"eta", "roughness", "uroughness", "vroughness", "remaproughness"}, "dielectric");
            b.kind = Bsdf::DielectricKind;
            Vec3 eta = spectrum_param(ps, "eta", Vec3(1.5, 1.5, 1.5));
            b.dielectric.eta = eta.y;  // one index for all channels (no dispersion): green's, 550 nm
            b.dielectric.mf = roughness_param(ps, "dielectric");
            if (!(b.dielectric.eta > 0)) throw SceneError(ps.where + ": dielectric: eta must be positive");
        } else {
            throw SceneError(ps.where + ": Material \"" + m.type +
                             "\" is not supported (diffuse, coateddiffuse, conductor, dielectric)");
        }
        out.push_back(b);
    }
    return out;
}

Accumulator render(const udm1scene::Scene &scene, const udm1scene::EmbreeScene &rt, const Options &opt, Stats *stats)
{
    if (opt.spp == 0) throw std::runtime_error("spp must be at least 1");
    uint64_t count = opt.count ? opt.count : (opt.first < opt.spp ? opt.spp - opt.first : 0);
    if (opt.first >= opt.spp || count > opt.spp - opt.first)
        throw std::runtime_error("sample range [" + std::to_string(opt.first) + ", " + std::to_string(opt.first + count) +
                                 ") is not inside [0, " + std::to_string(opt.spp) + ")");
    int max_depth = opt.max_depth >= 0 ? opt.max_depth : scene.max_depth;
    if (max_depth < 0 || max_depth > 1000) throw std::runtime_error("maxdepth must be in 0..1000");
    std::vector<Bsdf> bsdfs = materials(scene);
    Lights lights(scene, opt.near_light);

    udm1_preset_info info;
    if (udm1_preset_find(opt.sampler.c_str(), &info) != UDM1_OK)
        throw std::runtime_error("unknown sampler '" + opt.sampler + "' (udm1-seq list shows them)");
    uint32_t path_dims = 2 + DIMS_PER_VERTEX * (uint32_t)max_depth;
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    desc.preset = opt.sampler.c_str();
    desc.dimensions = std::max(2u, std::min(path_dims, info.max_dimensions));
    desc.point_count = (info.flags & UDM1_PRESET_POINT_SET) ? opt.spp : 0;
    desc.seed = opt.seed;
    desc.randomize = opt.randomize;
    udm1_seq *seq = nullptr;
    if (udm1_seq_create_desc(&desc, &seq) != UDM1_OK) throw std::runtime_error(udm1_last_error());

    udm1scene::Scene view = scene;
    if (opt.width > 0) view.width = opt.width, view.height = opt.height;
    Accumulator acc;
    acc.width = view.width, acc.height = view.height, acc.first = opt.first, acc.count = count;
    acc.sum.assign((size_t)acc.width * acc.height * 3, 0);
    const udm1scene::CameraRays camera(view);
    Tracer tracer{scene, rt, lights, bsdfs, Bsdf(), max_depth, opt.strategy, opt.roulette, opt.rr_depth};
    std::atomic<uint64_t> rays{0}, nonfinite{0}, clamped{0};
    auto t0 = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range2d<int>(0, acc.height, 8, 0, acc.width, 8), [&](const tbb::blocked_range2d<int> &r) {
        uint64_t local_rays = 0, local_nonfinite = 0, local_clamped = 0;
        for (int y = r.rows().begin(); y < r.rows().end(); ++y)
            for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                uint64_t stream = ((uint64_t)y << 32) | (uint32_t)x;
                int64_t *px = &acc.sum[3 * ((size_t)y * acc.width + x)];
                for (uint64_t i = opt.first; i < opt.first + count; ++i) {
                    udm1_cursor c;
                    udm1_cursor_start(&c, seq, stream, i, 0);
                    double uv[2];
                    udm1_cursor_fill_f64(&c, 2, uv);
                    Vec3 o, d;
                    camera.ray(x + uv[0], y + uv[1], &o, &d);
                    Vec3 L = tracer.trace(o, d, &c, &local_rays) * scene.film_scale;
                    for (int k = 0; k < 3; ++k) {
                        double v = L[k];
                        if (!std::isfinite(v)) {
                            ++local_nonfinite;
                            continue;
                        }
                        if (v > Accumulator::MAX_SAMPLE) v = Accumulator::MAX_SAMPLE, ++local_clamped;
                        px[k] += (int64_t)std::llround(v * Accumulator::SCALE);
                    }
                }
            }
        rays += local_rays, nonfinite += local_nonfinite, clamped += local_clamped;
    });
    udm1_seq_destroy(seq);
    acc.nonfinite = nonfinite, acc.clamped = clamped;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats->paths = (uint64_t)acc.width * acc.height * count;
    stats->rays = rays;
    stats->dimensions = desc.dimensions;
    stats->path_dimensions = path_dims;
    return acc;
}

}  // namespace udm1pt
