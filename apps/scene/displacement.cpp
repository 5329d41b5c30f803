// displacement.cpp - pbrt-v4's displaced plymesh: refine, displace, recompute the normals (displacement.h).
#include "displacement.h"

#include <array>
#include <cmath>
#include <unordered_map>

namespace udm1scene {

namespace {

struct Refiner {
    DisplacedMesh &m;
    const Mat4 &xf;
    double edge;
    std::vector<uint32_t> out;
    std::unordered_map<uint64_t, uint32_t> split;  // edge (low, high vertex) -> its midpoint

    Vec3 p(uint32_t v) const { return Vec3(m.P[3 * v], m.P[3 * v + 1], m.P[3 * v + 2]); }
    double dist(uint32_t a, uint32_t b) const { return length(xf.point(p(a)) - xf.point(p(b))); }

    uint32_t midpoint(uint32_t a, uint32_t b)
    {
        uint64_t key = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
        auto it = split.find(key);
        if (it != split.end()) return it->second;
        uint32_t v = (uint32_t)(m.P.size() / 3);
        split.emplace(key, v);
        for (int c = 0; c < 3; ++c) m.P.push_back((m.P[3 * a + c] + m.P[3 * b + c]) / 2);
        float n[3] = {m.N[3 * a] + m.N[3 * b], m.N[3 * a + 1] + m.N[3 * b + 1], m.N[3 * a + 2] + m.N[3 * b + 2]};
        float len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        float len = len2 > 0 ? std::sqrt(len2) : 1;
        for (float x : n) m.N.push_back(x / len);
        for (int c = 0; c < 2; ++c) m.UV.push_back((m.UV[2 * a + c] + m.UV[2 * b + c]) / 2);
        return v;
    }

    // pbrt-v4's Refine, as a loop over a stack of triangles (deep recursions on long edges stay off the call stack);
    // the two halves are refined first-half first, as pbrt-v4 recurses, so the vertices are numbered as its are
    void refine(uint32_t v0, uint32_t v1, uint32_t v2)
    {
        std::vector<std::array<uint32_t, 3>> todo{{v0, v1, v2}};
        while (!todo.empty()) {
            auto [a, b, c] = todo.back();
            todo.pop_back();
            double d01 = dist(a, b), d12 = dist(b, c), d20 = dist(c, a);
            if (d01 < edge && d12 < edge && d20 < edge) {
                out.insert(out.end(), {a, b, c});
                continue;
            }
            std::array<uint32_t, 3> v;  // the longest edge first
            if (d01 > d12) v = d01 > d20 ? std::array<uint32_t, 3>{a, b, c} : std::array<uint32_t, 3>{c, a, b};
            else v = d12 > d20 ? std::array<uint32_t, 3>{b, c, a} : std::array<uint32_t, 3>{c, a, b};
            uint32_t mid = midpoint(v[0], v[1]);
            todo.push_back({mid, v[1], v[2]});  // (popped second)
            todo.push_back({v[0], mid, v[2]});
        }
    }
};

}  // namespace

void face_normals(DisplacedMesh &m)
{
    size_t nv = m.P.size() / 3;
    std::vector<float> n(3 * nv, 0.0f);
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
        const uint32_t *v = &m.indices[i];
        float e10[3], e21[3];
        for (int c = 0; c < 3; ++c) e10[c] = m.P[3 * v[1] + c] - m.P[3 * v[0] + c], e21[c] = m.P[3 * v[2] + c] - m.P[3 * v[1] + c];
        float f[3] = {e10[1] * e21[2] - e10[2] * e21[1], e10[2] * e21[0] - e10[0] * e21[2], e10[0] * e21[1] - e10[1] * e21[0]};
        float len2 = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
        if (!(len2 > 0)) continue;
        float len = std::sqrt(len2);
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) n[3 * v[k] + c] += f[c] / len;
    }
    for (size_t k = 0; k < nv; ++k) {
        float len2 = n[3 * k] * n[3 * k] + n[3 * k + 1] * n[3 * k + 1] + n[3 * k + 2] * n[3 * k + 2];
        if (len2 > 0)
            for (int c = 0; c < 3; ++c) n[3 * k + c] /= std::sqrt(len2);
    }
    m.N = std::move(n);
}

void displace_mesh(DisplacedMesh &m, const Mat4 &world_from_object, double edgelength,
                   const std::function<double(const Vec3 &p, double u, double v)> &height)
{
    if (m.N.size() != m.P.size()) face_normals(m);
    Refiner r{m, world_from_object, edgelength, {}, {}};
    std::vector<uint32_t> old = std::move(m.indices);
    for (size_t i = 0; i + 2 < old.size(); i += 3) r.refine(old[i], old[i + 1], old[i + 2]);
    m.indices = std::move(r.out);
    size_t nv = m.P.size() / 3;
    for (size_t k = 0; k < nv; ++k) {
        float d = (float)height(Vec3(m.P[3 * k], m.P[3 * k + 1], m.P[3 * k + 2]), m.UV[2 * k], m.UV[2 * k + 1]);
        for (int c = 0; c < 3; ++c) m.P[3 * k + c] += d * m.N[3 * k + c];
    }
    face_normals(m);
}

}  // namespace udm1scene
