// test_pt_models.cpp - pbrt-v4's shapes, alpha cut-outs, layered and transmitting materials and textures as
// udm1-pt models them, against closed forms and independent computations: disks, cylinders and bilinear
// patches met where the equations say (under shears and mirrors), their light sampling's densities equal to
// what MIS evaluates at the hit and their irradiance equal to Lambert's; Loop subdivision keeping closed
// meshes closed and each control vertex's limit position fixed by Loop's limit rule at every level; alpha
// cut-outs as pbrt-v4 tests them (one hash per ray: stacked surfaces are correlated; a quadric's far side
// hashed anew); the coated conductor's and the medium's random walks consistent between sampling and
// evaluation, a smooth coat of index 1 equal to the bare metal; diffuse transmission conserving energy;
// the texture evaluator's checkerboards, mappings and float image channels.
#include "../c/check.h"

#include "alpha.h"
#include "bilinear_patch.h"
#include "bsdf.h"
#include "embree_scene.h"
#include "lights.h"
#include "loop_subdivision.h"
#include "material.h"
#include "quadrics.h"
#include "scene.h"
#include "textures.h"
#include "udm1app/image_write.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <unistd.h>

using namespace udm1scene;
using namespace udm1pt;

namespace {

const double PI = 3.14159265358979323846;

// The scene text loaded from a temporary .pbrt file (images it names are looked for in `dir`, if given).
Scene load_text(const std::string &text, const std::string &dir = "")
{
    std::string d = dir;
    if (d.empty()) {
        char tmpl[] = "/tmp/udm1_test_pt_models_XXXXXX";
        if (!mkdtemp(tmpl)) return Scene();
        d = tmpl;
    }
    std::string path = d + "/s.pbrt";
    std::ofstream(path) << text;
    Scene s = load_scene(path);
    std::remove(path.c_str());
    if (dir.empty()) rmdir(d.c_str());
    return s;
}

// Whether loading (and making the materials and lights of) the text fails with a message containing words.
bool refused(const std::string &text, const std::string &words)
{
    try {
        Scene s = load_text(text);
        Materials m(s);
        Lights l(s);
    } catch (const SceneError &e) {
        if (std::string(e.what()).find(words) != std::string::npos) return true;
        std::fprintf(stderr, "refused, but not for '%s': %s\n", words.c_str(), e.what());
        return false;
    }
    std::fprintf(stderr, "not refused (expected '%s')\n", words.c_str());
    return false;
}

const char *HEAD = "WorldBegin\n";

// ---- shapes ----

// Rays against a disk and a cylinder under a shear, a non-uniform scale and a mirror: each hit is on the
// quadric (its object-space point solves the quadric's equation and lies inside its clipping) and no
// nearer point of the ray is (checked by a fine march along the ray in object space).
void test_quadric_hits()
{
    for (const char *shape : {"Shape \"disk\" \"float radius\" [ 1.2 ] \"float innerradius\" [ 0.4 ] \"float phimax\" [ 290 ] "
                              "\"float height\" [ 0.3 ]",
                              "Shape \"cylinder\" \"float radius\" [ 0.8 ] \"float zmin\" [ -0.5 ] \"float zmax\" [ 1.1 ] "
                              "\"float phimax\" [ 250 ]"}) {
        Scene s = load_text(std::string(HEAD) + "Translate 0.2 -0.1 0.3\nRotate 35 1 1 0\nScale -1.3 0.6 1.1\n"
                                                "ConcatTransform [ 1 0 0 0  0.5 1 0 0  0 0 1 0  0 0 0 1 ]\n" + shape + "\n");
        const Shape &q = s.shapes[0];
        EmbreeScene rt(s);
        std::mt19937_64 rng(9);
        std::uniform_real_distribution<double> U(-1, 1);
        int hits = 0;
        const bool disk = q.kind == Shape::Disk;
        auto on = [&](Vec3 p, double tol) {  // the object-space point on the surface, inside its clipping
            Vec3 o = q.object_from_world.point(p);
            double rho = std::sqrt(o.x * o.x + o.y * o.y), phi = std::atan2(o.y, o.x);
            if (phi < 0) phi += 2 * PI;
            if (phi > q.phi_max + tol) return false;
            if (disk) return std::fabs(o.z - q.height) < tol && rho <= q.object_radius + tol && rho >= q.inner_radius - tol;
            return std::fabs(rho - q.object_radius) < tol && o.z >= q.zmin - tol && o.z <= q.zmax + tol;
        };
        for (int i = 0; i < 3000; ++i) {
            Vec3 o(3 * U(rng), 3 * U(rng), -4), target(1.5 * U(rng), 1.5 * U(rng), 1.5 * U(rng));
            Vec3 d = normalize(target - o);
            Hit h;
            bool hit = rt.intersect(o, d, 0, 1e30, &h);
            double t_end = hit ? h.t : 12;
            if (hit) {
                ++hits;
                CHECKF(on(h.p, 1e-5), "%s: hit %.6f %.6f %.6f is not on the shape", disk ? "disk" : "cylinder", h.p.x, h.p.y, h.p.z);
                CHECKF(std::fabs(length(h.ng) - 1) < 1e-9 && std::fabs(dot(h.ng, normalize(quadric_normal(q, h.p)))) > 1 - 1e-9,
                       "normal");
            }
            // no crossing of the surface before t_end: the sign of the implicit function along the ray
            double prev = 0;
            for (int k = 0; k <= 4000; ++k) {
                double t = t_end * k / 4000 * (1 - 1e-6);
                Vec3 ob = q.object_from_world.point(o + d * t);
                double f = disk ? ob.z - q.height : ob.x * ob.x + ob.y * ob.y - q.object_radius * q.object_radius;
                if (k > 0 && (f > 0) != (prev > 0)) {
                    Vec3 p = o + d * t;
                    CHECKF(!on(p, -1e-3), "%s: the ray crosses the shape at t %.6f before its hit at %.6f",
                           disk ? "disk" : "cylinder", t, t_end);
                }
                prev = f;
            }
        }
        CHECKF(hits > 300 && hits < 2700, "%s: %d hits of 3000", disk ? "disk" : "cylinder", hits);
    }
}

// Bilinear patches met exactly: each hit is the patch point p(u, v) at the reported (u, v), and the
// nearest one (the ray's point at any smaller t is farther from the surface than the march's step allows);
// a non-planar patch is not its two triangles (rays through the gap between them meet it or miss it).
void test_bilinear_hits()
{
    Scene s = load_text(std::string(HEAD) + "Rotate 20 1 0 0\nScale 1 1 -1\n"
                                            "Shape \"bilinearmesh\" \"point3 P\" [ -1 -1 0  1 -1 0.9  -1 1 1.2  1 1 -0.4 ]\n");
    EmbreeScene rt(s);
    Patch q = patch_of(s.shapes[0], 0);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> U(0, 1);
    int differ_from_triangles = 0;
    for (int i = 0; i < 2000; ++i) {
        double u = U(rng), v = U(rng);
        Vec3 target = q.at(u, v), o(4 * U(rng) - 2, 4 * U(rng) - 2, -5);
        Vec3 d = normalize(target - o);
        Hit h;
        bool hit = rt.intersect(o, d, 0, 1e30, &h);
        CHECKF(hit, "a ray aimed at the patch point (%.3f, %.3f) missed it", u, v);
        if (!hit) continue;
        // (t and (u, v) come back from Embree in float)
        CHECKF(h.t <= length(target - o) * (1 + 1e-6), "the hit is beyond the aimed-at point");
        Vec3 p = q.at(h.u, h.v);
        CHECKF(length(p - h.p) < 1e-5 * (1 + length(h.p)), "the hit is not p(u, v): %.3g", length(p - h.p));
        // the two triangles (p00 p10 p11) and (p00 p11 p01) through the same ray
        auto tri = [&](Vec3 a, Vec3 b, Vec3 c) {
            Vec3 e1 = b - a, e2 = c - a, pv = cross(d, e2);
            double det = dot(e1, pv);
            if (std::fabs(det) < 1e-14) return -1.0;
            Vec3 tv = o - a;
            double bu = dot(tv, pv) / det, qv = 0;
            Vec3 qq = cross(tv, e1);
            qv = dot(d, qq) / det;
            if (bu < 0 || qv < 0 || bu + qv > 1) return -1.0;
            return dot(e2, qq) / det;
        };
        double t1 = tri(q.p00, q.p10, q.p11), t2 = tri(q.p00, q.p11, q.p01), tt = t1 > 0 ? (t2 > 0 ? std::min(t1, t2) : t1) : t2;
        if (!(tt > 0) || std::fabs(tt - h.t) > 1e-3) ++differ_from_triangles;
    }
    CHECKF(differ_from_triangles > 100, "the non-planar patch behaves as its triangles (%d rays differ)", differ_from_triangles);
}

// Light sampling from disks, cylinders and patches: the density of each sample equals Lights::pdf at the
// hit of a ray along its direction (what MIS evaluates), and a disk's irradiance on its axis is
// L pi r^2 / (r^2 + h^2); a rectangular patch's (by solid angle near it, by area far) is the same as that
// of the same rectangle as two triangles.
void test_surface_lights()
{
    const char *lights[] = {
        "Translate 0 2 0\nRotate 90 1 0 0\nShape \"disk\" \"float radius\" [ 0.7 ]",
        "Translate 0.3 2.5 0.2\nRotate 90 0 1 0\nShape \"cylinder\" \"float radius\" [ 0.3 ] \"float zmin\" [ -1 ] \"float zmax\" [ 1 ] "
        "\"float phimax\" [ 270 ]",
        "Shape \"bilinearmesh\" \"point3 P\" [ -0.8 2 -0.5  0.8 2 -0.5  -0.8 2 0.5  0.8 2 0.5 ]",
        "Shape \"bilinearmesh\" \"point3 P\" [ -0.8 2 -0.5  0.8 2.6 -0.5  -0.8 2.4 0.5  0.8 1.9 0.7 ]",
    };
    const char *names[] = {"disk", "cylinder", "rectangle", "non-planar patch"};
    for (int k = 0; k < 4; ++k) {
        Scene s = load_text(std::string(HEAD) + "AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ] \"bool twosided\" true\n" +
                            lights[k] + "\n");
        EmbreeScene rt(s);
        Lights L(s);
        std::mt19937_64 rng(3);
        std::uniform_real_distribution<double> U(0, 1);
        for (Vec3 p : {Vec3(0, 0, 0), Vec3(0.2, 1.7, 0.1), Vec3(2, -5, 1)}) {
            int checked = 0;
            for (int i = 0; i < 400; ++i) {
                LightSample ls;
                if (!L.sample(p, Vec3(0, 1, 0), U(rng), U(rng), &ls)) continue;
                Hit h;
                if (!rt.intersect(p, ls.wi, 0, 1e30, &h) || std::fabs(h.t - ls.dist) > 1e-6 * (1 + ls.dist)) continue;
                double pdf = L.pdf(p, Vec3(0, 1, 0), h, ls.importance_sum);
                // (the hit is the sample's point to a float's precision: an area density's cosine amplifies that)
                double cos_l = std::fabs(dot(ls.n, ls.wi)), tol = 1e-5 / std::max(cos_l, 1e-3);
                CHECKF(std::fabs(pdf / ls.pdf - 1) < tol, "%s from %g %g %g: sampled density %.8g, MIS density %.8g",
                       names[k], p.x, p.y, p.z, ls.pdf, pdf);
                ++checked;
            }
            CHECKF(checked > 100, "%s: only %d samples reached their point", names[k], checked);
        }
    }
    // a disk's irradiance on its axis: E = L pi r^2 / (r^2 + h^2), by area sampling
    for (double h : {0.3, 2.0}) {
        Scene s = load_text(std::string(HEAD) + "AreaLightSource \"diffuse\" \"rgb L\" [ 2 2 2 ]\nTranslate 0 " +
                            std::to_string(h) + " 0\nRotate 90 1 0 0\nShape \"disk\" \"float radius\" [ 0.6 ]\n");
        Lights L(s);
        std::mt19937_64 rng(1);
        std::uniform_real_distribution<double> U(0, 1);
        double E = 0;
        const int N = 400000;
        for (int i = 0; i < N; ++i) {
            LightSample ls;
            if (L.sample(Vec3(0, 0, 0), Vec3(0, 1, 0), U(rng), U(rng), &ls)) E += ls.L.y * ls.wi.y / ls.pdf;
        }
        E /= N;
        double want = 2 * PI * 0.36 / (0.36 + h * h);
        CHECKF(std::fabs(E / want - 1) < 0.005, "disk light at height %g: irradiance %.5f, closed form %.5f", h, E, want);
    }
    // the rectangle as a patch and as two triangles: the same irradiance near and far
    Scene sp = load_text(std::string(HEAD) + "AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ] \"bool twosided\" true\n"
                                             "Shape \"bilinearmesh\" \"point3 P\" [ -0.8 2 -0.5  -0.8 2 0.5  0.8 2 -0.5  0.8 2 0.5 ]\n");
    Scene st = load_text(std::string(HEAD) + "AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ] \"bool twosided\" true\n"
                                             "Shape \"trianglemesh\" \"point3 P\" [ -0.8 2 -0.5  -0.8 2 0.5  0.8 2 -0.5  0.8 2 0.5 ] "
                                             "\"integer indices\" [ 0 1 2 2 1 3 ]\n");
    for (Vec3 p : {Vec3(0, 1.9, 0), Vec3(0.3, 0, 0), Vec3(3, -8, 0)}) {
        double E[2];
        for (int k = 0; k < 2; ++k) {
            Lights L(k ? st : sp);
            std::mt19937_64 rng(2);
            std::uniform_real_distribution<double> U(0, 1);
            double sum = 0;
            for (int i = 0; i < 200000; ++i) {
                LightSample ls;
                if (L.sample(p, Vec3(0, 1, 0), U(rng), U(rng), &ls) && ls.wi.y > 0) sum += ls.L.y * ls.wi.y / ls.pdf;
            }
            E[k] = sum / 200000;
        }
        CHECKF(std::fabs(E[0] / E[1] - 1) < 0.01, "rectangle from %g %g %g: as a patch %.6g, as triangles %.6g", p.x, p.y, p.z,
               E[0], E[1]);
    }
}

// ---- Loop subdivision ----

// Every edge of the mesh shared by exactly two faces that traverse it in opposite directions.
bool closed_and_oriented(const LoopMesh &m)
{
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t f = 0; f + 2 < m.indices.size(); f += 3)
        for (int k = 0; k < 3; ++k) ++directed[{m.indices[f + k], m.indices[f + (k + 1) % 3]}];
    for (const auto &e : directed)
        if (e.second != 1 || !directed.count({e.first.second, e.first.first})) return false;
    return true;
}

// The limit position of a control vertex by Loop's limit rule, written out here: interior, (1 - n gamma) p +
// gamma sum ring, gamma = 1 / (n + 3 / (8 beta)), the same at every level (the rule is the limit of the
// refinement); boundary, pbrt-v4's 3/5 p + 1/5 (its two boundary neighbours) at level 0, at level 1 (after
// 3/4 p + 1/8 (a + b) and the edges' midpoints) 13/20 p + 7/40 (a + b), and approaching the boundary curve's
// own limit 2/3 p + 1/6 (a + b) by a factor of 4 a level.
void test_loop_subdivision()
{
    // a tetrahedron centred at the origin: every vertex has valence 3 (beta 3/16, gamma 1/5) and ring
    // sum -p, so its limit position is p (1 - 3/5) - p / 5 = p / 5 at every level
    std::vector<Vec3> tet = {{1, 1, 1}, {-1, -1, 1}, {-1, 1, -1}, {1, -1, -1}};
    std::vector<uint32_t> tet_idx = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
    // a cube of 12 triangles: valences 3 to 6
    std::vector<Vec3> cube = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
    std::vector<uint32_t> cube_idx = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3};
    // an open grid of 3 x 3 vertices (8 faces): boundary vertices around one interior one
    std::vector<Vec3> grid;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) grid.emplace_back(i, 0.3 * ((i + j) % 2), j);
    std::vector<uint32_t> grid_idx = {0, 1, 3, 1, 4, 3, 1, 2, 4, 2, 5, 4, 3, 4, 6, 4, 7, 6, 4, 5, 7, 5, 8, 7};
    struct Case {
        const char *name;
        std::vector<Vec3> P;
        std::vector<uint32_t> idx;
        bool closed;
    } cases[] = {{"tetrahedron", tet, tet_idx, true}, {"cube", cube, cube_idx, true}, {"grid", grid, grid_idx, false}};
    for (const Case &c : cases) {
        // rings and boundaries from the control mesh's edges
        std::map<uint32_t, std::map<uint32_t, int>> edge_faces;  // vertex -> neighbour -> faces on the edge
        for (size_t f = 0; f < c.idx.size(); f += 3)
            for (int k = 0; k < 3; ++k) {
                uint32_t a = c.idx[f + k], b = c.idx[f + (k + 1) % 3];
                ++edge_faces[a][b], ++edge_faces[b][a];
            }
        std::vector<Vec3> level0(c.P.size()), level1(c.P.size()), curve(c.P.size());
        std::vector<char> boundary(c.P.size(), 0);
        for (uint32_t v = 0; v < c.P.size(); ++v) {
            std::vector<Vec3> bn;
            Vec3 sum;
            for (auto &nb : edge_faces[v]) {
                sum = sum + c.P[nb.first];
                if (nb.second == 1) bn.push_back(c.P[nb.first]);
            }
            int n = (int)edge_faces[v].size();
            if (!bn.empty()) {
                boundary[v] = 1;
                level0[v] = c.P[v] * 0.6 + (bn[0] + bn[1]) * 0.2;
                level1[v] = c.P[v] * (13.0 / 20) + (bn[0] + bn[1]) * (7.0 / 40);
                curve[v] = c.P[v] * (2.0 / 3) + (bn[0] + bn[1]) * (1.0 / 6);
            } else {
                double beta = n == 3 ? 3.0 / 16 : 3.0 / (8.0 * n), gamma = 1 / (n + 3 / (8 * beta));
                level0[v] = level1[v] = curve[v] = c.P[v] * (1 - n * gamma) + sum * gamma;
            }
        }
        std::vector<double> previous_error(c.P.size(), 0);
        for (int levels = 0; levels <= 4; ++levels) {
            LoopMesh m;
            std::string why;
            CHECKF(loop_subdivide(c.idx, c.P, levels, &m, &why), "%s: %s", c.name, why.c_str());
            size_t faces = c.idx.size() / 3 * (size_t)std::pow(4, levels);
            CHECKF(m.indices.size() == 3 * faces, "%s level %d: %zu faces", c.name, levels, m.indices.size() / 3);
            if (c.closed) {
                CHECKF(closed_and_oriented(m), "%s level %d: not closed or not consistently oriented", c.name, levels);
                CHECKF(m.P.size() == faces / 2 + 2, "%s level %d: %zu vertices for a closed mesh of %zu faces (Euler: F/2 + 2)",
                       c.name, levels, m.P.size(), faces);
            }
            for (size_t v = 0; v < c.P.size(); ++v) {
                double error = length(m.P[v] - curve[v]);
                if (levels <= 1 || !boundary[v]) {
                    Vec3 want = levels == 0 ? level0[v] : level1[v];
                    CHECKF(length(m.P[v] - want) < 1e-12, "%s level %d: vertex %zu's limit %.9f %.9f %.9f, the rule's %.9f %.9f %.9f",
                           c.name, levels, v, m.P[v].x, m.P[v].y, m.P[v].z, want.x, want.y, want.z);
                } else {
                    double ratio = previous_error[v] / error;
                    CHECKF(ratio > 3.5 && ratio < 4.5, "%s level %d: boundary vertex %zu approaches its curve's limit by %.3f",
                           c.name, levels, v, ratio);
                }
                previous_error[v] = error;
            }
            if (c.closed && levels > 0) {  // the limit normals point all out of the closed surface, or all in
                Vec3 centre;
                for (Vec3 p : m.P) centre = centre + p * (1.0 / m.P.size());
                int out = 0;
                for (size_t v = 0; v < m.P.size(); ++v) out += dot(m.N[v], m.P[v] - centre) > 0;
                CHECKF(out == 0 || out == (int)m.P.size(), "%s level %d: %d of %zu normals point out", c.name, levels, out,
                       m.P.size());
            }
        }
    }
    // the tetrahedron's limit normals at its corners point along the corners (by symmetry)
    LoopMesh m;
    std::string why;
    loop_subdivide(tet_idx, tet, 3, &m, &why);
    for (int v = 0; v < 4; ++v)
        CHECKF(std::fabs(std::fabs(dot(normalize(m.N[v]), normalize(tet[v]))) - 1) < 1e-9, "tetrahedron corner %d's normal", v);
    // meshes the rules do not apply to are refused
    CHECK(refused(std::string(HEAD) + "Shape \"loopsubdiv\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 0 0 1 0 -1 0 ] \"integer indices\" "
                                      "[ 0 1 2  1 0 3  1 0 4 ]",
                  "shared by more than two faces"));
    CHECK(refused(std::string(HEAD) + "Shape \"loopsubdiv\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 1 1 0 ] \"integer indices\" "
                                      "[ 0 1 2  1 2 3 ]",
                  "inconsistent orientation"));
    CHECK(refused(std::string(HEAD) + "Shape \"loopsubdiv\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ] \"integer indices\" [ 0 1 1 ]",
                  "repeats a vertex"));
    CHECK(refused(std::string(HEAD) + "Shape \"loopsubdiv\" \"integer levels\" [ -1 ] \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ] "
                                      "\"integer indices\" [ 0 1 2 ]",
                  "levels -1"));
}

// ---- alpha ----

// pbrt-v4's alpha test: constant 0 removes a shape for every ray (shadow rays too); 0.5 lets a ray through
// where the ray's hash exceeds it: half the rays, and two such surfaces on one ray see the same hash (a ray
// through the first passes the second); a sphere's far side sees the hash of the ray continued from its
// rejected near side (3/4 of the rays meet a sphere of alpha 1/2); a checkerboard alpha texture cuts squares.
void test_alpha()
{
    const std::string quad = "\"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] \"integer indices\" [ 0 1 2 0 2 3 ]";
    auto fraction = [](const EmbreeScene &rt, std::vector<int> *per_shape, bool occlusion) {
        std::mt19937_64 rng(4);
        std::uniform_real_distribution<double> U(-0.6, 0.6);
        int hit = 0;
        const int N = 20000;
        per_shape->assign(rt.scene().shapes.size(), 0);
        for (int i = 0; i < N; ++i) {
            Vec3 o(U(rng), U(rng), -5), d = normalize(Vec3(U(rng) * 0.01, U(rng) * 0.01, 1));
            Hit h;
            if (occlusion) {
                hit += rt.occluded(o, d, 0, 100);
            } else if (rt.intersect(o, d, 0, 100, &h)) {
                ++hit, ++(*per_shape)[h.shape];
                Hit again;  // deterministic: the same ray, the same answer
                CHECK(rt.intersect(o, d, 0, 100, &again) && again.shape == h.shape && again.t == h.t);
            }
        }
        return (double)hit / N;
    };
    std::vector<int> per;
    {
        Scene s = load_text(std::string(HEAD) + "Shape \"trianglemesh\" " + quad + " \"float alpha\" [ 0 ]\n");
        EmbreeScene rt(s);
        CHECK(fraction(rt, &per, false) == 0 && fraction(rt, &per, true) == 0);
    }
    for (const char *what : {"trianglemesh", "sphere"}) {
        bool sphere = std::string(what) == "sphere";
        Scene s = load_text(std::string(HEAD) + (sphere ? "Shape \"sphere\" \"float radius\" [ 3 ]" : "Shape \"trianglemesh\" " + quad) +
                            " \"float alpha\" [ 0.5 ]\n");
        EmbreeScene rt(s);
        double want = sphere ? 0.75 : 0.5, se = std::sqrt(want * (1 - want) / 20000);
        double f = fraction(rt, &per, false), g = fraction(rt, &per, true);
        CHECKF(std::fabs(f - want) < 4 * se && std::fabs(g - want) < 4 * se, "%s of alpha 0.5: %.4f of the rays meet it, "
               "%.4f of the shadow rays (expected %.2f)", what, f, g, want);
    }
    {  // two quads of alpha 0.5, one behind the other: the one behind is met by no ray (pbrt-v4's one hash per ray)
        Scene s = load_text(std::string(HEAD) + "Shape \"trianglemesh\" " + quad + " \"float alpha\" [ 0.5 ]\nTranslate 0 0 1\n"
                                                "Shape \"trianglemesh\" " + quad + " \"float alpha\" [ 0.5 ]\n");
        EmbreeScene rt(s);
        double f = fraction(rt, &per, false);
        CHECKF(std::fabs(f - 0.5) < 0.02 && per[1] == 0, "stacked alpha 0.5: %.4f met, %d rays met the one behind", f, per[1]);
    }
    {  // a checkerboard alpha (4 x 4 squares over the quad's (u, v)): a ray meets the quad exactly in tex1's squares
        Scene s = load_text(std::string(HEAD) + "Texture \"c\" \"float\" \"checkerboard\" \"float uscale\" [ 4 ] "
                                                "\"float vscale\" [ 4 ]\nShape \"trianglemesh\" " + quad +
                            " \"point2 uv\" [ 0 0 1 0 1 1 0 1 ] \"texture alpha\" \"c\"\n");
        EmbreeScene rt(s);
        std::mt19937_64 rng(6);
        std::uniform_real_distribution<double> U(-0.99, 0.99);
        int wrong = 0;
        for (int i = 0; i < 5000; ++i) {
            double x = U(rng), y = U(rng);
            Hit h;
            bool hit = rt.intersect(Vec3(x, y, -1), Vec3(0, 0, 1), 0, 10, &h);
            double u = (x + 1) / 2, v = (y + 1) / 2;
            bool tex1 = ((int)std::floor(4 * u) + (int)std::floor(4 * v)) % 2 == 0;
            double edge = std::min(std::fabs(4 * u - std::round(4 * u)), std::fabs(4 * v - std::round(4 * v)));
            if (edge > 1e-6 && hit != tex1) ++wrong;
        }
        CHECKF(wrong == 0, "checkerboard alpha: %d rays disagree with the squares", wrong);
    }
    // the hash itself: pbrt-v4's HashFloat, MurmurHash64A's low 32 bits over 2^32 (reference values computed
    // with pbrt-v4's own MurmurHash64A and HashFloat, util/hash.h of the snapshot)
    CHECK(murmur_hash64a("", 0) == 0ull);
    const char abc[] = "abc", ab24[] = "0123456789abcdefghijklmn";
    uint64_t h = murmur_hash64a(abc, 3), h24 = murmur_hash64a(ab24, 24);
    CHECKF(h == 0x9cc9c33498a95efbull && h24 == 0x484b192a1bc73e9cull, "MurmurHash64A: %016llx %016llx",
           (unsigned long long)h, (unsigned long long)h24);
    const float ro[3] = {0.5f, -1.25f, 3.0f}, rd[3] = {0.0f, 0.6f, 0.8f};
    CHECKF(ray_hash(ro, rd) == 0xb7376cbdu * 0x1p-32, "HashFloat of the ray: %.10f, pbrt-v4's 0.7156894803", ray_hash(ro, rd));
    // emitters: alpha 0 is a light only light sampling finds (a delta light); partial alpha is refused
    {
        Scene s = load_text(std::string(HEAD) + "AreaLightSource \"diffuse\"\nShape \"trianglemesh\" " + quad + " \"float alpha\" [ 0 ]\n");
        Lights L(s);
        LightSample ls;
        CHECK(L.sample(Vec3(0, 0, 2), Vec3(0, 0, -1), 0.3, 0.6, &ls) && ls.delta);
    }
    CHECK(refused(std::string(HEAD) + "AreaLightSource \"diffuse\"\nShape \"trianglemesh\" " + quad + " \"float alpha\" [ 0.5 ]\n",
                  "an emitting shape with an alpha texture or an alpha between 0 and 1"));
}

// ---- materials ----

void test_layered_materials()
{
    // sampling against evaluation (E[f cos / pdf] against f integrated uniformly), no energy created: a coated
    // conductor rough and smooth, with and without a medium in the coat; a coated diffuse with a medium
    struct Case {
        const char *name;
        Bsdf b;
    };
    std::vector<Case> cases;
    for (double top : {0.0, 0.2})
        for (double base : {0.0, 0.3})
            for (bool medium : {false, true}) {
                if (top == 0.0 && base == 0.0) continue;  // (a specular BSDF: no f() to integrate)
                Bsdf b;
                b.kind = Bsdf::CoatedConductor;
                Coated &c = b.coated;
                c.metal_base = true, c.top.eta = 1.5, c.top.mf.ax = c.top.mf.ay = top;
                c.metal.mf.ax = c.metal.mf.ay = base, c.metal.eta = Vec3(0.2, 0.4, 1.2), c.metal.k = Vec3(3.5, 2.5, 2.2);
                if (medium) c.albedo = Vec3(0.8, 0.8, 0.8), c.thickness = 0.2, c.g = 0.4;
                cases.push_back({"coated conductor", b});
            }
    Bsdf cd;
    cd.kind = Bsdf::CoatedDiffuse;
    cd.coated.bottom.R = Vec3(0.6, 0.6, 0.6), cd.coated.top.mf.ax = cd.coated.top.mf.ay = 0.2;
    cd.coated.albedo = Vec3(0.7, 0.7, 0.7), cd.coated.thickness = 0.3, cd.coated.g = -0.3;
    cases.push_back({"coated diffuse with a medium", cd});
    for (const Case &c : cases)
        for (Vec3 wo : {normalize(Vec3(0.2, 0.1, 1.0)), normalize(Vec3(0.8, -0.3, 0.3)), normalize(Vec3(0.1, 0.3, -0.9))}) {
            std::mt19937_64 rng(7);
            std::uniform_real_distribution<double> U(0, 1);
            const int N = 60000;
            double by_sampling = 0, by_uniform = 0;
            for (int i = 0; i < N; ++i) {
                Sample s;
                if (c.b.sample(wo, U(rng), U(rng), U(rng), &s) && s.pdf > 0) by_sampling += s.f.y * std::fabs(s.wi.z) / s.pdf;
                double z = 1 - 2 * U(rng), r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * PI * U(rng);
                by_uniform += c.b.f(wo, Vec3(r * std::cos(phi), r * std::sin(phi), z)).y * std::fabs(z) * 4 * PI;
            }
            by_sampling /= N, by_uniform /= N;
            const Coated &k = c.b.coated;
            bool smooth_top = k.top.mf.smooth();  // (f() leaves out the coat's specular reflection: add it)
            double expected = by_uniform + (smooth_top ? fresnel_dielectric(std::fabs(wo.z), k.top.eta) : 0);
            CHECKF(std::fabs(by_sampling - expected) < 0.02 + 0.03 * expected && by_sampling < 1.01,
                   "%s (coat %g, base %g, albedo %g), wo.z %.2f: albedo %.4f by sampling, %.4f by evaluation", c.name, k.top.mf.ax,
                   k.metal.mf.ax, k.albedo.y, wo.z, by_sampling, expected);
        }
    // a smooth coat of index 1 and (almost) no thickness is no coat: the bare conductor, f for f
    Bsdf bare;
    bare.kind = Bsdf::ConductorKind, bare.conductor.eta = Vec3(0.2, 0.9, 1.3), bare.conductor.k = Vec3(3.9, 2.4, 2.0);
    bare.conductor.mf.ax = bare.conductor.mf.ay = 0.25;
    Bsdf coat;
    coat.kind = Bsdf::CoatedConductor, coat.coated.metal_base = true, coat.coated.metal = bare.conductor;
    coat.coated.top.eta = 1, coat.coated.thickness = 1e-300;
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> U(-1, 1);
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
        Vec3 wo = normalize(Vec3(U(rng), U(rng), std::fabs(U(rng)) + 0.05)), wi = normalize(Vec3(U(rng), U(rng), std::fabs(U(rng)) + 0.05));
        Vec3 a = coat.f(wo, wi), b = bare.f(wo, wi);
        for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, std::fabs(a[ch] - b[ch]) / std::max(1e-3, b[ch]));
    }
    CHECKF(worst < 1e-9, "a coat of index 1 changes the conductor's f by up to %.3g relative", worst);
}

// Diffuse transmission: R + T = 1 conserves energy (E[f cos / pdf] = 1 exactly: each sample carries R or T
// over its probability), reflection on wo's side, transmission to the other, each Lambertian.
void test_diffuse_transmission()
{
    Bsdf b;
    b.kind = Bsdf::DiffuseTransmissionKind, b.transmission.R = Vec3(0.3, 0.3, 0.3), b.transmission.T = Vec3(0.7, 0.7, 0.7);
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> U(0, 1);
    double sum = 0, through = 0;
    const int N = 100000;
    Vec3 wo = normalize(Vec3(0.3, 0.2, 0.8));
    for (int i = 0; i < N; ++i) {
        Sample s;
        CHECK(b.sample(wo, U(rng), U(rng), U(rng), &s));
        double w = s.f.y * std::fabs(s.wi.z) / s.pdf;
        sum += w;
        if (s.wi.z < 0) {
            through += w;
            CHECK(!s.reflection);
        }
        CHECK(std::fabs(b.pdf(wo, s.wi) - s.pdf) < 1e-12 && std::fabs(b.f(wo, s.wi).y - s.f.y) < 1e-12);
    }
    CHECKF(std::fabs(sum / N - 1) < 1e-9, "R + T = 1: albedo %.12f", sum / N);
    CHECKF(std::fabs(through / N - 0.7) < 0.01, "transmitted %.4f of 0.7", through / N);
}

// ---- textures ----

// A small PNG or EXR written for a test, removed by the caller.
std::string temp_image(const std::vector<float> &px, int w, int h, int c, const char *ext)
{
    char path[64];
    std::snprintf(path, sizeof path, "/tmp/udm1-models-XXXXXX%s", ext);
    int fd = mkstemps(path, (int)std::strlen(ext));
    close(fd);
    udm1app::write_image(path, px, w, h, c);
    return path;
}

void test_textures()
{
    // a checkerboard: tex1 where floor(s) + floor(t) is even, tex2 where odd; 2D through its uv mapping
    // (uscale, vscale, udelta, vdelta), 3D through the point in its space
    Scene s = load_text(std::string(HEAD) +
                        "Texture \"c2\" \"spectrum\" \"checkerboard\" \"float uscale\" [ 4 ] \"float vscale\" [ 2 ] "
                        "\"float udelta\" [ 0.5 ] \"float vdelta\" [ -0.25 ] \"rgb tex1\" [ 0.9 0.8 0.7 ] \"rgb tex2\" [ 0.1 0.2 0.3 ]\n"
                        "AttributeBegin\nScale 2 2 2\nTexture \"c3\" \"float\" \"checkerboard\" \"integer dimension\" [ 3 ] "
                        "\"float tex1\" [ 5 ] \"float tex2\" [ -1 ]\nAttributeEnd\n"
                        "Texture \"m\" \"float\" \"mix\" \"texture tex1\" \"c3\" \"float tex2\" [ 2 ] \"float amount\" [ 0.25 ]\n"
                        "Texture \"dm\" \"float\" \"directionmix\" \"float tex1\" [ 1 ] \"float tex2\" [ 3 ] \"vector3 dir\" [ 0 0 2 ]\n"
                        "Texture \"k\" \"float\" \"constant\" \"float value\" [ 0.75 ]\n"
                        "Texture \"sc\" \"float\" \"scale\" \"texture tex\" \"k\" \"texture scale\" \"m\"\n"
                        "Shape \"sphere\"\n");
    Textures tx(s);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> U(-3, 3);
    for (int i = 0; i < 2000; ++i) {
        TexturePoint at;
        at.u = U(rng), at.v = U(rng), at.p = Vec3(U(rng), U(rng), U(rng)), at.n = normalize(Vec3(U(rng), U(rng), U(rng)));
        double s2 = 4 * at.u + 0.5, t2 = 2 * at.v - 0.25;
        bool odd2 = ((long)std::floor(s2) + (long)std::floor(t2)) % 2 != 0;
        Vec3 want2 = odd2 ? Vec3(0.1, 0.2, 0.3) : Vec3(0.9, 0.8, 0.7), got2 = tx.rgb(0, at);
        CHECKF(length(got2 - want2) < 1e-12, "checkerboard 2D at (%g, %g): %g %g %g", at.u, at.v, got2.x, got2.y, got2.z);
        Vec3 q = at.p * 0.5;  // (the texture space: the inverse of Scale 2)
        bool odd3 = ((long)std::floor(q.x) + (long)std::floor(q.y) + (long)std::floor(q.z)) % 2 != 0;
        double c3 = odd3 ? -1 : 5;
        CHECK(tx.value(1, at) == c3);
        CHECK(std::fabs(tx.value(2, at) - (0.75 * c3 + 0.25 * 2)) < 1e-12);
        double a = std::fabs(at.n.z);
        CHECK(std::fabs(tx.value(3, at) - (a * 1 + (1 - a) * 3)) < 1e-12);
        CHECK(std::fabs(tx.value(5, at) - 0.75 * (0.75 * c3 + 0.25 * 2)) < 1e-12);
    }
    // the mappings' coordinates as pbrt-v4 defines them
    TextureMapping sph, cyl, pl;
    sph.kind = TextureMapping::Spherical, cyl.kind = TextureMapping::Cylindrical, pl.kind = TextureMapping::Planar;
    pl.v1 = Vec3(1, 2, 0), pl.v2 = Vec3(0, -1, 3), pl.du = 0.5, pl.dv = -2;
    TexturePoint at;
    at.p = Vec3(1, 1, std::sqrt(2.0));
    double si, ti;
    Textures::map2d(sph, at, &si, &ti);
    CHECKF(std::fabs(si - 0.25) < 1e-12 && std::fabs(ti - 0.125) < 1e-12, "spherical: %g %g (theta / pi, phi / 2 pi)", si, ti);
    at.p = Vec3(0, -2, 0.7);
    Textures::map2d(cyl, at, &si, &ti);
    CHECKF(std::fabs(si - 0.25) < 1e-12 && std::fabs(ti - 0.7) < 1e-12, "cylindrical: %g %g", si, ti);
    at.p = Vec3(1, 2, 3);
    Textures::map2d(pl, at, &si, &ti);
    CHECKF(std::fabs(si - 5.5) < 1e-12 && std::fabs(ti - 5) < 1e-12, "planar: %g %g", si, ti);

    // float textures of images, as pbrt-v4's MIPMap reads them: bilinear, an RGB image's average and an
    // RGBA image's alpha (when not 1 everywhere); point-sampled, the first channel
    std::vector<float> rgb = {0.2f, 0.4f, 0.9f}, rgba = {0.2f, 0.4f, 0.9f, 0.25f}, opaque = {0.2f, 0.4f, 0.9f, 1.0f};
    std::string f3 = temp_image(rgb, 1, 1, 3, ".exr"), f4 = temp_image(rgba, 1, 1, 4, ".exr"), f1 = temp_image(opaque, 1, 1, 4, ".exr");
    std::string text = std::string(HEAD);
    int n = 0;
    for (const std::string &f : {f3, f4, f1})
        for (const char *filter : {"bilinear", "point"})
            text += "Texture \"t" + std::to_string(n++) + "\" \"float\" \"imagemap\" \"string filename\" \"" + f +
                    "\" \"string filter\" \"" + filter + "\"\n";
    text += "Shape \"sphere\"\n";
    Scene si2 = load_text(text);
    Textures ti2(si2);
    TexturePoint any;
    any.u = 0.3, any.v = 0.6;
    double want[6] = {(0.2 + 0.4 + 0.9) / 3, 0.2, 0.25, 0.2, (0.2 + 0.4 + 0.9) / 3, 0.2};
    for (int k = 0; k < 6; ++k)
        CHECKF(std::fabs(ti2.value(k, any) - want[k]) < 1e-6, "float image texture %d: %.6f, pbrt-v4 reads %.6f", k,
               ti2.value(k, any), want[k]);
    for (const std::string &f : {f3, f4, f1}) std::remove(f.c_str());
    // a texture and a float texture may share a name: each parameter finds its kind
    Scene shared = load_text(std::string(HEAD) + "Texture \"x\" \"spectrum\" \"constant\" \"rgb value\" [ 0.5 0.5 0.5 ]\n"
                                                 "Texture \"x\" \"float\" \"constant\" \"float value\" [ 0.3 ]\n"
                                                 "Material \"coateddiffuse\" \"texture reflectance\" \"x\" \"texture roughness\" \"x\"\n"
                                                 "Shape \"sphere\"\n");
    Materials ms(shared);
    CHECK(ms.size() == 1);
    // refusals: a mapping's parameter another mapping has no use for (pbrt-v4 refuses unused parameters), a
    // texture of the wrong kind, an unknown texture type
    CHECK(refused(std::string(HEAD) + "Texture \"t\" \"float\" \"checkerboard\" \"string mapping\" \"planar\" \"float uscale\" [ 2 ]\n",
                  "unsupported parameter 'uscale'"));
    CHECK(refused(std::string(HEAD) + "Texture \"t\" \"float\" \"constant\"\nTexture \"u\" \"spectrum\" \"mix\" \"texture tex1\" \"t\"\n",
                  "texture \"t\" was not made (a spectrum texture)"));
    CHECK(refused(std::string(HEAD) + "Texture \"t\" \"float\" \"marble\"\n", "\"marble\" is not supported"));
}

// Conductor spectra given over part of the visible range: pbrt-v4 takes them as 0 outside their data. An eta
// that drops to 0 where k does not renders (a complex index of 0 + i k); where both do, pbrt-v4's Fresnel term
// is not a number and its samples there black: the conductor renders with those wavelengths' samples left out
// (tests/python/test_tool_pt_spectra.py checks the image against pbrt-v4's). Negative values are refused.
void test_partial_conductor_spectra()
{
    CHECK(refused(std::string(HEAD) + "Material \"conductor\" \"spectrum eta\" [ 400 -0.2 700 0.2 ] \"spectrum k\" [ 300 3 900 3 ]\n"
                                      "Shape \"sphere\"\n",
                  "eta and k must not be negative"));
    for (const char *m : {"\"spectrum eta\" [ 400 0.2 700 0.2 ] \"spectrum k\" [ 300 3 900 3 ]",
                          "\"spectrum eta\" [ 300 0.2 900 0.2 ] \"spectrum k\" [ 400 3 700 3 ]",
                          "\"spectrum eta\" [ 400 0.2 700 0.2 ] \"spectrum k\" [ 400 3 700 3 ]"}) {
        Scene s = load_text(std::string(HEAD) + "Material \"conductor\" " + m + "\nShape \"sphere\"\n");
        Materials mats(s);
        CHECK(mats.size() == 1);
    }
}

}  // namespace

int main()
{
    test_quadric_hits();
    test_bilinear_hits();
    test_surface_lights();
    test_loop_subdivision();
    test_alpha();
    test_layered_materials();
    test_diffuse_transmission();
    test_textures();
    test_partial_conductor_spectra();
    CHECK_DONE();
}
