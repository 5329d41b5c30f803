// pixel_filter.h - pbrt-v4's pixel filters (PixelFilter "box", "gaussian", "mitchell", "sinc", "triangle")
// and how a camera sample finds its place on the film under them: filter importance sampling, as pbrt-v4's
// GetCameraSample does. The pixel's 2D sample u is mapped to an offset p from the pixel's centre drawn from
// the filter's distribution (box: uniform over its radius; triangle: a tent on each axis; gaussian, mitchell,
// sinc: pbrt-v4's table of the filter at 32 cells per unit of radius, sampled piecewise constant in |f|), and
// the sample's weight is f / pdf: 1 for box and triangle, sign(f) times the integral of the tabulated |f|
// for the others. A pixel is the weighted mean of its samples (sum w L / sum w), so that the constant
// cancels and only the sign matters: filters with negative lobes (mitchell, sinc) carry it.
//
// The tabulated filters are separable (f(x, y) = f1(x) f1(y)), so pbrt-v4's 2D table is the product of two
// 1D tables and its 2D sampling (the marginal in y from u[1], the conditional in x from u[0]) the same
// mapping as sampling each axis from its 1D table: FilmSampler does that, in double.
#pragma once

#include <string>
#include <vector>

namespace udm1scene {

// A PixelFilter as the scene file gives it (pbrt-v4's parameters and defaults, read as float as pbrt-v4
// reads them). Without a PixelFilter line pbrt-v4 uses a gaussian of radius 1.5 and sigma 0.5; udm1's own
// scenes (built in, PLY and OBJ) use the box of radius 1/2.
struct PixelFilter {
    std::string type = "box";       // box, gaussian, mitchell, sinc, triangle
    double xradius = 0.5, yradius = 0.5;
    double sigma = 0.5;             // gaussian
    double b = 1.0f / 3.0f, c = 1.0f / 3.0f;  // mitchell (pbrt-v4's "B", "C")
    double tau = 3;                 // sinc (Lanczos)
    std::string where;              // the PixelFilter's file:line ("" without one)

    // pbrt-v4's default for a filter type (its radius and parameters); throws std::invalid_argument for a type
    // pbrt-v4 does not have.
    static PixelFilter defaults(const std::string &type);
    // The box of radius 1/2: a sample's place is the pixel's corner plus u, bit for bit the unfiltered one.
    bool unit_box() const { return type == "box" && xradius == 0.5 && yradius == 0.5; }
    // The filter's value at an offset from the pixel's centre (pbrt-v4's Filter::Evaluate).
    double evaluate(double x, double y) const;
    // One axis of a separable filter (gaussian, mitchell, sinc, triangle; box: 1 inside its radius).
    double evaluate1(double x, double radius) const;
    // Why the parameters are not a filter pbrt-v4 renders ("" if they are): radii not positive and finite, or
    // too large to tabulate; a tabulated filter narrower than one cell (radius below 1/32); sigma or tau not
    // positive; a filter that is zero everywhere. `param` (if given) names the parameter at fault.
    std::string invalid(const char **param = nullptr) const;
};

// Where the samples of a pixel go under a filter, and their weights' signs (above).
class FilmSampler {
public:
    explicit FilmSampler(const PixelFilter &f);
    // Whether some samples weigh negative (mitchell and sinc: negative lobes): the film then sums the weights.
    bool signed_weights() const { return signed_; }
    bool unit_box() const { return unit_box_; }
    // The pixel's 2D sample u (in [0, 1)^2) becomes the sample's offset from the pixel's corner on the film
    // (the centre is at 0.5, 0.5), in place; returns the sign of its weight (+1 or -1). The unit box leaves u
    // as it is.
    int place(double u[2]) const
    {
        if (unit_box_) return 1;
        return place_filtered(u);
    }

private:
    struct Axis {
        double radius = 0;
        std::vector<double> value, cdf;  // the tabulated f1 at the cells' centres; the CDF of |f1| (cdf[n] = 1)
        // u in [0, 1) -> an offset in [-radius, radius] from the table, and the sign of its cell's value
        double sample(double u, int *sign) const;
    };
    int place_filtered(double u[2]) const;

    PixelFilter f_;
    bool unit_box_, tabulated_, triangle_, signed_ = false;
    Axis x_, y_;
};

}  // namespace udm1scene
