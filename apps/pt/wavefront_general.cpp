// wavefront_general.cpp - see wavefront_general.h.
#include "wavefront_general.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace udm1pt {

using udm1scene::Hit;

namespace {

const size_t BATCH = 4096;  // paths traced together

// Embree's SOA ray arrays (float) of up to BATCH rays and their hits.
struct Rays {
    std::vector<float> ox, oy, oz, dx, dy, dz, tnear, time, tfar, ngx, ngy, ngz, u, v;
    std::vector<unsigned> mask, id, flags, prim, geom, inst;
    std::vector<uint32_t> path;  // shadow rays: whose they are
    void resize(size_t n)
    {
        for (auto *f : {&ox, &oy, &oz, &dx, &dy, &dz, &tfar, &ngx, &ngy, &ngz, &u, &v}) f->resize(n);
        tnear.assign(n, 0.0f), time.assign(n, 0.0f), mask.assign(n, 0xFFFFFFFFu), flags.assign(n, 0);
        id.resize(n), prim.resize(n), geom.resize(n), inst.resize(n), path.resize(n);
        for (size_t i = 0; i < n; ++i) id[i] = (unsigned)i;
    }
    // ray k: o + t d for t in [0, tfar], as EmbreeScene::intersect and occluded hand it to Embree
    void set(size_t k, Vec3 o, Vec3 d, double far)
    {
        ox[k] = (float)o.x, oy[k] = (float)o.y, oz[k] = (float)o.z;
        dx[k] = (float)d.x, dy[k] = (float)d.y, dz[k] = (float)d.z;
        tfar[k] = far >= 3e38 ? std::numeric_limits<float>::infinity() : (float)far;
        geom[k] = RTC_INVALID_GEOMETRY_ID, inst[k] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCRayNp rays() { return {ox.data(), oy.data(), oz.data(), tnear.data(), dx.data(), dy.data(), dz.data(),
                              time.data(), tfar.data(), mask.data(), id.data(), flags.data()}; }
    RTCRayHitNp ray_hits()
    {
        return {rays(), {ngx.data(), ngy.data(), ngz.data(), u.data(), v.data(), prim.data(), geom.data(), {inst.data()}}};
    }
};

struct Buffers {
    std::vector<PathState> paths;
    std::vector<ShadowTest> shadows;
    std::vector<int> pixel;       // each path's pixel in the tile
    std::vector<uint8_t> alive;   // the path goes on after this vertex
    std::vector<uint32_t> walking;  // the walking shadow tests still on their way (their paths)
    Rays hits, occlusion, spheres;  // closest hits; shadow rays (occlusion), shadow rays to sphere lights (hits)
};

Buffers &buffers()  // one set per thread, reused from batch to batch
{
    thread_local Buffers b;
    if (b.paths.size() < BATCH) {
        b.paths.resize(BATCH), b.shadows.resize(BATCH), b.pixel.resize(BATCH), b.alive.resize(BATCH);
        b.walking.resize(BATCH);
        b.hits.resize(BATCH), b.occlusion.resize(BATCH), b.spheres.resize(BATCH);
    }
    return b;
}

}  // namespace

// One thread's batch: camera(), then per bounce trace() (closest hits, every live path's vertex through
// the estimator) and shadows() (the light samples' segments; arrived samples added; ended paths retired,
// the others compacted).
class GeneralWavefront::Batch {
public:
    Batch(const GeneralWavefront &w, const udm1_seq *seq, const udm1app::PixelOrder &order, int max_depth, int x0,
          int x1, int y0, int y1, uint64_t first, uint64_t count, const FilmResponse &film, Accumulator *acc,
          LoopCounts *counts)
        : w_(w), order_(order), x0_(x0), y0_(y0), W_(x1 - x0), first_(first), count_(count), film_(film), acc_(acc),
          counts_(counts), b_(buffers())
    {
        streams_.resize((size_t)W_ * (size_t)(y1 - y0));  // the tile's pixels' streams, once
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
                udm1_stream_init(&streams_[(size_t)(y - y0) * W_ + (x - x0)], seq, order.stream(x, y), 0,
                                 stream_dims(max_depth));
    }
    void camera(const udm1scene::CameraRays &camera, uint64_t start, size_t n);
    void trace();
    void shadows();
    size_t live() const { return n_; }

private:
    void finish(size_t j);

    const GeneralWavefront &w_;
    const udm1app::PixelOrder &order_;
    int x0_, y0_, W_;
    uint64_t first_, count_;
    const FilmResponse &film_;
    Accumulator *acc_;
    LoopCounts *counts_;
    Buffers &b_;
    std::vector<udm1_stream> streams_;
    const bool volumetric_ = w_.estimator_.volumetric();
    size_t n_ = 0;
    bool first_bounce_ = true;
    RTCIntersectContext ctx_;
};

void GeneralWavefront::Batch::finish(size_t j)  // path j ends: its radiance into its pixel's sums (as the scalar loop)
{
    int p = b_.pixel[j];
    int64_t *px = &acc_->sum[film_.stride * ((size_t)(y0_ + p / W_ - acc_->y0) * acc_->width + (x0_ + p % W_ - acc_->x0))];
    const PathState &path = b_.paths[j];
    const int sign = film_.weighted ? sample_sign(film_, path.pixel, path.index) : 1;
    add_sample(px, film_(path.L), sign, film_.weighted, &counts_->nonfinite, &counts_->clamped);
}

void GeneralWavefront::Batch::camera(const udm1scene::CameraRays &camera, uint64_t start, size_t n)
{
    n_ = n;
    first_bounce_ = true;
    uint64_t s = start % count_;
    int p = (int)(start / count_);
    for (size_t k = 0; k < n; ++k) {
        PathState &path = b_.paths[k];
        path = PathState();
        path.pixel = &streams_[p], path.index = order_.index(x0_ + p % W_, y0_ + p / W_, first_ + s);
        b_.pixel[k] = p;
        double uv[4];
        udm1_domain_draw_f64(udm1_domain_root(path.pixel, path.index), camera.has_lens() ? 4 : 2, uv);
        film_.sampler.place(uv);
        camera.ray(x0_ + p % W_ + uv[0], y0_ + p / W_ + uv[1], uv[2], uv[3], &path.o, &path.d);
        if (volumetric_) w_.estimator_.start(path);
        if (++s == count_) s = 0, ++p;  // the next pixel
    }
}

void GeneralWavefront::Batch::trace()
{
    Rays &R = b_.hits;
    const size_t n = n_;
    for (size_t j = 0; j < n; ++j) R.set(j, b_.paths[j].o, b_.paths[j].d, INFINITY);
    RTCRayHitNp q = R.ray_hits();
    rtcInitIntersectContext(&ctx_);
    if (first_bounce_) ctx_.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // camera rays of neighbouring pixels
    first_bounce_ = false;
    rtcIntersectNp(w_.rt_.handle(), &ctx_, &q, (unsigned)n);
    counts_->rays += n;
    const Estimator &est = w_.estimator_;
    for (size_t j = 0; j < n; ++j) {
        PathState &path = b_.paths[j];
        if (volumetric_) {
            Hit h;
            bool hit = R.geom[j] != RTC_INVALID_GEOMETRY_ID;
            if (hit) h = w_.rt_.hit_of(path.o, path.d, R.tfar[j], R.geom[j], R.prim[j], R.u[j], R.v[j], R.inst[j]);
            b_.alive[j] = est.step(path, hit ? &h : nullptr, &b_.shadows[j]);
            continue;
        }
        if (R.geom[j] == RTC_INVALID_GEOMETRY_ID) {
            est.miss(path);
            b_.shadows[j].active = false;
            b_.alive[j] = 0;
            continue;
        }
        Hit h = w_.rt_.hit_of(path.o, path.d, R.tfar[j], R.geom[j], R.prim[j], R.u[j], R.v[j], R.inst[j]);
        b_.alive[j] = est.scatter(path, h, &b_.shadows[j]);
    }
}

void GeneralWavefront::Batch::shadows()
{
    Rays &O = b_.occlusion, &S = b_.spheres;
    const size_t n = n_;
    size_t no = 0, ns = 0;
    size_t nw = 0;  // walking tests (the volumetric estimator's), piece by piece below
    for (size_t j = 0; j < n; ++j) {
        const ShadowTest &s = b_.shadows[j];
        if (!s.active) continue;
        if (s.walk) {
            b_.walking[nw++] = (uint32_t)j;
            continue;
        }
        Rays &R = s.sphere ? S : O;
        size_t &k = s.sphere ? ns : no;
        R.set(k, s.o, s.d, s.len);
        R.path[k++] = (uint32_t)j;
    }
    const Estimator &est = w_.estimator_;
    if (no) {
        RTCRayNp q = O.rays();
        rtcInitIntersectContext(&ctx_);
        rtcOccludedNp(w_.rt_.handle(), &ctx_, &q, (unsigned)no);
        for (size_t k = 0; k < no; ++k)
            if (!(O.tfar[k] < 0)) est.arrive(b_.paths[O.path[k]], b_.shadows[O.path[k]]);  // Embree sets tfar to -inf on a hit
    }
    if (ns) {
        RTCRayHitNp q = S.ray_hits();
        rtcInitIntersectContext(&ctx_);
        rtcIntersectNp(w_.rt_.handle(), &ctx_, &q, (unsigned)ns);
        for (size_t k = 0; k < ns; ++k) {
            uint32_t j = S.path[k];
            if (S.geom[k] == RTC_INVALID_GEOMETRY_ID || (int)w_.rt_.shape_of_hit(S.inst[k], S.geom[k]) == b_.shadows[j].shape)
                est.arrive(b_.paths[j], b_.shadows[j]);
        }
    }
    counts_->rays += no + ns;
    while (nw) {  // one closest-hit stream per piece: each test's first surface, then cross()
        Rays &W = b_.hits;  // (free: the bounce's hits are consumed)
        for (size_t k = 0; k < nw; ++k) {
            const ShadowTest &s = b_.shadows[b_.walking[k]];
            W.set(k, s.o, s.d, s.len);
        }
        RTCRayHitNp q = W.ray_hits();
        rtcInitIntersectContext(&ctx_);
        rtcIntersectNp(w_.rt_.handle(), &ctx_, &q, (unsigned)nw);
        counts_->rays += nw;
        size_t next = 0;
        for (size_t k = 0; k < nw; ++k) {
            uint32_t j = b_.walking[k];
            ShadowTest &s = b_.shadows[j];
            Hit h;
            bool hit = W.geom[k] != RTC_INVALID_GEOMETRY_ID;
            if (hit) {
                h = w_.rt_.hit_of(s.o, s.d, W.tfar[k], W.geom[k], W.prim[k], W.u[k], W.v[k], W.inst[k]);
                hit = !(s.sphere && (int)h.shape == s.shape);
            }
            Crossing c = est.cross(s, hit ? &h : nullptr);
            if (c == Crossing::Arrived) est.arrive(b_.paths[j], s);
            else if (c == Crossing::Onward) b_.walking[next++] = j;
        }
        nw = next;
    }
    size_t keep = 0;  // the paths that ended at this vertex retired, the others compacted
    for (size_t j = 0; j < n; ++j) {
        if (!b_.alive[j]) {
            finish(j);
            continue;
        }
        if (keep != j) b_.paths[keep] = b_.paths[j], b_.pixel[keep] = b_.pixel[j];
        ++keep;
    }
    n_ = keep;
}

void GeneralWavefront::render(const udm1_seq *seq, const udm1app::PixelOrder &order, int max_depth,
                              const udm1scene::CameraRays &camera, int x0, int x1, int y0, int y1, uint64_t first,
                              uint64_t count, const FilmResponse &film, Accumulator *acc, LoopCounts *counts) const
{
    Batch batch(*this, seq, order, max_depth, x0, x1, y0, y1, first, count, film, acc, counts);
    const uint64_t total = (uint64_t)(x1 - x0) * (uint64_t)(y1 - y0) * count;
    for (uint64_t start = 0; start < total; start += BATCH) {
        batch.camera(camera, start, (size_t)std::min<uint64_t>(BATCH, total - start));
        while (batch.live() > 0) {
            batch.trace();
            batch.shadows();
        }
    }
}

}  // namespace udm1pt
