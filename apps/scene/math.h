// math.h - the small vector and matrix types of the scene code (double precision).
#pragma once

#include <cmath>

namespace udm1scene {

struct Vec3 {
    double x = 0, y = 0, z = 0;
    Vec3() = default;
    Vec3(double a, double b, double c) : x(a), y(b), z(c) {}
    double operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
    double &operator[](int i) { return i == 0 ? x : i == 1 ? y : z; }
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator*(double s, Vec3 a) { return a * s; }
inline Vec3 mul(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) { return a * (1.0 / length(a)); }

// An orthonormal basis (t, b, n) around unit n (Duff et al. 2017), with the changes of frame.
struct Frame {
    Vec3 t, b, n;
    explicit Frame(Vec3 nn) : n(nn)
    {
        double s = std::copysign(1.0, n.z), a = -1.0 / (s + n.z), c = n.x * n.y * a;
        t = Vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
        b = Vec3(c, s + n.y * n.y * a, -n.y);
    }
    Vec3 to_local(Vec3 v) const { return Vec3(dot(v, t), dot(v, b), dot(v, n)); }
    Vec3 from_local(Vec3 v) const { return t * v.x + b * v.y + n * v.z; }
};

// sin and cos of 2 pi u for u in [0, 1), to about 2e-9: the quadrant from 4u, then Taylor series
// around pi/4 (|x| <= pi/4, terms to x^10) turned by 45 degrees. Plain arithmetic, so the same on every
// machine and thread, and several times faster than libm's sincos; no branches, so loops over
// samples vectorize.
inline void sincos_2pi(double u, double *s, double *c)
{
    const double half_sqrt2 = 0.70710678118654752440;
    double q4 = 4.0 * u;
    int q = (int)q4;                                     // quadrant 0..3
    double x = (q4 - q - 0.5) * 1.57079632679489661923;  // angle in the quadrant minus pi/4
    double x2 = x * x;
    double sn = x * (1 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880)))));
    double cs = 1 + x2 * (-0.5 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320 - x2 / 3628800))));
    double si = half_sqrt2 * (sn + cs), co = half_sqrt2 * (cs - sn);  // sin, cos of x + pi/4
    bool odd = q & 1, neg_s = q >= 2, neg_c = q == 1 || q == 2;  // turn by q quarter turns
    double s0 = odd ? co : si, c0 = odd ? si : co;
    *s = neg_s ? -s0 : s0;
    *c = neg_c ? -c0 : c0;
}

// Row-major 4x4 matrix; transforms points as m * (x, y, z, 1).
struct Mat4 {
    double m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    static Mat4 translate(Vec3 t);
    static Mat4 scale(Vec3 s);
    static Mat4 rotate(double degrees, Vec3 axis);
    static Mat4 look_at(Vec3 eye, Vec3 look, Vec3 up, bool *ok);  // pbrt's LookAt: camera-from-world
    Vec3 point(Vec3 p) const;
    Vec3 vector(Vec3 v) const;
    Vec3 normal(Vec3 n) const;  // by the inverse transpose; pass the inverse's transpose-less normal: see .cpp
    // The 3x3 part's transpose times v: a normal by the inverse transpose when this is the inverse.
    Vec3 transposed_vector(Vec3 v) const
    {
        return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z, m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
                m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
    }
    bool inverse(Mat4 *out) const;
    double scale_factor() const;  // the cube root of |det| of the 3x3 part
    double determinant3() const;  // of the 3x3 part (negative: the transform swaps handedness)
    bool affine() const { return m[3][0] == 0 && m[3][1] == 0 && m[3][2] == 0 && m[3][3] == 1; }
    // Whether the 3x3 part is s times an orthogonal matrix (a rotation, maybe with a reflection), each
    // entry of its Gram matrix A^T A within `tolerance` of s^2 I relative to s^2; *s then holds s.
    bool similarity(double tolerance, double *s) const;
};
Mat4 operator*(const Mat4 &a, const Mat4 &b);

}  // namespace udm1scene
