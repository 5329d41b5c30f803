// test_pt_scene.cpp - udm1-pt renders what a pbrt-v4 scene file describes, as pbrt-v4 renders it, or refuses
// it with its file and line: a sphere under any affine transform is the quadric it makes (met in object
// space, normals by the inverse transpose, texture coordinates from the object-space point, checked against
// the world-space quadric solved here), the same image from both path loops; emitters and glass oriented
// by ReverseOrientation and by transforms that swap handedness as pbrt-v4 orients them; what pbrt-v4 itself
// renders inconsistently (sphere lights that are not rigidly placed, spot lights and environment maps under
// transforms that are not similarities, projective transforms) and degenerate lenses refused; reflectance
// spectra clamped to [0, 1] per wavelength as pbrt-v4's materials clamp them.
#include "../c/check.h"

#include "embree_scene.h"
#include "integrator.h"
#include "lights.h"
#include "material.h"
#include "scene.h"
#include "spectrum.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>

using namespace udm1scene;
using namespace udm1pt;

namespace {

const double PI = 3.14159265358979323846;

// The scene text in a temporary .pbrt file, loaded (the file is removed); *error gets a SceneError's text.
bool load_text(const std::string &text, Scene *scene, std::string *error, std::string *path_out = nullptr)
{
    char dir[] = "/tmp/udm1_test_pt_scene_XXXXXX";
    if (!mkdtemp(dir)) return false;
    std::string path = std::string(dir) + "/s.pbrt";
    std::ofstream(path) << text;
    bool ok = true;
    try {
        *scene = load_scene(path);
        Materials materials(*scene);  // material errors too, as udm1-pt loads a scene
        Lights lights(*scene);
    } catch (const SceneError &e) {
        *error = e.what();
        ok = false;
    }
    std::remove(path.c_str());
    rmdir(dir);
    if (path_out) *path_out = path;
    return ok;
}

Scene load(const std::string &text)
{
    Scene s;
    std::string error;
    if (!load_text(text, &s, &error)) {
        std::fprintf(stderr, "unexpected scene error: %s\n", error.c_str());
        ++check_failures;
    }
    return s;
}

// The text is refused with "FILE:line:" and the words in one line.
void check_refused(const std::string &text, int line, const char *words)
{
    Scene s;
    std::string error, path;
    bool ok = load_text(text, &s, &error, &path);
    std::string where = path + ":" + std::to_string(line) + ":";
    CHECKF(!ok && error.find(where) == 0 && error.find(words) != std::string::npos && error.find('\n') == std::string::npos,
           "expected '%s ... %s', got %s", where.c_str(), words, ok ? "no error" : error.c_str());
}

const char *HEAD = "LookAt 0 0 -10  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 30 ]\nWorldBegin\n";

// 3x3 in long double: the tests' own algebra, independent of Mat4's
struct M3 {
    long double a[3][3];
};
M3 part3(const Mat4 &m)
{
    M3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r.a[i][j] = m.m[i][j];
    return r;
}
M3 inverse3(const M3 &m)
{
    const auto &a = m.a;
    long double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                      a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    M3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
            r.a[i][j] = (a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]) / det;
        }
    return r;
}
void apply(const M3 &m, const long double v[3], long double out[3])
{
    for (int i = 0; i < 3; ++i) out[i] = m.a[i][0] * v[0] + m.a[i][1] * v[1] + m.a[i][2] * v[2];
}

// A sheared, rotated, non-uniformly scaled and moved sphere, as the file gives it and as the test composes it.
const char *ELLIPSOID_XF = "Translate 1 -2 0.5\nRotate 37 1 2 3\nScale 2 0.5 1.25\n"
                           "ConcatTransform [ 1 0 0.3 0  0.6 1 0 0  0 0 1 0  0 0 0 1 ]\n";
Mat4 ellipsoid_xf()
{
    Mat4 shear;  // pbrt lists a matrix column by column: column 0 is (1, 0, 0.3), column 1 (0.6, 1, 0)
    shear.m[2][0] = 0.3, shear.m[0][1] = 0.6;
    return Mat4::translate(Vec3(1, -2, 0.5)) * Mat4::rotate(37, Vec3(1, 2, 3)) * Mat4::scale(Vec3(2, 0.5, 1.25)) * shear;
}

// Rays at the ellipsoid x = c + A y, |y| = r: intersect() and occluded() against the quadric solved here in
// world space, and the normals against its gradient A^-T A^-1 (x - c).
void test_ellipsoid_intersections()
{
    const double r = 0.7;
    Scene s = load(std::string(HEAD) + ELLIPSOID_XF + "Shape \"sphere\" \"float radius\" [ 0.7 ]\n");
    if (s.shapes.size() != 1) return;
    EmbreeScene rt(s);
    Mat4 m = ellipsoid_xf();
    M3 B = inverse3(part3(m));
    long double c[3] = {m.m[0][3], m.m[1][3], m.m[2][3]};
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(-1, 1);
    int hits = 0, misses = 0, bad_t = 0, bad_n = 0, bad_hit = 0, bad_occ = 0;
    for (int k = 0; k < 4000; ++k) {
        Vec3 o(8 * U(rng), 8 * U(rng), 8 * U(rng)), target(c[0] + 2.5 * U(rng), c[1] + 2.5 * U(rng), c[2] + 2.5 * U(rng));
        Vec3 d = normalize(target - o);
        // the ray's float values, as Embree sees them
        o = Vec3((float)o.x, (float)o.y, (float)o.z), d = Vec3((float)d.x, (float)d.y, (float)d.z);
        long double oc[3] = {o.x - c[0], o.y - c[1], o.z - c[2]}, dv[3] = {d.x, d.y, d.z}, p[3], q[3];
        apply(B, oc, p), apply(B, dv, q);  // y(t) = p + t q
        long double a = q[0] * q[0] + q[1] * q[1] + q[2] * q[2], b = 2 * (p[0] * q[0] + p[1] * q[1] + p[2] * q[2]);
        long double cc = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - (long double)r * r;
        long double disc = b * b - 4 * a * cc;
        if (std::fabs(disc) < 1e-4L * b * b + 1e-9L || cc < 1e-3L) continue;  // grazing, or starting on it or inside
        Hit h;
        bool got = rt.intersect(o, d, 0.0, 1e300, &h);
        if (disc < 0) {
            ++misses;
            bad_hit += got;
            continue;
        }
        long double t = (-b - std::sqrt(disc)) / (2 * a);
        if (t <= 0) continue;  // behind
        ++hits;
        if (!got) {
            ++bad_hit;
            continue;
        }
        bad_t += std::fabs(h.t - (double)t) > 1e-5 * std::max(1.0, (double)t);
        long double x[3] = {o.x + t * d.x - c[0], o.y + t * d.y - c[1], o.z + t * d.z - c[2]}, y[3], g[3];
        apply(B, x, y);
        for (int i = 0; i < 3; ++i) g[i] = B.a[0][i] * y[0] + B.a[1][i] * y[1] + B.a[2][i] * y[2];  // B^T y
        long double gl = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        double cosang = (double)((g[0] * h.ng.x + g[1] * h.ng.y + g[2] * h.ng.z) / gl);
        bad_n += !(cosang > 1 - 1e-9);
        bad_occ += rt.occluded(o, d, 0.0, (double)t * 0.999) || !rt.occluded(o, d, 0.0, (double)t * 1.001);
    }
    CHECKF(hits > 500 && misses > 500, "%d hits, %d misses", hits, misses);
    CHECKF(bad_hit == 0 && bad_t == 0 && bad_n == 0 && bad_occ == 0,
           "of %d hits and %d misses: %d wrong hit/miss, %d wrong t, %d wrong normals, %d wrong occlusions", hits, misses,
           bad_hit, bad_t, bad_n, bad_occ);
}

// pbrt-v4's texture coordinates of a sphere: longitude and colatitude of the object-space point.
void test_sphere_texture_coordinates()
{
    struct Case {
        const char *text;
        Mat4 m;
        double extent;  // of the shape in world space, about its centre
    } cases[] = {
        {"Translate 0.2 0.1 0\nRotate 90 1 0 0\nRotate 30 0 0 1\nScale 1.5 1.5 1.5\n",  // a world sphere
         Mat4::translate(Vec3(0.2, 0.1, 0)) * Mat4::rotate(90, Vec3(1, 0, 0)) * Mat4::rotate(30, Vec3(0, 0, 1)) *
             Mat4::scale(Vec3(1.5, 1.5, 1.5)),
         1.0},
        {"Scale -1 1 1\n", Mat4::scale(Vec3(-1, 1, 1)), 0.7},  // mirrored
        {ELLIPSOID_XF, ellipsoid_xf(), 1.0},
    };
    for (const Case &c : cases) {
        Scene s = load(std::string(HEAD) + c.text + "Shape \"sphere\" \"float radius\" [ 0.7 ]\n");
        if (s.shapes.size() != 1) continue;
        const Shape &sh = s.shapes[0];
        EmbreeScene rt(s);
        const Mat4 &m = c.m;
        M3 B = inverse3(part3(m));
        std::mt19937_64 rng(11);
        std::uniform_real_distribution<double> U(-1, 1);
        int n = 0, bad = 0;
        for (int k = 0; k < 2000; ++k) {
            Vec3 o(0, 0, -10), target(m.m[0][3] + c.extent * U(rng), m.m[1][3] + c.extent * U(rng), m.m[2][3]);
            Vec3 d = normalize(target - o);
            Hit h;
            if (!rt.intersect(o, d, 0.0, 1e300, &h)) continue;
            long double x[3] = {h.p.x - m.m[0][3], h.p.y - m.m[1][3], h.p.z - m.m[2][3]}, y[3];
            apply(B, x, y);
            long double len = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
            double phi = std::atan2((double)y[1], (double)y[0]);
            if (phi < 0) phi += 2 * PI;
            double u = phi / (2 * PI), v = 1 - std::acos((double)(y[2] / len)) / PI, hu, hv;
            if (u < 1e-3 || u > 1 - 1e-3 || v < 1e-3 || v > 1 - 1e-3) continue;  // the seam and the poles
            hit_uv(sh, h, &hu, &hv);
            ++n;
            bad += std::fabs(hu - u) > 1e-5 || std::fabs(hv - v) > 1e-5;
        }
        CHECKF(n > 500 && bad == 0, "%s: %d of %d hits with other texture coordinates than pbrt-v4's", c.text, bad, n);
    }
}

// The ellipsoid through both path loops: the same image bit for bit (the wavefront loop asks Embree for
// streams of rays, which call the ellipsoid's intersection N rays at a time).
void test_ellipsoid_in_both_loops()
{
    Scene s = load(std::string(HEAD) +
                   "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ]\n"
                   "Shape \"trianglemesh\" \"point3 P\" [ -3 4 -3  3 4 -3  3 4 3  -3 4 3 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n"
                   "AttributeEnd\nMaterial \"dielectric\" \"float roughness\" [ 0.1 ]\nAttributeBegin\n" +
                   ELLIPSOID_XF + "Shape \"sphere\" \"float radius\" [ 0.7 ]\nAttributeEnd\n"
                   "Material \"diffuse\"\nShape \"trianglemesh\" \"point3 P\" [ -9 -4 -9  9 -4 -9  9 -4 9  -9 -4 9 ] "
                   "\"integer indices\" [ 0 1 2 0 2 3 ]\n");
    if (s.shapes.size() != 3) return;
    EmbreeScene rt(s);
    Options o;
    o.width = o.height = 24, o.spp = 8, o.sampler = "sobol-owen";
    Stats st;
    o.loop = Loop::Scalar;
    Accumulator a = render(s, rt, o, &st);
    o.loop = Loop::Wavefront;
    Accumulator b = render(s, rt, o, &st);
    CHECK(a.sum == b.sum);
    int64_t total = 0;
    for (int64_t v : a.sum) total += v;
    CHECK(total > 0);
}

// ReverseOrientation and a transform that swaps handedness flip a one-sided emitter's side, where rays hit
// it and where it is sampled alike (pbrt-v4): a sphere light under ReverseOrientation shines inwards only.
void test_reversed_sphere_light()
{
    Scene s = load(std::string(HEAD) + "ReverseOrientation\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\n"
                                       "Shape \"sphere\" \"float radius\" [ 2 ]\n");
    if (s.shapes.size() != 1) return;
    EmbreeScene rt(s);
    Lights lights(s);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> U(0, 1);
    int outside = 0, inside = 0;
    for (int k = 0; k < 256; ++k) {
        LightSample ls;
        outside += lights.sample(Vec3(0, 0, -6), Vec3(), U(rng), U(rng), &ls);  // nothing reaches the outside
        if (lights.sample(Vec3(0.3, 0.2, 0.1), Vec3(), U(rng), U(rng), &ls)) inside += ls.L.x == 1;
    }
    CHECKF(outside == 0 && inside == 256, "light samples from outside: %d (want 0), from inside: %d (want 256)", outside,
           inside);
    Hit h;  // and the rays that hit it: from outside dark, from inside lit
    CHECK(rt.intersect(Vec3(0, 0, -6), Vec3(0, 0, 1), 0, 1e300, &h) && lights.emitted(h, Vec3(0, 0, -1)).x == 0);
    CHECK(rt.intersect(Vec3(0, 0, 0), Vec3(0, 0, 1), 0, 1e300, &h) && lights.emitted(h, Vec3(0, 0, -1)).x == 1);
}

// A reflection turns a sphere's normals inwards as ReverseOrientation does (pbrt-v4 flips them by orientation
// XOR handedness): a mirrored glass sphere renders as a reversed one, bit for bit (air in glass), and not as
// the plain one.
void test_mirrored_sphere_is_reversed()
{
    Accumulator img[3];
    const char *flips[3] = {"", "ReverseOrientation\n", "Scale -1 1 1\n"};
    for (int k = 0; k < 3; ++k) {
        Scene s = load(std::string(HEAD) + "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
                                           "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
                                           "Shape \"trianglemesh\" \"point3 P\" [ -9 -1.5 -9  9 -1.5 -9  9 -1.5 9  -9 -1.5 9 ] "
                                           "\"integer indices\" [ 0 1 2 0 2 3 ]\nMaterial \"dielectric\"\n" +
                       flips[k] + "Shape \"sphere\" \"float radius\" [ 1.5 ]\n");
        if (s.shapes.size() != 2) return;
        EmbreeScene rt(s);
        Options o;
        o.width = o.height = 16, o.spp = 16, o.sampler = "sobol-owen";
        Stats st;
        img[k] = render(s, rt, o, &st);
    }
    CHECK(img[1].sum == img[2].sum && img[0].sum != img[1].sum);
}

// Vertex normals under ReverseOrientation are flipped (pbrt-v4's TriangleMesh), and the geometric normal
// faces them: a one-sided emitter with normals shines the other way.
void test_reversed_vertex_normals()
{
    const std::string quad = "Shape \"trianglemesh\" \"point3 P\" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ] "
                             "\"normal N\" [ 0 -1 0  0 -1 0  0 -1 0  0 -1 0 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n";
    for (bool reverse : {false, true}) {
        Scene s = load(std::string(HEAD) + (reverse ? "ReverseOrientation\n" : "") + quad);
        if (s.shapes.size() != 1) continue;
        CHECKF(triangle_normal(s.shapes[0], 0).y == (reverse ? 1 : -1) && s.shapes[0].N[1] == (reverse ? 1 : -1),
               "reverse %d: normal %g, vertex normal %g", reverse, triangle_normal(s.shapes[0], 0).y, s.shapes[0].N[1]);
    }
}

// What pbrt-v4 renders inconsistently or degenerately is refused with the file and line.
void test_refusals()
{
    std::string h = HEAD;  // 3 lines: the shape below is on line 4 or later
    const std::string sphere = "Shape \"sphere\" \"float radius\" [ 1 ]\n";
    const std::string light = "AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\n";
    check_refused(h + light + "Scale 2 2 2\n" + sphere, 6, "scales or shears");
    check_refused(h + light + "Scale 1 1 3\n" + sphere, 6, "scales or shears");
    check_refused(h + light + "Scale -1 1 1\n" + sphere, 6, "swaps handedness");
    check_refused(h + "Transform [ 1 0 0 0  0 1 0 0  0 0 1 0.5  0 0 0 1 ]\n" + sphere, 5, "projective");
    check_refused(h + "Scale 1 2 1\nLightSource \"spot\"\n" + sphere, 5, "spot");
    check_refused(h + "Rotate 30 0 1 0\nScale 1 1 2\nLightSource \"infinite\" \"string filename\" \"sky.exr\"\n" + sphere, 6,
                  "untransformed image");
    check_refused(h + "Transform [ 1 0 0 0  0 1 0 0  0 0 1 1  0 0 0 1 ]\nLightSource \"point\"\n" + sphere, 5, "projective");
    check_refused("Transform [ 1 0 0 0  0 1 0 0  0 0 1 1  0 0 0 2 ]\nCamera \"perspective\"\nWorldBegin\n" + sphere, 2,
                  "projective");
    check_refused("Camera \"perspective\" \"float lensradius\" 0.1 \"float focaldistance\" 0\nWorldBegin\n" + sphere, 1,
                  "focaldistance 0");
    check_refused("Camera \"perspective\" \"float lensradius\" 0.1\n \"float focaldistance\" -2\nWorldBegin\n" + sphere, 2,
                  "focaldistance -2");
    check_refused("Camera \"perspective\" \"float lensradius\" -0.1\nWorldBegin\n" + sphere, 1, "lensradius -0.1");
    check_refused(h + "Transform [ 1 0 0 0  0 1 0 0  0 0 1 1  0 0 0 1 ]\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0 ] "
                      "\"normal N\" [ 0 0 1  0 0 1  0 0 1 ]\n", 5, "projective");
    // and what pbrt-v4 renders consistently is accepted: rigid sphere lights, a two-sided one mirrored,
    // a spot under a rotation and uniform scale, a lens of radius 0 whatever its focal distance
    Scene s;
    std::string error;
    for (const std::string &text :
         {h + light + "Rotate 40 1 1 0\nTranslate 1 2 3\n" + sphere,
          h + "AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ] \"bool twosided\" true\nScale -1 1 1\n" + sphere,
          h + "Rotate 30 1 0 0\nScale 3 3 3\nLightSource \"spot\"\n" + sphere,
          std::string("Camera \"perspective\" \"float lensradius\" 0 \"float focaldistance\" 0\nWorldBegin\n") + sphere})
        CHECKF(load_text(text, &s, &error), "refused: %s", error.c_str());
}

// Reflectance spectra are clamped to [0, 1] at every wavelength before they become RGB (pbrt-v4's materials
// clamp them; an RGB albedo above 1 is refused): a constant 2 reflects as 1, a constant -1 as 0, and a
// spectrum crossing 1 as the clamped one.
void test_albedo_spectra_clamped()
{
    auto rgb = [](std::vector<double> pairs) { return albedo_rgb(spectrum_from_pairs(pairs, "test")); };
    Vec3 two = rgb({300, 2, 900, 2}), neg = rgb({300, -1, 900, -1}), one = rgb({300, 1, 900, 1});
    CHECKF(std::fabs(two.x - 1) < 1e-9 && std::fabs(two.y - 1) < 1e-9 && std::fabs(two.z - 1) < 1e-9, "%g %g %g", two.x,
           two.y, two.z);
    CHECK(two.x == one.x && two.y == one.y && two.z == one.z);
    CHECK(neg.x == 0 && neg.y == 0 && neg.z == 0);
    Vec3 a = rgb({400, 0, 500, 8, 600, 0.5, 700, 2});
    Vec3 b = rgb({400, 0, 412.5, 1, 500, 1, 593.3333333333333, 1, 600, 0.5, 633.3333333333333, 1, 700, 1});
    CHECKF(std::fabs(a.x - b.x) < 1e-12 && std::fabs(a.y - b.y) < 1e-12 && std::fabs(a.z - b.z) < 1e-12,
           "%.15g %.15g %.15g against %.15g %.15g %.15g", a.x, a.y, a.z, b.x, b.y, b.z);
}

// An ObjectInstance is its object's shapes under the instance's transform times their own (pbrt-v4's
// composition): rays meet an instanced scene where they meet the same shapes written out under the composed
// transform - the same shape, t, point and geometric normal (by the inverse transpose), texture coordinates
// from the object's data - within float rounding (Embree transforms the ray in float). Meshes with vertex
// normals and uv, a sphere under a similarity and one made an ellipsoid by the instance, and a mirroring
// instance, whose sphere keeps its outward normal (pbrt-v4 flips a sphere's normal where its own transform
// swaps handedness, not where an instance's does).
void test_instances_equal_flattened_shapes()
{
    // (written out under a mirroring transform, the sphere is reversed back: ReverseOrientation around it)
    auto object = [](bool reverse_sphere) {
        std::string r = reverse_sphere ? "ReverseOrientation\n" : "";
        return "Translate 0.5 0 0\n" + r + "Shape \"sphere\" \"float radius\" 0.6\n" + r +
               "Shape \"trianglemesh\" \"point3 P\" [ -1 0 0  1 0 0  0 2 0.3 ] "
               "\"normal N\" [ 0 0.2 -1  0.3 0 -1  -0.3 0 -1 ] \"point2 uv\" [ 0 0 1 0 0.5 1 ]\n";
    };
    const char *places[] = {"Translate -1.5 0.7 0\nRotate 30 0 1 0\nScale 1 1.3 0.8\n",
                            "Translate 1.6 0.6 0.5\nRotate -50 1 1 0\nScale 0.7 0.7 0.7\n",
                            "Translate 0 -1 1\nScale -1 1 1\n"};
    std::string inst = std::string(HEAD) + "ObjectBegin \"o\"\n" + object(false) + "ObjectEnd\n", flat = HEAD;
    for (const char *p : places) {
        inst += std::string("AttributeBegin\n") + p + "ObjectInstance \"o\"\nAttributeEnd\n";
        bool mirror = std::string(p).find("Scale -1") != std::string::npos;
        flat += std::string("AttributeBegin\n") + p + object(mirror) + "AttributeEnd\n";
    }
    Scene a = load(inst), b = load(flat);
    if (a.instances.size() != 3 || b.shapes.size() != 6) {
        CHECKF(false, "instances %zu, shapes %zu", a.instances.size(), b.shapes.size());
        return;
    }
    EmbreeScene ra(a), rb(b);
    CameraRays camera(a);
    int rays = 0, hits = 0, differ = 0, instance_hits = 0;
    double worst_t = 0, worst_n = 0, worst_uv = 0;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) {
            Vec3 o, d;
            camera.ray((x + 0.5) * a.width / 96.0, (y + 0.5) * a.height / 96.0, &o, &d);
            Hit ha, hb;
            bool fa = ra.intersect(o, d, 0.0, 1e300, &ha), fb = rb.intersect(o, d, 0.0, 1e300, &hb);
            ++rays;
            if (fa != fb || (fa && a.shapes[ha.shape].kind != b.shapes[hb.shape].kind)) {
                ++differ;  // a ray through an edge, moved across it by a rounding
                continue;
            }
            if (!fa) continue;
            ++hits;
            instance_hits += ha.instance != nullptr;
            worst_t = std::max(worst_t, std::fabs(ha.t - hb.t) / hb.t);
            worst_n = std::max(worst_n, length(ha.ng - hb.ng));
            double ua, va, ub, vb;
            hit_uv(a.shapes[ha.shape], ha, &ua, &va), hit_uv(b.shapes[hb.shape], hb, &ub, &vb);
            worst_uv = std::max({worst_uv, std::fabs(ua - ub), std::fabs(va - vb)});
        }
    CHECKF(instance_hits > rays / 10 && differ <= rays / 200, "%d of %d rays hit instances, %d differ", instance_hits,
           rays, differ);
    CHECKF(worst_t < 2e-6 && worst_n < 2e-5 && worst_uv < 1e-4, "t %g, normal %g, uv %g", worst_t, worst_n, worst_uv);
    std::printf("instances: %d rays, %d hits (%d through instances), %d differ; t %.3g, normal %.3g, uv %.3g\n", rays,
                hits, instance_hits, differ, worst_t, worst_n, worst_uv);
}

}  // namespace

int main()
{
    test_ellipsoid_intersections();
    test_sphere_texture_coordinates();
    test_ellipsoid_in_both_loops();
    test_reversed_sphere_light();
    test_mirrored_sphere_is_reversed();
    test_reversed_vertex_normals();
    test_refusals();
    test_albedo_spectra_clamped();
    test_instances_equal_flattened_shapes();
    CHECK_DONE();
}
