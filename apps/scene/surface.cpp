// surface.cpp - see surface.h.
#include "surface.h"

#include "bilinear_patch.h"
#include "quadrics.h"

#include <cmath>

namespace udm1scene {

void hit_uv(const Shape &s, const Hit &h, double *u, double *v)
{
    if (s.quadric()) return quadric_uv(s, shape_point(h), u, v);
    if (s.kind == Shape::Bilinear) return patch_texture_uv(s, h.prim, h.u, h.v, u, v);
    double b0 = 1 - h.u - h.v;
    if (s.UV.empty()) {  // pbrt-v4: (0,0), (1,0), (1,1)
        *u = h.u + h.v, *v = h.v;
        return;
    }
    const uint32_t *i = &s.indices[3 * (size_t)h.prim];
    *u = b0 * s.UV[2 * i[0]] + h.u * s.UV[2 * i[1]] + h.v * s.UV[2 * i[2]];
    *v = b0 * s.UV[2 * i[0] + 1] + h.u * s.UV[2 * i[1] + 1] + h.v * s.UV[2 * i[2] + 1];
}

Vec3 interpolated_normal(const Shape &s, const Hit &h)
{
    if (s.kind == Shape::Bilinear) {
        Vec3 n = world_normal(h, patch_shading_normal(s, h.prim, h.u, h.v));
        double len = length(n);
        return len > 0 ? n * (1 / len) : h.ng;
    }
    if (s.kind != Shape::Triangles) return h.ng;
    const uint32_t *i = &s.indices[3 * (size_t)h.prim];
    auto N = [&](uint32_t k) { return Vec3(s.N[3 * k], s.N[3 * k + 1], s.N[3 * k + 2]); };
    Vec3 n = world_normal(h, N(i[0]) * (1 - h.u - h.v) + N(i[1]) * h.u + N(i[2]) * h.v);
    double len = length(n);
    return len > 0 ? n * (1 / len) : h.ng;
}

void surface_derivatives(const Shape &s, const Hit &h, Vec3 n, Vec3 *dpdu, Vec3 *dpdv)
{
    if (h.instance) {  // the shape's own derivatives (in the object's space), placed by the instance
        Hit local = h;
        local.instance = nullptr, local.p = shape_point(h);
        Vec3 nl = h.instance->world_from_object.transposed_vector(n);  // (a normal to the object's space)
        surface_derivatives(s, local, normalize(nl), dpdu, dpdv);
        *dpdu = world_vector(h, *dpdu), *dpdv = world_vector(h, *dpdv);
        return;
    }
    if (s.quadric()) return quadric_derivatives(s, h.p, dpdu, dpdv);
    if (s.kind == Shape::Bilinear) return patch_texture_derivatives(s, h.prim, h.u, h.v, dpdu, dpdv);
    const uint32_t *i = &s.indices[3 * (size_t)h.prim];
    auto P = [&](uint32_t k) { return Vec3(s.P[3 * k], s.P[3 * k + 1], s.P[3 * k + 2]); };
    double uv[3][2] = {{0, 0}, {1, 0}, {1, 1}};
    if (!s.UV.empty())
        for (int k = 0; k < 3; ++k) uv[k][0] = s.UV[2 * i[k]], uv[k][1] = s.UV[2 * i[k] + 1];
    double du02 = uv[0][0] - uv[2][0], dv02 = uv[0][1] - uv[2][1], du12 = uv[1][0] - uv[2][0], dv12 = uv[1][1] - uv[2][1];
    Vec3 dp02 = P(i[0]) - P(i[2]), dp12 = P(i[1]) - P(i[2]);
    double det = du02 * dv12 - dv02 * du12;
    bool ok = std::fabs(det) >= 1e-12;
    if (ok) {
        *dpdu = (dp02 * dv12 - dp12 * dv02) * (1 / det);
        *dpdv = (dp12 * du02 - dp02 * du12) * (1 / det);
        ok = dot(cross(*dpdu, *dpdv), cross(*dpdu, *dpdv)) > 0;
    }
    if (!ok) {
        Frame f(n);
        *dpdu = f.t, *dpdv = f.b;
    }
}

TexturePoint texture_point(const Shape &s, const Hit &h)
{
    TexturePoint tp;
    tp.p = h.p, tp.n = h.ng;
    hit_uv(s, h, &tp.u, &tp.v);
    return tp;
}

}  // namespace udm1scene
