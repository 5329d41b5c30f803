// bench_ao.cpp - udm1-ao's speed against a bare Embree loop, side by side in one run.
//
//  1. Rays per second of udm1-ao's renderer (udm1ao::render: sampling, cosine mapping, primary
//     and occlusion rays, TBB tiles) against a bare loop over the same rays, precomputed: the same
//     primary rays (rtcIntersect1) and the same occlusion rays, from arrays, over the same TBB tiles.
//     Both for each way of handing occlusion rays to Embree (single rtcOccluded1, packets of 8
//     rtcOccluded8, one rtcOccluded1M stream per pixel), and with and without Embree's robust
//     traversal (udm1 uses robust: without it rays leak through shared edges, tests/cpp/test_ao.cpp).
//     Runs alternate (bare, udm1-ao, bare, ...) and the median of each is reported, with the ratio.
//  2. The time each sampler adds per sample: its 2D points for every pixel and sample of the
//     image (udm1_seq_fill_f64, one call per pixel as udm1-ao makes it), one thread, in ns per
//     sample; and the whole render with that sampler against the bare loop.
//
// Usage: udm1_bench_ao [--scene S] [--size N] [--spp N] [--reps R]
#include "ao_render.h"
#include "builtin.h"
#include "embree_scene.h"
#include "scene.h"

#include <tbb/blocked_range2d.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

using namespace udm1scene;

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// The rays of one render, precomputed exactly as udm1-ao makes them.
struct Rays {
    int width = 0, height = 0;
    uint32_t spp = 0;
    std::vector<float> primary;     // 6 floats per pixel: origin, direction
    std::vector<uint8_t> hit;       // the primary ray hits (then the pixel has spp occlusion rays)
    std::vector<float> occlusion;   // 6 floats per ray, spp per hit pixel (zeros for misses)
    uint64_t count = 0;             // primary + occlusion rays
};

Rays make_rays(const Scene &scene, const EmbreeScene &rt, const udm1ao::Options &o)
{
    Rays r;
    r.width = o.width, r.height = o.height, r.spp = o.spp;
    size_t n = (size_t)o.width * o.height;
    r.primary.resize(6 * n), r.hit.resize(n), r.occlusion.assign(6 * n * o.spp, 0.0f);
    Scene view = scene;
    view.width = o.width, view.height = o.height;
    udm1_seq *seq = udm1ao::make_sampler(o);
    std::vector<double> uv(2 * (size_t)o.spp);
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            size_t i = (size_t)y * o.width + x;
            Vec3 org, d;
            camera_ray(view, x + 0.5, y + 0.5, &org, &d);
            float *p = &r.primary[6 * i];
            p[0] = (float)org.x, p[1] = (float)org.y, p[2] = (float)org.z, p[3] = (float)d.x, p[4] = (float)d.y,
            p[5] = (float)d.z;
            ++r.count;
            Hit h;
            if (!rt.intersect(org, d, 0.0, 1e300, &h)) continue;
            r.hit[i] = 1;
            Vec3 nrm = dot(h.ng, d) > 0 ? -h.ng : h.ng;
            Vec3 o2 = rt.spawn_origin(h, d, nrm);
            udm1_seq_fill_f64(seq, ((uint64_t)y << 32) | (uint32_t)x, 0, o.spp, 0, 2, uv.data(), 2);
            for (uint32_t k = 0; k < o.spp; ++k) {
                Vec3 w = udm1ao::cosine_direction(nrm, uv[2 * k], uv[2 * k + 1]);
                float *q = &r.occlusion[6 * (i * o.spp + k)];
                q[0] = (float)o2.x, q[1] = (float)o2.y, q[2] = (float)o2.z, q[3] = (float)w.x, q[4] = (float)w.y,
                q[5] = (float)w.z;
            }
            r.count += o.spp;
        }
    udm1_seq_destroy(seq);
    return r;
}

// The bare loop: the same tiles, the same rays, nothing else. Returns the sum of unoccluded rays.
uint64_t bare_loop(RTCScene scene, const Rays &r, udm1ao::Method method)
{
    std::atomic<uint64_t> total{0};
    tbb::parallel_for(tbb::blocked_range2d<int>(0, r.height, 16, 0, r.width, 16), [&](const tbb::blocked_range2d<int> &b) {
        uint64_t free_rays = 0;
        std::vector<RTCRay> stream(r.spp);
        RTCIntersectContext ctx;
        for (int y = b.rows().begin(); y < b.rows().end(); ++y)
            for (int x = b.cols().begin(); x < b.cols().end(); ++x) {
                size_t i = (size_t)y * r.width + x;
                const float *p = &r.primary[6 * i];
                rtcInitIntersectContext(&ctx);
                RTCRayHit rh;
                rh.ray.org_x = p[0], rh.ray.org_y = p[1], rh.ray.org_z = p[2];
                rh.ray.dir_x = p[3], rh.ray.dir_y = p[4], rh.ray.dir_z = p[5];
                rh.ray.tnear = 0, rh.ray.tfar = INFINITY, rh.ray.mask = ~0u, rh.ray.flags = 0, rh.ray.time = 0;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene, &ctx, &rh);
                if (!r.hit[i]) continue;
                const float *q = &r.occlusion[6 * i * r.spp];
                if (method == udm1ao::Method::Single) {
                    for (uint32_t k = 0; k < r.spp; ++k, q += 6) {
                        RTCRay ray;
                        ray.org_x = q[0], ray.org_y = q[1], ray.org_z = q[2], ray.dir_x = q[3], ray.dir_y = q[4],
                        ray.dir_z = q[5];
                        ray.tnear = 0, ray.tfar = INFINITY, ray.mask = ~0u, ray.flags = 0, ray.time = 0;
                        rtcOccluded1(scene, &ctx, &ray);
                        free_rays += ray.tfar >= 0;
                    }
                } else if (method == udm1ao::Method::Packet) {
                    for (uint32_t k0 = 0; k0 < r.spp; k0 += 8) {
                        RTCRay8 ray;
                        alignas(32) int valid[8];  // Embree reads the mask as one aligned vector
                        for (int j = 0; j < 8; ++j) {
                            uint32_t k = k0 + j < r.spp ? k0 + j : k0;
                            const float *s = q + 6 * k;
                            valid[j] = k0 + j < r.spp ? -1 : 0;
                            ray.org_x[j] = s[0], ray.org_y[j] = s[1], ray.org_z[j] = s[2];
                            ray.dir_x[j] = s[3], ray.dir_y[j] = s[4], ray.dir_z[j] = s[5];
                            ray.tnear[j] = 0, ray.tfar[j] = INFINITY, ray.mask[j] = ~0u, ray.flags[j] = 0;
                            ray.time[j] = 0, ray.id[j] = 0;
                        }
                        rtcOccluded8(valid, scene, &ctx, &ray);
                        for (int j = 0; j < 8 && k0 + j < r.spp; ++j) free_rays += ray.tfar[j] >= 0;
                    }
                } else {
                    for (uint32_t k = 0; k < r.spp; ++k) {
                        const float *s = q + 6 * k;
                        RTCRay &ray = stream[k];
                        ray.org_x = s[0], ray.org_y = s[1], ray.org_z = s[2], ray.dir_x = s[3], ray.dir_y = s[4],
                        ray.dir_z = s[5];
                        ray.tnear = 0, ray.tfar = INFINITY, ray.mask = ~0u, ray.flags = 0, ray.time = 0, ray.id = k;
                    }
                    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
                    rtcOccluded1M(scene, &ctx, stream.data(), r.spp, sizeof(RTCRay));
                    for (const RTCRay &ray : stream) free_rays += ray.tfar >= 0;
                }
            }
        total += free_rays;
    });
    return total;
}

const char *method_name(udm1ao::Method m)
{
    return m == udm1ao::Method::Single ? "single" : m == udm1ao::Method::Packet ? "packet8" : "stream";
}

}  // namespace

int main(int argc, char **argv)
{
    std::string scene_name = "builtin:cornell";
    int size = 256, reps = 5;
    uint32_t spp = 64;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--scene" && i + 1 < argc) scene_name = argv[++i];
        else if (a == "--size" && i + 1 < argc) size = std::atoi(argv[++i]);
        else if (a == "--spp" && i + 1 < argc) spp = (uint32_t)std::atoi(argv[++i]);
        else if (a == "--reps" && i + 1 < argc) reps = std::atoi(argv[++i]);
        else {
            std::fprintf(stderr, "usage: udm1_bench_ao [--scene S] [--size N] [--spp N] [--reps R]\n");
            return 2;
        }
    }
    if (size < 8 || size > 4096 || spp < 1 || spp > 4096 || reps < 1 || reps > 100) {
        std::fprintf(stderr, "udm1_bench_ao: --size 8..4096, --spp 1..4096, --reps 1..100\n");
        return 2;
    }
    Scene scene;
    try {
        scene = load_scene(scene_name, Need::Geometry);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "udm1_bench_ao: %s\n", e.what());
        return 1;
    }
    std::printf("udm1_bench_ao: %s, %dx%d, %u spp, %zu triangles, %u threads, median of %d alternating runs\n",
                scene_name.c_str(), size, size, spp, scene.triangle_count(), std::thread::hardware_concurrency(), reps);

    std::printf("\n1. rays/s: udm1-ao (sampler episwr) against a bare Embree loop over the same precomputed rays\n");
    std::printf("%-8s %-8s %14s %14s %8s\n", "bvh", "method", "bare rays/s", "udm1-ao rays/s", "ratio");
    for (bool robust : {true, false}) {
        EmbreeScene rt(scene, robust);
        udm1ao::Options o;
        o.width = o.height = size;
        o.spp = spp;
        Rays rays = make_rays(scene, rt, o);
        for (udm1ao::Method m : {udm1ao::Method::Single, udm1ao::Method::Packet, udm1ao::Method::Stream}) {
            o.method = m;
            std::vector<double> bare, ours;
            uint64_t bare_free = 0;
            double ours_sum = 0;
            for (int r = 0; r < reps + 1; ++r) {  // the first round warms up
                double t0 = now();
                bare_free = bare_loop(rt.handle(), rays, m);
                double t1 = now();
                udm1ao::Stats st;
                udm1ao::Image img = udm1ao::render(scene, rt, o, &st);
                if (r == 0) continue;
                bare.push_back(rays.count / (t1 - t0));
                ours.push_back(st.rays / st.seconds);
                ours_sum = 0;
                for (float v : img.values) ours_sum += v;
            }
            (void)bare_free;
            (void)ours_sum;
            double b = median(bare), u = median(ours);
            std::printf("%-8s %-8s %14.4g %14.4g %8.3f\n", robust ? "robust" : "fast", method_name(m), b, u, u / b);
        }
    }

    std::printf("\n2. the time each sampler adds per sample (its 2D points for the whole image, one thread), and\n"
                "   the whole render with it (all threads, streams, robust) against the bare loop over episwr's rays\n");
    std::printf("%-12s %12s %16s %16s %10s\n", "sampler", "ns/sample", "render ns/sample", "bare ns/sample", "render/bare");
    EmbreeScene rt(scene);
    udm1ao::Options base;
    base.width = base.height = size;
    base.spp = spp;
    Rays rays = make_rays(scene, rt, base);
    const char *samplers[] = {"pcg32",  "drand48",    "cmj", "grps",  "hammersley", "lp",  "halton", "halton-owen",
                              "sobol",  "sobol-owen", "pmj02", "wr-ao", "we",        "wgr", "episwr", "wr",
                              "wmmr",   "hwmmr",      "rd"};
    double samples = (double)size * size * spp;
    for (const char *name : samplers) {
        udm1ao::Options o = base;
        o.sampler = name;
        udm1_seq *seq = udm1ao::make_sampler(o);
        std::vector<double> uv(2 * (size_t)spp), gen, render, bare;
        for (int r = 0; r < reps + 1; ++r) {
            double t0 = now();
            {
                tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
                for (int y = 0; y < size; ++y)
                    for (int x = 0; x < size; ++x)
                        udm1_seq_fill_f64(seq, ((uint64_t)y << 32) | (uint32_t)x, 0, spp, 0, 2, uv.data(), 2);
            }
            double t1 = now();
            bare_loop(rt.handle(), rays, udm1ao::Method::Stream);
            double t2 = now();
            udm1ao::Stats st;
            udm1ao::render(scene, rt, o, &st);
            if (r == 0) continue;
            gen.push_back((t1 - t0) / samples * 1e9);
            bare.push_back((t2 - t1) / samples * 1e9);
            render.push_back(st.seconds / samples * 1e9);
        }
        udm1_seq_destroy(seq);
        std::printf("%-12s %12.2f %16.2f %16.2f %10.3f\n", name, median(gen), median(render), median(bare),
                    median(render) / median(bare));
    }
    return 0;
}
