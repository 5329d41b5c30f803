// grid_medium.h - pbrt-v4's heterogeneous media as its VolPathIntegrator samples them, in RGB: the density of
// a "uniformgrid" (trilinear between its samples, pbrt-v4's SampledGrid), a "nanovdb" grid (trilinear between
// its voxels, nanovdb_grid.h) or a "cloud" (pbrt-v4's procedural cloud over Perlin noise, udm1's improved
// noise with Perlin's table) at a point, the coefficients and emission there, and the majorants along a ray:
// for a uniform grid pbrt-v4's 16 x 16 x 16 grid of the density's maxima over the box, for a NanoVDB grid its
// 64 x 64 x 64 grid of the maxima of the voxels each cell's trilinear lookups can reach, and a 3D DDA through
// the cells; for a cloud one majorant over the box (its density is at most 1). Delta tracking against these majorants (estimator.h) is unbiased: each majorant
// bounds sigma_t everywhere along its piece of the ray.
#pragma once

#include "scene.h"

#include <udm1/udm1.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace udm1pt {

using udm1scene::Vec3;

// A piece [t0, t1) of a ray (world distances along its unit direction) and a majorant of sigma_t on it.
struct MajorantSegment {
    double t0 = 0, t1 = 0;
    Vec3 sigma_maj;
};

// pbrt-v4's MajorantGrid: res[0] x res[1] x res[2] cells over the unit box (the medium's box mapped to
// [0, 1]^3), each holding a bound of the density over the cell (x fastest): RES^3 for a uniform grid,
// NANOVDB_RES^3 for a NanoVDB grid, as pbrt-v4 sizes them.
struct MajorantGrid {
    static constexpr int RES = 16, NANOVDB_RES = 64;
    int res[3] = {RES, RES, RES};
    std::vector<float> max;
    double at(int x, int y, int z) const { return max[(size_t)x + res[0] * ((size_t)y + res[1] * (size_t)z)]; }
};

// The majorant segments of a ray through a medium's box, in order: a DDA through a MajorantGrid's cells (one
// segment per cell it crosses, pbrt-v4's DDAMajorantIterator) or, without a grid, the whole overlap as one
// segment of majorant sigma_t.
class MajorantIterator {
public:
    MajorantIterator() = default;  // no segments
    // A ray in the unit box's coordinates (o_unit + t d_unit) between t_min and t_max.
    MajorantIterator(Vec3 o_unit, Vec3 d_unit, double t_min, double t_max, const MajorantGrid *grid, Vec3 sigma_t);
    bool next(MajorantSegment *seg);
    // The cell the next segment is in (for tests).
    int cell(int axis) const { return voxel_[axis]; }

private:
    double t_min_ = INFINITY, t_max_ = -INFINITY;
    const MajorantGrid *grid_ = nullptr;
    Vec3 sigma_t_;
    double next_t_[3] = {0, 0, 0}, delta_t_[3] = {0, 0, 0};
    int step_[3] = {0, 0, 0}, limit_[3] = {0, 0, 0}, voxel_[3] = {0, 0, 0};
};

// A uniformgrid, nanovdb or cloud medium of a scene, ready to sample (immutable: threads share it).
class GridMedium {
public:
    explicit GridMedium(const udm1scene::Medium &m);
    ~GridMedium();
    GridMedium(const GridMedium &) = delete;
    GridMedium &operator=(const GridMedium &) = delete;

    // The coefficients and emitted radiance at world point p (0 outside the box).
    struct Point {
        Vec3 sigma_a, sigma_s, Le;
    };
    Point at(Vec3 p) const;
    // The density at a point of the unit box (the medium's box mapped to [0, 1]^3); a cloud's takes the point
    // of the medium's space.
    double grid_density(Vec3 unit) const;
    double cloud_density(Vec3 p_medium) const;
    // The majorant segments of the world ray o + t d (d unit) over [0, t_max).
    MajorantIterator majorants(Vec3 o, Vec3 d, double t_max) const;
    const MajorantGrid &majorant_grid() const { return grid_; }
    // The RGB of pbrt-v4's normalized blackbody at kelvin (> 100), from the medium's table.
    Vec3 blackbody(double kelvin) const;
    bool emissive() const { return emissive_; }

private:
    void nanovdb_majorants();  // pbrt-v4's NanoVDBMedium majorant grid
    void blackbody_table(double lo, double top);  // blackbody_ over the temperatures of grid values in [lo, top]
    double lookup(const std::vector<float> &values, Vec3 unit) const;  // trilinear, 0 outside (SampledGrid)
    double max_value(const std::vector<float> &values, Vec3 lo, Vec3 hi) const;  // over a box of the unit cube

    const udm1scene::Medium &m_;
    Vec3 extent_;  // p1 - p0
    Vec3 sigma_t_;
    MajorantGrid grid_;
    bool emissive_ = false;
    std::vector<Vec3> blackbody_;  // RGB at 100 K + i step_
    double bb_step_ = 1;
};

// The uniform values of one delta-tracking walk (pbrt-v4 draws them from an RNG seeded by a hash of sampler
// values or of the ray): splitmix64 from a seed, deterministic.
struct TrackingRandom {
    uint64_t state;
    explicit TrackingRandom(uint64_t seed) : state(udm1_mix64(seed ^ 0x5452414B494E4721ull)) {}
    double uniform()
    {
        state += UDM1_GOLDEN_GAMMA;
        return (double)(udm1_mix64(state) >> 11) * 0x1.0p-53;
    }
};

// A seed from doubles' bits (sampler values, a ray's origin and direction).
uint64_t tracking_seed(const double *v, int n);

}  // namespace udm1pt
