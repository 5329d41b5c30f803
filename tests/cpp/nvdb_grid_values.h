// nvdb_grid_values.h - the values of the NanoVDB test files (nvdb_grids.h) in closed form, and the names of
// the files the writer makes: what a test compares udm1-pt's reader against, without NanoVDB's builder
// (its templates take most of a test's compile time, under the sanitizers 40 s).
#pragma once

#include <cmath>

namespace nvdb_grids {

// The smooth density of the "ramp" grid at voxel (i, j, k): in [0.05, 1.05] over its box, 0 outside.
inline float ramp_density(int i, int j, int k)
{
    if (i < -12 || i > 11 || j < -6 || j > 13 || k < -9 || k > 9) return 0.0f;
    return (float)(0.55 + 0.5 * std::sin(0.31 * i + 0.17) * std::cos(0.23 * j - 0.4) * std::cos(0.19 * k + 0.3));
}
// Its voxel size and origin: index (i, j, k) is at world RAMP_ORIGIN + RAMP_VOXEL * (i, j, k).
constexpr double RAMP_VOXEL = 0.0625;
constexpr double RAMP_ORIGIN[3] = {0.3, -0.2, 0.1};

// The sphere of the "sphere" and "fire" files: radius 1 at (2, 2, 2), voxel size 0.1 (index (20, 20, 20)
// at its centre: in one of the root's octants, so that the files stay small).
constexpr double SPHERE_CENTRE = 2, SPHERE_VOXEL = 0.1;

// The temperature of the fire sphere at voxel (i, j, k): hot inside, cooling outwards, 0 past radius 1.2.
inline float fire_temperature(int i, int j, int k)
{
    i -= 20, j -= 20, k -= 20;
    double r = 0.1 * std::sqrt((double)(i * i + j * j + k * k));
    return r > 1.2 ? 0.0f : (float)(900 + 1400 * (1.2 - r));
}

// The kinds of file the writer makes (nvdb_grids::write).
inline const char *const KINDS_LIST[] = {"sphere", "fire", "ramp", "named", "double", "temperature-double", "level-set",
                                         "negative", "nan", "empty"};

}  // namespace nvdb_grids
