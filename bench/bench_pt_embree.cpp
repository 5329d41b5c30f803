// bench_pt_embree.cpp - how much of udm1-pt's render time is Embree's: udm1-pt's scalar loop
// (--loop scalar, one query at a time through EmbreeScene, which records them) against a bare replay
// of its own rays, side by side in one run. The measurement that led to the wavefront loop
// (apps/pt/wavefront_diffuse.h), which udm1-pt now uses on this scene by default.
//
// The render is run once with one thread while EmbreeScene records every query (origin, direction,
// tnear, tfar, intersect or occluded, in float, exactly as handed to Embree). Then, alternating, best
// of --reps rounds, both threads:
//   - the bare replay (anchor): the recorded queries through rtcIntersect1 / rtcOccluded1, the calls
//     udm1-pt makes, over TBB chunks, with nothing else (no sampling, shading, normals, lights);
//   - the same queries as streams (rtcIntersect1M / rtcOccluded1M of 256 consecutive queries of one
//     kind), what a wavefront path tracer could hand Embree at best;
//   - udm1-pt's render (udm1pt::render, the same options) of those same rays;
//   - both replays again on the same scene built without robust traversal (Embree's fastest, which
//     udm1 does not use: rays through shared edges can leak), the least Embree could cost.
// Embree's share of the render time = replay time / render time: the rest is udm1-pt's own work, so
// 1 / share bounds any speed-up that leaves Embree's queries as they are.
//
// Usage: udm1_bench_pt_embree [--scene S] [--size WxH] [--spp N] [--sampler S] [--reps R]
#include "builtin.h"
#include "embree_scene.h"
#include "integrator.h"
#include "scene.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <thread>
#include <vector>

using namespace udm1scene;

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// A recorded query as the Embree ray it was (id: its place in a stream).
RTCRay ray_of(const RayQuery &a, unsigned id = 0)
{
    return RTCRay{a.org[0], a.org[1], a.org[2], a.tnear, a.dir[0], a.dir[1], a.dir[2], 0, a.tfar, 0xFFFFFFFF, id, 0};
}

// The queries through the calls udm1-pt makes, one at a time; returns the number of hits (checked
// against the stream replay's: both did the same work).
uint64_t replay_single(RTCScene scene, const std::vector<RayQuery> &q)
{
    std::atomic<uint64_t> hits{0};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, q.size(), 4096), [&](const tbb::blocked_range<size_t> &r) {
        uint64_t local = 0;
        RTCIntersectContext ctx;
        for (size_t i = r.begin(); i < r.end(); ++i) {
            const RayQuery &a = q[i];
            rtcInitIntersectContext(&ctx);
            if (a.shadow) {
                RTCRay ray = ray_of(a);
                rtcOccluded1(scene, &ctx, &ray);
                local += ray.tfar < 0;
            } else {
                RTCRayHit rh;
                rh.ray = ray_of(a);
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene, &ctx, &rh);
                local += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            }
        }
        hits += local;
    });
    return hits;
}

// The same queries, each kind in streams of 256 consecutive queries.
uint64_t replay_streams(RTCScene scene, const std::vector<RayQuery> &rays, const std::vector<RayQuery> &shadows)
{
    const size_t M = 256;
    std::atomic<uint64_t> hits{0};
    auto run = [&](const std::vector<RayQuery> &q, bool shadow) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, q.size(), 4096), [&](const tbb::blocked_range<size_t> &r) {
            uint64_t local = 0;
            std::vector<RTCRayHit> rh(M);
            std::vector<RTCRay> sh(M);
            RTCIntersectContext ctx;
            for (size_t b = r.begin(); b < r.end(); b += M) {
                size_t n = std::min(M, r.end() - b);
                for (size_t k = 0; k < n; ++k) {
                    RTCRay ray = ray_of(q[b + k], (unsigned)k);
                    if (shadow) {
                        sh[k] = ray;
                    } else {
                        rh[k].ray = ray;
                        rh[k].hit.geomID = RTC_INVALID_GEOMETRY_ID;
                        rh[k].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                    }
                }
                rtcInitIntersectContext(&ctx);
                if (shadow) {
                    rtcOccluded1M(scene, &ctx, sh.data(), (unsigned)n, sizeof(RTCRay));
                    for (size_t k = 0; k < n; ++k) local += sh[k].tfar < 0;
                } else {
                    rtcIntersect1M(scene, &ctx, rh.data(), (unsigned)n, sizeof(RTCRayHit));
                    for (size_t k = 0; k < n; ++k) local += rh[k].hit.geomID != RTC_INVALID_GEOMETRY_ID;
                }
            }
            hits += local;
        });
    };
    run(rays, false);
    run(shadows, true);
    return hits;
}

bool parse_size(const char *s, int *w, int *h) { return std::sscanf(s, "%dx%d", w, h) == 2 && *w >= 8 && *h >= 8 && *w <= 4096 && *h <= 4096; }

}  // namespace

int main(int argc, char **argv)
{
    std::string scene_name = "builtin:cornell";
    udm1pt::Options o;
    o.sampler = "wr";
    o.spp = 32;
    o.loop = udm1pt::Loop::Scalar;  // the loop whose queries EmbreeScene records
    o.width = o.height = 128;
    int reps = 3;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        bool ok = i + 1 < argc;
        if (ok && a == "--scene") scene_name = argv[++i];
        else if (ok && a == "--size") ok = parse_size(argv[++i], &o.width, &o.height);
        else if (ok && a == "--spp") o.spp = (uint32_t)std::atoi(argv[++i]), ok = o.spp >= 1 && o.spp <= 4096;
        else if (ok && a == "--sampler") o.sampler = argv[++i];
        else if (ok && a == "--reps") reps = std::atoi(argv[++i]), ok = reps >= 1 && reps <= 100;
        else ok = false;
        if (!ok) {
            std::fprintf(stderr, "usage: udm1_bench_pt_embree [--scene S] [--size WxH (8..4096)] [--spp 1..4096] "
                                 "[--sampler S] [--reps 1..100]\n");
            return 2;
        }
    }
    try {
        Scene scene = load_scene(scene_name);
        EmbreeScene rt(scene), fast(scene, false);
        udm1pt::Materials materials(scene);
        udm1pt::Stats st;
        std::vector<RayQuery> log;
        {
            tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
            rt.record_queries(&log);
            udm1pt::render(scene, rt, materials, o, &st);
            rt.record_queries(nullptr);
        }
        if (log.size() != st.rays) {  // every query the render counted was recorded, and nothing else
            std::fprintf(stderr, "udm1_bench_pt_embree: recorded %zu queries, the render counted %llu\n", log.size(),
                         (unsigned long long)st.rays);
            return 1;
        }
        std::vector<RayQuery> rays, shadows;
        for (const RayQuery &q : log) (q.shadow ? shadows : rays).push_back(q);
        std::printf("udm1_bench_pt_embree: %s, %dx%d, %u spp, sampler %s, %u threads, best of %d alternating rounds\n",
                    scene_name.c_str(), o.width, o.height, o.spp, o.sampler.c_str(), std::thread::hardware_concurrency(),
                    reps);
        std::printf("queries recorded: %zu (%zu intersect, %zu occluded), %.3f per path\n\n", log.size(), rays.size(),
                    shadows.size(), (double)log.size() / (double)st.paths);
        double best_single = 1e300, best_stream = 1e300, best_render = 1e300, best_fast = 1e300, best_fast_stream = 1e300;
        uint64_t hits_single = 0, hits_stream = 0, hits_fast = 0, hits_fast_stream = 0;
        for (int r = 0; r < reps + 1; ++r) {  // round 0 warms up
            double t0 = now();
            hits_single = replay_single(rt.handle(), log);
            double t1 = now();
            hits_stream = replay_streams(rt.handle(), rays, shadows);
            double t2 = now();
            udm1pt::render(scene, rt, materials, o, &st);
            double t3 = now();
            hits_fast = replay_single(fast.handle(), log);
            double t4 = now();
            hits_fast_stream = replay_streams(fast.handle(), rays, shadows);
            double t5 = now();
            if (r == 0) continue;
            best_fast = std::min(best_fast, t4 - t3);
            best_fast_stream = std::min(best_fast_stream, t5 - t4);
            best_single = std::min(best_single, t1 - t0);
            best_stream = std::min(best_stream, t2 - t1);
            best_render = std::min(best_render, t3 - t2);
        }
        if (hits_single != hits_stream || hits_fast != hits_fast_stream) {
            std::fprintf(stderr, "udm1_bench_pt_embree: the replays disagree (%llu against %llu hits)\n",
                         (unsigned long long)hits_single, (unsigned long long)hits_stream);
            return 1;
        }
        double n = (double)log.size();
        std::printf("%-58s %9s %12s %8s\n", "queries of one udm1-pt render", "seconds", "queries/s", "ratio");
        std::printf("%-58s %9.4f %12.4g %8.2f\n", "bare replay, rtcIntersect1/rtcOccluded1 (anchor)", best_single,
                    n / best_single, 1.0);
        std::printf("%-58s %9.4f %12.4g %8.2f\n", "bare replay, streams of 256 (rtcIntersect1M/rtcOccluded1M)",
                    best_stream, n / best_stream, best_single / best_stream);
        std::printf("%-58s %9.4f %12.4g %8.2f\n", "udm1-pt render (udm1pt::render, the same rays)", best_render,
                    n / best_render, best_single / best_render);
        std::printf("%-58s %9.4f %12.4g %8.2f\n", "bare replay, not robust, rtcIntersect1/rtcOccluded1", best_fast,
                    n / best_fast, best_single / best_fast);
        std::printf("%-58s %9.4f %12.4g %8.2f\n", "bare replay, not robust, streams of 256", best_fast_stream,
                    n / best_fast_stream, best_single / best_fast_stream);
        std::printf("\nEmbree's share of udm1-pt's render time: %.1f %% (single queries), %.1f %% (as streams); "
                    "without robust traversal %.1f %% (single), %.1f %% (streams)\n",
                    100 * best_single / best_render, 100 * best_stream / best_render, 100 * best_fast / best_render,
                    100 * best_fast_stream / best_render);
        std::printf("hits: %llu of %zu queries (robust), %llu (not robust)\n", (unsigned long long)hits_single,
                    log.size(), (unsigned long long)hits_fast);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "udm1_bench_pt_embree: %s\n", e.what());
        return 1;
    }
    return 0;
}
