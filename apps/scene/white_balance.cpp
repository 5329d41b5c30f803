// white_balance.cpp - see white_balance.h.
#include "white_balance.h"

#include "spectrum.h"

#include <cmath>

namespace udm1scene {

namespace {

// Bradford's cone responses from XYZ (the standard matrix, as pbrt-v4 uses it)
const double LMS_FROM_XYZ[3][3] = {{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}};

Vec3 apply(const double m[3][3], Vec3 v)
{
    return Vec3(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z);
}

void invert(const double a[3][3], double r[3][3])
{
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
            r[i][j] = (a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]) / det;
        }
}

Vec3 xyz_of_xy(double x, double y) { return Vec3(x / y, 1, (1 - x - y) / y); }  // (at luminance 1)

}  // namespace

void white_balance_source(double kelvin, double *x, double *y)
{
    const double cct = kelvin * 1.4388 / 1.4380;
    if (cct < 4000) {  // (the CIE D illuminants are not defined there: a blackbody)
        Vec3 c = spectrum_xyz(Spectrum::blackbody(cct));
        double sum = c.x + c.y + c.z;
        *x = c.x / sum, *y = c.y / sum;
        return;
    }
    // the CIE daylight locus (CIE 15: x_D from the temperature, y_D from x_D)
    double xd = cct <= 7000 ? -4.607e9 / (cct * cct * cct) + 2.9678e6 / (cct * cct) + 0.09911e3 / cct + 0.244063
                            : -2.0064e9 / (cct * cct * cct) + 1.9018e6 / (cct * cct) + 0.24748e3 / cct + 0.23704;
    *x = xd, *y = -3 * xd * xd + 2.870 * xd - 0.275;
}

bool white_balance_rgb(double kelvin, Vec3 rows[3])
{
    double sx, sy;
    white_balance_source(kelvin, &sx, &sy);
    Vec3 d65 = spectrum_xyz(*named_spectrum("stdillum-D65"));
    double sum = d65.x + d65.y + d65.z;
    Vec3 src = apply(LMS_FROM_XYZ, xyz_of_xy(sx, sy)), dst = apply(LMS_FROM_XYZ, xyz_of_xy(d65.x / sum, d65.y / sum));
    double xyz_from_lms[3][3];
    invert(LMS_FROM_XYZ, xyz_from_lms);
    bool finite = true;
    for (int c = 0; c < 3; ++c) {  // column c: the image of the primary c
        Vec3 e;
        e[c] = 1;
        Vec3 lms = apply(LMS_FROM_XYZ, rgb_to_xyz(e));
        for (int k = 0; k < 3; ++k) lms[k] *= dst[k] / src[k];
        Vec3 col = xyz_to_rgb(apply(xyz_from_lms, lms));
        for (int r = 0; r < 3; ++r) rows[r][c] = col[r], finite &= std::isfinite(col[r]);
    }
    return finite;
}

}  // namespace udm1scene
