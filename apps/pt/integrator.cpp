// integrator.cpp - see integrator.h.
#include "integrator.h"

#include "udm1app/pixel_order.h"
#include "udm1app/sampler.h"

#include "estimator.h"
#include "wavefront_diffuse.h"
#include "wavefront_general.h"

#include "spectrum.h"
#include "white_balance.h"

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

using udm1scene::Hit;

namespace {

// A walking shadow test (the volumetric estimator's), piece by piece: whether its sample arrives.
bool walk(const Estimator &est, const udm1scene::EmbreeScene &rt, ShadowTest &s, uint64_t *rays)
{
    for (;;) {
        ++*rays;
        Hit sh;
        bool hit = rt.intersect(s.o, s.d, 0.0, s.len, &sh) && !(s.sphere && (int)sh.shape == s.shape);
        Crossing c = est.cross(s, hit ? &sh : nullptr);
        if (c != Crossing::Onward) return c == Crossing::Arrived;
    }
}

// One path, one Embree query at a time, through the estimator of estimator.h.
Vec3 trace(const Estimator &est, const udm1scene::EmbreeScene &rt, PathState &p, uint64_t *rays)
{
    ShadowTest shadow;
    const bool volumetric = est.volumetric();
    if (volumetric) est.start(p);
    for (;;) {
        Hit h;
        ++*rays;
        bool hit = rt.intersect(p.o, p.d, 0.0, 1e300, &h);
        bool more;
        if (volumetric) {
            more = est.step(p, hit ? &h : nullptr, &shadow);
        } else {
            if (!hit) {
                est.miss(p);
                break;
            }
            more = est.scatter(p, h, &shadow);
        }
        if (shadow.active) {
            bool free;
            if (shadow.walk) {
                free = walk(est, rt, shadow, rays);
            } else if (shadow.sphere) {
                ++*rays;
                Hit sh;
                free = !rt.intersect(shadow.o, shadow.d, 0.0, shadow.len, &sh) || (int)sh.shape == shadow.shape;
            } else {
                ++*rays;
                free = !rt.occluded(shadow.o, shadow.d, 0.0, shadow.len);
            }
            if (free) est.arrive(p, shadow);
        }
        if (!more) break;
    }
    return p.L;
}

}  // namespace

FilmResponse::FilmResponse(const udm1scene::Scene &scene)
    : scale(scene.film_scale), max_component(scene.max_component), clamp(std::isfinite(scene.max_component)),
      balance(scene.white_balance > 0), sampler(scene.pixel_filter), weighted(sampler.signed_weights()),
      stride(weighted ? 4 : 3)
{
    if (balance && !udm1scene::white_balance_rgb(scene.white_balance, wb))
        throw std::runtime_error("white balance " + std::to_string(scene.white_balance) + " K is not finite");
    for (int c = 0; c < 3; ++c) {  // (column c of XYZ from RGB: the XYZ of the primary c)
        Vec3 e;
        e[c] = 1;
        Vec3 col = udm1scene::rgb_to_xyz(e);
        for (int r = 0; r < 3; ++r) xyz[r][c] = col[r];
    }
}

Sequence make_sequence(const Options &opt, uint32_t dims)
{
    // at least 2 dimensions, at most the preset's own (the domains pad the rest)
    return udm1app::shared_render_sampler(opt.sampler, dims, true, opt.spp, opt.seed, opt.randomize, "udm1-pt");
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

    // The film, and the image: the whole film or, cropped, a window of it. The loops render the window's pixels
    // in the film's coordinates (their samples those of the whole film's render), and the image is re-based.
    udm1scene::Scene view = scene;
    if (opt.width > 0) view.width = opt.width, view.height = opt.height;
    const int image_width = view.width, image_height = view.height;
    int ox = 0, oy = 0;  // the image's corner on the film
    if (opt.film_width > 0) view.width = opt.film_width, view.height = opt.film_height, ox = opt.film_x0, oy = opt.film_y0;
    int bounds[4] = {opt.bounds[0], opt.bounds[1], opt.bounds[2], opt.bounds[3]};
    udm1app::check_pixel_bounds(bounds, image_width, image_height);  // before anything is allocated
    bounds[0] += ox, bounds[2] += ox, bounds[1] += oy, bounds[3] += oy;
    const udm1app::PixelOrder order = udm1app::make_pixel_order(opt.sampler, opt.randomize, opt.spp, opt.seed,
                                                                view.width, view.height);
    Sequence seq_owner = make_sequence(opt, path_dims(max_depth));  // (shared by the renders of its sample ranges)
    const udm1_seq *seq = seq_owner.get();
    const FilmResponse film(scene);
    Accumulator acc;
    acc.reset(view.width, view.height, bounds[0], bounds[1], bounds[2] - bounds[0], bounds[3] - bounds[1],
              film.weighted ? std::vector<std::string>{"R", "G", "B", "W"} : std::vector<std::string>{"R", "G", "B"},
              SAMPLE_SCALE);
    acc.spp = opt.spp, acc.first = opt.first, acc.count = count;
    const udm1scene::CameraRays camera(view);
    const Estimator estimator(scene, lights, materials, max_depth, opt.strategy, opt.roulette, opt.rr_depth);
    std::unique_ptr<DiffuseWavefront> diffuse;
    std::unique_ptr<GeneralWavefront> general;
    if (opt.loop != Loop::Scalar) {
        if (diffuse_wavefront_unsupported(scene, opt).empty())
            diffuse = std::make_unique<DiffuseWavefront>(scene, rt, materials, lights, max_depth, opt.roulette, opt.rr_depth);
        else
            general = std::make_unique<GeneralWavefront>(rt, estimator);
    }
    std::atomic<uint64_t> rays{0}, nonfinite{0}, clamped{0};
    auto t0 = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range2d<int>(bounds[1], bounds[3], 8, bounds[0], bounds[2], 8), [&](const tbb::blocked_range2d<int> &r) {
        if (diffuse || general) {
            LoopCounts n;
            if (diffuse)
                diffuse->render(seq, order, camera, r.cols().begin(), r.cols().end(), r.rows().begin(), r.rows().end(), opt.first,
                                count, film, &acc, &n);
            else
                general->render(seq, order, max_depth, camera, r.cols().begin(), r.cols().end(), r.rows().begin(),
                                r.rows().end(), opt.first, count, film, &acc, &n);
            rays += n.rays, nonfinite += n.nonfinite, clamped += n.clamped;
            return;
        }
        uint64_t local_rays = 0, local_nonfinite = 0, local_clamped = 0;
        for (int y = r.rows().begin(); y < r.rows().end(); ++y)
            for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                int64_t *px = &acc.sum[film.stride * ((size_t)(y - acc.y0) * acc.width + (x - acc.x0))];
                udm1_stream pixel;  // the pixel's randomization, once: its samples' domains draw inline
                udm1_stream_init(&pixel, seq, order.stream(x, y), 0, stream_dims(max_depth));
                for (uint64_t n = opt.first; n < opt.first + count; ++n) {
                    const uint64_t i = order.index(x, y, n);
                    udm1_domain sample = udm1_domain_root(&pixel, i);
                    double uv[4];
                    udm1_domain_draw_f64(sample, camera.has_lens() ? 4 : 2, uv);
                    const int sign = film.sampler.place(uv);
                    PathState path;
                    path.pixel = &pixel, path.index = i;
                    camera.ray(x + uv[0], y + uv[1], uv[2], uv[3], &path.o, &path.d);
                    add_sample(px, film(trace(estimator, rt, path, &local_rays)), sign, film.weighted, &local_nonfinite,
                               &local_clamped);
                }
            }
        rays += local_rays, nonfinite += local_nonfinite, clamped += local_clamped;
    });
    acc.nonfinite = nonfinite, acc.clamped = clamped;
    acc.full_width = image_width, acc.full_height = image_height, acc.x0 -= ox, acc.y0 -= oy;  // (the image's own)
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats->paths = (uint64_t)acc.width * acc.height * count;
    stats->rays = rays;
    stats->dimensions = udm1_seq_dimensions(seq);
    stats->path_dimensions = path_dims(max_depth);
    stats->loop = diffuse ? "wavefront" : general ? "wavefront-general" : "scalar";
    return acc;
}

}  // namespace udm1pt
