// quadrics.cpp - see quadrics.h.
#include "quadrics.h"

#include <algorithm>
#include <cmath>

namespace udm1scene {

namespace {

const double PI = 3.14159265358979323846;

// phi of (x, y) in [0, 2 pi), as pbrt-v4 measures it
double phi_of(double x, double y)
{
    double phi = std::atan2(y, x);
    return phi < 0 ? phi + 2 * PI : phi;
}

// The roots of a t^2 + b t + c with the discriminant in pbrt-v4's form 4 a (r + |v|)(r - |v|), v the
// ray's offset from the axis or centre at its closest approach: false if there are none.
bool roots(double a, double b, double c, double r, double len, double *t0, double *t1)
{
    (void)c;
    double disc = 4 * a * (r + len) * (r - len);
    if (!(disc >= 0) || !(a > 0)) return false;
    double root = std::sqrt(disc), q = b < 0 ? -0.5 * (b - root) : -0.5 * (b + root);
    *t0 = q / a, *t1 = q != 0 ? c / q : *t0;
    if (*t0 > *t1) std::swap(*t0, *t1);
    return true;
}

// An object-space normal to world space by the inverse transpose (unnormalized).
Vec3 to_world_normal(const Shape &s, Vec3 n)
{
    const Mat4 &inv = s.object_from_world;
    return Vec3(inv.m[0][0] * n.x + inv.m[1][0] * n.y + inv.m[2][0] * n.z,
                inv.m[0][1] * n.x + inv.m[1][1] * n.y + inv.m[2][1] * n.z,
                inv.m[0][2] * n.x + inv.m[1][2] * n.y + inv.m[2][2] * n.z);
}

}  // namespace

int quadric_hits(const Shape &s, Vec3 o, Vec3 d, double tnear, double tfar, double t[2])
{
    Vec3 oo = s.object_from_world.point(o), dd = s.object_from_world.vector(d);
    const double r = s.object_radius;
    int n = 0;
    auto keep = [&](double x) {
        if (x > tnear && x <= tfar) t[n++] = x;
    };
    if (s.kind == Shape::Disk) {
        if (dd.z == 0) return 0;
        double th = (s.height - oo.z) / dd.z;
        if (!(th > tnear && th <= tfar)) return 0;
        double x = oo.x + th * dd.x, y = oo.y + th * dd.y, r2 = x * x + y * y;
        if (r2 > r * r || r2 < s.inner_radius * s.inner_radius) return 0;
        if (phi_of(x, y) > s.phi_max) return 0;
        t[0] = th;
        return 1;
    }
    double t0, t1;
    if (s.kind == Shape::Sphere) {
        double a = dot(dd, dd), b = 2 * dot(oo, dd), c = dot(oo, oo) - r * r;
        if (!(a > 0)) return 0;
        Vec3 v = oo - dd * (b / (2 * a));
        if (!roots(a, b, c, r, length(v), &t0, &t1)) return 0;
        keep(t0);
        if (t1 != t0) keep(t1);
        return n;
    }
    // a cylinder about the z axis
    double a = dd.x * dd.x + dd.y * dd.y, b = 2 * (dd.x * oo.x + dd.y * oo.y), c = oo.x * oo.x + oo.y * oo.y - r * r;
    if (!(a > 0)) return 0;
    double f = b / (2 * a), vx = oo.x - f * dd.x, vy = oo.y - f * dd.y;
    if (!roots(a, b, c, r, std::sqrt(vx * vx + vy * vy), &t0, &t1)) return 0;
    for (double x : {t0, t1}) {
        if (n == 1 && x == t[0]) continue;
        if (!(x > tnear && x <= tfar)) continue;
        double z = oo.z + x * dd.z, px = oo.x + x * dd.x, py = oo.y + x * dd.y;
        if (z < s.zmin || z > s.zmax || phi_of(px, py) > s.phi_max) continue;
        t[n++] = x;
    }
    return n;
}

Vec3 quadric_normal(const Shape &s, Vec3 p)
{
    if (s.kind == Shape::Sphere) return sphere_normal(s, p);
    Vec3 q = s.object_from_world.point(p);
    Vec3 n = s.kind == Shape::Disk ? Vec3(0, 0, 1) : Vec3(q.x, q.y, 0);
    return normalize(to_world_normal(s, n));
}

void quadric_uv(const Shape &s, Vec3 p, double *u, double *v)
{
    Vec3 q = s.object_from_world.point(p);
    if (s.kind == Shape::Sphere) {
        Vec3 d = q * (1 / s.object_radius);
        *u = phi_of(d.x, d.y) / (2 * PI);
        *v = 1 - std::acos(std::clamp(d.z, -1.0, 1.0)) / PI;
        return;
    }
    *u = phi_of(q.x, q.y) / s.phi_max;
    if (s.kind == Shape::Disk)
        *v = (s.object_radius - std::sqrt(q.x * q.x + q.y * q.y)) / (s.object_radius - s.inner_radius);
    else
        *v = (q.z - s.zmin) / (s.zmax - s.zmin);
}

void quadric_derivatives(const Shape &s, Vec3 p, Vec3 *dpdu, Vec3 *dpdv)
{
    Vec3 d = s.object_from_world.point(p);
    if (s.kind == Shape::Sphere) {
        double r = s.object_radius, rho = std::sqrt(d.x * d.x + d.y * d.y);
        *dpdu = Vec3(-2 * PI * d.y, 2 * PI * d.x, 0);
        double cos_phi = rho > 0 ? d.x / rho : 1, sin_phi = rho > 0 ? d.y / rho : 0;
        double theta = std::acos(std::clamp(d.z / r, -1.0, 1.0));
        *dpdv = Vec3(d.z * cos_phi, d.z * sin_phi, -r * std::sin(theta)) * (-PI);  // v = 1 - theta / pi
    } else if (s.kind == Shape::Disk) {
        double rho = std::sqrt(d.x * d.x + d.y * d.y);
        *dpdu = Vec3(-s.phi_max * d.y, s.phi_max * d.x, 0);
        *dpdv = rho > 0 ? Vec3(d.x, d.y, 0) * ((s.inner_radius - s.object_radius) / rho) : Vec3(-1, 0, 0);
    } else {
        *dpdu = Vec3(-s.phi_max * d.y, s.phi_max * d.x, 0);
        *dpdv = Vec3(0, 0, s.zmax - s.zmin);
    }
    *dpdu = s.world_from_object.vector(*dpdu), *dpdv = s.world_from_object.vector(*dpdv);
}

double quadric_area(const Shape &s)
{
    const double r = s.object_radius;
    if (s.kind == Shape::Sphere) return 4 * PI * r * r;
    if (s.kind == Shape::Disk) return s.phi_max * 0.5 * (r * r - s.inner_radius * s.inner_radius);
    return (s.zmax - s.zmin) * r * s.phi_max;
}

void quadric_sample_area(const Shape &s, double u1, double u2, Vec3 *p, Vec3 *n)
{
    Vec3 q, nq;
    if (s.kind == Shape::Disk) {  // Shirley and Chiu's concentric map, as pbrt-v4's SampleUniformDiskConcentric
        double ox = 2 * u1 - 1, oy = 2 * u2 - 1, r = 0, theta = 0;
        if (ox != 0 || oy != 0) {
            if (std::fabs(ox) > std::fabs(oy)) r = ox, theta = PI / 4 * (oy / ox);
            else r = oy, theta = PI / 2 - PI / 4 * (ox / oy);
        }
        q = Vec3(r * std::cos(theta) * s.object_radius, r * std::sin(theta) * s.object_radius, s.height);
        nq = Vec3(0, 0, 1);
    } else {
        double z = (1 - u1) * s.zmin + u1 * s.zmax, phi = u2 * s.phi_max;
        q = Vec3(s.object_radius * std::cos(phi), s.object_radius * std::sin(phi), z);
        nq = Vec3(q.x, q.y, 0);
    }
    *p = s.world_from_object.point(q);
    *n = normalize(to_world_normal(s, nq));
}

}  // namespace udm1scene
