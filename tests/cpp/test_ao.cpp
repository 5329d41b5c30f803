// test_ao.cpp - the ambient occlusion estimator: closed forms (an open plane is 1, a closed box 0,
// the foot of an infinite wall 1/2), unbiasedness over randomizations, determinism across runs,
// threads and ray methods.
#include "../c/check.h"

#include "ao_render.h"
#include "builtin.h"
#include "embree_scene.h"

#include <tbb/global_control.h>

#include <cmath>
#include <cstring>

using namespace udm1scene;

static udm1ao::Image render(const Scene &s, const EmbreeScene &rt, const char *sampler, uint32_t spp, uint64_t seed,
                            int size, udm1ao::Method m = udm1ao::Method::Stream, uint32_t randomize = UDM1_RANDOMIZE_DEFAULT)
{
    udm1ao::Options o;
    o.sampler = sampler;
    o.spp = spp;
    o.seed = seed;
    o.width = o.height = size;
    o.method = m;
    o.randomize = randomize;
    udm1ao::Stats st;
    return udm1ao::render(s, rt, o, &st);
}

static void test_cosine_directions()
{
    // the mapping against libm: (sqrt(u1) cos 2 pi u2, sqrt(u1) sin 2 pi u2, sqrt(1 - u1)) in the normal's
    // frame, for normals in every octant and on the axes, u on a grid that includes the quadrant edges
    const double TWO_PI = 6.283185307179586;
    double worst = 0;
    for (Vec3 n : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, -1, 0), normalize(Vec3(1, -2, 3)),
                   normalize(Vec3(-0.3, 0.2, -0.9))})
        for (int i = 0; i <= 64; ++i)
            for (int j = 0; j < 400; ++j) {
                double u1 = i / 64.0 * (1 - 1e-12), u2 = j / 400.0;
                Vec3 w = udm1ao::cosine_direction(n, u1, u2);
                // the component along n is sqrt(1 - u1); the azimuth is 2 pi u2 from the frame's first axis
                Vec3 t = udm1ao::cosine_direction(n, 1 - 1e-300, 0.0), b = udm1ao::cosine_direction(n, 1 - 1e-300, 0.25);
                Vec3 want = t * (std::sqrt(u1) * std::cos(TWO_PI * u2)) + b * (std::sqrt(u1) * std::sin(TWO_PI * u2)) +
                            n * std::sqrt(1 - u1);
                worst = std::fmax(worst, length(w - want));
                worst = std::fmax(worst, std::fabs(length(w) - 1));
            }
    CHECKF(worst < 3e-7, "cosine directions differ from libm's by %g (float rounding is 6e-8)", worst);
}

static void test_closed_forms()
{
    Scene plane = builtin_scene("plane"), box = builtin_scene("box");
    EmbreeScene rp(plane), rb(box);
    for (const char *sampler : {"wr-ao", "sobol-owen", "pcg32", "episwr"}) {
        udm1ao::Image a = render(plane, rp, sampler, 16, 3, 24), b = render(box, rb, sampler, 16, 3, 24);
        int bad = 0;
        for (float v : a.values) bad += v != 1.0f;
        for (float v : b.values) bad += v != 0.0f;
        CHECKF(bad == 0, "%s: %d pixels off the closed forms (plane 1, box 0)", sampler, bad);
    }
    // the 4D variant (jittered primary rays) keeps the closed forms
    for (const char *sampler : {"sobol-owen", "halton", "pcg32"}) {
        udm1ao::Options o;
        o.sampler = sampler, o.spp = 16, o.seed = 4, o.width = o.height = 20, o.jitter = true;
        udm1ao::Stats st;
        udm1ao::Image a = udm1ao::render(plane, rp, o, &st), b = udm1ao::render(box, rb, o, &st);
        int bad = 0;
        for (float v : a.values) bad += v != 1.0f;
        for (float v : b.values) bad += v != 0.0f;
        CHECKF(bad == 0, "%s with jitter: %d pixels off the closed forms", sampler, bad);
    }
    // hard cases for the ray offsets: the same scenes shrunk and moved far from the origin. Rays start
    // 2^-18 of the coordinates' magnitude off the surface, so the closed forms must hold wherever the
    // box is larger than a few offsets: half-size >= 1e-5 x its distance from the origin.
    const double cases[][2] = {{1e-4, 0}, {1e-4, 1}, {1e-2, 0}, {1e-2, 1}, {1e-2, 1e3}, {1, 0},
                               {1, 1e3}, {1, 3e4}, {1e2, 0}, {1e2, 1e6}, {1e4, 0}, {1e4, 1e8}};
    for (const auto &c : cases) {
        double sc = c[0], far = c[1];
        Mat4 m = Mat4::translate(Vec3(far, -far, far)) * Mat4::scale(Vec3(sc, sc, sc));
        for (Scene *src : {&plane, &box}) {
            Scene t = *src;
            for (Shape &sh : t.shapes)
                for (size_t i = 0; i < sh.P.size(); i += 3) {
                    Vec3 q = m.point(Vec3(sh.P[i], sh.P[i + 1], sh.P[i + 2]));
                    sh.P[i] = (float)q.x, sh.P[i + 1] = (float)q.y, sh.P[i + 2] = (float)q.z;
                }
            t.camera.world_from_camera = m * t.camera.world_from_camera;
            EmbreeScene rt(t);
            udm1ao::Image a = render(t, rt, "wr-ao", 16, 3, 24);
            float want = src == &plane ? 1.0f : 0.0f;
            int bad = 0;
            for (float v : a.values) bad += v != want;
            CHECKF(bad == 0, "%s scaled %g moved %g: %d pixels are not %g", t.source.c_str(), sc, far, bad, want);
        }
    }
    // the foot of a wall infinitely tall and wide: half of the cosine-weighted hemisphere is blocked
    Scene wall = builtin_scene("wall");
    EmbreeScene rw(wall);
    for (const char *sampler : {"wr-ao", "sobol-owen", "halton"}) {
        udm1ao::Options o;
        o.sampler = sampler;
        o.spp = 4096;
        udm1_seq *seq = udm1ao::make_sampler(o);
        for (double d : {1e-3, 0.5, 3.0}) {  // any distance from an infinite wall gives 1/2
            double a = udm1ao::ao_at(rw, Vec3(0.3, 0, -d), Vec3(0, 1, 0), seq, 7, 4096, 0, 1e300, udm1ao::Method::Packet);
            CHECKF(std::fabs(a - 0.5) < 0.01, "%s at distance %g: AO %g, expected 1/2", sampler, d, a);
        }
        udm1_seq_destroy(seq);
    }
}

// A floor (y = 0, z < 0) and a wall (z = 0) of height H, both very wide.
static Scene finite_wall(double H)
{
    Scene s;
    s.source = "test:finite-wall";
    const double L = 1e5;
    auto quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
        Shape sh;
        for (Vec3 p : {a, b, c, d}) sh.P.insert(sh.P.end(), {(float)p.x, (float)p.y, (float)p.z});
        sh.indices = {0, 1, 2, 2, 3, 0};
        s.shapes.push_back(sh);
    };
    quad(Vec3(-L, 0, -L), Vec3(L, 0, -L), Vec3(L, 0, 0), Vec3(-L, 0, 0));
    quad(Vec3(-L, 0, 0), Vec3(L, 0, 0), Vec3(L, H, 0), Vec3(-L, H, 0));
    return s;
}

static void test_form_factor()
{
    // At distance d from a wall of height H (infinitely wide) the wall's cosine-weighted share of the
    // hemisphere is the 2D form factor F = (1 - d / sqrt(d^2 + H^2)) / 2, so A = 1 - F. Uniform
    // (not cosine) directions would give other values: this pins the cosine weighting.
    Scene s = finite_wall(1.0);
    EmbreeScene rt(s);
    udm1ao::Options o;
    o.sampler = "sobol-owen";
    o.spp = 1 << 16;
    udm1_seq *seq = udm1ao::make_sampler(o);
    for (double d : {0.25, 1.0, 4.0}) {
        double expected = 1 - 0.5 * (1 - d / std::sqrt(d * d + 1));
        double a = udm1ao::ao_at(rt, Vec3(0, 0, -d), Vec3(0, 1, 0), seq, 11, o.spp, 0, 1e300, udm1ao::Method::Packet);
        CHECKF(std::fabs(a - expected) < 2e-3, "distance %g from a unit wall: AO %.5f, expected %.5f", d, a, expected);
        // the maximum distance option: rays shorter than the distance to the wall see nothing
        double b = udm1ao::ao_at(rt, Vec3(0, 0, -d), Vec3(0, 1, 0), seq, 11, 4096, 0, 0.9 * d, udm1ao::Method::Single);
        CHECKF(b == 1.0, "max distance %g at distance %g: AO %g, expected 1", 0.9 * d, d, b);
    }
    udm1_seq_destroy(seq);
}

static void test_unbiased()
{
    // a randomly shifted sampler: the mean over seeds converges to the reference
    Scene s = builtin_scene("cornell");
    EmbreeScene rt(s);
    const int S = 16;
    udm1ao::Image ref = render(s, rt, "sobol-owen", 4096, 99, S);
    std::vector<double> mean(S * S, 0.0);
    const int seeds = 64;
    for (int k = 0; k < seeds; ++k) {
        udm1ao::Image a = render(s, rt, "wr-ao", 16, 1000 + k, S, udm1ao::Method::Packet, UDM1_RANDOMIZE_SHIFT);
        for (int i = 0; i < S * S; ++i) mean[i] += a.values[i] / seeds;
    }
    double bias = 0, worst = 0;
    for (int i = 0; i < S * S; ++i) {
        bias += (mean[i] - ref.values[i]) / (S * S);
        worst = std::fmax(worst, std::fabs(mean[i] - ref.values[i]));
    }
    // per pixel sd of a 16-spp estimate <= 0.125, of the mean over 64 seeds <= 0.016; of their mean <= 0.001
    CHECKF(std::fabs(bias) < 0.005, "mean over seeds differs from the reference by %g on average", bias);
    CHECKF(worst < 0.08, "a pixel's mean over seeds differs by %g", worst);
    // without randomization every seed gives the same (biased) image: the average equals one render
    udm1ao::Image fixed1 = render(s, rt, "wr-ao", 16, 1, S, udm1ao::Method::Packet, UDM1_RANDOMIZE_NONE);
    udm1ao::Image fixed2 = render(s, rt, "wr-ao", 16, 2, S, udm1ao::Method::Packet, UDM1_RANDOMIZE_NONE);
    CHECK(fixed1.values == fixed2.values);
}

static void test_deterministic()
{
    Scene s = builtin_scene("cornell");
    EmbreeScene rt(s);
    udm1ao::Image a = render(s, rt, "sobol-owen", 32, 5, 48), b = render(s, rt, "sobol-owen", 32, 5, 48);
    CHECK(a.values == b.values);
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        udm1ao::Image c = render(s, rt, "sobol-owen", 32, 5, 48);
        CHECK(a.values == c.values);
    }
    {  // the jittered variant too
        udm1ao::Options o;
        o.sampler = "sobol-owen", o.spp = 8, o.width = o.height = 40, o.jitter = true;
        udm1ao::Stats st;
        udm1ao::Image j1 = udm1ao::render(s, rt, o, &st);
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        udm1ao::Image j2 = udm1ao::render(s, rt, o, &st);
        CHECK(j1.values == j2.values);
    }
    int differ = 0;
    for (udm1ao::Method m : {udm1ao::Method::Single, udm1ao::Method::Packet}) {
        udm1ao::Image d = render(s, rt, "sobol-owen", 32, 5, 48, m);
        for (size_t i = 0; i < a.values.size(); ++i) differ += a.values[i] != d.values[i];
    }
    CHECKF(differ == 0, "%d pixels differ between the ray methods", differ);
}

int main()
{
    test_cosine_directions();
    test_closed_forms();
    test_form_factor();
    test_unbiased();
    test_deterministic();
    CHECK_DONE();
}
