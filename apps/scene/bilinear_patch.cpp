// bilinear_patch.cpp - see bilinear_patch.h.
#include "bilinear_patch.h"

#include <algorithm>
#include <cmath>

namespace udm1scene {

namespace {

inline Vec3 lerp(double t, Vec3 a, Vec3 b) { return a * (1 - t) + b * t; }
inline double max_abs(Vec3 v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }
// The determinant of the 3 x 3 matrix of columns a, b, c.
inline double det3(Vec3 a, Vec3 b, Vec3 c) { return dot(a, cross(b, c)); }

// pbrt-v4's SampleLinear: x in [0, 1) with density proportional to (1 - x) a + x b.
double sample_linear(double u, double a, double b)
{
    if (u == 0 && a == 0) return 0;
    double x = u * (a + b) / (a + std::sqrt((1 - u) * a * a + u * b * b));
    return std::min(x, 0x1.fffffffffffffp-1);
}

}  // namespace

Vec3 Patch::at(double u, double v) const { return lerp(u, lerp(v, p00, p01), lerp(v, p10, p11)); }

void Patch::derivatives(double u, double v, Vec3 *dpdu, Vec3 *dpdv) const
{
    *dpdu = lerp(v, p10, p11) - lerp(v, p00, p01);
    *dpdv = lerp(u, p01, p11) - lerp(u, p00, p10);
}

bool Patch::rectangle() const
{
    auto same = [](Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
    if (same(p00, p01) || same(p01, p11) || same(p11, p10) || same(p10, p00)) return false;
    Vec3 n = normalize(cross(p10 - p00, p01 - p00));
    if (std::fabs(dot(normalize(p11 - p00), n)) > 1e-5) return false;
    Vec3 c = (p00 + p01 + p10 + p11) * 0.25;
    double d2[4] = {dot(p00 - c, p00 - c), dot(p01 - c, p01 - c), dot(p10 - c, p10 - c), dot(p11 - c, p11 - c)};
    for (int i = 1; i < 4; ++i)
        if (std::fabs(d2[i] - d2[0]) / d2[0] > 1e-4) return false;
    return true;
}

double Patch::area() const
{
    if (rectangle()) return length(p00 - p01) * length(p00 - p10);
    const int n = 3;
    Vec3 p[n + 1][n + 1];
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) p[i][j] = at((double)i / n, (double)j / n);
    double a = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) a += 0.5 * length(cross(p[i + 1][j + 1] - p[i][j], p[i + 1][j] - p[i][j + 1]));
    return a;
}

void Patch::corner_weights(double w[4]) const
{
    w[0] = length(cross(p10 - p00, p01 - p00)), w[1] = length(cross(p10 - p00, p11 - p10));
    w[2] = length(cross(p01 - p00, p11 - p01)), w[3] = length(cross(p11 - p10, p11 - p01));
}

Patch patch_of(const Shape &s, unsigned prim)
{
    const uint32_t *i = &s.indices[4 * (size_t)prim];
    auto P = [&](uint32_t k) { return Vec3(s.P[3 * k], s.P[3 * k + 1], s.P[3 * k + 2]); };
    return {P(i[0]), P(i[1]), P(i[2]), P(i[3])};
}

int patch_hits(const Patch &q, Vec3 o, Vec3 d, double tnear, double tfar, double t[2], double uv[2][2])
{
    // the distance from the ray to the u isolines is a quadratic in u
    double a = dot(cross(q.p10 - q.p00, q.p01 - q.p11), d);
    double c = dot(cross(q.p00 - o, d), q.p01 - q.p00);
    double b = dot(cross(q.p10 - o, d), q.p11 - q.p10) - (a + c);
    double u[2];
    if (a == 0) {
        if (b == 0) return 0;
        u[0] = u[1] = -c / b;
    } else {
        double disc = b * b - 4 * a * c;
        if (disc < 0) return 0;
        double q2 = -0.5 * (b + std::copysign(std::sqrt(disc), b));
        u[0] = q2 / a, u[1] = q2 != 0 ? c / q2 : u[0];
        if (u[0] > u[1]) std::swap(u[0], u[1]);
    }
    // hits closer than eps (relative to the coordinates' magnitudes) are the ray's own origin
    const double eps = 30 * 0x1p-53 *
                       (max_abs(o) + max_abs(d) + max_abs(q.p00) + max_abs(q.p10) + max_abs(q.p01) + max_abs(q.p11));
    int n = 0;
    for (int k = 0; k < 2; ++k) {
        if (k == 1 && u[1] == u[0]) break;
        if (!(u[k] >= 0 && u[k] <= 1)) continue;
        Vec3 uo = lerp(u[k], q.p00, q.p10), ud = lerp(u[k], q.p01, q.p11) - uo, deltao = uo - o;
        Vec3 perp = cross(d, ud);
        double p2 = dot(perp, perp);
        double v1 = det3(deltao, d, perp), t1 = det3(deltao, ud, perp);
        if (!(p2 > 0) || !(v1 >= 0 && v1 <= p2) || !(t1 > p2 * eps)) continue;
        double th = t1 / p2;
        if (!(th > tnear && th <= tfar)) continue;
        t[n] = th, uv[n][0] = u[k], uv[n][1] = v1 / p2;
        ++n;
    }
    if (n == 2 && t[1] < t[0]) {
        std::swap(t[0], t[1]);
        std::swap(uv[0][0], uv[1][0]), std::swap(uv[0][1], uv[1][1]);
    }
    return n;
}

Vec3 patch_shading_normal(const Shape &s, unsigned prim, double u, double v)
{
    if (s.N.empty()) return Vec3();
    const uint32_t *i = &s.indices[4 * (size_t)prim];
    auto N = [&](uint32_t k) { return Vec3(s.N[3 * k], s.N[3 * k + 1], s.N[3 * k + 2]); };
    Vec3 n = lerp(u, lerp(v, N(i[0]), N(i[2])), lerp(v, N(i[1]), N(i[3])));
    double len = length(n);
    return len > 0 ? n * (1 / len) : Vec3();
}

Vec3 patch_normal(const Shape &s, unsigned prim, double u, double v)
{
    Patch q = patch_of(s, prim);
    Vec3 dpdu, dpdv;
    q.derivatives(u, v, &dpdu, &dpdv);
    Vec3 n = cross(dpdu, dpdv);
    if (!(dot(n, n) > 0)) {  // a degenerate corner (two vertices equal): the orientation at the centre
        q.derivatives(0.5, 0.5, &dpdu, &dpdv);
        n = cross(dpdu, dpdv);
    }
    if (!(dot(n, n) > 0)) return Vec3(0, 0, 1);
    n = normalize(n);
    if (!s.N.empty()) {
        Vec3 ns = patch_shading_normal(s, prim, u, v);
        return dot(n, ns) < 0 ? -n : n;
    }
    return s.reverse_orientation ? -n : n;
}

void patch_texture_uv(const Shape &s, unsigned prim, double u, double v, double *su, double *sv)
{
    if (s.UV.empty()) {
        *su = u, *sv = v;
        return;
    }
    const uint32_t *i = &s.indices[4 * (size_t)prim];
    auto T = [&](uint32_t k, int c) { return (double)s.UV[2 * k + c]; };
    for (int c = 0; c < 2; ++c) {
        double x = (1 - u) * ((1 - v) * T(i[0], c) + v * T(i[2], c)) + u * ((1 - v) * T(i[1], c) + v * T(i[3], c));
        (c == 0 ? *su : *sv) = x;
    }
}

void patch_texture_derivatives(const Shape &s, unsigned prim, double u, double v, Vec3 *dpds, Vec3 *dpdt)
{
    Patch q = patch_of(s, prim);
    Vec3 dpdu, dpdv;
    q.derivatives(u, v, &dpdu, &dpdv);
    *dpds = dpdu, *dpdt = dpdv;
    if (s.UV.empty()) return;
    const uint32_t *i = &s.indices[4 * (size_t)prim];
    auto T = [&](uint32_t k, int c) { return (double)s.UV[2 * k + c]; };
    // d(s, t)/du and d(s, t)/dv, then their reciprocals where not degenerate (pbrt-v4's)
    double dsdu = (1 - v) * (T(i[1], 0) - T(i[0], 0)) + v * (T(i[3], 0) - T(i[2], 0));
    double dtdu = (1 - v) * (T(i[1], 1) - T(i[0], 1)) + v * (T(i[3], 1) - T(i[2], 1));
    double dsdv = (1 - u) * (T(i[2], 0) - T(i[0], 0)) + u * (T(i[3], 0) - T(i[1], 0));
    double dtdv = (1 - u) * (T(i[2], 1) - T(i[0], 1)) + u * (T(i[3], 1) - T(i[1], 1));
    auto inv = [](double x) { return std::fabs(x) < 1e-8 ? 0.0 : 1 / x; };
    double duds = inv(dsdu), dvds = inv(dsdv), dudt = inv(dtdu), dvdt = inv(dtdv);
    Vec3 a = dpdu * duds + dpdv * dvds, b = dpdu * dudt + dpdv * dvdt;
    Vec3 c = cross(a, b);
    if (c.x == 0 && c.y == 0 && c.z == 0) return;
    if (dot(cross(dpdu, dpdv), c) < 0) b = -b;
    *dpds = a, *dpdt = b;
}

void sample_bilinear(double u1, double u2, const double w[4], double *u, double *v)
{
    *v = sample_linear(u2, w[0] + w[1], w[2] + w[3]);
    *u = sample_linear(u1, (1 - *v) * w[0] + *v * w[2], (1 - *v) * w[1] + *v * w[3]);
}

double bilinear_pdf(double u, double v, const double w[4])
{
    if (u < 0 || u > 1 || v < 0 || v > 1) return 0;
    double sum = w[0] + w[1] + w[2] + w[3];
    if (sum == 0) return 1;
    return 4 * ((1 - u) * (1 - v) * w[0] + u * (1 - v) * w[1] + (1 - u) * v * w[2] + u * v * w[3]) / sum;
}

}  // namespace udm1scene
