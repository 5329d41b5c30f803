// ao_render.cpp - see ao_render.h.
#include "ao_render.h"

#include "udm1app/pixel_order.h"
#include "udm1app/sampler.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <vector>
#include <cmath>
#include <stdexcept>

namespace udm1ao {

using udm1scene::Vec3;

namespace {

using udm1scene::Frame;  // Duff et al. 2017, "Building an orthonormal basis, revisited"
using udm1scene::sincos_2pi;

struct Scratch {  // per-thread buffers
    std::vector<float> dirs;
    std::vector<RTCRay> rays;
    std::vector<double> uv;
};

// Directions for `count` points into dx, dy, dz: one loop the compiler vectorizes (the same
// arithmetic as direction(), so the same bits).
// Also built for AVX2 (4 doubles a step), chosen at run time; -ffp-contract=off keeps FMA out, so
// both versions round the same operations the same way and give the same bits.
__attribute__((target_clones("avx2", "default")))
void directions(const Frame &f, const double *uv, uint32_t count, float *dx, float *dy, float *dz)
{
    const double tx = f.t.x, ty = f.t.y, tz = f.t.z, bx = f.b.x, by = f.b.y, bz = f.b.z, nx = f.n.x, ny = f.n.y,
                 nz = f.n.z;
#pragma omp simd
    for (uint32_t k = 0; k < count; ++k) {
        double u1 = uv[2 * k], u2 = uv[2 * k + 1];
        double r = std::sqrt(u1), s, c;
        sincos_2pi(u2, &s, &c);
        double x = r * c, y = r * s, z = std::sqrt(std::max(0.0, 1.0 - u1));
        dx[k] = (float)(tx * x + bx * y + nx * z);
        dy[k] = (float)(ty * x + by * y + ny * z);
        dz[k] = (float)(tz * x + bz * y + nz * z);
    }
}

// Occlusion rays from o around frame f, one per 2D point (uv: u1, u2 pairs): the number unoccluded.
// Every method traces the same float rays, so they give the same answer.
uint32_t unoccluded(const udm1scene::EmbreeScene &rt, Vec3 o, const Frame &f, const double *uv, uint32_t count,
                    double tfar, Method method, Scratch *scratch)
{
    scratch->dirs.resize(3 * (size_t)count);
    float *dx = scratch->dirs.data(), *dy = dx + count, *dz = dy + count;
    directions(f, uv, count, dx, dy, dz);
    uint32_t free_rays = 0;
    const float far = tfar >= 3e38 ? INFINITY : (float)tfar;
    const float ox = (float)o.x, oy = (float)o.y, oz = (float)o.z;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    if (method == Method::Single) {
        for (uint32_t k = 0; k < count; ++k) {
            RTCRay r;
            r.org_x = ox, r.org_y = oy, r.org_z = oz, r.dir_x = dx[k], r.dir_y = dy[k], r.dir_z = dz[k];
            r.tnear = 0.0f, r.tfar = far, r.time = 0, r.mask = 0xFFFFFFFF, r.id = 0, r.flags = 0;
            rtcOccluded1(rt.handle(), &ctx, &r);
            free_rays += r.tfar >= 0;
        }
        return free_rays;
    }
    if (method == Method::Packet) {
        RTCRay8 r;
        for (int j = 0; j < 8; ++j) {
            r.org_x[j] = ox, r.org_y[j] = oy, r.org_z[j] = oz;
            r.time[j] = 0, r.mask[j] = 0xFFFFFFFF, r.id[j] = 0, r.flags[j] = 0;
        }
        for (uint32_t k0 = 0; k0 < count; k0 += 8) {
            alignas(32) int valid[8];  // Embree reads the mask as one aligned vector
            for (uint32_t j = 0; j < 8; ++j) {
                uint32_t k = k0 + j < count ? k0 + j : k0;
                valid[j] = k0 + j < count ? -1 : 0;
                r.dir_x[j] = dx[k], r.dir_y[j] = dy[k], r.dir_z[j] = dz[k];
                r.tnear[j] = 0.0f, r.tfar[j] = far;
            }
            rtcOccluded8(valid, rt.handle(), &ctx, &r);
            for (uint32_t j = 0; j < 8 && k0 + j < count; ++j) free_rays += r.tfar[j] >= 0;
        }
        return free_rays;
    }
    // Stream: all rays of the pixel in one call
    std::vector<RTCRay> &rays = scratch->rays;
    rays.resize(count);
    for (uint32_t k = 0; k < count; ++k) {
        RTCRay &r = rays[k];
        r.org_x = ox, r.org_y = oy, r.org_z = oz, r.dir_x = dx[k], r.dir_y = dy[k], r.dir_z = dz[k];
        r.tnear = 0.0f, r.tfar = far, r.time = 0, r.mask = 0xFFFFFFFF, r.id = k, r.flags = 0;
    }
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    rtcOccluded1M(rt.handle(), &ctx, rays.data(), count, sizeof(RTCRay));
    for (const RTCRay &r : rays) free_rays += r.tfar >= 0;
    return free_rays;
}

}  // namespace

Vec3 cosine_direction(Vec3 n, double u1, double u2)
{
    double uv[2] = {u1, u2};
    float d[3];
    directions(Frame(n), uv, 1, &d[0], &d[1], &d[2]);
    return Vec3(d[0], d[1], d[2]);
}

// The samples [first, first + count) of pixel (x, y), dims values each, as the pixel order names them: one
// fill per pixel, or per sample in Z-order. False with udm1_last_error() set on failure.
static bool fill_pixel(const udm1_seq *seq, const udm1app::PixelOrder &order, int x, int y, uint64_t first, uint32_t count,
                       uint32_t dim0, uint32_t dims, double *out)
{
    if (!order.zorder) return udm1_seq_fill_f64(seq, order.stream(x, y), first, count, dim0, dims, out, dims) == UDM1_OK;
    for (uint32_t i = 0; i < count; ++i)
        if (udm1_seq_fill_f64(seq, 0, order.index(x, y, first + i), 1, dim0, dims, out + (size_t)i * dims, dims) != UDM1_OK)
            return false;
    return true;
}

// The sampler's dimensions: the directions' pair (and with --jitter the pixel's before it)
static uint32_t sampler_dims(const Options &opt)
{
    if (opt.jitter && opt.direction_dim)
        throw std::runtime_error("--direction-dims is for renders without --jitter (which takes dims 0..3)");
    return opt.jitter ? 4 : opt.direction_dim + 2;
}

udm1_seq *make_sampler(const Options &opt)
{
    return udm1app::create_render_sampler(opt.sampler, sampler_dims(opt), false, opt.spp, opt.seed, opt.randomize, "AO");
}

// make_sampler's sampler, shared by the renders of one image's sample ranges (udm1app::shared_render_sampler)
static std::shared_ptr<const udm1_seq> shared_sampler(const Options &opt)
{
    return udm1app::shared_render_sampler(opt.sampler, sampler_dims(opt), false, opt.spp, opt.seed, opt.randomize, "AO");
}

double ao_at(const udm1scene::EmbreeScene &rt, Vec3 p, Vec3 n, const udm1_seq *seq, uint64_t stream, uint32_t spp,
             uint32_t dim0, double max_distance, Method method)
{
    std::vector<double> uv(2 * (size_t)spp);
    if (udm1_seq_fill_f64(seq, stream, 0, spp, dim0, 2, uv.data(), 2) != UDM1_OK)
        throw std::runtime_error(udm1_last_error());
    Scratch scratch;
    Vec3 o = p + n * udm1scene::ray_offset(p);
    return (double)unoccluded(rt, o, Frame(n), uv.data(), spp, max_distance, method, &scratch) / spp;
}

Image render(const udm1scene::Scene &scene, const udm1scene::EmbreeScene &rt, const Options &opt, Stats *stats)
{
    if (opt.spp == 0) throw std::runtime_error("spp must be at least 1");
    const uint32_t count = opt.count ? opt.count : (opt.first < opt.spp ? opt.spp - opt.first : 0);
    if (opt.first >= opt.spp || count > opt.spp - opt.first)
        throw std::runtime_error("sample range [" + std::to_string(opt.first) + ", " +
                                 std::to_string((uint64_t)opt.first + count) + ") is not inside [0, " +
                                 std::to_string(opt.spp) + ")");
    udm1scene::Scene view = scene;  // the camera at the asked resolution
    if (opt.width > 0) view.width = opt.width, view.height = opt.height;
    int bounds[4] = {opt.bounds[0], opt.bounds[1], opt.bounds[2], opt.bounds[3]};
    udm1app::check_pixel_bounds(bounds, view.width, view.height);
    const udm1app::PixelOrder order = udm1app::make_pixel_order(opt.sampler, opt.randomize, opt.spp, opt.seed,
                                                                view.width, view.height);
    const std::shared_ptr<const udm1_seq> seq_owner = shared_sampler(opt);  // (shared by the renders of its sample ranges)
    const udm1_seq *seq = seq_owner.get();
    Image img;
    img.width = bounds[2] - bounds[0];
    img.height = bounds[3] - bounds[1];
    img.values.assign((size_t)img.width * img.height, 0.0f);
    udm1app::PartialImage &sums = img.sums;
    sums.reset(view.width, view.height, bounds[0], bounds[1], img.width, img.height, {"A"}, 1.0);
    sums.spp = opt.spp, sums.first = opt.first, sums.count = count;
    const uint32_t dims = opt.jitter ? 4 : 2;
    auto t0 = std::chrono::steady_clock::now();
    std::atomic<uint64_t> rays{0};
    std::string error;
    std::mutex error_mutex;
    std::atomic<bool> failed{false};
    tbb::parallel_for(tbb::blocked_range2d<int>(bounds[1], bounds[3], 16, bounds[0], bounds[2], 16),
                      [&](const tbb::blocked_range2d<int> &r) {
        Scratch scratch;
        std::vector<double> &uv = scratch.uv;
        uint64_t local_rays = 0;
        for (int y = r.rows().begin(); y < r.rows().end(); ++y)
            for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                uv.resize((size_t)count * dims);
                if (!fill_pixel(seq, order, x, y, opt.first, count, opt.jitter ? 0 : opt.direction_dim, dims, uv.data())) {
                    std::lock_guard<std::mutex> lock(error_mutex);
                    error = udm1_last_error();  // per thread: copy it here
                    failed = true;
                    continue;
                }
                uint32_t free_rays = 0;
                if (!opt.jitter) {  // one primary hit at the pixel centre, `count` directions
                    Vec3 o, d;
                    udm1scene::camera_ray(view, x + 0.5, y + 0.5, &o, &d);
                    udm1scene::Hit h;
                    ++local_rays;
                    if (!rt.intersect(o, d, 0.0, 1e300, &h)) {
                        free_rays = count;  // the sky: nothing occludes it
                    } else {
                        Vec3 n = dot(h.ng, d) > 0 ? -h.ng : h.ng;
                        free_rays = unoccluded(rt, rt.spawn_origin(h, d, n), Frame(n), uv.data(), count, opt.max_distance,
                                               opt.method, &scratch);
                        local_rays += count;
                    }
                } else {  // a jittered primary ray per sample, one direction each
                    for (uint32_t k = 0; k < count; ++k) {
                        Vec3 o, d;
                        udm1scene::camera_ray(view, x + uv[4 * k], y + uv[4 * k + 1], &o, &d);
                        udm1scene::Hit h;
                        ++local_rays;
                        if (!rt.intersect(o, d, 0.0, 1e300, &h)) {
                            ++free_rays;
                            continue;
                        }
                        Vec3 n = dot(h.ng, d) > 0 ? -h.ng : h.ng;
                        free_rays += unoccluded(rt, rt.spawn_origin(h, d, n), Frame(n), &uv[4 * k + 2], 1,
                                                opt.max_distance, Method::Single, &scratch);
                        ++local_rays;
                    }
                }
                size_t i = (size_t)(y - bounds[1]) * img.width + (x - bounds[0]);
                sums.sum[i] = free_rays;
                img.values[i] = (float)((double)free_rays / count);
            }
        rays += local_rays;
    });
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats->rays = rays;
    if (failed) throw std::runtime_error(error.empty() ? "sampling failed" : error);
    return img;
}

}  // namespace udm1ao
