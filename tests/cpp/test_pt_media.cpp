// test_pt_media.cpp - udm1-pt's participating media (Integrator "volpath", pt/media.h) against closed forms:
// the transmittance exp(-sigma_t d) of an absorbing slab, with the medium inside or outside its shape as
// MediumInterface and the surface's orientation put it, and around the camera; the radiance
// Lescale Le (1 - exp(-sigma_a d)) of a glowing slab and Le (1 - a^D) of an infinite glowing medium of
// scattering albedo a at maximum depth D; energy conserved by a scattering sphere (chromatic, anisotropic,
// bare or inside glass) in a white furnace; the three light-finding strategies agreeing in the mean through
// chromatic scattering media; interface surfaces invisible; the Henyey-Greenstein phase function
// normalized, sampled by its density, of mean cosine g; both path loops rendering the same image.
#include "../c/check.h"
#include "scene_text.h"

#include "embree_scene.h"
#include "integrator.h"
#include "lights.h"
#include "material.h"
#include "media.h"
#include "scene.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>

using namespace udm1scene;
using namespace udm1pt;

namespace {

Scene load(const std::string &text) { return load_scene_text(text); }

double image_mean(const Accumulator &a, int channel)
{
    std::vector<float> m = a.mean();
    double s = 0;
    for (size_t i = channel; i < m.size(); i += 3) s += m[i];
    return s / (m.size() / 3);
}

Accumulator run(const Scene &s, Options o, Stats *st = nullptr)
{
    EmbreeScene rt(s);
    Stats local;
    return render(s, rt, o, st ? st : &local);
}

// The mean of each channel over seeds 1..n and its standard error (the spread of the per-seed means).
struct Estimate {
    double mean[3], se[3];
};
Estimate estimate(const Scene &s, Options o, int seeds)
{
    EmbreeScene rt(s);
    std::vector<double> m[3];
    for (int k = 0; k < seeds; ++k) {
        o.seed = 1 + (uint64_t)k;
        Stats st;
        Accumulator a = render(s, rt, o, &st);
        for (int c = 0; c < 3; ++c) m[c].push_back(image_mean(a, c));
    }
    Estimate e;
    for (int c = 0; c < 3; ++c) {
        double mu = 0, v = 0;
        for (double x : m[c]) mu += x;
        mu /= seeds;
        for (double x : m[c]) v += (x - mu) * (x - mu);
        e.mean[c] = mu, e.se[c] = std::sqrt(v / (seeds - 1) / seeds);
    }
    return e;
}

// Within 5 standard errors, or `floor` relative.
bool agree(double a, double sa, double b, double sb, double floor)
{
    return std::fabs(a - b) <= std::max(5 * std::sqrt(sa * sa + sb * sb), floor * std::fabs(b));
}

// A camera at z = -5 looking down +z through a narrow field (rays within 0.15 degrees of the axis) at an
// emitter of radiance 1 filling the view at z = 5; `world` is added after WorldBegin, `before` before the
// camera, `emitter` false leaves the emitter out.
std::string view(const std::string &world, const std::string &before = "", bool emitter = true,
                 const std::string &integrator = "Integrator \"volpath\" \"integer maxdepth\" [ 5 ]\n")
{
    std::string s = before +
                    "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 0.2 ]\n"
                    "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\n" +
                    integrator + "WorldBegin\n";
    if (emitter)
        s += "AttributeBegin\n AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\n Material \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\n"
             " Shape \"trianglemesh\" \"point3 P\" [ -10 -10 5  10 -10 5  10 10 5  -10 10 5 ] \"integer indices\" [ 0 2 1 0 3 2 ]\n"
             "AttributeEnd\n";
    return s + world;
}

// The cube [-h, h]^3 about `at`, its triangles' normals outwards (no vertex normals).
std::string cube(double h, const char *at = "0 0 0")
{
    char buf[600];
    std::snprintf(buf, sizeof buf,
                  "Translate %s\nShape \"trianglemesh\" \"point3 P\" [ -%g -%g -%g  %g -%g -%g  %g %g -%g  -%g %g -%g  "
                  "-%g -%g %g  %g -%g %g  %g %g %g  -%g %g %g ]\n"
                  " \"integer indices\" [ 0 2 1 0 3 2  4 5 6 4 6 7  0 5 4 0 1 5  3 6 2 3 7 6  0 7 3 0 4 7  1 6 5 1 2 6 ]\n",
                  at, h, h, h, h, h, h, h, h, h, h, h, h, h, h, h, h, h, h, h, h, h, h, h, h);
    return buf;
}

const char *INK = "MakeNamedMedium \"ink\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.5 1 2 ] \"rgb sigma_s\" [ 0 0 0 ]\n";

// Within `rel` relative and the accumulator's resolution (2^-24 a sample). A ray that passes a surface
// starts a few 1e-6 past it (udm1scene::ray_offset): a medium's path is that much shorter.
void check_rgb(const Accumulator &a, Vec3 want, double rel, const char *what)
{
    for (int c = 0; c < 3; ++c)
        CHECKF(std::fabs(image_mean(a, c) - want[c]) <= rel * want[c] + 1e-7, "%s, channel %d: %.9g, expected %.9g", what,
               c, image_mean(a, c), want[c]);
}

Vec3 expv(Vec3 s, double d) { return Vec3(std::exp(-s.x * d), std::exp(-s.y * d), std::exp(-s.z * d)); }

void test_absorbing_slab()
{
    Options o;
    o.spp = 4;
    const Vec3 ink(0.5, 1, 2);
    // the unit cube with the medium inside (its normals face out: "outside" is outside): exp(-sigma_a 1)
    Scene in = load(view(std::string(INK) + "Material \"interface\"\nMediumInterface \"ink\" \"\"\n" + cube(0.5)));
    Stats st;
    Accumulator a = run(in, o, &st);
    check_rgb(a, expv(ink, 1), 1e-4, "ink inside a unit cube");
    CHECK(std::string(st.loop) == "wavefront-general");  // (media are outside the diffuse wavefront loop)
    // each path loop the same, bit for bit
    o.loop = Loop::Scalar;
    CHECK(run(in, o).sum == a.sum);
    o.loop = Loop::Auto;
    // "" "ink": inside nothing, outside the ink, as pbrt-v4 assigns it by the normal: a ray leaving the cube
    // on its normals' side travels in the ink to the emitter, 4.5 away
    Scene out = load(view(std::string(INK) + "Material \"interface\"\nMediumInterface \"\" \"ink\"\n" + cube(0.5)));
    check_rgb(run(out, o), expv(ink, 4.5), 1e-4, "ink outside a unit cube");  // (a blue of 1e-4: to 1e-3)
    // ReverseOrientation turns the cube's normals in: the same MediumInterface puts the ink inside again
    Scene rev = load(view(std::string(INK) + "ReverseOrientation\nMaterial \"interface\"\nMediumInterface \"\" \"ink\"\n" +
                          cube(0.5)));
    check_rgb(run(rev, o), expv(ink, 1), 1e-4, "ink outside a reversed cube");
    // the camera in the ink (the outside medium at Camera, kept across WorldBegin): 10 to the emitter
    Scene cam = load(view("", "MakeNamedMedium \"haze\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.05 0.1 0.2 ] "
                              "\"rgb sigma_s\" [ 0 0 0 ]\nMediumInterface \"\" \"haze\"\n"));
    check_rgb(run(cam, o), expv(Vec3(0.05, 0.1, 0.2), 10), 1e-4, "the camera in the haze");
    // the same medium by a spectrum: a constant spectrum reduces to its constant, pbrt-v4's "scale" multiplies
    Scene sp = load(view("MakeNamedMedium \"ink\" \"string type\" \"homogeneous\" \"spectrum sigma_a\" [ 300 0.25 800 0.25 ]"
                         " \"rgb sigma_s\" [ 0 0 0 ] \"float scale\" [ 4 ]\nMaterial \"interface\"\nMediumInterface \"ink\" \"\"\n" +
                         cube(0.5)));
    check_rgb(run(sp, o), expv(Vec3(1, 1, 1), 1), 1e-4, "a constant spectrum sigma_a 0.25, scale 4");
    // a preset: pbrt-v4's table (Ketchup: sigma_a 0.061 0.97 1.45 per mm, its sigma'_s as sigma_s); the
    // scattering is seen as extinction along the axis, minus what scatters back into it (small: 1 % at most)
    Scene pre = load(view("MakeNamedMedium \"k\" \"string type\" \"homogeneous\" \"string preset\" \"Ketchup\"\n"
                          "Material \"interface\"\nMediumInterface \"k\" \"\"\n" + cube(0.5)));
    CHECK(pre.media.size() == 1 && pre.media[0].sigma_a.y == 0.97 && pre.media[0].sigma_s.x == 0.18);
    // Integrator "path" leaves media out, as pbrt-v4's PathIntegrator: the emitter as it is
    Scene path = load(view(std::string(INK) + "Material \"interface\"\nMediumInterface \"ink\" \"\"\n" + cube(0.5), "", true,
                           "Integrator \"path\"\n"));
    check_rgb(run(path, o), Vec3(1, 1, 1), 1e-6, "Integrator path");
}

// A floor lit straight down by a distant light, seen straight down, the camera and the floor in a haze that
// only absorbs: pbrt-v4 ends a shadow ray to a light at infinity at twice the scene's bounding radius R, so the
// floor receives exp(-sigma 2 R) of the light: (0.5 / pi) exp(-sigma (2 R + h)) from height h. A uniform sky adds
// nothing: pbrt-v4's volumetric path tracer leaves it to BSDF sampling, whose rays never leave the haze.
void test_light_at_infinity_through_a_medium()
{
    Scene s = load("MakeNamedMedium \"haze\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.1 0.2 0.4 ] "
                   "\"rgb sigma_s\" [ 0 0 0 ]\nMediumInterface \"\" \"haze\"\n"
                   "LookAt 0 3 0  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 0.2 ]\n"
                   "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\n"
                   "Integrator \"volpath\"\nWorldBegin\n"
                   "LightSource \"distant\" \"point3 from\" [ 0 1 0 ] \"point3 to\" [ 0 0 0 ] \"rgb L\" [ 1 1 1 ]\n"
                   "LightSource \"infinite\" \"rgb L\" [ 5 5 5 ]\n"
                   "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
                   "Shape \"trianglemesh\" \"point3 P\" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ] \"integer indices\" [ 0 2 1 0 3 2 ]\n");
    Options o;
    o.spp = 4;
    const double R = std::sqrt(2.0), PI = 3.14159265358979323846;
    Vec3 T = expv(Vec3(0.1, 0.2, 0.4), 2 * R + 3);
    check_rgb(run(s, o), T * (0.5 / PI), 1e-4, "a floor under a distant light in a haze");
}

void test_glowing_medium()
{
    Options o;
    o.spp = 4;
    const char *glow = "MakeNamedMedium \"glow\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.5 1 2 ] \"rgb sigma_s\" [ 0 0 0 ] "
                       "\"rgb Le\" [ 1 2 3 ] \"float Lescale\" [ 2 ]\n";
    // a unit slab that emits sigma_a Le per unit length and absorbs: Lescale Le (1 - exp(-sigma_a))
    Scene s = load(view(std::string(glow) + "Material \"interface\"\nMediumInterface \"glow\" \"\"\n" + cube(0.5), "", false));
    Vec3 T = expv(Vec3(0.5, 1, 2), 1);
    check_rgb(run(s, o), Vec3(2 * (1 - T.x), 4 * (1 - T.y), 6 * (1 - T.z)), 1e-4, "a glowing unit slab");
    // pbrt-v4 adds a medium's emission below the maximum depth only: none at maxdepth 0
    o.max_depth = 0;
    check_rgb(run(s, o), Vec3(), 0, "a glowing slab at maxdepth 0");
    o.max_depth = -1;
    // inside an infinite glowing medium that absorbs: Lescale Le
    Scene inf = load(view("AttributeBegin\nTranslate 0 0 1e4\nShape \"sphere\" \"float radius\" [ 1 ]\nAttributeEnd\n",
                          std::string(glow) + "MediumInterface \"glow\"\n", false));
    check_rgb(run(inf, o), Vec3(2, 4, 6), 1e-9, "inside an infinite glowing medium");
    // ... that also scatters, albedo a: the emission of D segments, Le (1 - a^D) at maximum depth D. Chromatic,
    // blue only absorbs: a path whose distances blue draws never scatters, and only the weighting of every
    // channel by the average of the channels' densities finds red and green's scattered light in full
    // (drawing by one channel and dividing by its density alone would miss a third of it)
    Scene sc = load(view("AttributeBegin\nTranslate 0 0 1e4\nShape \"sphere\" \"float radius\" [ 1 ]\nAttributeEnd\n",
                         "MakeNamedMedium \"glow\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.5 1 0.25 ] "
                         "\"rgb sigma_s\" [ 0.5 1 0 ] \"rgb Le\" [ 1 2 3 ] \"float g\" [ -0.3 ]\nMediumInterface \"glow\"\n",
                         false, "Integrator \"volpath\" \"integer maxdepth\" [ 3 ]\n"));
    o.width = o.height = 8, o.spp = 64;
    Estimate e = estimate(sc, o, 4);
    const double want[3] = {1 * (1 - 0.125), 2 * (1 - 0.125), 3};
    for (int c = 0; c < 3; ++c)
        CHECKF(agree(e.mean[c], e.se[c], want[c], 0, 0.01), "infinite scattering glow, channel %d: %.5f +- %.5f, expected %.5f",
               c, e.mean[c], e.se[c], want[c]);
}

// A sphere of medium that only scatters (chromatic, anisotropic) in a white environment: energy is conserved,
// the image is 1 everywhere; so it is inside glass (a lossless boundary).
void test_scattering_furnace()
{
    const char *head = "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 30 ]\n"
                       "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
                       "Integrator \"volpath\" \"integer maxdepth\" [ 1000 ]\nWorldBegin\n"
                       "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
                       "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0 0 0 ] "
                       "\"rgb sigma_s\" [ 1 2 4 ] \"float g\" [ 0.5 ]\n";
    for (const char *material : {"Material \"interface\"\n", "Material \"dielectric\" \"float eta\" [ 1.5 ]\n"}) {
        Scene s = load(std::string(head) + material + "MediumInterface \"fog\" \"\"\nShape \"sphere\" \"float radius\" [ 1 ]\n");
        Options o;
        o.spp = 64;
        Estimate e = estimate(s, o, 4);
        for (int c = 0; c < 3; ++c)
            CHECKF(agree(e.mean[c], e.se[c], 1, 0, 0.01), "%s furnace, channel %d: %.5f +- %.5f, expected 1", material, c,
                   e.mean[c], e.se[c]);
    }
}

// A Cornell-like box with a chromatic scattering sphere, a glass sphere of chromatic absorbing and scattering
// medium, a glowing cube, an area light and (with `point`) a point light in the fog.
std::string media_box(bool point)
{
    std::string s =
        "LookAt 0 0 -3.4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 12 ] \"integer yresolution\" [ 12 ]\n"
        "Integrator \"volpath\" \"integer maxdepth\" [ 8 ]\nWorldBegin\n"
        "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.1 0.05 0.2 ] \"rgb sigma_s\" [ 1 2.5 4 ] "
        "\"float g\" [ 0.6 ]\n"
        "MakeNamedMedium \"ruby\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.1 0.6 0.9 ] \"rgb sigma_s\" [ 0.5 0.3 0 ]\n"
        "MakeNamedMedium \"glow\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 1.5 1.5 1.5 ] \"rgb sigma_s\" [ 0.5 0.5 0.5 ] "
        "\"rgb Le\" [ 1 0.6 0.3 ]\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 12 12 12 ]\n"
        "Shape \"trianglemesh\" \"point3 P\" [ -0.3 0.999 -0.3  0.3 0.999 -0.3  0.3 0.999 0.3  -0.3 0.999 0.3 ] "
        "\"integer indices\" [ 0 1 2 0 2 3 ]\nAttributeEnd\n"
        "Material \"diffuse\" \"rgb reflectance\" [ 0.7 0.7 0.7 ]\n"
        "Shape \"trianglemesh\" \"point3 P\" [ -1 -1 -1  1 -1 -1  1 -1 1  -1 -1 1 ] \"integer indices\" [ 0 2 1 0 3 2 ]\n"
        "Shape \"trianglemesh\" \"point3 P\" [ -1 1 -1  1 1 -1  1 1 1  -1 1 1 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n"
        "Shape \"trianglemesh\" \"point3 P\" [ -1 -1 1  1 -1 1  1 1 1  -1 1 1 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n"
        "Material \"diffuse\" \"rgb reflectance\" [ 0.65 0.1 0.1 ]\n"
        "Shape \"trianglemesh\" \"point3 P\" [ -1 -1 -1  -1 -1 1  -1 1 1  -1 1 -1 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n"
        "AttributeBegin\nMaterial \"interface\"\nMediumInterface \"fog\" \"\"\nTranslate -0.45 -0.5 0.25\n"
        "Shape \"sphere\" \"float radius\" [ 0.45 ]\nAttributeEnd\n"
        "AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nMediumInterface \"ruby\" \"\"\nTranslate 0.45 -0.6 -0.2\n"
        "Shape \"sphere\" \"float radius\" [ 0.4 ]\nAttributeEnd\n"
        "AttributeBegin\nMaterial \"interface\"\nMediumInterface \"glow\" \"\"\n" + cube(0.2, "0.35 0.3 0.5") + "AttributeEnd\n";
    if (point) s += "LightSource \"point\" \"point3 from\" [ -0.45 -0.5 0.25 ] \"rgb I\" [ 0.5 0.5 0.5 ]\n";
    return s;
}

void test_strategies_agree()
{
    Options o;
    o.spp = 128;
    for (bool point : {false, true}) {
        Scene s = load(media_box(point));
        o.strategy = Strategy::Mis;
        Estimate mis = estimate(s, o, 4);
        for (Strategy st : {Strategy::Nee, Strategy::Bsdf}) {
            if (point && st == Strategy::Bsdf) continue;  // (BSDF and phase sampling never find a point light)
            o.strategy = st;
            Estimate e = estimate(s, o, 4);
            for (int c = 0; c < 3; ++c)
                CHECKF(agree(e.mean[c], e.se[c], mis.mean[c], mis.se[c], 0.005),
                       "media box%s, strategy %d, channel %d: %.5f +- %.5f, MIS %.5f +- %.5f", point ? " with a point light" : "",
                       (int)st, c, e.mean[c], e.se[c], mis.mean[c], mis.se[c]);
        }
    }
}

// The same box without its spheres, with the fog as a cube (triangles only: Embree's streams return the hits
// of single queries): the scalar and the wavefront loop render it bit for bit, and sample ranges add up.
void test_loops_agree()
{
    std::string text = media_box(true);
    size_t a = text.find("AttributeBegin\nMaterial \"interface\"\nMediumInterface \"fog\"");
    size_t b = text.find("AttributeBegin\nMaterial \"interface\"\nMediumInterface \"glow\"");
    text = text.substr(0, a) + "AttributeBegin\nMaterial \"interface\"\nMediumInterface \"fog\" \"\"\n" + cube(0.4, "-0.4 -0.5 0.2") +
           "AttributeEnd\n" + text.substr(b);
    Scene s = load(text);
    Options o;
    o.spp = 16, o.sampler = "wmmr";
    Stats sw, ss;
    Accumulator w = run(s, o, &sw);
    o.loop = Loop::Scalar;
    Accumulator sc = run(s, o, &ss);
    CHECK(std::string(sw.loop) == "wavefront-general" && std::string(ss.loop) == "scalar");
    CHECK(sw.rays == ss.rays && w.sum == sc.sum);
    Options x = o, y = o;
    x.count = 5, y.first = 5;
    Accumulator p = run(s, x), q = run(s, y);
    for (size_t i = 0; i < p.sum.size(); ++i) p.sum[i] += q.sum[i];
    CHECK(p.sum == sc.sum);
}

// Interface surfaces without media are invisible: a box of them around a diffuse sphere renders the image
// of the scene with one far out of sight, path for path (the same sampler values: passing a surface draws
// none), within float rounding of the rays' origins.
void test_interface_invisible()
{
    for (const char *integrator : {"volpath", "path"}) {
        std::string head = std::string("LookAt 0 0 -3.4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
                                       "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n"
                                       "Integrator \"") + integrator + "\"\nWorldBegin\n"
                           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 12 12 12 ]\n"
                           "Shape \"trianglemesh\" \"point3 P\" [ -0.3 0.999 -0.3  0.3 0.999 -0.3  0.3 0.999 0.3  -0.3 0.999 0.3 ] "
                           "\"integer indices\" [ 0 1 2 0 2 3 ]\nAttributeEnd\n"
                           "Material \"diffuse\" \"rgb reflectance\" [ 0.7 0.7 0.7 ]\n"
                           "Shape \"trianglemesh\" \"point3 P\" [ -1 -1 -1  1 -1 -1  1 -1 1  -1 -1 1 ] \"integer indices\" [ 0 2 1 0 3 2 ]\n"
                           "Shape \"trianglemesh\" \"point3 P\" [ -1 1 -1  1 1 -1  1 1 1  -1 1 1 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n"
                           "Shape \"trianglemesh\" \"point3 P\" [ -1 -1 1  1 -1 1  1 1 1  -1 1 1 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n"
                           "AttributeBegin\nTranslate 0.2 -0.5 0\nShape \"sphere\" \"float radius\" [ 0.4 ]\nAttributeEnd\n"
                           "Material \"interface\"\n";
        Scene boxed = load(head + cube(0.6, "0.1 -0.35 0"));  // (clear of the walls: no coplanar faces)
        Scene far = load(head + cube(0.001, "0 0 -1000"));
        Scene none = load(head.substr(0, head.rfind("Material \"interface\"")));
        Options o;
        o.spp = 64;
        std::vector<float> a = run(boxed, o).mean(), b = run(far, o).mean();
        double worst = 0, sum_a = 0, sum_b = 0;
        int off = 0;
        for (size_t i = 0; i < a.size(); ++i) {
            double d = std::fabs(a[i] - b[i]) / std::max(1e-3f, b[i]);
            worst = std::max(worst, d), off += d > 1e-4, sum_a += a[i], sum_b += b[i];
        }
        CHECKF(off <= (int)a.size() / 100 && std::fabs(sum_a / sum_b - 1) < 1e-4,
               "%s: an interface box changes %d of %zu values by more than 1e-4 (the largest by %.3g), the mean by %.3g",
               integrator, off, a.size(), worst, sum_a / sum_b - 1);
        // and the scene without interface surfaces (the path estimator: power heuristic) in the mean
        o.spp = 256;
        Estimate e = estimate(none, o, 4), f = estimate(far, o, 4);
        for (int c = 0; c < 3; ++c)
            CHECKF(agree(f.mean[c], f.se[c], e.mean[c], e.se[c], 0.003), "%s: channel %d: %.5f +- %.5f, without %.5f +- %.5f",
                   integrator, c, f.mean[c], f.se[c], e.mean[c], e.se[c]);
    }
}

void test_phase_function()
{
    const double PI = 3.14159265358979323846;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(0, 1);
    for (double c : {-1.0, -0.3, 0.0, 0.8, 1.0}) CHECK(hg_phase(c, 1.5) == hg_phase(c, 0.99) && hg_phase(c, -3) == hg_phase(c, -0.99));
    for (double g : {-0.7, 0.0, 0.0005, 0.3, 0.9, 1.5}) {
        // normalized over the sphere (midpoint rule in cos theta)
        double integral = 0;
        const int N = 200000;
        for (int i = 0; i < N; ++i) integral += 2 * PI * hg_phase(-1 + (i + 0.5) * 2.0 / N, g) * 2.0 / N;
        CHECKF(std::fabs(integral - 1) < (g > 0.95 ? 2e-3 : 1e-4), "g %g: the phase function integrates to %.6f", g, integral);
        // sampled by its density, mean cosine with the direction of propagation g (clamped to 0.99)
        Vec3 wo = normalize(Vec3(0.3, -0.5, 0.8));
        double sum = 0, worst = 0;
        const int M = 200000;
        for (int i = 0; i < M; ++i) {
            double pdf;
            Vec3 wi = sample_hg(wo, g, U(rng), U(rng), &pdf);
            worst = std::max(worst, std::fabs(length(wi) - 1) + std::fabs(pdf / hg_phase(dot(wo, wi), g) - 1));
            sum += dot(-wo, wi);
        }
        double gc = std::min(g, 0.99), se = std::sqrt((1 - gc * gc) / 3 / M) + 1e-4;
        CHECKF(worst < 1e-8, "g %g: a sample's density or length is off by %.3g", g, worst);
        CHECKF(std::fabs(sum / M - gc) < 5 * se, "g %g: mean cosine %.5f, expected %.5f", g, sum / M, gc);
    }
}

}  // namespace

int main()
{
    test_phase_function();
    test_absorbing_slab();
    test_glowing_medium();
    test_light_at_infinity_through_a_medium();
    test_scattering_furnace();
    test_strategies_agree();
    test_loops_agree();
    test_interface_invisible();
    CHECK_DONE();
}
