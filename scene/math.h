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
    bool inverse(Mat4 *out) const;
    double scale_factor() const;  // the cube root of |det| of the 3x3 part
};
Mat4 operator*(const Mat4 &a, const Mat4 &b);

}  // namespace udm1scene
