// test_pt.cpp - the path tracer's core: furnaces with closed forms, the three light-finding
// strategies agreeing in the mean, BSDF sampling consistent with BSDF evaluation (diffuse and
// coated diffuse, energy never created), exact determinism across threads and split sample
// ranges, and the film file round trip.
#include "../c/check.h"

#include "builtin.h"
#include "embree_scene.h"
#include "film_io.h"
#include "integrator.h"
#include "lights.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <unistd.h>

using namespace udm1scene;
using namespace udm1pt;

static double image_mean(const Accumulator &a, int channel)
{
    std::vector<float> m = a.mean();
    double s = 0;
    for (size_t i = channel; i < m.size(); i += 3) s += m[i];
    return s / (m.size() / 3);
}

static Accumulator run(const Scene &s, const EmbreeScene &rt, Options o)
{
    Stats st;
    return render(s, rt, o, &st);
}

// A closed sphere (or box) whose walls emit 1 on both sides and reflect albedo a (diffuse).
static Scene furnace(double albedo, const char *name = "furnace")
{
    Scene s = builtin_scene(name);
    for (Material &m : s.materials) m.params.params[0].numbers = {albedo, albedo, albedo};
    return s;
}

static void test_furnace()
{
    for (double a : {0.5, 0.8}) {
        Scene s = furnace(a);
        EmbreeScene rt(s);
        Options o;
        o.width = o.height = 12;
        // truncated at maxdepth 3 without roulette: BSDF sampling sees emission 1 at every vertex and
        // carries exactly a^k, so every sample is 1 + a + a^2 + a^3
        o.max_depth = 3, o.roulette = false, o.spp = 8, o.strategy = Strategy::Bsdf;
        double exact = 1 + a + a * a + a * a * a;
        Accumulator t = run(s, rt, o);
        CHECKF(std::fabs(image_mean(t, 0) - exact) < 1e-6, "albedo %g, depth 3, BSDF: %.9f, expected %.9f", a,
               image_mean(t, 0), exact);
        for (Strategy st : {Strategy::Mis, Strategy::Nee}) {
            o.strategy = st, o.spp = 64;
            double m = image_mean(run(s, rt, o), 1);
            CHECKF(std::fabs(m - exact) < 0.02 * exact, "albedo %g, depth 3, strategy %d: %.5f, expected %.5f", a, (int)st,
                   m, exact);
        }
        // the box: exact with BSDF sampling; MIS (BSDF sampling covers the edges, where light sampling's
        // variance is unbounded) within noise
        Scene box = furnace(a, "furnace-box");
        EmbreeScene rb(box);
        o.spp = 8, o.strategy = Strategy::Bsdf;
        CHECK(std::fabs(image_mean(run(box, rb, o), 0) - exact) < 1e-6);
        o.spp = 64, o.strategy = Strategy::Mis;
        double mb = image_mean(run(box, rb, o), 0);
        CHECKF(std::fabs(mb - exact) < 0.02 * exact, "box, albedo %g, depth 3, MIS: %.5f, expected %.5f", a, mb, exact);
        // unbounded depth with roulette: L / (1 - a)
        o.max_depth = 1000, o.roulette = true, o.spp = 64;
        for (Strategy st : {Strategy::Mis, Strategy::Nee, Strategy::Bsdf}) {
            o.strategy = st;
            double m = image_mean(run(s, rt, o), 2), want = 1 / (1 - a);
            CHECKF(std::fabs(m - want) < 0.02 * want, "albedo %g, strategy %d: %.5f, expected L/(1-a) = %.5f", a, (int)st,
                   m, want);
        }
    }
}

static void test_strategies_agree()
{
    // the Cornell box: MIS, light sampling only and BSDF sampling only converge to the same image mean
    Scene s = builtin_scene("cornell");
    EmbreeScene rt(s);
    Options o;
    o.width = o.height = 64, o.spp = 256, o.sampler = "sobol-owen";
    double mean[3][3];
    int k = 0;
    for (Strategy st : {Strategy::Mis, Strategy::Nee, Strategy::Bsdf}) {
        o.strategy = st;
        Accumulator a = run(s, rt, o);
        for (int c = 0; c < 3; ++c) mean[k][c] = image_mean(a, c);
        ++k;
    }
    for (int c = 0; c < 3; ++c) {
        CHECKF(std::fabs(mean[1][c] / mean[0][c] - 1) < 0.01, "channel %d: NEE %.5f against MIS %.5f", c, mean[1][c],
               mean[0][c]);
        CHECKF(std::fabs(mean[2][c] / mean[0][c] - 1) < 0.02, "channel %d: BSDF %.5f against MIS %.5f", c, mean[2][c],
               mean[0][c]);
    }
}

// E[f cos / pdf] over BSDF samples against the same albedo by uniform sphere sampling of f.
static void albedo_check(const Bsdf &b, Vec3 wo, const char *what)
{
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(0, 1);
    const int N = 400000;
    double by_sampling = 0, by_uniform = 0;
    for (int i = 0; i < N; ++i) {
        Sample s;
        if (b.sample(wo, U(rng), U(rng), U(rng), &s) && s.pdf > 0) by_sampling += s.f.y * std::fabs(s.wi.z) / s.pdf;
        double z = 1 - 2 * U(rng), r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * M_PI * U(rng);
        Vec3 wi(r * std::cos(phi), r * std::sin(phi), z);
        by_uniform += b.f(wo, wi).y * std::fabs(z) * 4 * M_PI;
    }
    by_sampling /= N, by_uniform /= N;
    CHECKF(std::fabs(by_sampling - by_uniform) < 0.01 + 0.02 * by_uniform, "%s: albedo %.4f by sampling, %.4f by evaluation",
           what, by_sampling, by_uniform);
    CHECKF(by_sampling <= 1.0 + 0.01, "%s: albedo %.4f creates energy", what, by_sampling);
}

static void test_bsdf_consistency()
{
    Bsdf d;
    d.kind = Bsdf::Diffuse, d.diffuse.R = Vec3(0.7, 0.7, 0.7);
    albedo_check(d, normalize(Vec3(0.3, 0.1, 0.9)), "diffuse");
    for (double rough : {0.0, 0.05, 0.3}) {
        Bsdf c;
        c.kind = Bsdf::CoatedDiffuse;
        c.coated.bottom.R = Vec3(0.8, 0.8, 0.8);
        c.coated.top.mf.ax = c.coated.top.mf.ay = rough;
        for (Vec3 wo : {normalize(Vec3(0.2, 0.0, 1.0)), normalize(Vec3(0.9, 0.3, 0.2)), normalize(Vec3(0.1, 0.2, -0.8))}) {
            char what[96];
            std::snprintf(what, sizeof what, "coated diffuse, roughness %g, wo.z %.2f", rough, wo.z);
            if (rough == 0.0) {  // a smooth coat: f() has no specular part; check energy by sampling only
                std::mt19937_64 rng(3);
                std::uniform_real_distribution<double> U(0, 1);
                double sum = 0;
                for (int i = 0; i < 200000; ++i) {
                    Sample s;
                    if (c.sample(wo, U(rng), U(rng), U(rng), &s) && s.pdf > 0) sum += s.f.y * std::fabs(s.wi.z) / s.pdf;
                }
                sum /= 200000;
                CHECKF(sum > 0.3 && sum <= 1.01, "%s: albedo %.4f", what, sum);
            } else {
                albedo_check(c, wo, what);
            }
        }
    }
    // the coat over black reflects only Fresnel: at normal incidence about 4% for eta 1.5
    Bsdf black;
    black.kind = Bsdf::CoatedDiffuse;
    black.coated.top.mf.ax = black.coated.top.mf.ay = 0.05;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> U(0, 1);
    double sum = 0;
    for (int i = 0; i < 200000; ++i) {
        Sample s;
        if (black.sample(Vec3(0, 0, 1), U(rng), U(rng), U(rng), &s) && s.pdf > 0) sum += s.f.y * std::fabs(s.wi.z) / s.pdf;
    }
    sum /= 200000;
    CHECKF(std::fabs(sum - fresnel_dielectric(1.0, 1.5)) < 0.01, "coat over black: albedo %.4f, Fresnel %.4f", sum,
           fresnel_dielectric(1.0, 1.5));
}

// Next-event estimation of the irradiance from one triangle light (radiance 1) at points from
// very near (solid-angle sampling) to far (area sampling), against Lambert's closed form for a
// polygon: E = 1/2 sum_i angle(v_i, v_i+1) (n . unit(v_i x v_i+1)).
static void test_light_sampling()
{
    Scene s;
    Shape tri;
    tri.P = {-1, -1, 1, 1, -1, 1, 0, 1, 1};
    tri.indices = {0, 1, 2};
    tri.light = 0;
    s.shapes.push_back(tri);
    AreaLight al;
    al.twosided = true;
    s.lights.push_back(al);
    Lights lights(s);
    Vec3 v[3] = {Vec3(-1, -1, 1), Vec3(1, -1, 1), Vec3(0, 1, 1)}, n(0, 0, 1);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> U(0, 1);
    for (double z : {0.9, 0.5, 0.0, -3.0, -20.0}) {
        Vec3 p(0.1, -0.2, z);
        double exact = 0;
        for (int i = 0; i < 3; ++i) {
            Vec3 a = normalize(v[i] - p), b = normalize(v[(i + 1) % 3] - p);
            exact += std::acos(std::clamp(dot(a, b), -1.0, 1.0)) * std::fabs(dot(n, normalize(cross(a, b))));
        }
        exact /= 2;
        const int N = 400000;
        double sum = 0, sum2 = 0;
        int failed = 0;
        for (int k = 0; k < N; ++k) {
            LightSample ls;
            double x = 0;
            if (lights.sample(p, U(rng), U(rng), &ls)) {
                x = std::max(0.0, dot(n, ls.wi)) * ls.L.y / ls.pdf;
                // the sampled point lies on the light, and pdf() agrees with the sample's density
                Hit h;
                h.shape = 0, h.prim = 0, h.p = p + ls.wi * ls.dist, h.ng = Vec3(0, 0, -1);
                CHECK(std::fabs(h.p.z - 1) < 1e-9);
                CHECK(std::fabs(lights.pdf(p, h) / ls.pdf - 1) < 1e-9);
            } else {
                ++failed;
            }
            sum += x, sum2 += x * x;
        }
        double mean = sum / N, se = std::sqrt(std::max(0.0, sum2 / N - mean * mean) / N);
        CHECKF(std::fabs(mean - exact) < 4 * se + 1e-4 * exact && failed == 0,
               "z %g: NEE irradiance %.6f +- %.1e, Lambert %.6f, %d samples failed", z, mean, se, exact, failed);
        if (z >= 0) CHECKF(se < 3e-3 * exact, "z %g: standard error %.2e of %.4f: not bounded", z, se, exact);
    }
}

static void test_deterministic()
{
    Scene s = builtin_scene("cornell");
    EmbreeScene rt(s);
    Options o;
    o.width = 40, o.height = 30, o.spp = 12, o.sampler = "hwmmr";
    Accumulator whole = run(s, rt, o);
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        Accumulator again = run(s, rt, o);
        CHECK(again.sum == whole.sum);
    }
    // split ranges add up to the whole run exactly, whatever the split
    for (uint64_t cut : {1ull, 5ull, 11ull}) {
        Options a = o, b = o;
        a.first = 0, a.count = cut, b.first = cut, b.count = o.spp - cut;
        Accumulator x = run(s, rt, a), y = run(s, rt, b);
        int differ = 0;
        for (size_t i = 0; i < whole.sum.size(); ++i) differ += x.sum[i] + y.sum[i] != whole.sum[i];
        CHECKF(differ == 0, "split at %llu: %d sums differ from the whole run", (unsigned long long)cut, differ);
    }
    // a point set (K = spp) too
    o.sampler = "pmj02";
    Accumulator pw = run(s, rt, o);
    Options a = o, b = o;
    a.count = 4, b.first = 4;
    Accumulator x = run(s, rt, a), y = run(s, rt, b);
    for (size_t i = 0; i < pw.sum.size(); ++i) x.sum[i] += y.sum[i];
    CHECK(x.sum == pw.sum);
    // the seed matters
    o.sampler = "hwmmr", o.seed = 2;
    CHECK(run(s, rt, o).sum != whole.sum);
}

static void test_film_round_trip()
{
    Partial p;
    p.made_by = "test render";
    p.spp = 10;
    p.acc.width = 3, p.acc.height = 2, p.acc.first = 2, p.acc.count = 5;
    for (int i = 0; i < 18; ++i) p.acc.sum.push_back((int64_t)i * 0x123456789ll + (i % 3) * 7);  // distinct per channel
    p.acc.sum[4] = (int64_t)1 << 62;
    char path[] = "/tmp/udm1_test_pt_XXXXXX";
    int fd = mkstemp(path);
    close(fd);
    std::string file = std::string(path) + ".exr";
    write_partial(file, p);
    Partial q = read_partial(file);
    CHECK(q.acc.sum == p.acc.sum);
    CHECK(q.made_by == p.made_by && q.spp == 10 && q.acc.first == 2 && q.acc.count == 5);
    CHECK(q.acc.width == 3 && q.acc.height == 2);
    std::remove(file.c_str());
    std::remove(path);
}

int main()
{
    test_furnace();
    test_strategies_agree();
    test_bsdf_consistency();
    test_light_sampling();
    test_deterministic();
    test_film_round_trip();
    CHECK_DONE();
}
