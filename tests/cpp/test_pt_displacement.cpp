// test_pt_displacement.cpp - pbrt-v4's displaced plymesh (displacement.h) against what its rules imply: every edge
// shorter than edgelength in world space (measured after a non-uniform scale), the refined mesh watertight (an edge
// shared by two triangles is split once for both: no crack), each new vertex's uv the mean of its edge's ends (a
// planar uv stays the same affine function of the point), a constant height lifting a flat mesh by exactly that
// much along its normal, a height read at each vertex's uv, normals recomputed from the displaced faces; and the
// scene loader displacing a plymesh by its named float texture under its transform, in object space.
#include "../c/check.h"
#include "scene_text.h"

#include "displacement.h"
#include "scene.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

using namespace udm1scene;

namespace {

// A flat 2 x 2 square of two triangles at z = 0, uv = (x, y) / 2 + 1/2, normals +z.
DisplacedMesh square()
{
    DisplacedMesh m;
    m.P = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    m.N = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    m.UV = {0, 0, 1, 0, 1, 1, 0, 1};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

Vec3 vertex(const DisplacedMesh &m, uint32_t k) { return Vec3(m.P[3 * k], m.P[3 * k + 1], m.P[3 * k + 2]); }

void test_edges_and_watertight()
{
    DisplacedMesh m = square();
    Mat4 xf = Mat4::scale(Vec3(3, 0.5, 1));  // world edges 3x longer in x, half as long in y
    const double edge = 0.4;
    displace_mesh(m, xf, edge, [](const Vec3 &, double, double) { return 0.0; });
    CHECKF(m.indices.size() / 3 > 40, "%zu triangles", m.indices.size() / 3);
    double longest = 0;
    std::map<std::pair<uint32_t, uint32_t>, int> uses;
    for (size_t i = 0; i < m.indices.size(); i += 3)
        for (int e = 0; e < 3; ++e) {
            uint32_t a = m.indices[i + e], b = m.indices[i + (e + 1) % 3];
            longest = std::max(longest, length(xf.point(vertex(m, a)) - xf.point(vertex(m, b))));
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    CHECKF(longest < edge, "the longest world edge %.6f is not below %.2f", longest, edge);
    // watertight: an edge inside the square is used twice, one on its border once (no T-junction leaves an edge
    // of one triangle half-covered by two of the other)
    int bad = 0;
    for (const auto &[e, n] : uses) {
        Vec3 a = vertex(m, e.first), b = vertex(m, e.second);
        bool border = (std::fabs(a.x) == 1 && a.x == b.x) || (std::fabs(a.y) == 1 && a.y == b.y);
        bad += n != (border ? 1 : 2);
    }
    CHECKF(bad == 0, "%d edges used the wrong number of times (a crack)", bad);
    // uv the same affine function of the point at every vertex, normals still +z on the flat mesh
    for (size_t k = 0; k < m.P.size() / 3; ++k) {
        Vec3 p = vertex(m, (uint32_t)k);
        CHECKF(std::fabs(m.UV[2 * k] - (p.x / 2 + 0.5)) < 1e-6 && std::fabs(m.UV[2 * k + 1] - (p.y / 2 + 0.5)) < 1e-6,
               "vertex %zu: uv (%g, %g) at (%g, %g)", k, m.UV[2 * k], m.UV[2 * k + 1], p.x, p.y);
        CHECK(m.N[3 * k + 2] == 1.0f && m.N[3 * k] == 0.0f && m.N[3 * k + 1] == 0.0f);
    }
}

void test_heights()
{
    DisplacedMesh m = square();
    displace_mesh(m, Mat4(), 0.5, [](const Vec3 &, double, double) { return 0.25; });
    for (size_t k = 0; k < m.P.size() / 3; ++k) CHECKF(m.P[3 * k + 2] == 0.25f, "vertex %zu at z %g", k, m.P[3 * k + 2]);
    // a height read at the vertex's uv (and its object-space point): z = 0.3 u, a plane tilted about y
    DisplacedMesh t = square();
    displace_mesh(t, Mat4(), 0.5, [](const Vec3 &p, double u, double) { return 0.3 * u + 0 * p.x; });
    double worst = 0;
    for (size_t k = 0; k < t.P.size() / 3; ++k) worst = std::max(worst, std::fabs(t.P[3 * k + 2] - 0.3 * t.UV[2 * k]));
    CHECKF(worst < 1e-6, "z differs from 0.3 u by up to %g", worst);
    // the normals recomputed from the tilted faces: (-0.15, 0, 1) normalized (dz/dx = 0.3 / 2)
    double nx = -0.15 / std::sqrt(1 + 0.15 * 0.15), nz = 1 / std::sqrt(1 + 0.15 * 0.15);
    for (size_t k = 0; k < t.P.size() / 3; ++k)
        CHECKF(std::fabs(t.N[3 * k] - nx) < 1e-5 && std::fabs(t.N[3 * k + 2] - nz) < 1e-5, "vertex %zu normal (%g, %g, %g)", k,
               t.N[3 * k], t.N[3 * k + 1], t.N[3 * k + 2]);
}

void test_without_normals()
{
    // no vertex normals: the faces' before refining (the square's face normal is +z: ccw seen from +z)
    DisplacedMesh m = square();
    m.N.clear();
    displace_mesh(m, Mat4(), 1.0, [](const Vec3 &, double, double) { return -0.5; });
    for (size_t k = 0; k < m.P.size() / 3; ++k) CHECK(m.P[3 * k + 2] == -0.5f);
}

void test_scene_loader()
{
    // the grid of tests/scenes/displacement/grid.ply lifted by a constant texture under scale and rotation: every
    // vertex on the plane through the lifted grid (object z = 0.2), world edges below edgelength
    const std::string ply = std::string(UDM1_TEST_SCENES) + "/displacement/grid.ply";
    std::string text = "LookAt 0 -3 3  0 0 0  0 0 1\nCamera \"perspective\"\nWorldBegin\n"
                       "Texture \"lift\" \"float\" \"constant\" \"float value\" [ 0.2 ]\n"
                       "AttributeBegin\nTranslate 1 2 3\nScale 0.4 0.4 0.4\nRotate 30 1 0 0\n"
                       "Shape \"plymesh\" \"string filename\" \"" + ply + "\" \"texture displacement\" \"lift\" \"float edgelength\" [ 0.1 ]\n"
                       "AttributeEnd\n"
                       "Shape \"plymesh\" \"string filename\" \"" + ply + "\"\n";
    Scene s = load_scene_text(text);
    CHECK(s.shapes.size() == 2);
    if (s.shapes.size() != 2) return;
    const Shape &d = s.shapes[0], &plain = s.shapes[1];
    CHECKF(d.indices.size() > 10 * plain.indices.size(), "%zu displaced triangles, %zu undisplaced", d.indices.size() / 3,
           plain.indices.size() / 3);
    Mat4 xf = Mat4::translate(Vec3(1, 2, 3)) * Mat4::scale(Vec3(0.4, 0.4, 0.4)) * Mat4::rotate(30, Vec3(1, 0, 0));
    Vec3 o = xf.point(Vec3(0, 0, 0.2)), n = normalize(xf.normal(Vec3(0, 0, 1)));
    double off = 0, longest = 0;
    for (size_t k = 0; k < d.P.size(); k += 3) off = std::max(off, std::fabs(dot(Vec3(d.P[k], d.P[k + 1], d.P[k + 2]) - o, n)));
    for (size_t i = 0; i < d.indices.size(); i += 3)
        for (int e = 0; e < 3; ++e) {
            uint32_t a = d.indices[i + e], b = d.indices[i + (e + 1) % 3];
            longest = std::max(longest, length(Vec3(d.P[3 * a], d.P[3 * a + 1], d.P[3 * a + 2]) -
                                               Vec3(d.P[3 * b], d.P[3 * b + 1], d.P[3 * b + 2])));
        }
    CHECKF(off < 1e-6, "a displaced vertex is %g off the lifted plane", off);
    CHECKF(longest < 0.1 && longest > 0.03, "the longest world edge is %g (edgelength 0.1)", longest);
    CHECK(d.N.size() == d.P.size());
    for (size_t k = 0; k < d.N.size(); k += 3)
        CHECKF(std::fabs(dot(Vec3(d.N[k], d.N[k + 1], d.N[k + 2]), n) - 1) < 1e-5, "normal %zu off the plane's", k / 3);
}

}  // namespace

int main()
{
    test_edges_and_watertight();
    test_heights();
    test_without_normals();
    test_scene_loader();
    CHECK_DONE();
}
