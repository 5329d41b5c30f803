// bench_pt_wavefront.cpp - a feasibility measurement for udm1-pt's speed target (issue 6): how fast
// would a wavefront path loop trace udm1-pt's own estimator, with Embree streams and shading
// vectorized over paths in float? Measured side by side with udm1-pt's render of the same scene, spp
// and sampler, each with its RMSE against one reference, so that the speed is compared at equal error.
//
// A prototype, not a renderer: it models only what the Cornell box needs (triangles, untextured
// diffuse materials, triangle area lights sampled by area, no lens, no vertex normals) and refuses any
// other scene. Its estimator is udm1-pt's (pt/integrator.h): the same dimension layout and sampler
// points, next-event estimation with the power heuristic, cosine-weighted BSDF sampling, roulette from
// vertex 3; only the arithmetic differs (float, and the order of the paths' work), so its error per
// sample matches udm1-pt's within noise, which the report shows.
//
// Per tile of at most 8 x 8 pixels (all its samples at once, one path per lane): camera rays; then per bounce
// one stream of closest-hit queries (rtcIntersect1M), the sampler's six values per path (the library's
// cursor, one call per path), the shading loop over all live paths (vectorized: light sample, MIS,
// BSDF sample, roulette), one stream of shadow queries (rtcOccluded1M), compaction.
//
// Usage: udm1_bench_pt_wavefront [--size WxH] [--spp N] [--sampler S] [--randomize R] [--reps R]
//                                [--reference EXR]
// (--randomize none shows what the per-pixel randomization's hashing costs both renderers)
#include "../tools/common/image_read.h"
#include "builtin.h"
#include "embree_scene.h"
#include "integrator.h"
#include "material.h"
#include "scene.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

using namespace udm1scene;

namespace {

const float PI_F = 3.14159265358979323846f;
const int TILE = 8;

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// The scene as the prototype needs it, per triangle (Embree's geomID is the shape index).
struct Flat {
    std::vector<size_t> first;                // shape -> its first triangle's entry below
    std::vector<float> nx, ny, nz;            // unit geometric normal (triangle_normal)
    std::vector<float> rr, rg, rb;            // diffuse reflectance / pi
    std::vector<float> er, eg, eb;            // emitted radiance (0: not a light)
    std::vector<uint8_t> twosided;
    std::vector<float> area, prob;            // light triangles: area, choice probability
    std::vector<double> cdf;                  // the lights' power CDF, in udm1-pt's order (Lights)
    // per light, for the vectorized loop: vertices, normal, choice probability, area, radiance, two-sided
    std::vector<float> lx0, ly0, lz0, lx1, ly1, lz1, lx2, ly2, lz2, lnx, lny, lnz, lprob, larea, ler, leg, leb;
    std::vector<int> ltwo;
};

Flat flatten(const Scene &scene, const udm1pt::Materials &materials)
{
    Flat f;
    std::vector<Vec3> p0, p1, p2;  // per light: its vertices and triangle entry
    std::vector<size_t> tri;
    if (scene.camera.lens_radius > 0) throw std::runtime_error("the prototype has no thin lens");
    for (size_t k = 0; k < scene.shapes.size(); ++k) {
        const Shape &s = scene.shapes[k];
        if (s.kind != Shape::Triangles || !s.N.empty())
            throw std::runtime_error(s.where + ": the prototype takes triangle meshes without vertex normals only");
        Vec3 R;
        if (s.material >= 0) {
            const Material &m = scene.materials[s.material];
            const Param *refl = m.params.find("reflectance");
            if (m.type != "diffuse" || (refl && refl->type == "texture"))
                throw std::runtime_error(s.where + ": the prototype takes untextured diffuse materials only");
            Hit h;
            Vec3 ns(0, 0, 1);
            udm1pt::Bsdf scratch;
            R = materials.at(s.material, s, h, Vec3(0, 0, 1), &ns, &scratch).diffuse.R;
        } else {
            R = udm1pt::Bsdf().diffuse.R;
        }
        Vec3 L;
        bool two = false;
        if (s.light >= 0) L = scene.lights[s.light].L * scene.lights[s.light].scale, two = scene.lights[s.light].twosided;
        f.first.push_back(f.nx.size());
        for (unsigned t = 0; t < s.indices.size() / 3; ++t) {
            Vec3 n = triangle_normal(s, t);
            f.nx.push_back((float)n.x), f.ny.push_back((float)n.y), f.nz.push_back((float)n.z);
            f.rr.push_back((float)(R.x / M_PI)), f.rg.push_back((float)(R.y / M_PI)), f.rb.push_back((float)(R.z / M_PI));
            f.er.push_back((float)L.x), f.eg.push_back((float)L.y), f.eb.push_back((float)L.z);
            f.twosided.push_back(two);
            const uint32_t *i = &s.indices[3 * (size_t)t];
            auto P = [&](uint32_t v) { return Vec3(s.P[3 * v], s.P[3 * v + 1], s.P[3 * v + 2]); };
            double a = 0.5 * length(cross(P(i[1]) - P(i[0]), P(i[2]) - P(i[0])));
            f.area.push_back((float)a);
            f.prob.push_back(0);
            if (s.light >= 0) {
                p0.push_back(P(i[0])), p1.push_back(P(i[1])), p2.push_back(P(i[2]));
                tri.push_back(f.nx.size() - 1);
                double power = (0.2126 * L.x + 0.7152 * L.y + 0.0722 * L.z) * a * M_PI * (two ? 2 : 1);
                f.cdf.push_back((f.cdf.empty() ? 0 : f.cdf.back()) + std::max(0.0, power));
            }
        }
    }
    if (f.cdf.empty() || !(f.cdf.back() > 0)) throw std::runtime_error("the prototype needs an area light");
    for (size_t l = 0; l < tri.size(); ++l) {
        size_t t = tri[l];
        f.prob[t] = (float)((f.cdf[l] - (l ? f.cdf[l - 1] : 0)) / f.cdf.back());
        f.lx0.push_back((float)p0[l].x), f.ly0.push_back((float)p0[l].y), f.lz0.push_back((float)p0[l].z);
        f.lx1.push_back((float)p1[l].x), f.ly1.push_back((float)p1[l].y), f.lz1.push_back((float)p1[l].z);
        f.lx2.push_back((float)p2[l].x), f.ly2.push_back((float)p2[l].y), f.lz2.push_back((float)p2[l].z);
        f.lnx.push_back(f.nx[t]), f.lny.push_back(f.ny[t]), f.lnz.push_back(f.nz[t]);
        f.lprob.push_back(f.prob[t]), f.larea.push_back(f.area[t]);
        f.ler.push_back(f.er[t]), f.leg.push_back(f.eg[t]), f.leb.push_back(f.eb[t]), f.ltwo.push_back(f.twosided[t]);
    }
    return f;
}

// The live paths of one tile, structure of arrays.
struct Paths {
    std::vector<float> ox, oy, oz, dx, dy, dz, br, bg, bb, lr, lg, lb, pb, qx, qy, qz;
    std::vector<int> pixel;
    std::vector<udm1_cursor> cursor;
    void resize(size_t n)
    {
        for (auto *v : floats()) v->resize(n);
        pixel.resize(n), cursor.resize(n);
    }
    void move(size_t to, size_t from)  // compaction: path `from` into slot `to`
    {
        for (auto *v : floats()) (*v)[to] = (*v)[from];
        pixel[to] = pixel[from], cursor[to] = cursor[from];
    }

private:
    std::array<std::vector<float> *, 16> floats()
    {
        return {&ox, &oy, &oz, &dx, &dy, &dz, &br, &bg, &bb, &lr, &lg, &lb, &pb, &qx, &qy, &qz};
    }
};

// What the shading loop needs of each live path's hit, and what it hands the shadow stream.
struct Work {
    std::vector<float> px, py, pz, nx, ny, nz, t, u[6];  // hit point, geometric normal, distance, sampler values
    std::vector<float> ra, ga, ba;                        // reflectance / pi at the hit
    std::vector<int> light;                               // the light chosen for next-event estimation
    std::vector<float> sx, sy, sz, sdx, sdy, sdz, slen, cr, cg, cb;  // shadow ray and its contribution
    std::vector<uint8_t> alive;
    void resize(size_t n)
    {
        for (auto *v : {&px, &py, &pz, &nx, &ny, &nz, &t, &u[0], &u[1], &u[2], &u[3], &u[4], &u[5], &ra, &ga, &ba, &sx,
                        &sy, &sz, &sdx, &sdy, &sdz, &slen, &cr, &cg, &cb})
            v->resize(n);
        light.resize(n), alive.resize(n);
    }
};

inline float offset_of(float x, float y, float z, float t)
{
    return std::max(std::max(std::max(std::fabs(x), std::fabs(y)), std::max(std::fabs(z), std::fabs(t))), 0x1p-24f) *
           0x1p-18f;
}

// sin and cos of 2 pi u (udm1scene::sincos_2pi in float: quadrant, then series around pi/4)
inline void sincos2pi_f(float u, float *s, float *c)
{
    float q4 = 4.0f * u;
    int q = (int)q4;
    float x = (q4 - (float)q - 0.5f) * 1.57079632679489661923f, x2 = x * x;
    float sn = x * (1 + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040))));
    float cs = 1 + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320))));
    float si = 0.70710678f * (sn + cs), co = 0.70710678f * (cs - sn);
    bool odd = q & 1, neg_s = q >= 2, neg_c = q == 1 || q == 2;
    float s0 = odd ? co : si, c0 = odd ? si : co;
    *s = neg_s ? -s0 : s0;
    *c = neg_c ? -c0 : c0;
}

// The vectorized part: for live paths [0, n), next-event estimation (a shadow ray and its would-be
// contribution), the BSDF sample, throughput, roulette and the next ray. alive[j] = 0 ends path j.
__attribute__((target_clones("avx2", "default"))) void shade(size_t n, Paths &P, Work &W, const Flat &F, int depth)
{
    // plain pointers, so that the compiler sees the arrays do not alias (the vectors' own fields would)
    float *__restrict ox = P.ox.data(), *__restrict oy = P.oy.data(), *__restrict oz = P.oz.data();
    float *__restrict dxs = P.dx.data(), *__restrict dys = P.dy.data(), *__restrict dzs = P.dz.data();
    float *__restrict br = P.br.data(), *__restrict bg = P.bg.data(), *__restrict bbs = P.bb.data();
    float *__restrict pbs = P.pb.data(), *__restrict qxs = P.qx.data(), *__restrict qys = P.qy.data();
    float *__restrict qzs = P.qz.data();
    const float *__restrict hpx = W.px.data(), *__restrict hpy = W.py.data(), *__restrict hpz = W.pz.data();
    const float *__restrict hnx = W.nx.data(), *__restrict hny = W.ny.data(), *__restrict hnz = W.nz.data();
    const float *__restrict ht = W.t.data(), *__restrict u0 = W.u[0].data(), *__restrict u1 = W.u[1].data();
    const float *__restrict u3 = W.u[3].data(), *__restrict u4 = W.u[4].data(), *__restrict u5 = W.u[5].data();
    const float *__restrict ra = W.ra.data(), *__restrict ga = W.ga.data(), *__restrict ba = W.ba.data();
    const int *__restrict light = W.light.data();
    float *__restrict sxs = W.sx.data(), *__restrict sys = W.sy.data(), *__restrict szs = W.sz.data();
    float *__restrict sdx = W.sdx.data(), *__restrict sdy = W.sdy.data(), *__restrict sdz = W.sdz.data();
    float *__restrict slen = W.slen.data(), *__restrict cr = W.cr.data(), *__restrict cg = W.cg.data();
    float *__restrict cb = W.cb.data();
    uint8_t *__restrict alive = W.alive.data();
    const float *__restrict lx0 = F.lx0.data(), *__restrict ly0 = F.ly0.data(), *__restrict lz0 = F.lz0.data();
    const float *__restrict lx1 = F.lx1.data(), *__restrict ly1 = F.ly1.data(), *__restrict lz1 = F.lz1.data();
    const float *__restrict lx2 = F.lx2.data(), *__restrict ly2 = F.ly2.data(), *__restrict lz2 = F.lz2.data();
    const float *__restrict lnxs = F.lnx.data(), *__restrict lnys = F.lny.data(), *__restrict lnzs = F.lnz.data();
    const float *__restrict lprob = F.lprob.data(), *__restrict larea = F.larea.data();
    const float *__restrict ler = F.ler.data(), *__restrict leg = F.leg.data(), *__restrict leb = F.leb.data();
    const int *__restrict ltwo = F.ltwo.data();
#pragma omp simd
    for (size_t j = 0; j < n; ++j) {
        float px = hpx[j], py = hpy[j], pz = hpz[j], nx = hnx[j], ny = hny[j], nz = hnz[j];
        float wox = -dxs[j], woy = -dys[j], woz = -dzs[j];
        float cos_o = nx * wox + ny * woy + nz * woz;
        // next-event estimation, by area on the chosen light triangle
        int l = light[j];
        float su = std::sqrt(u0[j]), b0 = 1 - su, b1 = u1[j] * su, b2 = 1 - b0 - b1;
        float qx = lx0[l] * b0 + lx1[l] * b1 + lx2[l] * b2;
        float qy = ly0[l] * b0 + ly1[l] * b1 + ly2[l] * b2;
        float qz = lz0[l] * b0 + lz1[l] * b1 + lz2[l] * b2;
        float ex = qx - px, ey = qy - py, ez = qz - pz, d2 = ex * ex + ey * ey + ez * ez, dist = std::sqrt(d2);
        float wx = ex / dist, wy = ey / dist, wz = ez / dist;
        float cl = lnxs[l] * wx + lnys[l] * wy + lnzs[l] * wz;  // the light's normal against the direction to it
        bool emits = (ltwo[l] != 0) | (cl < 0);
        float pdf_l = lprob[l] * d2 / (std::fabs(cl) * larea[l]);
        float cos_i = nx * wx + ny * wy + nz * wz;
        bool same = cos_i * cos_o > 0;  // (bitwise & and | below: no branches in the loop)
        float pdf_b = std::fabs(cos_i) * (1 / PI_F);
        float w = pdf_l * pdf_l / (pdf_l * pdf_l + pdf_b * pdf_b);
        float k = same & emits & (d2 > 0) & (pdf_l > 0) & (pdf_l < 3e38f) ? std::fabs(cos_i) * w / pdf_l : 0;
        cr[j] = br[j] * ra[j] * ler[l] * k;
        cg[j] = bg[j] * ga[j] * leg[l] * k;
        cb[j] = bbs[j] * ba[j] * leb[l] * k;
        float side = cos_i > 0 ? 1.0f : -1.0f, off = offset_of(px, py, pz, ht[j]);
        float sx = px + side * nx * off, sy = py + side * ny * off, sz = pz + side * nz * off;
        float gx = qx - sx, gy = qy - sy, gz = qz - sz;
        sxs[j] = sx, sys[j] = sy, szs[j] = sz, sdx[j] = wx, sdy[j] = wy, sdz[j] = wz;
        slen[j] = std::sqrt(gx * gx + gy * gy + gz * gz) - 2 * offset_of(qx, qy, qz, 0);
        // the BSDF sample: cosine-weighted on the side of wo, in the frame of the normal (Duff et al.)
        float sgn = nz >= 0 ? 1.0f : -1.0f, aa = -1 / (sgn + nz), bb = nx * ny * aa;
        float tx = 1 + sgn * nx * nx * aa, ty = sgn * bb, tz = -sgn * nx;
        float bx = bb, by = sgn + ny * ny * aa, bz = -ny;
        float r = std::sqrt(u4[j]), sp, cp;
        sincos2pi_f(u5[j], &sp, &cp);
        float lz = std::sqrt(std::max(0.0f, 1 - u4[j]));
        lz = cos_o < 0 ? -lz : lz;
        float lx = r * cp, ly = r * sp;
        float dx = tx * lx + bx * ly + nx * lz, dy = ty * lx + by * ly + ny * lz, dz = tz * lx + bz * ly + nz * lz;
        float inv = 1 / std::sqrt(dx * dx + dy * dy + dz * dz);
        dx *= inv, dy *= inv, dz *= inv;
        float beta_r = br[j] * ra[j] * PI_F, beta_g = bg[j] * ga[j] * PI_F, beta_b = bbs[j] * ba[j] * PI_F;
        float m = std::max(beta_r, std::max(beta_g, beta_b));
        bool live = (cos_o != 0) & (std::fabs(lz) > 0) & (m > 0);
        bool roulette = (depth >= 3) & (m < 1);
        float q = 1 - m, s = roulette ? 1 / (1 - q) : 1.0f;
        live = live & !(roulette & (u3[j] < q));
        beta_r *= s, beta_g *= s, beta_b *= s;
        br[j] = beta_r, bg[j] = beta_g, bbs[j] = beta_b;
        pbs[j] = std::fabs(lz) * (1 / PI_F);
        float side2 = nx * dx + ny * dy + nz * dz > 0 ? 1.0f : -1.0f;
        ox[j] = px + side2 * nx * off, oy[j] = py + side2 * ny * off, oz[j] = pz + side2 * nz * off;
        dxs[j] = dx, dys[j] = dy, dzs[j] = dz;
        qxs[j] = px, qys[j] = py, qzs[j] = pz;
        alive[j] = live;
    }
}

struct Result {
    double seconds = 0;
    std::vector<double> image;  // RGB per pixel, the mean over the samples
    uint64_t rays = 0;
};

Result render_wavefront(const Scene &scene, const EmbreeScene &rt, const Flat &F, udm1_seq *seq, int W, int H,
                        uint32_t spp, int max_depth)
{
    Scene view = scene;
    view.width = W, view.height = H;
    const CameraRays camera(view);
    Result res;
    res.image.assign((size_t)W * H * 3, 0.0);
    std::atomic<uint64_t> rays{0};
    double t0 = now();
    tbb::parallel_for(tbb::blocked_range2d<int>(0, H, TILE, 0, W, TILE), [&](const tbb::blocked_range2d<int> &r) {
        size_t npix = (size_t)r.rows().size() * r.cols().size(), n = npix * spp;
        // one set of buffers per thread, reused from tile to tile (no page faults per tile)
        thread_local Paths P;
        thread_local Work Wk;
        thread_local std::vector<double> acc;
        thread_local std::vector<RTCRayHit> rh;
        thread_local std::vector<RTCRay> sh;
        thread_local std::vector<int> shadow_of;
        if (P.ox.size() < n) P.resize(n), Wk.resize(n), rh.resize(n), sh.resize(n), shadow_of.resize(n);
        acc.assign(npix * 3, 0.0);
        size_t k = 0;
        for (int y = r.rows().begin(); y < r.rows().end(); ++y)
            for (int x = r.cols().begin(); x < r.cols().end(); ++x)
                for (uint32_t i = 0; i < spp; ++i, ++k) {
                    udm1_cursor_start(&P.cursor[k], seq, ((uint64_t)y << 32) | (uint32_t)x, i, 0);
                    double uv[2];
                    udm1_cursor_fill_f64(&P.cursor[k], 2, uv);
                    Vec3 o, d;
                    camera.ray(x + uv[0], y + uv[1], &o, &d);
                    P.ox[k] = (float)o.x, P.oy[k] = (float)o.y, P.oz[k] = (float)o.z;
                    P.dx[k] = (float)d.x, P.dy[k] = (float)d.y, P.dz[k] = (float)d.z;
                    P.br[k] = P.bg[k] = P.bb[k] = 1, P.lr[k] = P.lg[k] = P.lb[k] = 0;
                    P.pixel[k] = (int)(k / spp);
                }
        uint64_t local_rays = 0;
        RTCIntersectContext ctx;
        for (int depth = 0; n > 0; ++depth) {
            for (size_t j = 0; j < n; ++j) {
                RTCRayHit &q = rh[j];
                q.ray = RTCRay{P.ox[j], P.oy[j], P.oz[j], 0.0f, P.dx[j], P.dy[j], P.dz[j], 0, INFINITY, 0xFFFFFFFF, (unsigned)j, 0};
                q.hit.geomID = RTC_INVALID_GEOMETRY_ID, q.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcInitIntersectContext(&ctx);
            rtcIntersect1M(rt.handle(), &ctx, rh.data(), (unsigned)n, sizeof(RTCRayHit));
            local_rays += n;
            // hits: emission (MIS against the BSDF sample that found it), then the paths that go on
            size_t m = 0;
            for (size_t j = 0; j < n; ++j) {
                const RTCRayHit &q = rh[j];
                if (q.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
                    int px = P.pixel[j];
                    acc[3 * px] += P.lr[j], acc[3 * px + 1] += P.lg[j], acc[3 * px + 2] += P.lb[j];
                    continue;
                }
                size_t tri = F.first[q.hit.geomID] + q.hit.primID;
                float t = q.ray.tfar, hx = P.ox[j] + P.dx[j] * t, hy = P.oy[j] + P.dy[j] * t, hz = P.oz[j] + P.dz[j] * t;
                float nx = F.nx[tri], ny = F.ny[tri], nz = F.nz[tri];
                if (F.er[tri] > 0 || F.eg[tri] > 0 || F.eb[tri] > 0) {
                    float cosw = -(nx * P.dx[j] + ny * P.dy[j] + nz * P.dz[j]);
                    if (F.twosided[tri] || cosw > 0) {
                        float w = 1;
                        if (depth > 0) {
                            float ex = hx - P.qx[j], ey = hy - P.qy[j], ez = hz - P.qz[j], d2 = ex * ex + ey * ey + ez * ez;
                            float pl = F.prob[tri] * d2 / (std::fabs(cosw) * F.area[tri]);  // Lights::pdf
                            w = P.pb[j] * P.pb[j] / (P.pb[j] * P.pb[j] + pl * pl);
                        }
                        P.lr[j] += P.br[j] * F.er[tri] * w, P.lg[j] += P.bg[j] * F.eg[tri] * w, P.lb[j] += P.bb[j] * F.eb[tri] * w;
                    }
                }
                if (depth == max_depth) {
                    int px = P.pixel[j];
                    acc[3 * px] += P.lr[j], acc[3 * px + 1] += P.lg[j], acc[3 * px + 2] += P.lb[j];
                    continue;
                }
                // compact into slot m (m <= j): the path's state and this hit
                if (m != j) P.move(m, j);
                Wk.px[m] = hx, Wk.py[m] = hy, Wk.pz[m] = hz, Wk.nx[m] = nx, Wk.ny[m] = ny, Wk.nz[m] = nz, Wk.t[m] = t;
                Wk.ra[m] = F.rr[tri], Wk.ga[m] = F.rg[tri], Wk.ba[m] = F.rb[tri];
                double u[6];
                udm1_cursor_fill_f64(&P.cursor[m], 6, u);
                for (int d = 0; d < 6; ++d) Wk.u[d][m] = (float)u[d];
                // the light, by power with sample reuse (Lights::sample)
                double target = u[0] * F.cdf.back();
                size_t l = std::upper_bound(F.cdf.begin(), F.cdf.end(), target) - F.cdf.begin();
                if (l >= F.cdf.size()) l = F.cdf.size() - 1;
                double lo = l ? F.cdf[l - 1] : 0.0;
                Wk.u[0][m] = (float)std::min((target - lo) / (F.cdf[l] - lo), 0x1.fffffffffffffp-1);
                Wk.light[m] = (int)l;
                ++m;
            }
            n = m;
            shade(n, P, Wk, F, depth);
            // shadow rays of the paths whose light sample contributes
            size_t ns = 0;
            for (size_t j = 0; j < n; ++j)
                if ((Wk.cr[j] > 0 || Wk.cg[j] > 0 || Wk.cb[j] > 0) && Wk.slen[j] > 0) {
                    sh[ns] = RTCRay{Wk.sx[j], Wk.sy[j], Wk.sz[j], 0.0f, Wk.sdx[j], Wk.sdy[j], Wk.sdz[j], 0, Wk.slen[j],
                                    0xFFFFFFFF, (unsigned)ns, 0};
                    shadow_of[ns++] = (int)j;
                }
            rtcInitIntersectContext(&ctx);
            rtcOccluded1M(rt.handle(), &ctx, sh.data(), (unsigned)ns, sizeof(RTCRay));
            local_rays += ns;
            for (size_t s = 0; s < ns; ++s)
                if (sh[s].tfar >= 0) {
                    int j = shadow_of[s];
                    P.lr[j] += Wk.cr[j], P.lg[j] += Wk.cg[j], P.lb[j] += Wk.cb[j];
                }
            // paths that ended at this vertex
            size_t keep = 0;
            for (size_t j = 0; j < n; ++j) {
                if (!Wk.alive[j]) {
                    int px = P.pixel[j];
                    acc[3 * px] += P.lr[j], acc[3 * px + 1] += P.lg[j], acc[3 * px + 2] += P.lb[j];
                    continue;
                }
                if (keep != j) P.move(keep, j);
                ++keep;
            }
            n = keep;
        }
        size_t p = 0;
        for (int y = r.rows().begin(); y < r.rows().end(); ++y)
            for (int x = r.cols().begin(); x < r.cols().end(); ++x, ++p)
                for (int c = 0; c < 3; ++c) res.image[3 * ((size_t)y * W + x) + c] = acc[3 * p + c] / spp;
        rays += local_rays;
    });
    res.seconds = now() - t0;
    res.rays = rays;
    return res;
}

// An image as the project's comparison takes it (udm1-pt compare: linear RGB clamped to [0, 1]).
udm1app::LoadedImage as_image(const std::vector<double> &rgb, int W, int H)
{
    udm1app::LoadedImage im;
    im.width = W, im.height = H, im.channels = 3;
    im.pixels.assign(rgb.begin(), rgb.end());
    return im;
}

double rmse(const udm1app::LoadedImage &a, const udm1app::LoadedImage &ref)
{
    return udm1app::compare(a, ref, true, nullptr).rmse;
}

}  // namespace

int main(int argc, char **argv)
{
    int W = 128, H = 128, reps = 3;
    uint32_t spp = 64;
    std::string sampler = "sobol", reference;
    uint32_t randomize = UDM1_RANDOMIZE_DEFAULT;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        bool ok = i + 1 < argc;
        if (ok && a == "--size") ok = std::sscanf(argv[++i], "%dx%d", &W, &H) == 2 && W >= 8 && H >= 8 && W <= 4096 && H <= 4096;
        else if (ok && a == "--spp") spp = (uint32_t)std::atoi(argv[++i]), ok = spp >= 1 && spp <= 4096;
        else if (ok && a == "--sampler") sampler = argv[++i];
        else if (ok && a == "--reps") reps = std::atoi(argv[++i]), ok = reps >= 1 && reps <= 100;
        else if (ok && a == "--reference") reference = argv[++i];
        else if (ok && a == "--randomize") {
            std::string v = argv[++i];
            ok = v == "none" || v == "default";
            randomize = v == "none" ? UDM1_RANDOMIZE_NONE : UDM1_RANDOMIZE_DEFAULT;
        }
        else ok = false;
        if (!ok) {
            std::fprintf(stderr, "usage: udm1_bench_pt_wavefront [--size WxH (8..4096)] [--spp 1..4096] [--sampler S] "
                                 "[--randomize none|default] [--reps 1..100] [--reference EXR]\n");
            return 2;
        }
    }
    try {
        Scene scene = load_scene("builtin:cornell");
        EmbreeScene rt(scene);
        udm1pt::Materials materials(scene);
        Flat F = flatten(scene, materials);
        for (unsigned k = 0; k < scene.shapes.size(); ++k)  // Embree numbered the shapes' geometries in order
            if (!rtcGetGeometry(rt.handle(), k)) throw std::runtime_error("Embree's geometry ids are not the shapes'");
        udm1pt::Options o;
        o.sampler = sampler, o.spp = spp, o.width = W, o.height = H, o.randomize = randomize;
        int max_depth = scene.max_depth;
        udm1pt::Sequence seq = udm1pt::make_sequence(o, 2 + 6 * (uint32_t)max_depth);  // udm1-pt's own
        udm1app::LoadedImage ref;
        if (!reference.empty()) {
            ref = udm1app::read_image(reference);
            if (ref.width != W || ref.height != H || ref.channels < 3)
                throw std::runtime_error("--reference '" + reference + "': not a " + std::to_string(W) + "x" +
                                         std::to_string(H) + " RGB image");
        }
        double best_pt = 1e300, best_wf = 1e300;
        std::vector<double> pt_image((size_t)W * H * 3);
        Result wf;
        udm1pt::Stats st;
        for (int r = 0; r < reps + 1; ++r) {  // round 0 warms up
            double t0 = now();
            udm1pt::Accumulator acc = udm1pt::render(scene, rt, materials, o, &st);
            double t1 = now();
            wf = render_wavefront(scene, rt, F, seq.get(), W, H, spp, max_depth);
            if (r == 0) {
                for (size_t p = 0; p < (size_t)W * H * 3; ++p)
                    pt_image[p] = (double)acc.sum[p] / udm1pt::SAMPLE_SCALE / spp * scene.film_scale;
                continue;
            }
            best_pt = std::min(best_pt, t1 - t0);
            best_wf = std::min(best_wf, wf.seconds);
        }
        auto mean = [](const std::vector<double> &im, int c) {
            double s = 0;
            for (size_t p = c; p < im.size(); p += 3) s += im[p];
            return s / (double)(im.size() / 3);
        };
        std::printf("udm1_bench_pt_wavefront: builtin:cornell, %dx%d, %u spp, sampler %s, randomization %s, best of %d "
                    "alternating rounds\n", W, H, spp, sampler.c_str(), randomize == UDM1_RANDOMIZE_NONE ? "none" : "default", reps);
        std::printf("%-44s %9s %10s %10s %28s %10s\n", "renderer", "seconds", "rays", "ratio", "mean RGB", "RMSE");
        auto row = [&](const char *name, double secs, uint64_t nrays, const std::vector<double> &im) {
            std::string e = ref.pixels.empty() ? "n/a" : std::to_string(rmse(as_image(im, W, H), ref));
            std::printf("%-44s %9.4f %10llu %10.2f %9.5f %9.5f %9.5f %10s\n", name, secs, (unsigned long long)nrays,
                        best_pt / secs, mean(im, 0), mean(im, 1), mean(im, 2), e.c_str());
        };
        row("udm1-pt render (anchor)", best_pt, st.rays, pt_image);
        row("wavefront prototype (streams, float SIMD)", best_wf, wf.rays, wf.image);
        // the same estimator on the same sampler points: the images differ by float rounding only
        std::printf("\nthe two images differ by RMSE %.3g; the prototype takes %.3f of udm1-pt's time\n",
                    rmse(as_image(wf.image, W, H), as_image(pt_image, W, H)), best_wf / best_pt);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "udm1_bench_pt_wavefront: %s\n", e.what());
        return 1;
    }
    return 0;
}
