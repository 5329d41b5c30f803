// wavefront_diffuse.cpp - see wavefront_diffuse.h.
#include "wavefront_diffuse.h"

#include "media.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace udm1pt {

using udm1scene::Hit;
using udm1scene::Scene;
using udm1scene::Shape;

std::string diffuse_wavefront_unsupported(const Scene &scene, const Options &opt)
{
    if (opt.strategy != Strategy::Mis) return "only MIS (--strategy mis) has a wavefront loop";
    if (scene.camera.lens_radius > 0) return "the camera has a thin lens";
    if (uses_media(scene)) return "participating media";
    if (!scene.instances.empty()) return scene.instances[0].where + ": an object instance";
    bool light = false;
    for (const Shape &s : scene.shapes) {
        if (s.kind != Shape::Triangles) return s.where + ": a shape that is not a triangle mesh";
        if (!s.N.empty()) return s.where + ": vertex normals";
        if (s.has_alpha()) return s.where + ": an alpha cut-out";
        light = light || s.light >= 0;
        if (s.material < 0) continue;
        const udm1scene::Material &m = scene.materials[s.material];
        if (m.type != "diffuse") return s.where + ": a " + m.type + " material";
        if (m.params.find("displacement")) return s.where + ": a bump map";
        if (m.params.find("normalmap")) return s.where + ": a normal map";
        const udm1scene::Param *refl = m.params.find("reflectance");
        if (refl && refl->type == "texture") return s.where + ": a textured reflectance";
    }
    if (!light) return "no area light";
    if (!scene.light_sources.empty()) return scene.light_sources[0].where + ": a LightSource";
    return "";
}

namespace {

const float PI_F = 3.14159265358979323846f;
const size_t BATCH = 4096;  // paths traced together (a tile's worth at 64 spp)
const int DIMS_PER_VERTEX = 6;

// [0, 1) in double to [0, 1) in float (rounding to nearest could give 1)
inline float unit_float(double u) { return std::min((float)u, 0x1.fffffep-1f); }

// udm1scene::ray_offset in float
inline float offset_of(float x, float y, float z, float t)
{
    return std::max(std::max(std::max(std::fabs(x), std::fabs(y)), std::max(std::fabs(z), std::fabs(t))), 0x1p-24f) *
           0x1p-18f;
}

// udm1scene::sincos_2pi in float (quadrant, then series around pi/4)
inline void sincos_2pi_f(float u, float *s, float *c)
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

// The live paths of a batch, structure of arrays: ray, throughput, radiance so far, the BSDF
// sample's density and the vertex it left (for MIS at the light it may hit; its normal only where the
// light choice depends on the point: `normals`), pixel (in the tile), and the sample index.
struct Paths {
    std::vector<float> ox, oy, oz, dx, dy, dz, br, bg, bb, lr, lg, lb, pb, qx, qy, qz, qnx, qny, qnz;
    std::vector<int> pixel;
    std::vector<uint64_t> index;
    bool normals = true;
    void resize(size_t n)
    {
        for (auto *v : floats()) v->resize(n);
        qnx.resize(n), qny.resize(n), qnz.resize(n), pixel.resize(n), index.resize(n);
    }
    void move(size_t to, size_t from)  // compaction: path `from` into slot `to`
    {
        for (auto *v : floats()) (*v)[to] = (*v)[from];
        if (normals) qnx[to] = qnx[from], qny[to] = qny[from], qnz[to] = qnz[from];
        pixel[to] = pixel[from], index[to] = index[from];
    }

private:
    std::array<std::vector<float> *, 16> floats()
    {
        return {&ox, &oy, &oz, &dx, &dy, &dz, &br, &bg, &bb, &lr, &lg, &lb, &pb, &qx, &qy, &qz};
    }
};

// What the shading loop reads of each live path's vertex, and what it writes for the shadow stream.
struct Vertices {
    std::vector<float> px, py, pz, nx, ny, nz, t, u[DIMS_PER_VERTEX];  // hit, geometric normal, distance, sampler
    std::vector<float> ra, ga, ba;                                     // reflectance / pi at the hit
    std::vector<int> light;                                            // the light chosen for NEE
    std::vector<float> prob;                                           // the probability of that choice (0: none)
    std::vector<float> sx, sy, sz, sdx, sdy, sdz, slen, cr, cg, cb;    // shadow ray and its contribution
    std::vector<uint8_t> alive, maybe_near;  // maybe_near: Lights::by_area decides
    void resize(size_t n)
    {
        for (auto *v : {&px, &py, &pz, &nx, &ny, &nz, &t, &u[0], &u[1], &u[2], &u[3], &u[4], &u[5], &ra, &ga, &ba, &sx,
                        &sy, &sz, &sdx, &sdy, &sdz, &slen, &cr, &cg, &cb})
            v->resize(n);
        light.resize(n), prob.resize(n), alive.resize(n), maybe_near.resize(n);
    }
};

// Next-event estimation done in double by Lights (a light sampled by solid angle): it replaces what
// the vectorized loop computed for path j.
struct NearSample {
    size_t j;
    float sx, sy, sz, dx, dy, dz, len, cr, cg, cb;
};

// What Embree's SOA stream needs beside the rays' origins and directions: constant inputs (tnear, time,
// mask, id, flags), tfar, and the hit.
struct Stream {
    std::vector<float> tnear, time, tfar, ngx, ngy, ngz, u, v;
    std::vector<unsigned> mask, id, flags, prim, geom, inst;
    void resize(size_t n)
    {
        tnear.assign(n, 0.0f), time.assign(n, 0.0f), tfar.resize(n), ngx.resize(n), ngy.resize(n), ngz.resize(n);
        u.resize(n), v.resize(n), mask.assign(n, 0xFFFFFFFFu), id.resize(n), flags.assign(n, 0), prim.resize(n);
        geom.resize(n), inst.resize(n);
        for (size_t i = 0; i < n; ++i) id[i] = (unsigned)i;
    }
};

struct Buffers {
    Paths paths;
    Vertices vertices;
    Stream hits;  // the streams' other arrays (origins, directions: the paths' and the vertices')
    std::vector<NearSample> near;
    std::vector<double> u;  // sampler values, DIMS_PER_VERTEX per path
};

struct Shading {
    int depth, rr_depth;
    bool roulette;
};

// For live paths [0, n) with their DIMS_PER_VERTEX sampler values u, where the light choice does not
// depend on the point (LightChoice::fixed): the light each samples (Lights::choose's double operations,
// so the same light, rescaled u and probability), the values as floats, and whether the light may be
// near enough for solid-angle sampling (a test with a margin that never misses a near light:
// Lights::by_area then decides).
__attribute__((target_clones("avx2", "default"))) void choose_lights(size_t n, const double *__restrict u, Vertices &V,
                                                                     const DiffuseWavefront::LightChoice &C,
                                                                     const DiffuseWavefront::LightNear &N)
{
    float *__restrict f0 = V.u[0].data(), *__restrict f1 = V.u[1].data(), *__restrict f2 = V.u[2].data();
    float *__restrict f3 = V.u[3].data(), *__restrict f4 = V.u[4].data(), *__restrict f5 = V.u[5].data();
    float *__restrict prob = V.prob.data();
    const float *__restrict hpx = V.px.data(), *__restrict hpy = V.py.data(), *__restrict hpz = V.pz.data();
    int *__restrict light = V.light.data();
    uint8_t *__restrict maybe_near = V.maybe_near.data();
    const double *__restrict cdf = C.cdf.data(), *__restrict lo = C.lo.data(), *__restrict hi = C.hi.data();
    const float *__restrict lprob = C.prob.data();
    const int *__restrict pick = C.pick.data();
    const double *__restrict cx = N.cx.data(), *__restrict cy = N.cy.data(), *__restrict cz = N.cz.data();
    const double *__restrict area = N.area.data();
    const int count = (int)C.cdf.size(), first = (int)C.first;
    const double total = C.cdf.back(), near = N.near;
#pragma omp simd
    for (size_t j = 0; j < n; ++j) {
        const double *um = u + DIMS_PER_VERTEX * j;
        double target = um[0] * total;
        int i = 0;
        for (int c = 0; c < count; ++c) i += cdf[c] <= target;
        int k = pick[i], l = first + k;
        double r = std::min((target - lo[k]) / (hi[k] - lo[k]), 0x1.fffffffffffffp-1);
        f0[j] = unit_float(r >= 0 ? r : 0), f1[j] = unit_float(um[1]), f2[j] = unit_float(um[2]);
        f3[j] = unit_float(um[3]), f4[j] = unit_float(um[4]), f5[j] = unit_float(um[5]);
        light[j] = l, prob[j] = lprob[k];
        // Lights::far's test in double (as it), with a 1 % margin for its different rounding
        double dx = cx[l] - hpx[j], dy = cy[l] - hpy[j], dz = cz[l] - hpz[j];
        maybe_near[j] = area[l] >= 0.99 * near * (dx * dx + dy * dy + dz * dz);
    }
}

// The vectorized part: for live paths [0, n), next-event estimation by area (a shadow ray and its
// would-be contribution), the BSDF sample (cosine-weighted), throughput, roulette and the next ray.
// alive[j] = 0 ends path j. Every lane does the same float operations, whatever its neighbours.
__attribute__((target_clones("avx2", "default"))) void shade(size_t n, Paths &P, Vertices &V,
                                                             const DiffuseWavefront::LightArrays &F, Shading sh)
{
    // plain pointers, so that the compiler sees the arrays do not alias (the vectors' own fields would)
    float *__restrict ox = P.ox.data(), *__restrict oy = P.oy.data(), *__restrict oz = P.oz.data();
    float *__restrict dxs = P.dx.data(), *__restrict dys = P.dy.data(), *__restrict dzs = P.dz.data();
    float *__restrict br = P.br.data(), *__restrict bg = P.bg.data(), *__restrict bbs = P.bb.data();
    float *__restrict pbs = P.pb.data(), *__restrict qxs = P.qx.data(), *__restrict qys = P.qy.data();
    float *__restrict qzs = P.qz.data(), *__restrict qnxs = P.qnx.data(), *__restrict qnys = P.qny.data();
    float *__restrict qnzs = P.qnz.data();
    const float *__restrict hpx = V.px.data(), *__restrict hpy = V.py.data(), *__restrict hpz = V.pz.data();
    const float *__restrict hnx = V.nx.data(), *__restrict hny = V.ny.data(), *__restrict hnz = V.nz.data();
    const float *__restrict ht = V.t.data(), *__restrict u0 = V.u[0].data(), *__restrict u1 = V.u[1].data();
    const float *__restrict u3 = V.u[3].data(), *__restrict u4 = V.u[4].data(), *__restrict u5 = V.u[5].data();
    const float *__restrict ra = V.ra.data(), *__restrict ga = V.ga.data(), *__restrict ba = V.ba.data();
    const int *__restrict light = V.light.data();
    float *__restrict sxs = V.sx.data(), *__restrict sys = V.sy.data(), *__restrict szs = V.sz.data();
    float *__restrict sdx = V.sdx.data(), *__restrict sdy = V.sdy.data(), *__restrict sdz = V.sdz.data();
    float *__restrict slen = V.slen.data(), *__restrict cr = V.cr.data(), *__restrict cg = V.cg.data();
    float *__restrict cb = V.cb.data();
    uint8_t *__restrict alive = V.alive.data();
    const float *__restrict lx0 = F.x0.data(), *__restrict ly0 = F.y0.data(), *__restrict lz0 = F.z0.data();
    const float *__restrict lx1 = F.x1.data(), *__restrict ly1 = F.y1.data(), *__restrict lz1 = F.z1.data();
    const float *__restrict lx2 = F.x2.data(), *__restrict ly2 = F.y2.data(), *__restrict lz2 = F.z2.data();
    const float *__restrict lnxs = F.nx.data(), *__restrict lnys = F.ny.data(), *__restrict lnzs = F.nz.data();
    const float *__restrict lprob = V.prob.data(), *__restrict larea = F.area.data();
    const float *__restrict ler = F.er.data(), *__restrict leg = F.eg.data(), *__restrict leb = F.eb.data();
    const int *__restrict ltwo = F.twosided.data();
    const bool may_roulette = sh.roulette && sh.depth >= sh.rr_depth;
#pragma omp simd
    for (size_t j = 0; j < n; ++j) {
        float px = hpx[j], py = hpy[j], pz = hpz[j], nx = hnx[j], ny = hny[j], nz = hnz[j];
        float wox = -dxs[j], woy = -dys[j], woz = -dzs[j];
        float cos_o = nx * wox + ny * woy + nz * woz;
        // next-event estimation: a point on the chosen light triangle, by area (Lights::sample)
        int l = light[j];
        float su = std::sqrt(u0[j]), b0 = 1 - su, b1 = u1[j] * su, b2 = 1 - b0 - b1;
        float qx = lx0[l] * b0 + lx1[l] * b1 + lx2[l] * b2;
        float qy = ly0[l] * b0 + ly1[l] * b1 + ly2[l] * b2;
        float qz = lz0[l] * b0 + lz1[l] * b1 + lz2[l] * b2;
        float ex = qx - px, ey = qy - py, ez = qz - pz, d2 = ex * ex + ey * ey + ez * ez, dist = std::sqrt(d2);
        float wx = ex / dist, wy = ey / dist, wz = ez / dist;
        float cl = lnxs[l] * wx + lnys[l] * wy + lnzs[l] * wz;  // the light's normal against the direction to it
        bool emits = (ltwo[l] != 0) | (cl < 0);
        float pdf_l = lprob[j] * d2 / (std::fabs(cl) * larea[l]);
        float cos_i = nx * wx + ny * wy + nz * wz;
        bool same = cos_i * cos_o > 0;  // (bitwise & and | below: no branches in the loop)
        float pdf_b = std::fabs(cos_i) * (1 / PI_F);
        float w = pdf_l * pdf_l / (pdf_l * pdf_l + pdf_b * pdf_b);  // the power heuristic
        float k = same & emits & (d2 > 0) & (pdf_l > 0) & (pdf_l < 3e38f) ? std::fabs(cos_i) * w / pdf_l : 0;
        cr[j] = br[j] * ra[j] * ler[l] * k;
        cg[j] = bg[j] * ga[j] * leg[l] * k;
        cb[j] = bbs[j] * ba[j] * leb[l] * k;
        // the shadow ray: from p offset to the light's side to q offset to p's side of the light
        // (udm1scene::shadow_segment)
        float side = cos_i > 0 ? 1.0f : -1.0f, off = offset_of(px, py, pz, ht[j]);
        float sx = px + side * nx * off, sy = py + side * ny * off, sz = pz + side * nz * off;
        float lside = lnxs[l] * (sx - qx) + lnys[l] * (sy - qy) + lnzs[l] * (sz - qz) > 0 ? 1.0f : -1.0f;
        float qoff = lside * offset_of(qx, qy, qz, 0);
        float gx = qx + lnxs[l] * qoff - sx, gy = qy + lnys[l] * qoff - sy, gz = qz + lnzs[l] * qoff - sz;
        float glen = std::sqrt(gx * gx + gy * gy + gz * gz), ginv = glen > 0 ? 1 / glen : 0;
        sxs[j] = sx, sys[j] = sy, szs[j] = sz, sdx[j] = gx * ginv, sdy[j] = gy * ginv, sdz[j] = gz * ginv;
        slen[j] = glen;
        // the BSDF sample: cosine-weighted on the side of wo, in the normal's frame (udm1scene::Frame)
        float sgn = std::copysign(1.0f, nz), aa = -1 / (sgn + nz), bb = nx * ny * aa;
        float tx = 1 + sgn * nx * nx * aa, ty = sgn * bb, tz = -sgn * nx;
        float bx = bb, by = sgn + ny * ny * aa, bz = -ny;
        float r = std::sqrt(u4[j]), sp, cp;
        sincos_2pi_f(u5[j], &sp, &cp);
        float lz = std::sqrt(std::max(0.0f, 1 - u4[j]));
        lz = cos_o < 0 ? -lz : lz;
        float lx = r * cp, ly = r * sp;
        float dx = tx * lx + bx * ly + nx * lz, dy = ty * lx + by * ly + ny * lz, dz = tz * lx + bz * ly + nz * lz;
        float inv = 1 / std::sqrt(dx * dx + dy * dy + dz * dz);
        dx *= inv, dy *= inv, dz *= inv;
        // throughput: f cos / pdf = R for a diffuse surface
        float beta_r = br[j] * ra[j] * PI_F, beta_g = bg[j] * ga[j] * PI_F, beta_b = bbs[j] * ba[j] * PI_F;
        float m = std::max(beta_r, std::max(beta_g, beta_b));
        bool live = (cos_o != 0) & (std::fabs(lz) > 0) & (m > 0) & (m < 3e38f);
        bool rr = may_roulette & (m < 1);  // roulette where the throughput is below 1
        float q = 1 - m, s = rr ? 1 / (1 - q) : 1.0f;
        live = live & !(rr & (u3[j] < q));
        br[j] = beta_r * s, bg[j] = beta_g * s, bbs[j] = beta_b * s;
        pbs[j] = std::fabs(lz) * (1 / PI_F);
        float side2 = nx * dx + ny * dy + nz * dz > 0 ? 1.0f : -1.0f;
        ox[j] = px + side2 * nx * off, oy[j] = py + side2 * ny * off, oz[j] = pz + side2 * nz * off;
        dxs[j] = dx, dys[j] = dy, dzs[j] = dz;
        qxs[j] = px, qys[j] = py, qzs[j] = pz, qnxs[j] = nx, qnys[j] = ny, qnzs[j] = nz;
        alive[j] = live;
    }
}

}  // namespace

DiffuseWavefront::DiffuseWavefront(const Scene &scene, const udm1scene::EmbreeScene &rt, const Materials &materials,
                     const Lights &lights, int max_depth, bool roulette, int rr_depth)
    : scene_(scene), rt_(rt), lights_(lights), max_depth_(max_depth), rr_depth_(rr_depth), roulette_(roulette)
{
    Triangles &T = tri_;
    std::vector<size_t> first_of_shape;  // each shape's first triangle's entry
    for (size_t k = 0; k < scene.shapes.size(); ++k) {
        const Shape &s = scene.shapes[k];
        Vec3 R = default_material().diffuse.R;
        if (s.material >= 0) {
            Hit h;
            Vec3 ns(0, 0, 1);
            Bsdf scratch;
            R = materials.at(s.material, s, h, Vec3(0, 0, 1), &ns, &scratch).diffuse.R;
        }
        first_of_shape.push_back(T.nx.size());
        for (unsigned t = 0; t < s.indices.size() / 3; ++t) {
            Vec3 n = udm1scene::triangle_normal(s, t);
            T.nx.push_back((float)n.x), T.ny.push_back((float)n.y), T.nz.push_back((float)n.z);
            T.rr.push_back((float)(R.x / M_PI)), T.rg.push_back((float)(R.y / M_PI)), T.rb.push_back((float)(R.z / M_PI));
            Hit h;
            h.shape = (unsigned)k, h.prim = t;
            T.light.push_back(lights.light_of(h));
        }
    }
    for (unsigned g = 0; g < rt.geometry_count(); ++g) T.first.push_back(first_of_shape[rt.shape_of_geometry(g)]);
    LightNear &C = near_;
    for (size_t i = 0; i < lights.count(); ++i) {
        const Lights::Light &l = lights.light(i);
        C.cx.push_back(l.centroid.x), C.cy.push_back(l.centroid.y), C.cz.push_back(l.centroid.z);
        C.area.push_back(l.area);
    }
    C.near = lights.near();
    LightChoice &F = choice_;
    const std::vector<double> *cdf = nullptr;
    F.fixed = lights.fixed_choice(&F.first, &cdf);
    if (F.fixed) {
        F.cdf = *cdf;
        for (size_t k = 0; k < F.cdf.size(); ++k) {
            double lo = k ? F.cdf[k - 1] : 0.0;
            F.lo.push_back(lo), F.hi.push_back(F.cdf[k]), F.prob.push_back((float)((F.cdf[k] - lo) / F.cdf.back()));
        }
        for (size_t i = 0; i <= F.cdf.size(); ++i) {  // as Lights::choose: clamped, then past lights of no power
            size_t k = std::min(i, F.cdf.size() - 1);
            while (k > 0 && F.cdf[k] == F.cdf[k - 1]) --k;
            F.pick.push_back((int)k);
        }
    }
    LightArrays &L = lights_f_;
    for (size_t i = 0; i < lights.count(); ++i) {
        const Lights::Light &l = lights.light(i);
        L.x0.push_back((float)l.p0.x), L.y0.push_back((float)l.p0.y), L.z0.push_back((float)l.p0.z);
        L.x1.push_back((float)l.p1.x), L.y1.push_back((float)l.p1.y), L.z1.push_back((float)l.p1.z);
        L.x2.push_back((float)l.p2.x), L.y2.push_back((float)l.p2.y), L.z2.push_back((float)l.p2.z);
        L.nx.push_back((float)l.n.x), L.ny.push_back((float)l.n.y), L.nz.push_back((float)l.n.z);
        L.area.push_back((float)l.area);
        L.er.push_back((float)l.L.x), L.eg.push_back((float)l.L.y), L.eb.push_back((float)l.L.z);
        L.twosided.push_back(l.twosided);
    }
}

// One thread's batch of paths through the stages of a bounce. render() runs, per batch: camera(), then
// per vertex trace() (closest hits), gather() (emission; ended paths retired; the rest compacted),
// sample() (the sampler's values, the light choice, solid-angle light samples in double), shade_all()
// (the vectorized shading) and shadows() (occlusion, the light samples that arrive; ended paths retired).
class DiffuseWavefront::Batch {
public:
    Batch(const DiffuseWavefront &w, const udm1_seq *seq, const udm1app::PixelOrder &order, int x0, int x1, int y0,
          int y1, uint64_t first, uint64_t count, const FilmResponse &film, Accumulator *acc, LoopCounts *counts)
        : w_(w), order_(order), x0_(x0), y0_(y0), W_(x1 - x0), first_(first), count_(count),
          film_(film), acc_(acc), counts_(counts), b_(buffers())
    {
        b_.paths.normals = !w.choice_.fixed;
        // the tile's pixels' streams, once: every path's domains draw from its pixel's (integrator.h)
        streams_.resize((size_t)W_ * (size_t)(y1 - y0));
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
                udm1_stream_init(&streams_[(size_t)(y - y0) * W_ + (x - x0)], seq, order.stream(x, y), 0,
                                 stream_dims(w.max_depth_));
    }
    // The camera rays of paths [start, start + n) of the tile (path k: pixel k / count, sample
    // first + k % count); n of them are now live.
    void camera(const udm1scene::CameraRays &camera, uint64_t start, size_t n);
    // Closest hits of the n live paths.
    void trace(int depth);
    // Emission found by the hits (MIS against the BSDF sample that found it); paths that left the scene
    // or reached the maximum depth retired, the others compacted with their vertex.
    void gather(int depth);
    // This vertex's sampler values, light choice and near-light samples.
    void sample(int depth);
    // Light sample, BSDF sample, roulette and the next ray (vectorized), then the near-light samples in.
    void shade_all(int depth);
    // The shadow rays; the light samples that arrive added, ended paths retired, the rest compacted.
    void shadows();
    size_t live() const { return n_; }

private:
    static Buffers &buffers()  // one set per thread, reused from batch to batch
    {
        thread_local Buffers b;
        if (b.paths.ox.size() < BATCH) {
            b.paths.resize(BATCH), b.vertices.resize(BATCH), b.hits.resize(BATCH);
            b.u.resize(BATCH * DIMS_PER_VERTEX);
        }
        return b;
    }
    void finish(size_t j);

    const DiffuseWavefront &w_;
    const udm1app::PixelOrder &order_;
    int x0_, y0_, W_;
    uint64_t first_, count_;
    const FilmResponse &film_;
    Accumulator *acc_;
    LoopCounts *counts_;
    Buffers &b_;
    std::vector<udm1_stream> streams_;  // the tile's pixels', by pixel
    size_t n_ = 0;  // live paths
    RTCIntersectContext ctx_;
};

void DiffuseWavefront::Batch::finish(size_t j)  // path j ends: its radiance into its pixel's fixed-point sums
{
    const Paths &P = b_.paths;
    int p = P.pixel[j];
    int64_t *px = &acc_->sum[film_.stride * ((size_t)(y0_ + p / W_ - acc_->y0) * acc_->width + (x0_ + p % W_ - acc_->x0))];
    const int sign = film_.weighted ? sample_sign(film_, &streams_[p], P.index[j]) : 1;
    add_sample(px, film_(Vec3(P.lr[j], P.lg[j], P.lb[j])), sign, film_.weighted, &counts_->nonfinite, &counts_->clamped);
}

void DiffuseWavefront::Batch::camera(const udm1scene::CameraRays &camera, uint64_t start, size_t n)
{
    Paths &P = b_.paths;
    n_ = n;
    {
        uint64_t s = start % count_;
        int p = (int)(start / count_);
        for (size_t k = 0; k < n; ++k) {
            P.index[k] = order_.index(x0_ + p % W_, y0_ + p / W_, first_ + s), P.pixel[k] = p;
            if (++s == count_) s = 0, ++p;  // the next pixel
        }
    }
    // the root domain's 2 values of every path: the position in the pixel
    for (size_t k = 0; k < n; ++k) udm1_domain_draw_f64(udm1_domain_root(&streams_[P.pixel[k]], P.index[k]), 2, &b_.u[2 * k]);
    if (!film_.sampler.unit_box())  // the pixel filter places them (the unit box leaves them as they are)
        for (size_t k = 0; k < n; ++k) film_.sampler.place(&b_.u[2 * k]);
    Vec3 co, ca, cb, cc;
    camera.pinhole(&co, &ca, &cb, &cc);
    const double *uv = b_.u.data();
    const int *pixel = P.pixel.data();
    float *dx = P.dx.data(), *dy = P.dy.data(), *dz = P.dz.data();
    const int x0 = x0_, y0 = y0_, W = W_;
#pragma omp simd
    for (size_t k = 0; k < n; ++k) {  // normalize(a + px b + py c)
        double px = x0 + pixel[k] % W + uv[2 * k], py = y0 + pixel[k] / W + uv[2 * k + 1];
        double ex = ca.x + px * cb.x + py * cc.x, ey = ca.y + px * cb.y + py * cc.y, ez = ca.z + px * cb.z + py * cc.z;
        double inv = 1 / std::sqrt(ex * ex + ey * ey + ez * ez);
        dx[k] = (float)(ex * inv), dy[k] = (float)(ey * inv), dz[k] = (float)(ez * inv);
    }
    for (size_t k = 0; k < n; ++k) {
        P.ox[k] = (float)co.x, P.oy[k] = (float)co.y, P.oz[k] = (float)co.z;
        P.br[k] = P.bg[k] = P.bb[k] = 1, P.lr[k] = P.lg[k] = P.lb[k] = 0;
    }
}

void DiffuseWavefront::Batch::trace(int depth)
{
    Paths &P = b_.paths;
    Stream &S = b_.hits;
    const size_t n = n_;
    std::fill_n(S.tfar.begin(), n, INFINITY);
    std::fill_n(S.geom.begin(), n, RTC_INVALID_GEOMETRY_ID);
    std::fill_n(S.inst.begin(), n, RTC_INVALID_GEOMETRY_ID);
    RTCRayHitNp q{{P.ox.data(), P.oy.data(), P.oz.data(), S.tnear.data(), P.dx.data(), P.dy.data(), P.dz.data(),
                   S.time.data(), S.tfar.data(), S.mask.data(), S.id.data(), S.flags.data()},
                  {S.ngx.data(), S.ngy.data(), S.ngz.data(), S.u.data(), S.v.data(), S.prim.data(), S.geom.data(),
                   {S.inst.data()}}};
    rtcInitIntersectContext(&ctx_);
    if (depth == 0) ctx_.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // camera rays of neighbouring pixels
    rtcIntersectNp(w_.rt_.handle(), &ctx_, &q, (unsigned)n);
    counts_->rays += n;
}

void DiffuseWavefront::Batch::gather(int depth)
{
    Paths &P = b_.paths;
    Vertices &V = b_.vertices;
    const Stream &S = b_.hits;
    const Triangles &T = w_.tri_;
    const LightArrays &F = w_.lights_f_;
    size_t m = 0;
    for (size_t j = 0; j < n_; ++j) {
        if (S.geom[j] == RTC_INVALID_GEOMETRY_ID) {
            finish(j);
            continue;
        }
        size_t tri = T.first[S.geom[j]] + S.prim[j];
        float t = S.tfar[j], hx = P.ox[j] + P.dx[j] * t, hy = P.oy[j] + P.dy[j] * t, hz = P.oz[j] + P.dz[j] * t;
        float nx = T.nx[tri], ny = T.ny[tri], nz = T.nz[tri];
        if (int li = T.light[tri]; li >= 0 && (F.twosided[li] || nx * P.dx[j] + ny * P.dy[j] + nz * P.dz[j] < 0)) {
            float w = 1;
            if (depth > 0) {  // the density with which light sampling at the last vertex finds this point
                Hit h;
                h.shape = w_.rt_.shape_of_geometry(S.geom[j]), h.prim = S.prim[j], h.t = t;
                h.p = Vec3(hx, hy, hz), h.ng = Vec3(nx, ny, nz);
                Vec3 qn = P.normals ? Vec3(P.qnx[j], P.qny[j], P.qnz[j]) : Vec3();  // (a fixed choice ignores it)
                float pl = (float)w_.lights_.pdf(Vec3(P.qx[j], P.qy[j], P.qz[j]), qn, h);
                float pb = P.pb[j];
                w = pb * pb / (pb * pb + pl * pl);
            }
            P.lr[j] += P.br[j] * F.er[li] * w, P.lg[j] += P.bg[j] * F.eg[li] * w, P.lb[j] += P.bb[j] * F.eb[li] * w;
        }
        if (depth == w_.max_depth_) {
            finish(j);
            continue;
        }
        // compact into slot m (m <= j): the path's state and this vertex
        if (m != j) P.move(m, j);
        V.px[m] = hx, V.py[m] = hy, V.pz[m] = hz, V.nx[m] = nx, V.ny[m] = ny, V.nz[m] = nz, V.t[m] = t;
        V.ra[m] = T.rr[tri], V.ga[m] = T.rg[tri], V.ba[m] = T.rb[tri];
        ++m;
    }
    n_ = m;
}

void DiffuseWavefront::Batch::sample(int depth)
{
    Paths &P = b_.paths;
    Vertices &V = b_.vertices;
    std::vector<double> &u = b_.u;
    const Lights &lights = w_.lights_;
    const size_t n = n_;
    // this vertex's 6 values for every live path (the domains of integrator.h)
    for (size_t m = 0; m < n; ++m)
        vertex_values(&streams_[P.pixel[m]], P.index[m], depth, &u[DIMS_PER_VERTEX * m]);
    // the light each path samples (Lights::choose at its point and normal: the same light, rescaled u and
    // probability as the scalar loop's, in double), the values as floats, and whether the light may be
    // near enough for solid-angle sampling (Lights::far's test with a 1 % margin for its rounding:
    // Lights::by_area then decides)
    const LightNear &C = w_.near_;
    if (w_.choice_.fixed) choose_lights(n, u.data(), V, w_.choice_, C);
    for (size_t m = 0; m < n && !w_.choice_.fixed; ++m) {
        const double *um = &u[DIMS_PER_VERTEX * m];
        for (int d = 1; d < DIMS_PER_VERTEX; ++d) V.u[d][m] = unit_float(um[d]);
        size_t l = 0;
        double reuse = 0, prob = 0;
        Vec3 p(V.px[m], V.py[m], V.pz[m]), ng(V.nx[m], V.ny[m], V.nz[m]);
        bool chosen = lights.choose(um[0], p, ng, &l, &reuse, &prob);
        V.light[m] = (int)l, V.u[0][m] = unit_float(reuse), V.prob[m] = chosen ? (float)prob : 0.0f;
        double dx = C.cx[l] - p.x, dy = C.cy[l] - p.y, dz = C.cz[l] - p.z;
        V.maybe_near[m] = chosen && C.area[l] >= 0.99 * C.near * (dx * dx + dy * dy + dz * dz);
    }
    b_.near.clear();
    for (size_t m = 0; m < n; ++m) {
        if (!V.maybe_near[m]) continue;
        const double *um = &u[DIMS_PER_VERTEX * m];
        size_t l = (size_t)V.light[m];
        Vec3 p(V.px[m], V.py[m], V.pz[m]);
        if (lights.by_area(l, p)) continue;
        // near the light: by solid angle, in double, as the scalar loop
        NearSample ns{m, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
        LightSample ls;
        Vec3 ng(V.nx[m], V.ny[m], V.nz[m]), wo(-P.dx[m], -P.dy[m], -P.dz[m]);
        bool ok = lights.sample(p, ng, um[0], um[1], &ls);
        double cos_i = ok ? udm1scene::dot(ng, ls.wi) : 0, cos_o = udm1scene::dot(ng, wo);
        if (ok && cos_i * cos_o > 0) {
            double pdf_b = std::fabs(cos_i) / M_PI;
            double k = std::fabs(cos_i) * ls.pdf / (ls.pdf * ls.pdf + pdf_b * pdf_b);  // |cos| w / pdf
            udm1scene::Segment sg = udm1scene::shadow_segment(p, ng, V.t[m], ls.q, ls.n);
            ns.sx = (float)sg.o.x, ns.sy = (float)sg.o.y, ns.sz = (float)sg.o.z;
            ns.dx = (float)sg.d.x, ns.dy = (float)sg.d.y, ns.dz = (float)sg.d.z;
            ns.len = (float)sg.len;
            ns.cr = (float)(P.br[m] * V.ra[m] * ls.L.x * k);
            ns.cg = (float)(P.bg[m] * V.ga[m] * ls.L.y * k);
            ns.cb = (float)(P.bb[m] * V.ba[m] * ls.L.z * k);
        }
        b_.near.push_back(ns);
    }
}

void DiffuseWavefront::Batch::shade_all(int depth)
{
    Vertices &V = b_.vertices;
    shade(n_, b_.paths, V, w_.lights_f_, Shading{depth, w_.rr_depth_, w_.roulette_});
    for (const NearSample &s : b_.near) {
        V.sx[s.j] = s.sx, V.sy[s.j] = s.sy, V.sz[s.j] = s.sz, V.sdx[s.j] = s.dx, V.sdy[s.j] = s.dy, V.sdz[s.j] = s.dz;
        V.slen[s.j] = s.len, V.cr[s.j] = s.cr, V.cg[s.j] = s.cg, V.cb[s.j] = s.cb;
    }
}

void DiffuseWavefront::Batch::shadows()
{
    Paths &P = b_.paths;
    Vertices &V = b_.vertices;  // Embree's stream takes non-const arrays
    Stream &S = b_.hits;
    const size_t n = n_;
    // shadow rays of the paths whose light sample contributes; the others inactive (tfar < tnear)
    size_t active_rays = 0;
    float *stfar = S.tfar.data();
    for (size_t j = 0; j < n; ++j) {
        bool active = ((V.cr[j] > 0) | (V.cg[j] > 0) | (V.cb[j] > 0)) & (V.slen[j] > 0);
        stfar[j] = active ? V.slen[j] : -1.0f;
        active_rays += active;
    }
    RTCRayNp sh{V.sx.data(), V.sy.data(), V.sz.data(), S.tnear.data(), V.sdx.data(), V.sdy.data(), V.sdz.data(),
                S.time.data(), stfar, S.mask.data(), S.id.data(), S.flags.data()};
    rtcInitIntersectContext(&ctx_);
    rtcOccludedNp(w_.rt_.handle(), &ctx_, &sh, (unsigned)n);
    counts_->rays += active_rays;
    // the light samples that reached their light, then the paths that ended at this vertex
    size_t keep = 0;
    for (size_t j = 0; j < n; ++j) {
        if (stfar[j] >= 0) P.lr[j] += V.cr[j], P.lg[j] += V.cg[j], P.lb[j] += V.cb[j];
        if (!V.alive[j]) {
            finish(j);
            continue;
        }
        if (keep != j) P.move(keep, j);
        ++keep;
    }
    n_ = keep;
}

void DiffuseWavefront::render(const udm1_seq *seq, const udm1app::PixelOrder &order, const udm1scene::CameraRays &camera,
                              int x0, int x1, int y0, int y1, uint64_t first, uint64_t count, const FilmResponse &film,
                              Accumulator *acc, LoopCounts *counts) const
{
    Batch batch(*this, seq, order, x0, x1, y0, y1, first, count, film, acc, counts);
    const uint64_t total = (uint64_t)(x1 - x0) * (uint64_t)(y1 - y0) * count;
    for (uint64_t start = 0; start < total; start += BATCH) {
        batch.camera(camera, start, (size_t)std::min<uint64_t>(BATCH, total - start));
        for (int depth = 0; batch.live() > 0; ++depth) {
            batch.trace(depth);
            batch.gather(depth);
            batch.sample(depth);
            batch.shade_all(depth);
            batch.shadows();
        }
    }
}

}  // namespace udm1pt
