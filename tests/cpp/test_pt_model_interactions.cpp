// test_pt_model_interactions.cpp - pbrt-v4's shapes, alpha cut-outs and textures of udm1-pt where they meet
// the rest of the format: inside object instances (each shape kind, instanced, hit where and as the same
// shape placed directly is: point, normals, texture coordinates, derivatives, textured material, alpha
// cut-outs); names resolved when the scene is complete (an alpha texture or a texture's input made after its
// use) and file names by pbrt-v4's path rule inside included files; alpha cut-outs passed by both of
// Integrator "volpath"'s loops, their paths and their shadow rays, and the new shapes as media boundaries.
#include "../c/check.h"

#include "embree_scene.h"
#include "integrator.h"
#include "material.h"
#include "scene.h"
#include "surface.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

using namespace udm1scene;
using namespace udm1pt;

namespace {

// The scene text loaded from `dir`/s.pbrt (a fresh temporary folder if dir is empty), or an empty scene
// after a failed check.
Scene load_text(const std::string &text, const std::string &dir = "", std::string *error = nullptr)
{
    std::string d = dir;
    if (d.empty()) {
        char tmpl[] = "/tmp/udm1_test_pt_interactions_XXXXXX";
        if (!mkdtemp(tmpl)) return Scene();
        d = tmpl;
    }
    std::string path = d + "/s.pbrt";
    std::ofstream(path) << text;
    Scene s;
    try {
        s = load_scene(path);
    } catch (const SceneError &e) {
        if (error) *error = e.what();
        else std::fprintf(stderr, "unexpected scene error: %s\n", e.what()), ++check_failures;
    }
    std::remove(path.c_str());
    if (dir.empty()) rmdir(d.c_str());
    return s;
}

double distance(Vec3 a, Vec3 b) { return length(a - b); }

// ---- object instances ----

// Each shape kind placed by an ObjectInstance (the instance's transform times the shape's own inside the
// block) against the same shape placed directly by the product of the two: random rays meet both alike, and
// at each hit the point, the geometric and shading normals, the texture coordinates, dp/du and dp/dv (as
// vectors of the world) and the textured material agree. A binary alpha texture cuts both alike; alpha 0
// hides an instanced shape from both queries.
void test_instanced_shapes()
{
    // (the non-uniform scale inside the block: vertex normals are normalized in the shape's space, as pbrt-v4
    // normalizes them, so an instance's scale must be uniform for the two to interpolate the same normals)
    const std::string outer = "Translate 0.3 -0.2 0.1\nRotate 35 1 2 0.5\nScale 1.3 1.3 1.3\n",
                      inner = "Rotate 20 0 0 1\nScale 1 1.6 0.8\n";
    const std::string material = "Texture \"c\" \"spectrum\" \"checkerboard\" \"float uscale\" [ 6 ] \"float vscale\" [ 6 ] "
                                 "\"rgb tex1\" [ 0.9 0.2 0.1 ] \"rgb tex2\" [ 0.1 0.3 0.8 ]\n"
                                 "Texture \"cut\" \"float\" \"checkerboard\" \"float uscale\" [ 3 ] \"float vscale\" [ 3 ]\n"
                                 "Material \"diffuse\" \"texture reflectance\" \"c\"\n";
    const std::string quad_uv = "\"point2 uv\" [ 0 0 1 0 1 1 0 1 ]";
    const std::string shapes[] = {
        "Shape \"sphere\" \"float radius\" [ 0.8 ]",
        "Shape \"sphere\" \"float radius\" [ 0.8 ] \"texture alpha\" \"cut\"",  // (user geometry)
        "Shape \"cylinder\" \"float radius\" [ 0.6 ] \"float zmin\" [ -0.7 ] \"float zmax\" [ 0.5 ] \"float phimax\" [ 300 ]",
        "Shape \"disk\" \"float radius\" [ 0.9 ] \"float innerradius\" [ 0.2 ] \"float height\" [ 0.1 ]",
        "Shape \"bilinearmesh\" \"point3 P\" [ -1 -1 0  1 -1 0.3  -1 1 0.2  1 1 -0.4 ] \"normal N\" [ 0 0 1  0.3 0 1  0 0.2 1  "
        "-0.2 -0.2 1 ] \"point2 uv\" [ 0 0 1 0 0 1 1 1 ]",
        "Shape \"trianglemesh\" \"point3 P\" [ -1 -1 0  1 -1 0.2  1 1 0  -1 1 -0.3 ] \"integer indices\" [ 0 1 2 0 2 3 ] "
        "\"normal N\" [ 0 0 1  0.2 0 1  0 0.3 1  -0.3 0 1 ] " + quad_uv,
        "Shape \"trianglemesh\" \"point3 P\" [ -1 -1 0  1 -1 0.2  1 1 0  -1 1 -0.3 ] \"integer indices\" [ 0 1 2 0 2 3 ] " +
            quad_uv + " \"texture alpha\" \"cut\"",  // (an alpha filter)
    };
    for (const std::string &shape : shapes) {
        Scene placed = load_text("WorldBegin\n" + material + "AttributeBegin\n" + outer + inner + shape + "\nAttributeEnd\n");
        Scene instanced = load_text("WorldBegin\n" + material + "ObjectBegin \"o\"\n" + inner + shape + "\nObjectEnd\nAttributeBegin\n" +
                                    outer + "ObjectInstance \"o\"\nAttributeEnd\n");
        if (placed.shapes.size() != 1 || instanced.instances.size() != 1) {
            CHECKF(false, "%s: not loaded as expected", shape.c_str());
            continue;
        }
        EmbreeScene ra(placed), rb(instanced);
        Materials ma(placed), mb(instanced);
        std::mt19937_64 rng(11);
        std::uniform_real_distribution<double> U(-1, 1);
        int hits = 0, disagree = 0, bad = 0;
        const int N = 3000;
        for (int i = 0; i < N; ++i) {
            Vec3 o = normalize(Vec3(U(rng), U(rng), U(rng))) * 5, target = Vec3(0.3, -0.2, 0.1) + Vec3(U(rng), U(rng), U(rng)) * 0.9;
            Vec3 d = normalize(target - o);
            Hit a, b;
            bool ha = ra.intersect(o, d, 0, 100, &a), hb = rb.intersect(o, d, 0, 100, &b);
            if (ha != hb || ra.occluded(o, d, 0, 100) != ha || rb.occluded(o, d, 0, 100) != hb) {
                ++disagree;  // (float rounding at an edge)
                continue;
            }
            if (!ha) continue;
            ++hits;
            const Shape &sa = placed.shapes[a.shape], &sb = instanced.shapes[b.shape];
            double ua, va, ub, vb;
            hit_uv(sa, a, &ua, &va), hit_uv(sb, b, &ub, &vb);
            Vec3 na = shading_normal(sa, a), nb = shading_normal(sb, b);
            Vec3 dua, dva, dub, dvb;
            surface_derivatives(sa, a, na, &dua, &dva), surface_derivatives(sb, b, nb, &dub, &dvb);
            Vec3 wo = -d, nsa = na, nsb = nb;
            Bsdf sca, scb;
            Vec3 Ra = ma.at(0, sa, a, wo, &nsa, &sca).diffuse.R, Rb = mb.at(0, sb, b, wo, &nsb, &scb).diffuse.R;
            double scale = std::max({1.0, length(dua), length(dva)});
            bool edge = std::fabs(6 * ua - std::round(6 * ua)) < 1e-3 || std::fabs(6 * va - std::round(6 * va)) < 1e-3;
            bool ok = b.instance && distance(a.p, b.p) < 1e-4 && distance(a.ng, b.ng) < 1e-4 && distance(na, nb) < 1e-4 &&
                      std::fabs(ua - ub) < 1e-4 && std::fabs(va - vb) < 1e-4 && distance(dua, dub) < 1e-4 * scale &&
                      distance(dva, dvb) < 1e-4 * scale && (edge || distance(Ra, Rb) < 1e-9);
            if (!ok && bad++ < 3)
                std::fprintf(stderr,
                             "%s\n  placed:    p %.5f %.5f %.5f ng %.4f %.4f %.4f ns %.4f %.4f %.4f uv %.4f %.4f dpdu %.4f %.4f %.4f\n"
                             "  instanced: p %.5f %.5f %.5f ng %.4f %.4f %.4f ns %.4f %.4f %.4f uv %.4f %.4f dpdu %.4f %.4f %.4f\n",
                             shape.c_str(), a.p.x, a.p.y, a.p.z, a.ng.x, a.ng.y, a.ng.z, na.x, na.y, na.z, ua, va, dua.x, dua.y,
                             dua.z, b.p.x, b.p.y, b.p.z, b.ng.x, b.ng.y, b.ng.z, nb.x, nb.y, nb.z, ub, vb, dub.x, dub.y, dub.z);
        }
        CHECKF(bad == 0 && hits > N / 10 && disagree < N / 200, "%s: %d of %d hits differ, %d rays met one and not the other",
               shape.c_str(), bad, hits, disagree);
    }
    // alpha 0 inside an object: the instance is never met, by either query
    Scene s = load_text("WorldBegin\nObjectBegin \"o\"\nShape \"sphere\" \"float alpha\" [ 0 ]\nObjectEnd\nObjectInstance \"o\"\n"
                        "Translate 3 0 0\nObjectInstance \"o\"\nShape \"sphere\" \"float radius\" [ 0.1 ]\n");
    EmbreeScene rt(s);
    Hit h;
    CHECK(!rt.intersect(Vec3(0, 0.5, -5), Vec3(0, 0, 1), 0, 100, &h) && !rt.occluded(Vec3(3, 0.5, -5), Vec3(0, 0, 1), 0, 100));
    CHECK(rt.intersect(Vec3(3, 0, -5), Vec3(0, 0, 1), 0, 100, &h) && h.instance == nullptr && std::fabs(h.t - 4.9) < 1e-5);
}

// ---- names and files ----

// Names pbrt-v4 resolves when it creates the scene: a shape's alpha texture and a texture's texture-valued
// inputs made after their use (a spectrum texture may use a float texture made later, any texture an image
// texture made later; a texture of its own kind made later is refused, as pbrt-v4 makes them in order).
// File names by the path rule: an image texture and a normal map named in an included file of another
// folder are looked for in the main file's.
void test_names_and_files()
{
    Scene s = load_text("WorldBegin\nShape \"sphere\" \"texture alpha\" \"a\"\n"
                        "Texture \"m\" \"spectrum\" \"mix\" \"texture amount\" \"f\" \"rgb tex1\" [ 1 0 0 ]\n"
                        "Texture \"f\" \"float\" \"constant\" \"float value\" [ 0.25 ]\n"
                        "Texture \"a\" \"float\" \"checkerboard\"\n"
                        "Material \"diffuse\" \"texture reflectance\" \"m\"\nShape \"sphere\" \"float radius\" [ 0.5 ]\n");
    CHECK(s.shapes.size() == 2 && s.textures.size() == 3);
    if (s.shapes.size() == 2 && s.textures.size() == 3) {
        CHECK(s.shapes[0].alpha_tex == 2 && s.shapes[1].alpha_tex < 0 && s.textures[0].amount.tex == 1);
        Materials m(s);  // (the textures resolve and evaluate)
        Hit h;
        h.p = Vec3(0, 0, 0.5), h.ng = Vec3(0, 0, 1), h.shape = 1;
        Vec3 ns = h.ng;
        Bsdf scratch;
        Vec3 R = m.at(0, s.shapes[1], h, Vec3(0, 0, 1), &ns, &scratch).diffuse.R;  // 0.75 (1, 0, 0) + 0.25 (1, 1, 1)
        CHECKF(std::fabs(R.x - 1) < 1e-12 && std::fabs(R.y - 0.25) < 1e-12, "mix of a later amount: %g %g", R.x, R.y);
    }
    std::string error;
    load_text("WorldBegin\nTexture \"s\" \"float\" \"scale\" \"texture tex\" \"f\"\n"
              "Texture \"f\" \"float\" \"constant\"\nShape \"sphere\"\n", "", &error);
    CHECKF(error.find("is made after the texture that uses it") != std::string::npos, "a later texture of its kind: '%s'",
           error.c_str());
    error.clear();
    load_text("WorldBegin\nShape \"sphere\" \"texture alpha\" \"none\"\n", "", &error);
    CHECKF(error.find("float texture \"none\" was not made") != std::string::npos, "an alpha texture made nowhere: '%s'",
           error.c_str());

    // the path rule: textures/ramp.png and normal-map.png beside the main file, named in sub/materials.pbrt
    char tmpl[] = "/tmp/udm1_test_pt_interactions_XXXXXX";
    if (!mkdtemp(tmpl)) return;
    std::string dir = tmpl;
    mkdir((dir + "/sub").c_str(), 0700);
    mkdir((dir + "/textures").c_str(), 0700);
    auto copy = [](const std::string &from, const std::string &to) {
        std::ifstream in(from, std::ios::binary);
        std::ofstream(to, std::ios::binary) << in.rdbuf();
    };
    copy(std::string(UDM1_TEST_SCENES) + "/ramp.png", dir + "/textures/ramp.png");
    copy(std::string(UDM1_TEST_SCENES) + "/ramp.png", dir + "/textures/late.png");
    copy(std::string(UDM1_TEST_SCENES) + "/normal-map.png", dir + "/normal-map.png");
    std::ofstream(dir + "/sub/materials.pbrt")
        << "Texture \"r\" \"float\" \"imagemap\" \"string filename\" \"textures/ramp.png\"\n"
           "Texture \"s\" \"float\" \"scale\" \"texture tex\" \"late\"\n"  // (an image texture made later)
           "Texture \"late\" \"float\" \"imagemap\" \"string filename\" \"textures/late.png\"\n"
           "Material \"coateddiffuse\" \"texture roughness\" \"s\" \"string normalmap\" \"normal-map.png\"\n";
    Scene p = load_text("WorldBegin\nInclude \"sub/materials.pbrt\"\nShape \"sphere\"\n", dir);
    CHECK(p.textures.size() == 3 && p.materials.size() == 1);
    if (p.textures.size() == 3 && p.materials.size() == 1) {
        CHECKF(p.textures[0].filename == dir + "/textures/ramp.png", "imagemap: %s", p.textures[0].filename.c_str());
        CHECK(p.textures[1].tex1.tex == 2 && p.textures[2].filename == dir + "/textures/late.png");
        const Param *nm = p.materials[0].params.find("normalmap");
        CHECKF(nm && nm->strings[0] == dir + "/normal-map.png", "normalmap: %s", nm ? nm->strings[0].c_str() : "none");
        try {
            Materials m(p);  // (reads both images)
            CHECK(m.size() == 1);
        } catch (const SceneError &e) {
            CHECKF(false, "the materials of the included file: %s", e.what());
        }
    }
    for (const char *f : {"/sub/materials.pbrt", "/textures/ramp.png", "/textures/late.png", "/normal-map.png"}) std::remove((dir + f).c_str());
    rmdir((dir + "/sub").c_str()), rmdir((dir + "/textures").c_str()), rmdir(dir.c_str());
}

// ---- volpath ----

// A scene for Integrator "volpath": an emitting quad seen through a fog, and between them a diffuse blocker.
std::string volpath_scene(const std::string &blocker)
{
    return "Integrator \"volpath\" \"integer maxdepth\" [ 5 ]\nLookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n"
           "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.1 0.1 0.1 ] \"rgb sigma_s\" [ 0.3 0.3 0.3 ]\n"
           "MediumInterface \"\" \"fog\"\nCamera \"perspective\" \"float fov\" [ 40 ]\nWorldBegin\n"
           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 2 2 2 ]\nTranslate 0 0 3\n"
           "Shape \"trianglemesh\" \"point3 P\" [ -2 -2 0  2 -2 0  2 2 0  -2 2 0 ] \"integer indices\" [ 0 2 1 0 3 2 ]\nAttributeEnd\n" +
           blocker;
}

// Alpha cut-outs under Integrator "volpath", in both loops: a blocker of alpha 0 is passed by every path and
// every shadow ray (the image is the one without it, bit for bit); alpha 1 blocks. The new shapes bound media:
// a fog inside a closed box of bilinear patches renders as inside the same box of triangles.
void test_volpath()
{
    const std::string quad = "\"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] \"integer indices\" [ 0 1 2 0 2 3 ]";
    const std::string blocker = "Translate 0 0 1\nShape \"trianglemesh\" " + quad, disk = "Translate 0 0 1\nShape \"disk\"";
    for (Loop loop : {Loop::Scalar, Loop::Auto}) {
        Options o;
        o.spp = 4, o.loop = loop;
        auto run = [&](const std::string &text) {
            Scene s = load_text(volpath_scene(text));
            EmbreeScene rt(s);
            Stats st;
            Accumulator a = render(s, rt, o, &st);
            CHECK(loop == Loop::Scalar || std::string(st.loop) == "wavefront-general");
            return a.sum;
        };
        auto none = run(""), cut = run(blocker + " \"float alpha\" [ 0 ]\n"), solid = run(blocker + "\n");
        auto cut_disk = run(disk + " \"float alpha\" [ 0 ]\n"), solid_disk = run(disk + "\n");
        CHECK(!none.empty() && none == cut && none == cut_disk && none != solid && none != solid_disk);
    }
    // a fog in a unit cube of bilinear patches (each face one patch, p00 p01 p10 p11 below: its normal outward)
    // and of triangles
    const char *faces[6][4] = {{"-1 -1 -1", "1 -1 -1", "-1 1 -1", "1 1 -1"}, {"-1 -1 1", "-1 1 1", "1 -1 1", "1 1 1"},
                               {"-1 -1 -1", "-1 1 -1", "-1 -1 1", "-1 1 1"}, {"1 -1 -1", "1 -1 1", "1 1 -1", "1 1 1"},
                               {"-1 -1 -1", "-1 -1 1", "1 -1 -1", "1 -1 1"}, {"-1 1 -1", "1 1 -1", "-1 1 1", "1 1 1"}};
    std::string patches, triangles;
    for (auto &f : faces) {
        patches += std::string("Shape \"bilinearmesh\" \"point3 P\" [ ") + f[0] + " " + f[2] + " " + f[1] + " " + f[3] + " ]\n";
        triangles += std::string("Shape \"trianglemesh\" \"point3 P\" [ ") + f[0] + " " + f[2] + " " + f[3] + " " + f[1] +
                     " ] \"integer indices\" [ 0 1 2 0 2 3 ]\n";
    }
    auto box = [&](const std::string &walls) {
        std::string text = "Integrator \"volpath\"\nLookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
                           "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n"
                           "MakeNamedMedium \"thick\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 1.5 0.5 0.2 ] "
                           "\"rgb sigma_s\" [ 0 0 0 ]\nWorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
                           "AttributeBegin\nMaterial \"interface\"\nMediumInterface \"thick\" \"\"\nScale 0.8 0.8 0.8\n" + walls +
                           "AttributeEnd\n";
        Scene s = load_text(text);
        EmbreeScene rt(s);
        Options o;
        o.spp = 4;
        Stats st;
        Accumulator a = render(s, rt, o, &st);
        std::vector<float> m = a.mean();
        double c[3] = {0, 0, 0};
        for (size_t i = 0; i < m.size(); ++i) c[i % 3] += m[i];
        return Vec3(c[0], c[1], c[2]) * (3.0 / m.size());
    };
    Vec3 p = box(patches), t = box(triangles);
    // (through the middle the fog leaves exp(-1.6 sigma_a): red well below blue; away from it, 1)
    CHECKF(p.x < 0.8 * p.z && std::fabs(p.x - t.x) < 1e-3 * t.x && std::fabs(p.z - t.z) < 1e-3 * t.z,
           "fog in a box of patches %.5f %.5f %.5f, of triangles %.5f %.5f %.5f", p.x, p.y, p.z, t.x, t.y, t.z);
}

}  // namespace

int main()
{
    test_instanced_shapes();
    test_names_and_files();
    test_volpath();
    CHECK_DONE();
}
