// bilinear_warp.cpp - see bilinear_warp.h.
#include "bilinear_warp.h"

#include <algorithm>
#include <cmath>

namespace udm1pt {

namespace {

// The last i in [0, n - 2] at which below(i) holds (below true up to some index, false after), 0 if none.
template <class F> size_t last_below(size_t n, F below)
{
    size_t a = 1, b = n - 1;  // below holds on [1, a), fails on [b, n - 1)
    while (a < b) {
        size_t m = a + (b - a) / 2;
        if (below(m))
            a = m + 1;
        else
            b = m;
    }
    return std::min(a - 1, n - 2);
}

// t in [0, 1] with integral over [0, t] of (1 - s) a + s b ds = u (a, b >= 0; u at most (a + b) / 2): the root
// of (b - a) t^2 / 2 + a t - u, in the form without cancellation.
double invert_linear(double a, double b, double u)
{
    double d = a + std::sqrt(std::max(0.0, a * a + 2 * (b - a) * u));
    return d > 0 ? std::clamp(2 * u / d, 0.0, 1.0) : 0.0;
}

const double ONE_MINUS_EPS = 0x1.fffffffffffffp-1;

// x clamped to [0, 1] (not a number: 0), so that the cell index is defined.
inline double unit(double x) { return x >= 0 ? std::min(x, 1.0) : 0.0; }

}  // namespace

BilinearWarp::BilinearWarp(const float *values, int w, int h, std::vector<std::vector<float>> params, bool density)
    : w_(w), h_(h), params_(std::move(params))
{
    size_t tables = 1;
    strides_.assign(params_.size(), 0);
    for (size_t d = params_.size(); d-- > 0;) strides_[d] = tables, tables *= params_[d].size();
    const size_t n = (size_t)w * h;
    values_.assign(values, values + tables * n);
    if (!density) return;
    scale_ = (double)(w - 1) * (h - 1);  // (the normalized values per cell, as a density on the unit square)
    conditional_.assign(tables * n, 0.0);
    marginal_.assign(tables * h, 0.0);
    for (size_t t = 0; t < tables; ++t) {
        double *v = &values_[t * n], *cond = &conditional_[t * n], *marg = &marginal_[t * h];
        for (int y = 0; y < h; ++y)
            for (int x = 1; x < w; ++x)  // (in units of cells)
                cond[y * w + x] = cond[y * w + x - 1] + 0.5 * (v[y * w + x - 1] + v[y * w + x]);
        for (int y = 1; y < h; ++y) marg[y] = marg[y - 1] + 0.5 * (cond[y * w - 1] + cond[(y + 1) * w - 1]);
        const double norm = marg[h - 1] > 0 ? 1 / marg[h - 1] : 0;
        for (size_t i = 0; i < n; ++i) v[i] *= norm, cond[i] *= norm;
        for (int y = 0; y < h; ++y) marg[y] *= norm;
    }
}

BilinearWarp::Corners BilinearWarp::corners(const double *param) const
{
    Corners c;
    for (size_t d = 0; d < params_.size(); ++d) {
        const std::vector<float> &p = params_[d];
        if (p.size() < 2) continue;
        size_t i = last_below(p.size(), [&](size_t k) { return p[k] <= param[d]; });
        double t = (param[d] - p[i]) / ((double)p[i + 1] - p[i]);
        t = t >= 0 ? std::min(t, 1.0) : 0.0;  // (clamped at the ends; not a number: the first)
        for (int k = 0; k < c.n; ++k) {
            c.slice[c.n + k] = c.slice[k] + (i + 1) * strides_[d], c.weight[c.n + k] = c.weight[k] * t;
            c.slice[k] += i * strides_[d], c.weight[k] *= 1 - t;
        }
        c.n *= 2;
    }
    return c;
}

double BilinearWarp::eval(double x, double y, const double *param) const
{
    const Corners c = corners(param);
    const size_t n = (size_t)w_ * h_;
    x = unit(x) * (w_ - 1), y = unit(y) * (h_ - 1);
    int col = std::min((int)x, w_ - 2), row = std::min((int)y, h_ - 2);
    double fx = x - col, fy = y - row;
    size_t i = (size_t)row * w_ + col;
    double v00 = at(values_, c, n, i), v10 = at(values_, c, n, i + 1), v01 = at(values_, c, n, i + w_),
           v11 = at(values_, c, n, i + w_ + 1);
    return ((1 - fy) * ((1 - fx) * v00 + fx * v10) + fy * ((1 - fx) * v01 + fx * v11)) * scale_;
}

void BilinearWarp::sample(double u1, double u2, const double *param, double *x, double *y, double *pdf) const
{
    const Corners c = corners(param);
    const size_t n = (size_t)w_ * h_;
    u1 = std::clamp(unit(u1), 1 - ONE_MINUS_EPS, ONE_MINUS_EPS), u2 = std::clamp(unit(u2), 1 - ONE_MINUS_EPS, ONE_MINUS_EPS);
    // the row by the marginal distribution, then the place in it
    size_t row = last_below((size_t)h_, [&](size_t k) { return at(marginal_, c, h_, k) < u2; });
    u2 -= at(marginal_, c, h_, row);
    const size_t r = row * w_;
    double r0 = at(conditional_, c, n, r + w_ - 1), r1 = at(conditional_, c, n, r + 2 * w_ - 1);
    double fy = invert_linear(r0, r1, u2);
    // the column by the conditional distribution along that height, then the place in it
    u1 *= (1 - fy) * r0 + fy * r1;
    auto cond = [&](size_t k) { return (1 - fy) * at(conditional_, c, n, r + k) + fy * at(conditional_, c, n, r + w_ + k); };
    size_t col = last_below((size_t)w_, [&](size_t k) { return cond(k) < u1; });
    u1 -= cond(col);
    const size_t i = r + col;
    double c0 = (1 - fy) * at(values_, c, n, i) + fy * at(values_, c, n, i + w_),
           c1 = (1 - fy) * at(values_, c, n, i + 1) + fy * at(values_, c, n, i + w_ + 1);
    double fx = invert_linear(c0, c1, u1);
    *x = (col + fx) / (w_ - 1), *y = (row + fy) / (h_ - 1);
    *pdf = ((1 - fx) * c0 + fx * c1) * scale_;
}

void BilinearWarp::invert(double x, double y, const double *param, double *u1, double *u2, double *pdf) const
{
    const Corners c = corners(param);
    const size_t n = (size_t)w_ * h_;
    x = unit(x) * (w_ - 1), y = unit(y) * (h_ - 1);
    int col = std::min((int)x, w_ - 2), row = std::min((int)y, h_ - 2);
    double fx = x - col, fy = y - row;
    const size_t r = (size_t)row * w_, i = r + col;
    double c0 = (1 - fy) * at(values_, c, n, i) + fy * at(values_, c, n, i + w_),
           c1 = (1 - fy) * at(values_, c, n, i + 1) + fy * at(values_, c, n, i + w_ + 1);
    *pdf = ((1 - fx) * c0 + fx * c1) * scale_;
    double r0 = at(conditional_, c, n, r + w_ - 1), r1 = at(conditional_, c, n, r + 2 * w_ - 1);
    double along = fx * (c0 + 0.5 * fx * (c1 - c0)) + (1 - fy) * at(conditional_, c, n, i) + fy * at(conditional_, c, n, i + w_);
    double row_total = (1 - fy) * r0 + fy * r1;
    *u1 = row_total > 0 ? std::clamp(along / row_total, 0.0, 1.0) : 0.0;
    *u2 = std::clamp(fy * (r0 + 0.5 * fy * (r1 - r0)) + at(marginal_, c, h_, row), 0.0, 1.0);
}

}  // namespace udm1pt
