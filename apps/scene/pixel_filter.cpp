// pixel_filter.cpp - see pixel_filter.h.
#include "pixel_filter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace udm1scene {

namespace {

constexpr double PI = 3.14159265358979323846;
constexpr double MAX_RADIUS = 1024;  // pixels: tables of 32 cells per unit of radius stay small

double gaussian(double x, double sigma) { return std::exp(-x * x / (2 * sigma * sigma)) / std::sqrt(2 * PI * sigma * sigma); }

double sinc(double x)
{
    double t = PI * x;
    return 1 - t * t == 1 ? 1 : std::sin(t) / t;
}

bool tabulated(const std::string &type) { return type == "gaussian" || type == "mitchell" || type == "sinc"; }

// The number of cells of pbrt-v4's table along an axis of this radius: int(32 r).
int cells(double radius) { return (int)(32 * radius); }

// pbrt-v4's tent on [-r, r]: the left half from u < 1/2 (u remapped to [0, 1)), the right from the rest.
double tent(double u, double r)
{
    if (u < 0.5) return -r + r * std::sqrt(2 * u);
    double v = std::min((u - 0.5) * 2, 1.0);
    return r * (1 - std::sqrt(1 - v));
}

}  // namespace

PixelFilter PixelFilter::defaults(const std::string &type)
{
    PixelFilter f;
    f.type = type;
    if (type == "box") f.xradius = f.yradius = 0.5;
    else if (type == "gaussian") f.xradius = f.yradius = 1.5;
    else if (type == "mitchell" || type == "triangle") f.xradius = f.yradius = 2;
    else if (type == "sinc") f.xradius = f.yradius = 4;
    else throw std::invalid_argument(type);
    return f;
}

double PixelFilter::evaluate1(double x, double radius) const
{
    if (type == "box") return std::fabs(x) <= radius ? 1 : 0;
    if (type == "triangle") return std::max(0.0, radius - std::fabs(x));
    if (type == "gaussian") return std::max(0.0, gaussian(x, sigma) - gaussian(radius, sigma));
    if (type == "mitchell") {
        double t = std::fabs(2 * x / radius);
        if (t <= 1) return ((12 - 9 * b - 6 * c) * t * t * t + (-18 + 12 * b + 6 * c) * t * t + (6 - 2 * b)) / 6;
        if (t <= 2) return ((-b - 6 * c) * t * t * t + (6 * b + 30 * c) * t * t + (-12 * b - 48 * c) * t + (8 * b + 24 * c)) / 6;
        return 0;
    }
    if (type == "sinc") return std::fabs(x) > radius ? 0 : sinc(x) * sinc(x / tau);
    return 0;
}

double PixelFilter::evaluate(double x, double y) const { return evaluate1(x, xradius) * evaluate1(y, yradius); }

std::string PixelFilter::invalid(const char **param) const
{
    const char *unused;
    if (!param) param = &unused;
    for (int a = 0; a < 2; ++a) {
        double r = a == 0 ? xradius : yradius;
        *param = a == 0 ? "xradius" : "yradius";
        if (!(r > 0) || !std::isfinite(r)) return std::string(*param) + " must be positive";
        if (r > MAX_RADIUS) return std::string(*param) + " above 1024 pixels is not modelled";
        if (tabulated(type) && cells(r) < 1)
            return std::string(*param) + " below 1/32 leaves pbrt-v4's table of the filter (32 cells per unit of radius) "
                                         "without a cell";
    }
    *param = type == "gaussian" ? "sigma" : type == "sinc" ? "tau" : "B";
    if (type == "gaussian" && !(sigma > 0 && std::isfinite(sigma))) return "sigma must be positive";
    if (type == "sinc" && !(tau > 0 && std::isfinite(tau))) return "tau must be positive";
    if (type == "mitchell" && !(std::isfinite(b) && std::isfinite(c))) return "B and C must be finite";
    for (int a = 0; a < 2 && tabulated(type); ++a) {
        double r = a == 0 ? xradius : yradius;
        int n = cells(r);
        bool any = false;
        for (int i = 0; i < n && !any; ++i) any = evaluate1(-r + (i + 0.5) / n * 2 * r, r) != 0;
        if (!any) return "the filter is zero at every cell of pbrt-v4's table of it (pbrt-v4 renders such a film black)";
    }
    *param = "";
    return "";
}

FilmSampler::FilmSampler(const PixelFilter &f)
    : f_(f), unit_box_(f.unit_box()), tabulated_(tabulated(f.type)), triangle_(f.type == "triangle")
{
    if (!tabulated_) return;
    for (int a = 0; a < 2; ++a) {
        Axis &ax = a == 0 ? x_ : y_;
        ax.radius = a == 0 ? f.xradius : f.yradius;
        const int n = std::max(cells(ax.radius), 1);
        ax.value.resize(n), ax.cdf.assign(n + 1, 0.0);
        for (int i = 0; i < n; ++i) {
            ax.value[i] = f.evaluate1(-ax.radius + (i + 0.5) / n * 2 * ax.radius, ax.radius);
            if (ax.value[i] < 0) signed_ = true;
            ax.cdf[i + 1] = ax.cdf[i] + std::fabs(ax.value[i]);
        }
        const double total = ax.cdf[n];
        for (int i = 1; i <= n; ++i) ax.cdf[i] = total > 0 ? ax.cdf[i] / total : (double)i / n;
        ax.cdf[n] = 1;
    }
}

double FilmSampler::Axis::sample(double u, int *sign) const
{
    const int n = (int)value.size();
    // the cell: the last whose CDF is at most u (pbrt-v4's FindInterval), then u's place inside it
    int o = (int)(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()) - 1;
    o = std::min(std::max(o, 0), n - 1);
    double du = u - cdf[o], width = cdf[o + 1] - cdf[o];
    if (width > 0) du /= width;
    *sign = value[o] < 0 ? -1 : 1;
    double t = (o + du) / n;
    return (1 - t) * -radius + t * radius;
}

int FilmSampler::place_filtered(double u[2]) const
{
    if (tabulated_) {
        int sx, sy;
        double px = x_.sample(u[0], &sx), py = y_.sample(u[1], &sy);
        u[0] = 0.5 + px, u[1] = 0.5 + py;
        return sx * sy;
    }
    if (triangle_) {
        u[0] = 0.5 + tent(u[0], f_.xradius), u[1] = 0.5 + tent(u[1], f_.yradius);
        return 1;
    }
    // box: uniform over [-radius, radius] on each axis
    u[0] = 0.5 + ((1 - u[0]) * -f_.xradius + u[0] * f_.xradius);
    u[1] = 0.5 + ((1 - u[1]) * -f_.yradius + u[1] * f_.yradius);
    return 1;
}

}  // namespace udm1scene
