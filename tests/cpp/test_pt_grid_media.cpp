// test_pt_grid_media.cpp - udm1-pt's grid media (pt/grid_medium.h, the estimator's delta and ratio tracking):
// the majorant grid bounds the density everywhere, the DDA visits every majorant cell a ray crosses with
// segments that tile the ray's overlap with the box, the cloud's density stays in [0, 1] under its
// majorant 1, and rendered through the whole estimator a grid of constant density inside its box gives the
// closed-form transmittance and glow of an absorbing slab and the same image as the homogeneous medium of
// that density in a scene that scatters (light sampling through ratio-tracked shadow rays, MIS).
#include "../c/check.h"
#include "scene_text.h"

#include "embree_scene.h"
#include "grid_medium.h"
#include "integrator.h"
#include "scene.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <unistd.h>

using namespace udm1scene;
using namespace udm1pt;

namespace {

Scene load(const std::string &text) { return load_scene_text(text); }

Vec3 image_mean(const Scene &s, uint32_t spp, int size)
{
    EmbreeScene rt(s);
    Options o;
    o.spp = spp, o.width = o.height = size, o.loop = Loop::Scalar;
    Stats st;
    Accumulator a = render(s, rt, o, &st);
    std::vector<float> m = a.mean();
    Vec3 v;
    for (size_t i = 0; i < m.size(); ++i) v[i % 3] += m[i];
    return v * (3.0 / m.size());
}

Medium random_grid(std::mt19937_64 &rng, int nx, int ny, int nz)
{
    Medium m;
    m.kind = Medium::UniformGrid;
    m.sigma_a = Vec3(0.2, 0.5, 1), m.sigma_s = Vec3(1, 0.5, 0.25);
    m.nx = nx, m.ny = ny, m.nz = nz;
    m.p0 = Vec3(-1, -0.5, 0), m.p1 = Vec3(2, 1, 0.5);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < nx * ny * nz; ++i) m.density.push_back(i > 0 && u(rng) < 0.3 ? 0.0f : (float)(1 + 3 * u(rng)));
    return m;
}

void test_majorants_bound_the_density()
{
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    for (auto [nx, ny, nz] : {std::tuple{1, 1, 1}, {3, 5, 2}, {16, 16, 16}, {37, 4, 23}}) {
        Medium m = random_grid(rng, nx, ny, nz);
        GridMedium g(m);
        const MajorantGrid &mg = g.majorant_grid();
        const int R = MajorantGrid::RES;
        int worse = 0;
        double top = 0;
        for (int i = 0; i < 200000; ++i) {
            Vec3 p(u(rng), u(rng), u(rng));
            double d = g.grid_density(p);
            top = std::max(top, d);
            if (d > mg.at(std::min(R - 1, (int)(p.x * R)), std::min(R - 1, (int)(p.y * R)), std::min(R - 1, (int)(p.z * R))) * (1 + 1e-6))
                ++worse;
        }
        CHECKF(worse == 0, "%dx%dx%d: %d points above their cell's majorant", nx, ny, nz, worse);
        CHECKF(top > 0.5, "%dx%dx%d: the density is never above 0.5 (%g)", nx, ny, nz, top);
    }
    // the cloud: a density in [0, 1], its majorant sigma_t
    Medium c;
    c.kind = Medium::Cloud, c.sigma_a = Vec3(1, 2, 3), c.sigma_s = Vec3(1, 1, 1), c.wispiness = 2, c.frequency = 4;
    GridMedium g(c);
    double lo = 1, hi = 0;
    for (int i = 0; i < 100000; ++i) {
        double d = g.cloud_density(Vec3(u(rng), u(rng), u(rng)));
        lo = std::min(lo, d), hi = std::max(hi, d);
    }
    CHECKF(lo >= 0 && hi <= 1 && hi > 0.5 && lo < 0.5, "cloud density in [%g, %g]", lo, hi);
    MajorantIterator it = g.majorants(Vec3(0.5, 0.5, -3), Vec3(0, 0, 1), 1e30);
    MajorantSegment seg;
    CHECK(it.next(&seg) && std::fabs(seg.t0 - 3) < 1e-9 && std::fabs(seg.t1 - 4) < 1e-9 && seg.sigma_maj.z == 4 && !it.next(&seg));
}

void test_dda_visits_every_cell()
{
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    Medium m = random_grid(rng, 9, 7, 5);
    m.medium_from_world = Mat4::scale(Vec3(1, 2, 0.5));  // (the box seen through a transform: same t)
    GridMedium g(m);
    const int R = MajorantGrid::RES;
    int rays = 0, missed = 0, gaps = 0, bounds = 0;
    for (int i = 0; i < 5000; ++i) {
        Vec3 o(-3 + 6 * u(rng), -3 + 6 * u(rng), -3 + 6 * u(rng));
        double a = 2 * M_PI * u(rng), z = 2 * u(rng) - 1, r = std::sqrt(1 - z * z);
        Vec3 d(r * std::cos(a), r * std::sin(a), z);
        if (i % 10 == 0) d = Vec3(0, 0, i % 20 ? 1 : -1), o.x = o.y = 0.1;  // (axis-aligned rays: zero components)
        double t_max = 1 + 6 * u(rng);
        MajorantIterator it = g.majorants(o, d, t_max);
        std::vector<std::tuple<double, double, int>> segs;  // t0, t1, cell
        MajorantSegment seg;
        for (;;) {
            int cell = it.cell(0) + R * (it.cell(1) + R * it.cell(2));
            if (!it.next(&seg)) break;
            segs.push_back({seg.t0, seg.t1, cell});
            // the segment's majorant bounds sigma_t at points along it
            for (int k = 0; k < 4; ++k) {
                double t = seg.t0 + (seg.t1 - seg.t0) * u(rng);
                GridMedium::Point mp = g.at(o + d * t);
                for (int c = 0; c < 3; ++c) bounds += mp.sigma_a[c] + mp.sigma_s[c] > seg.sigma_maj[c] * (1 + 1e-6) + 1e-12;
            }
        }
        if (segs.empty()) continue;
        ++rays;
        for (size_t k = 1; k < segs.size(); ++k) gaps += std::get<0>(segs[k]) != std::get<1>(segs[k - 1]);
        // every cell a dense walk along the overlap finds is one the DDA visited
        std::set<int> visited;
        for (auto &s : segs) visited.insert(std::get<2>(s));
        double t0 = std::get<0>(segs.front()), t1 = std::get<1>(segs.back());
        for (int k = 1; k < 2000; ++k) {
            Vec3 pm = m.medium_from_world.point(o + d * (t0 + (t1 - t0) * k / 2000.0));
            int c[3];
            for (int ax = 0; ax < 3; ++ax)
                c[ax] = std::clamp((int)std::floor((pm[ax] - m.p0[ax]) / (m.p1[ax] - m.p0[ax]) * R), 0, R - 1);
            missed += !visited.count(c[0] + R * (c[1] + R * c[2]));
        }
    }
    CHECKF(rays > 400, "%d rays met the box", rays);
    CHECKF(missed == 0, "%d points in cells the DDA did not visit", missed);
    CHECKF(gaps == 0, "%d gaps between segments", gaps);
    CHECKF(bounds == 0, "%d points above their segment's majorant", bounds);
}

// An absorbing slab |z| < 0.5 (interface box) in a grid of constant density 0.5 whose box is larger by more
// than half a cell (so the density is constant where the slab is), viewed through towards an emitter of
// radiance 1: exp(-sigma_a scale density); with Le and a constant Lescale grid c the slab adds
// c Le (1 - exp(-...)).
const char *SLAB = R"(LookAt 0 0 -5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 1 ]
Integrator "volpath" "integer maxdepth" [ 5 ]
WorldBegin
AttributeBegin
AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
Shape "trianglemesh" "point3 P" [ -9 -9 5  9 -9 5  9 9 5  -9 9 5 ] "integer indices" [ 0 2 1 0 3 2 ]
AttributeEnd
%s
AttributeBegin
Material "interface"
MediumInterface "m" ""
Shape "trianglemesh" "point3 P" [ -1 -1 -0.5  1 -1 -0.5  1 1 -0.5  -1 1 -0.5  -1 -1 0.5  1 -1 0.5  1 1 0.5  -1 1 0.5 ]
    "integer indices" [ 0 2 1 0 3 2  4 5 6 4 6 7  0 5 4 0 1 5  3 6 2 3 7 6  0 7 3 0 4 7  1 6 5 1 2 6 ]
AttributeEnd
)";

std::string slab(const std::string &medium)
{
    char buf[4096];
    std::snprintf(buf, sizeof buf, SLAB, medium.c_str());
    return buf;
}

const std::string CONSTANT_GRID = "\"integer nx\" [ 4 ] \"integer ny\" [ 4 ] \"integer nz\" [ 4 ] \"point3 p0\" [ -2 -2 -2 ] "
                                  "\"point3 p1\" [ 2 2 2 ] \"float density\" [ " + [] {
                                      std::string s;
                                      for (int i = 0; i < 64; ++i) s += "0.5 ";
                                      return s;
                                  }() + "]";

void test_constant_grid_closed_forms()
{
    // transmittance (delta tracking: absorption ends paths; the estimate is unbiased)
    Scene s = load(slab("MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"rgb sigma_a\" [ 0.5 1 2 ] "
                        "\"rgb sigma_s\" [ 0 0 0 ] \"float scale\" [ 2 ] " + CONSTANT_GRID));
    Vec3 m = image_mean(s, 256, 8);
    for (int c = 0; c < 3; ++c) {
        double expect = std::exp(-(c == 0 ? 0.5 : c == 1 ? 1.0 : 2.0));
        CHECKF(std::fabs(m[c] / expect - 1) < 0.03, "channel %d: transmittance %.5f, expected %.5f", c, m[c], expect);
    }
    // glow: a Lescale grid of constant 3 over Le 0.5
    std::string lescale = "\"float Lescale\" [ ";
    for (int i = 0; i < 64; ++i) lescale += "3 ";
    s = load(slab("MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"rgb sigma_a\" [ 1 1 1 ] \"rgb sigma_s\" [ 0 0 0 ] "
                  "\"rgb Le\" [ 0.5 0.5 0.5 ] " + lescale + "] " + CONSTANT_GRID));
    m = image_mean(s, 256, 8);
    double T = std::exp(-0.5), expect = T + 1.5 * (1 - T);
    for (int c = 0; c < 3; ++c) CHECKF(std::fabs(m[c] / expect - 1) < 0.03, "channel %d: glow %.5f, expected %.5f", c, m[c], expect);
}

// A scattering, chromatic sphere of medium lit by a point and a sphere light: a grid of constant density d
// (its box larger than the sphere by more than half a cell) renders the image of the homogeneous medium of
// sigma d, within the statistics of both renders.
void test_constant_grid_as_homogeneous()
{
    const char *scene = R"(LookAt 0 0.5 -4  0 0.3 0  0 1 0
Camera "perspective" "float fov" [ 35 ]
Integrator "volpath" "integer maxdepth" [ 6 ]
WorldBegin
LightSource "point" "point3 from" [ 2 3 -2 ] "rgb I" [ 6 6 6 ]
AttributeBegin
AreaLightSource "diffuse" "rgb L" [ 3 3 3 ]
Translate -2 2 1
Shape "sphere" "float radius" [ 0.4 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "point3 P" [ -6 -1 -6  6 -1 -6  6 -1 6  -6 -1 6 ] "integer indices" [ 0 2 1 0 3 2 ]
%s
AttributeBegin
Material "interface"
MediumInterface "m" ""
Shape "sphere" "float radius" [ 1 ]
AttributeEnd
)";
    char a[4096], b[4096];
    std::snprintf(a, sizeof a, scene, ("MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"rgb sigma_a\" [ 0.2 0.4 0.8 ] "
                                      "\"rgb sigma_s\" [ 2 1.5 1 ] \"float g\" [ 0.4 ] " + CONSTANT_GRID).c_str());
    std::snprintf(b, sizeof b, scene, "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.1 0.2 0.4 ] "
                                      "\"rgb sigma_s\" [ 1 0.75 0.5 ] \"float g\" [ 0.4 ]");
    Vec3 mg = image_mean(load(a), 256, 24), mh = image_mean(load(b), 256, 24);
    for (int c = 0; c < 3; ++c)
        CHECKF(std::fabs(mg[c] / mh[c] - 1) < 0.02, "channel %d: grid %.5f, homogeneous %.5f", c, mg[c], mh[c]);
}

}  // namespace

int main()
{
    test_majorants_bound_the_density();
    test_dda_visits_every_cell();
    test_constant_grid_closed_forms();
    test_constant_grid_as_homogeneous();
    CHECK_DONE();
}
