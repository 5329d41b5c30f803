// bilinear_warp.h - a function on the unit square given at the nodes of a regular w x h grid and bilinear
// between them, for each value of up to three parameters (its tables interpolated linearly between the
// parameters' tabulated values, clamped at their ends): evaluated, and, as a density (each table normalized
// to integrate to 1), sampled and inverted by its marginal and conditional distribution functions (the
// inversions solve the quadratics of a bilinear density exactly). pbrt-v4's PiecewiseLinear2D models the
// same warp, which its MeasuredBxDF (pt/bsdf.h, Measured) uses; the sums here are in double.
#pragma once

#include <cstddef>
#include <vector>

namespace udm1pt {

class BilinearWarp {
public:
    static constexpr int MAX_PARAMS = 3;
    BilinearWarp() = default;
    // `values`: one table of h rows of w values (w, h >= 2) for each combination of the parameters' values,
    // the first parameter's slowest. `params`: each parameter's increasing values (one value: no dependence).
    // `density`: normalize each table and build what sampling needs; else evaluate the values as they are.
    BilinearWarp(const float *values, int w, int h, std::vector<std::vector<float>> params, bool density);
    // The value (a density if made as one) at (x, y) in [0, 1]^2, for the parameters param[0..].
    double eval(double x, double y, const double *param = nullptr) const;
    // (u1, u2) uniform in [0, 1)^2 to a point (*x, *y) distributed as the density, and the density there.
    void sample(double u1, double u2, const double *param, double *x, double *y, double *pdf) const;
    // The inverse of sample(): the (u1, u2) that sample() maps to (x, y), and the density there.
    void invert(double x, double y, const double *param, double *u1, double *u2, double *pdf) const;

private:
    struct Corners {  // the tables interpolated for the parameters: index and weight of each
        int n = 1;
        std::size_t slice[1 << MAX_PARAMS] = {0};
        double weight[1 << MAX_PARAMS] = {1};
    };
    Corners corners(const double *param) const;
    double at(const std::vector<double> &v, const Corners &c, std::size_t stride, std::size_t i) const
    {
        double s = 0;
        for (int k = 0; k < c.n; ++k) s += c.weight[k] * v[c.slice[k] * stride + i];
        return s;
    }
    int w_ = 0, h_ = 0;
    double scale_ = 1;  // a density's: (w - 1) (h - 1)
    std::vector<std::vector<float>> params_;
    std::vector<std::size_t> strides_;  // in tables, per parameter
    std::vector<double> values_;      // normalized if a density
    std::vector<double> conditional_; // per table and row: the cumulative integral along the row (w values)
    std::vector<double> marginal_;    // per table: the cumulative integral over rows (h values)
};

}  // namespace udm1pt
