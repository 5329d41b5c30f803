// math.cpp - see math.h.
#include "math.h"

#include <utility>

namespace udm1scene {

Mat4 operator*(const Mat4 &a, const Mat4 &b)
{
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a.m[i][k] * b.m[k][j];
            r.m[i][j] = s;
        }
    return r;
}

Mat4 Mat4::translate(Vec3 t)
{
    Mat4 r;
    r.m[0][3] = t.x;
    r.m[1][3] = t.y;
    r.m[2][3] = t.z;
    return r;
}

Mat4 Mat4::scale(Vec3 s)
{
    Mat4 r;
    r.m[0][0] = s.x;
    r.m[1][1] = s.y;
    r.m[2][2] = s.z;
    return r;
}

Mat4 Mat4::rotate(double degrees, Vec3 axis)
{
    Vec3 a = normalize(axis);
    double t = degrees * 3.14159265358979323846 / 180.0, c = std::cos(t), s = std::sin(t);
    Mat4 r;
    r.m[0][0] = a.x * a.x + (1 - a.x * a.x) * c;
    r.m[0][1] = a.x * a.y * (1 - c) - a.z * s;
    r.m[0][2] = a.x * a.z * (1 - c) + a.y * s;
    r.m[1][0] = a.x * a.y * (1 - c) + a.z * s;
    r.m[1][1] = a.y * a.y + (1 - a.y * a.y) * c;
    r.m[1][2] = a.y * a.z * (1 - c) - a.x * s;
    r.m[2][0] = a.x * a.z * (1 - c) - a.y * s;
    r.m[2][1] = a.y * a.z * (1 - c) + a.x * s;
    r.m[2][2] = a.z * a.z + (1 - a.z * a.z) * c;
    return r;
}

Mat4 Mat4::look_at(Vec3 eye, Vec3 look, Vec3 up, bool *ok)
{
    // pbrt: the world-from-camera matrix has columns right, new up, direction, eye; LookAt is its inverse
    Mat4 wfc;
    Vec3 dir = look - eye;
    *ok = length(dir) > 0 && length(up) > 0;
    if (!*ok) return wfc;
    dir = normalize(dir);
    Vec3 right = cross(normalize(up), dir);
    if (length(right) == 0) {
        *ok = false;
        return wfc;
    }
    right = normalize(right);
    Vec3 new_up = cross(dir, right);
    for (int i = 0; i < 3; ++i) {
        wfc.m[i][0] = right[i];
        wfc.m[i][1] = new_up[i];
        wfc.m[i][2] = dir[i];
        wfc.m[i][3] = eye[i];
    }
    Mat4 cfw;
    wfc.inverse(&cfw);
    return cfw;
}

Vec3 Mat4::point(Vec3 p) const
{
    double r[4];
    for (int i = 0; i < 4; ++i) r[i] = m[i][0] * p.x + m[i][1] * p.y + m[i][2] * p.z + m[i][3];
    return r[3] == 1.0 ? Vec3(r[0], r[1], r[2]) : Vec3(r[0] / r[3], r[1] / r[3], r[2] / r[3]);
}

Vec3 Mat4::vector(Vec3 v) const
{
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Vec3 Mat4::normal(Vec3 n) const
{
    Mat4 inv;
    inverse(&inv);  // normals go by the inverse transpose
    return {inv.m[0][0] * n.x + inv.m[1][0] * n.y + inv.m[2][0] * n.z,
            inv.m[0][1] * n.x + inv.m[1][1] * n.y + inv.m[2][1] * n.z,
            inv.m[0][2] * n.x + inv.m[1][2] * n.y + inv.m[2][2] * n.z};
}

bool Mat4::inverse(Mat4 *out) const
{
    // Gauss-Jordan with partial pivoting
    double a[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 8; ++j) a[i][j] = j < 4 ? m[i][j] : (j - 4 == i ? 1.0 : 0.0);
    for (int c = 0; c < 4; ++c) {
        int piv = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::fabs(a[r][c]) > std::fabs(a[piv][c])) piv = r;
        if (a[piv][c] == 0.0) return false;
        if (piv != c)
            for (int j = 0; j < 8; ++j) std::swap(a[c][j], a[piv][j]);
        double d = a[c][c];
        for (int j = 0; j < 8; ++j) a[c][j] /= d;
        for (int r = 0; r < 4; ++r)
            if (r != c) {
                double f = a[r][c];
                for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
            }
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) out->m[i][j] = a[i][j + 4];
    return true;
}

double Mat4::determinant3() const
{
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

double Mat4::scale_factor() const { return std::cbrt(std::fabs(determinant3())); }

bool Mat4::similarity(double tolerance, double *s) const
{
    double g[3][3], trace = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            g[i][j] = m[0][i] * m[0][j] + m[1][i] * m[1][j] + m[2][i] * m[2][j];
            if (i == j) trace += g[i][j];
        }
    double s2 = trace / 3;
    if (!(s2 > 0) || !std::isfinite(s2)) return false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (!(std::fabs(g[i][j] - (i == j ? s2 : 0.0)) <= tolerance * s2)) return false;
    *s = std::sqrt(s2);
    return true;
}

}  // namespace udm1scene
